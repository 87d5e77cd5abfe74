// Tests of the geometry JSON layer (json_reader, geometry_io): exact round trips, file order,
// defaults, and errors that name the file, the JSON path and the bad value.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"
#include "tests/support/geometry_error.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_geometry_io {

using namespace iga;

namespace {

const std::string kBad = std::string(IGA_SOURCE_DIR) + "/tests/data/bad/";
const std::string kModels = std::string(IGA_SOURCE_DIR) + "/tests/data/models/";

/// The geometry section of a model file, as the model loader reads it.
GeometryModel load_geometry(const std::string& path) {
  const Json doc = read_json_file(path);
  return parse_geometry(doc.at("geometry"), path, JsonPointer("/geometry"));
}

/// Geometry -> JSON text -> geometry, through the same reader as files.
GeometryModel text_round_trip(const GeometryModel& m) {
  return parse_geometry(parse_json_text(geometry_to_json(m).dump(), "mem.json"), "mem.json",
                        JsonPointer("/geometry"));
}

GeometryModel hand_built() {
  GeometryModel m;
  const std::vector<Vector3d> P = {{0, 0, 0}, {1, 0.25, 0}, {2, 1, 0.5}, {3, 1, 0}};
  m.entities.emplace_back("rail", NurbsCurve(2, {0, 0, 0, 0.4, 1, 1, 1}, P,
                                             {1, std::numbers::sqrt2 / 2, 1.0 / 3.0, 1}));
  std::vector<Vector3d> net;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 2; ++i) net.emplace_back(0.1 * i, 0.3 * j, 0.7 * i * j);
  NurbsSurface patch(1, {0, 0, 1, 1}, 2, {0, 0, 0, 1, 1, 1}, net, {1, 0.9, 0.8, 0.7, 1, 1.1});
  patch.set_normal_sign(-1);
  m.entities.emplace_back("patch", patch);
  const Placement tilted{Vector3d(0.1, -0.2, 0.3), Vector3d(0, 0.6, 0.8), Vector3d(1, 0, 0)};
  m.entities.emplace_back("plane", Plane(tilted));
  m.entities.emplace_back("sphere", Sphere(tilted, 0.3));
  Cylinder cyl(Placement{}, 1.0 / 7.0);
  cyl.set_domain({{0, 2 * std::numbers::pi}, {-1, 2}});
  m.entities.emplace_back("cylinder", cyl);
  m.entities.emplace_back("torus", Torus(tilted, 2.0, 0.1));
  Cone cone(Placement{}, 0.3);
  cone.set_normal_sign(-1);
  m.entities.emplace_back("cone", cone);
  m.entities.emplace_back("hyperboloid", Hyperboloid(Placement{}, -0.1));
  m.entities.emplace_back("revolution", Revolution(Placement{}, {0.0, 0.1, 0.5}));
  m.entities.emplace_back("group", PatchGroup{{"patch", "sphere"}});
  return m;
}

}  // namespace

TEST_CASE("geometry_io: every entity type survives save -> parse exactly", "[geometry][io]") {
  const GeometryModel m = hand_built();
  const GeometryModel back = text_round_trip(m);
  REQUIRE(back.entities.size() == m.entities.size());
  for (std::size_t i = 0; i < m.entities.size(); ++i) {
    INFO(m.entities[i].first);
    CHECK(back.entities[i].first == m.entities[i].first);
    CHECK(entity_type(back.entities[i].second) == entity_type(m.entities[i].second));
    CHECK(back.entities[i].second == m.entities[i].second);
  }
  CHECK(back == m);
}

TEST_CASE("geometry_io: rational control points round-trip bit for bit", "[geometry][io]") {
  // The file holds P and w; the curve stores w P. Written coordinates must reproduce w P.
  std::mt19937 gen(12345);
  std::uniform_real_distribution<double> coord(-1e3, 1e3), weight(0.01, 10.0);
  std::vector<Vector3d> P(40);
  std::vector<double> w(40);
  for (std::size_t i = 0; i < P.size(); ++i) {
    P[i] = Vector3d(coord(gen), coord(gen), coord(gen) * 1e-7);
    w[i] = weight(gen);
  }
  std::vector<double> U = {0, 0, 0, 0};
  for (int k = 1; k < 37; ++k) U.push_back(k / 37.0);
  U.insert(U.end(), {1, 1, 1, 1});
  GeometryModel m;
  m.entities.emplace_back("c", NurbsCurve(3, U, P, w));
  const GeometryModel once = text_round_trip(m);
  CHECK(once == m);
  CHECK(text_round_trip(once) == once);
}

TEST_CASE("geometry_io: saved text is stable on a second round", "[geometry][io]") {
  const GeometryModel m = load_geometry(kModels + "all_entities.json");
  const std::string first = format_json(geometry_to_json(m));
  const GeometryModel again =
      parse_geometry(parse_json_text(first, "first.json"), "first.json", JsonPointer("/geometry"));
  CHECK(again == m);
  CHECK(format_json(geometry_to_json(again)) == first);
}

TEST_CASE("geometry_io: entities keep the file order and not alphabetical order",
          "[geometry][io]") {
  const GeometryModel m = load_geometry(kModels + "all_entities.json");
  std::vector<std::string> names;
  for (const auto& [name, e] : m.entities) names.push_back(name);
  const std::vector<std::string> expected = {"rail", "roof",   "floor",  "ball", "drum",
                                             "ring", "funnel", "saddle", "bowl", "obstacle"};
  CHECK(names == expected);
  // Writing keeps that order too.
  const Json j = geometry_to_json(m);
  std::vector<std::string> written;
  for (auto it = j.begin(); it != j.end(); ++it) written.push_back(it.key());
  CHECK(written == expected);
}

TEST_CASE("geometry_io: a plain nlohmann::json is accepted with keys in its sorted order",
          "[geometry][io]") {
  nlohmann::json j;
  j["zeta"] = {{"type", "plane"}, {"center", {0, 0, 0}}, {"axis", {0, 0, 1}}};
  j["alpha"] = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}};
  const GeometryModel m = parse_geometry(j, "plain", JsonPointer("/geometry"));
  REQUIRE(m.entities.size() == 2);
  CHECK(m.entities[0].first == "alpha");
  CHECK(m.entities[1].first == "zeta");
}

TEST_CASE("geometry_io: omitted keys take the documented defaults", "[geometry][io]") {
  const Json j = Json::parse(R"({
    "c": {"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
          "control_points": [[0, 0, 0], [1, 2, 3]]},
    "s": {"type": "sphere", "center": [1, 2, 3], "radius": 2},
    "h": {"type": "hyperboloid", "a": 0.5},
    "x": {"type": "cylinder", "center": [0, 0, 0], "axis": [1, 0, 0], "radius": 1}
  })");
  const GeometryModel m = parse_geometry(j, "d.json", JsonPointer("/geometry"));
  const NurbsCurve& c = *m.curve("c");
  CHECK_FALSE(c.is_rational());
  CHECK(c.weight(1) == 1.0);
  const auto& s = std::get<Sphere>(*m.find("s"));
  CHECK(s.placement().axis == Vector3d::UnitZ());
  CHECK(s.domain() == Sphere::default_domain());
  CHECK(s.normal_sign() == 1);
  const auto& h = std::get<Hyperboloid>(*m.find("h"));
  CHECK(h.placement() == Placement{});
  CHECK(std::isinf(h.domain().u.lo));
  // axis = x with the default ref_dir = x: the frame falls back to a valid e_x.
  const Surface& x = *m.surface("x");
  const SurfaceDerivs d = x.derivs(0.3, 0.2, 1);
  CHECK(d.Su.cross(d.Sv).norm() == Approx(1.0).epsilon(1e-12));
  CHECK(text_round_trip(m) == m);
}

TEST_CASE("geometry_io: domain null bounds are unbounded and partial domains keep defaults",
          "[geometry][io]") {
  const Json j = Json::parse(R"({
    "p": {"type": "plane", "center": [0, 0, 0], "axis": [0, 0, 1],
          "domain": {"u": [null, 2], "v": [-1, null]}},
    "c": {"type": "cylinder", "center": [0, 0, 0], "axis": [0, 0, 1], "radius": 1,
          "domain": {"v": [0, 3]}}
  })");
  const GeometryModel m = parse_geometry(j, "d.json", JsonPointer("/geometry"));
  const Domain2 dp = m.surface("p")->domain();
  CHECK(dp.u.lo == -std::numeric_limits<double>::infinity());
  CHECK(dp.u.hi == 2.0);
  CHECK(dp.v.lo == -1.0);
  CHECK(dp.v.hi == std::numeric_limits<double>::infinity());
  const Domain2 dc = m.surface("c")->domain();
  CHECK(dc.u == Cylinder::default_domain().u);
  CHECK(dc.v == (Interval{0.0, 3.0}));
  const Json out = geometry_to_json(m);
  CHECK(out["p"]["domain"]["u"][0].is_null());
  CHECK(out["p"]["domain"]["v"][1].is_null());
}

TEST_CASE("geometry_io: \"inward\" flips the normal of NURBS and analytic surfaces",
          "[geometry][io]") {
  const GeometryModel m = load_geometry(kModels + "all_entities.json");
  CHECK(m.surface("roof")->normal_sign() == -1);
  CHECK(m.surface("funnel")->normal_sign() == -1);
  CHECK(m.surface("floor")->normal_sign() == 1);
  CHECK(geometry_to_json(m)["roof"]["normal"] == "inward");
}

TEST_CASE("geometry_io: patch groups resolve to their member surfaces", "[geometry][io]") {
  const GeometryModel m = load_geometry(kModels + "all_entities.json");
  const std::vector<const Surface*> s = m.surfaces_of("obstacle");
  REQUIRE(s.size() == 3);
  CHECK(s[0] == m.surface("roof"));
  CHECK(s[1] == m.surface("floor"));
  CHECK(s[2] == m.surface("ball"));
  CHECK(m.surfaces_of("ball") == std::vector<const Surface*>{m.surface("ball")});
  CHECK(m.surface("rail") == nullptr);
  CHECK(m.surface("obstacle") == nullptr);
  CHECK(m.curve("rail") != nullptr);
  CHECK_THROWS_AS(m.surfaces_of("rail"), std::out_of_range);
  CHECK_THROWS_AS(m.surfaces_of("nothing"), std::out_of_range);
  CHECK(entity_type(*m.find("obstacle")) == "patch_group");
  CHECK(entity_type(*m.find("rail")) == "nurbs_curve");
  CHECK(entity_type(*m.find("bowl")) == "revolution");
}

TEST_CASE("geometry_io: loaded NURBS evaluate the geometry of the file", "[geometry][io]") {
  const GeometryModel m = load_geometry(kModels + "all_entities.json");
  const NurbsCurve& rail = *m.curve("rail");
  CHECK((rail.point(0.0) - Vector3d(0, 0, 0)).norm() == Approx(0.0).margin(1e-14));
  CHECK((rail.point(1.0) - Vector3d(3, 1, 0)).norm() == Approx(0.0).margin(1e-14));
  CHECK(rail.weight(1) == 0.7071067811865476);
  const auto& roof = std::get<NurbsSurface>(*m.find("roof"));
  CHECK(roof.num_u() == 3);
  CHECK(roof.num_v() == 2);
  CHECK((roof.control_point(1, 1) - Vector3d(0.5, 1, 1.5)).norm() ==
        Approx(0.0).margin(1e-15));  // u index fastest
}

// ---- errors -------------------------------------------------------------------------------

namespace {

struct BadCase {
  const char* file;
  const char* pointer;
  std::vector<std::string> fragments;  // pieces the message must contain (value, reason)
};

}  // namespace

TEST_CASE("geometry_io: bad geometry files name the file and the JSON path and the value",
          "[geometry][io][errors]") {
  const std::vector<BadCase> cases = {
      {"malformed_json.json", "/geometry", {"malformed JSON", "line 5, column 5", "expected '}'"}},
      {"missing_key.json", "/geometry/rail", {"missing required key \"knots\""}},
      {"unknown_key.json", "/geometry/ball/colour", {"unknown key \"colour\"", "radius"}},
      {"wrong_type.json", "/geometry/ball/radius", {"expected a number, got string \"abc\""}},
      {"decreasing_knots.json",
       "/geometry/patch/knots/u/4",
       {"knots must be non-decreasing, got 0.25 after 0.5"}},
      {"knot_count.json", "/geometry/rail/knots", {"expected 8 knots", "got 7"}},
      {"weight_not_positive.json", "/geometry/rail/weights/1", {"weight must be > 0, got -0.5"}},
      {"overflow_number.json", "/geometry/rail/control_points/1/2", {"1e999", "line 7"}},
      {"degree_zero.json", "/geometry/rail/degree", {"degree must be in 1..10, got 0"}},
      {"interior_multiplicity.json",
       "/geometry/rail/knots/5",
       {"interior knot 0.5 has multiplicity 3 > degree 2"}},
      {"control_point_size.json",
       "/geometry/roof/control_points/3",
       {"expected 3 coordinates [x, y, z], got array [1,2]"}},
      {"negative_radius.json", "/geometry/drum/radius", {"must be > 0, got -3"}},
      {"torus_minor_radius.json", "/geometry/ring/minor_radius", {"must be > 0", "got 0"}},
      {"group_names_curve.json",
       "/geometry/obstacle/patches/1",
       {"\"rail\" is a nurbs_curve", "surfaces only"}},
      {"group_unknown_name.json",
       "/geometry/obstacle/patches/1",
       {"\"roof\" does not name an entity"}},
      {"duplicate_key.json", "/geometry/ball/radius", {"duplicate key \"radius\""}},
      {"unknown_type.json", "/geometry/rail/type", {"unknown entity type", "got \"nurbs_curv\""}},
      {"domain_reversed.json", "/geometry/floor/domain/u", {"lo < hi", "got [1,-1]"}},
      {"bad_normal.json", "/geometry/floor/normal", {"\"outward\" or \"inward\"", "got \"up\""}},
      {"weights_count.json", "/geometry/rail/weights", {"expected 2 weights", "got 3"}},
      {"coordinate_too_large.json",
       "/geometry/rail/control_points/1/1",
       {"must lie within +-1e+100", "got 1e+308"}},
      {"weight_tiny.json",
       "/geometry/rail/weights/0",
       {"weight must lie in [1e-100, 1e+100]", "got 1e-300"}},
      {"weight_ratio.json",
       "/geometry/rail/weights/1",
       {"differ by a factor of at most 1e10", "smallest is 1.0 (index 0)", "got 1000000000000.0"}},
      {"radius_too_large.json",
       "/geometry/ball/radius",
       {"must lie in [1e-100, 1e+100]", "got 1e+308"}},
      {"domain_too_large.json",
       "/geometry/floor/domain/u/0",
       {"must lie within +-1e+100", "got -1e+308"}},
  };
  for (const BadCase& c : cases) {
    const std::string path = kBad + c.file;
    INFO(c.file);
    try {
      load_geometry(path);
      FAIL("accepted " << c.file);
    } catch (const ModelError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(e.file() == path);
      CHECK(e.pointer() == c.pointer);
      CHECK(what.rfind(path + ": " + c.pointer + ": ", 0) == 0);
      for (const std::string& f : c.fragments) CHECK(what.find(f) != std::string::npos);
    }
  }
}

TEST_CASE("json_reader: malformed text reports line and column from the byte offset",
          "[geometry][io][errors]") {
  const std::string text = "{\n  \"a\": [1, 2,\n        3,, 4]\n}";
  try {
    parse_json_text(text, "t.json");
    FAIL("accepted malformed JSON");
  } catch (const ModelError& e) {
    INFO(e.what());
    CHECK(e.pointer() == "/a/3");
    CHECK(std::string(e.what()).find("line 3, column 11") != std::string::npos);
  }
  // Unterminated document: the position is the end of the text.
  try {
    parse_json_text("{\"a\": 1", "t.json");
    FAIL("accepted truncated JSON");
  } catch (const ModelError& e) {
    CHECK(std::string(e.what()).find("line 1, column 8") != std::string::npos);
  }
}

TEST_CASE("json_reader: type errors say what was expected and what came",
          "[geometry][io][errors]") {
  const Json j = Json::parse(R"({"n": "abc", "i": 2.5, "b": 1, "long": [
    1000000, 2000000, 3000000, 4000000, 5000000, 6000000, 7000000, 8000000, 9000000]})");
  const JsonCursor root(j, "c.json");
  CHECK_THROWS_WITH(root["n"].as_number(), "c.json: /n: expected a number, got string \"abc\"");
  CHECK_THROWS_WITH(root["i"].as_int(), "c.json: /i: expected an integer, got 2.5");
  CHECK_THROWS_WITH(root["b"].as_bool(), "c.json: /b: expected true or false, got number 1");
  CHECK_THROWS_WITH(root["x"], "c.json: missing required key \"x\"");
  CHECK_THROWS_WITH(root["long"].as_string(),
                    Catch::Matches("c\\.json: /long: expected a string, got array "
                                   "\\[1000000,2000000,.*\\.\\.\\."));
  CHECK(short_dump(j["long"]).size() <= 60);
  // Non-finite values built in memory are rejected too.
  const Json inf = {{"x", std::numeric_limits<double>::infinity()}};
  CHECK_THROWS_WITH(JsonCursor(inf, "m")["x"].as_number(),
                    "m: /x: expected a finite number, got inf");
}

TEST_CASE("geometry_io: errors in memory name the element and not just the entity",
          "[geometry][io][errors]") {
  const ModelError e1 =
      iga::test::geometry_error(R"({"s": {"type": "nurbs_surface", "degree": [2, 1],
      "knots": {"u": [0, 0, 0, 1, 1, 1], "v": [0, 0, 1, 1]},
      "control_points": [[0,0,0],[1,0,0],[2,0,0],[0,1,0],[1,1,0]]}})");
  CHECK(e1.pointer() == "/geometry/s/control_points");
  CHECK(e1.message().find("expected 6 control points") != std::string::npos);
  CHECK(e1.message().find("got 5") != std::string::npos);

  const ModelError e2 = iga::test::geometry_error(R"({"c": {"type": "nurbs_curve", "degree": 2,
      "knots": [0, 0, 0.5, 1, 1, 1], "control_points": [[0,0,0],[1,0,0],[2,0,0]]}})");
  CHECK(e2.pointer() == "/geometry/c/knots/2");
  CHECK(e2.message().find("clamped") != std::string::npos);

  const ModelError e3 = iga::test::geometry_error(R"({"k": {"type": "cone", "center": [0,0,0],
      "axis": [0,0,1], "alpha": 1.6}})");
  CHECK(e3.pointer() == "/geometry/k/alpha");
  CHECK(e3.message() == "must be in (0, pi/2) radians, got 1.6");

  const ModelError e4 = iga::test::geometry_error(R"({"p": {"type": "plane", "center": [0,0,0],
      "axis": [0,0,2], "ref_dir": [0,0,-1]}})");
  CHECK(e4.pointer() == "/geometry/p/ref_dir");

  const ModelError e5 =
      iga::test::geometry_error(R"({"g": {"type": "patch_group", "patches": ["g"]}})");
  CHECK(e5.pointer() == "/geometry/g/patches/0");
  CHECK(e5.message().find("is a patch_group") != std::string::npos);

  const ModelError e6 = iga::test::geometry_error(R"({"c": {"type": "nurbs_curve", "degree": 11,
      "knots": [0, 1], "control_points": []}})");
  CHECK(e6.message() == "degree must be in 1..10, got 11");

  const ModelError e7 = iga::test::geometry_error(R"([1, 2])");
  CHECK(e7.pointer() == "/geometry");
  CHECK(e7.message().find("got array [1,2]") != std::string::npos);
}

TEST_CASE(
    "geometry_io: a construction's \"refine\" takes one count or a pair [u, v] and leaves "
    "the surface unchanged",
    "[geometry][io]") {
  const std::string cyl = R"({"type": "construction", "shape": "cylinder", "center": [0, 0, 0],
      "axis": [0, 1, 0], "ref_dir": [0, 0, 1], "radius": 2, "height": 3, "start_deg": -40,
      "end_deg": 40)";
  auto surface = [](const std::string& entity) {
    const GeometryModel m = parse_geometry(parse_json_text("{\"s\": " + entity + "}", "g.json"),
                                           "g.json", JsonPointer("/geometry"));
    return std::get<NurbsSurface>(m.entities.front().second);
  };
  const NurbsSurface base = surface(cyl + "}");
  const NurbsSurface a = surface(cyl + R"(, "refine": {"elevate": [1, 2], "subdivide": [3, 2]}})");
  const NurbsSurface b = surface(cyl + R"(, "refine": {"elevate": 1, "subdivide": 2}})");
  CHECK(base.degree_u() == 2);
  CHECK(base.degree_v() == 1);
  CHECK(a.degree_u() == 3);
  CHECK(a.degree_v() == 3);
  CHECK(a.knots_u().breaks().size() == 4);
  CHECK(a.knots_v().breaks().size() == 3);
  CHECK(b.degree_u() == 3);
  CHECK(b.degree_v() == 2);
  CHECK(b.knots_u().breaks().size() == 3);
  for (double u : {0.0, 0.3, 0.71, 1.0})
    for (double v : {0.0, 0.45, 1.0}) {
      CHECK((a.point(u, v) - base.point(u, v)).norm() <= 1e-14);
      CHECK((b.point(u, v) - base.point(u, v)).norm() <= 1e-14);
    }
  const ModelError e =
      iga::test::geometry_error("{\"s\": " + cyl + R"(, "refine": {"elevate": [1, 2, 3]}}})");
  CHECK(e.pointer() == "/geometry/s/refine/elevate");
  CHECK_THAT(std::string(e.what()), Catch::Contains("expected a count or a pair [u, v]"));
  const ModelError f =
      iga::test::geometry_error("{\"s\": " + cyl + R"(, "refine": {"subdivide": [2, 0]}}})");
  CHECK(f.pointer() == "/geometry/s/refine/subdivide/1");
  CHECK_THAT(std::string(f.what()), Catch::Contains("must be in 1..1024, got 0"));
}

// ---- limits of the reader (issue 11: deep nesting, huge values, non-regular files) ----------

namespace {

/// The ModelError of parsing `text` (FAIL if none).
ModelError parse_error_of(const std::string& text) {
  try {
    parse_json_text(text, "deep.json");
  } catch (const ModelError& e) {
    return e;
  }
  FAIL("no ModelError");
  return ModelError("", "", "");
}

std::string nested_arrays(std::size_t levels, bool closed = true) {
  return std::string(levels, '[') + "0" + (closed ? std::string(levels, ']') : "");
}

/// A fresh scratch folder for this test process.
std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("iga_geometry_io_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace

TEST_CASE("json_reader: nesting is limited to 256 levels with a located error",
          "[geometry][io][errors][limits]") {
  static_assert(kMaxJsonDepth == 256);
  // 256 levels are read; 257 are not, and the error points at the 257th bracket.
  CHECK(parse_json_text(nested_arrays(256), "ok.json").is_array());
  const ModelError e = parse_error_of(nested_arrays(257));
  CHECK(e.message() == "arrays and objects nested deeper than 256 levels (line 1, column 257)");
  // The documents of the report: 40,000 and 300,000 levels under "app", 60,000 at the root.
  for (const std::size_t levels : {std::size_t{40000}, std::size_t{300000}}) {
    INFO(levels);
    const ModelError a =
        parse_error_of("{\"geometry\": {},\n \"app\": " + nested_arrays(levels) + "}");
    CHECK(a.pointer().rfind("/app/0/0/0", 0) == 0);
    // The root object is level 1: the 256th '[' of "app" (column 9 + 255) is level 257.
    CHECK(a.message() == "arrays and objects nested deeper than 256 levels (line 2, column 264)");
    CHECK(std::string(a.what()).size() < 400);  // the 256-level pointer is abbreviated
  }
  const ModelError root = parse_error_of(nested_arrays(60000));
  CHECK(root.message().find("nested deeper than 256 levels") != std::string::npos);
  // Objects count as levels too.
  std::string objects;
  for (int i = 0; i < 300; ++i) objects += "{\"k\": ";
  objects += "0";
  objects.append(300, '}');
  CHECK(parse_error_of(objects).pointer().rfind("/k/k/k", 0) == 0);
}

TEST_CASE("json_reader: an unclosed 1 MB run of opening brackets is rejected with a located error",
          "[geometry][io][errors][limits]") {
  // Rejected in 52 s before: the error path built a million-level pointer, quadratically. The
  // time (linear in the brackets) is measured by bench/bench_model_setup.cpp, not here.
  const ModelError e = parse_error_of(nested_arrays(std::size_t{1} << 20, false));
  CHECK(e.message() == "arrays and objects nested deeper than 256 levels (line 1, column 257)");
  // Unclosed but shallow: the end of the text.
  CHECK(parse_error_of("[[[[").message().find("malformed JSON at line 1, column 5") == 0);
}

TEST_CASE("json_reader: a document holds at most 10 million values",
          "[geometry][io][errors][limits]") {
  static_assert(kMaxJsonValues == 10'000'000);
  std::string text = "[0";
  text.reserve(2 * kMaxJsonValues + 2);
  for (std::size_t i = 1; i + 1 < kMaxJsonValues; ++i) text += ",0";  // the array + 10^7 - 1 zeros
  CHECK(parse_json_text(text + "]", "big.json").size() == kMaxJsonValues - 1);
  const ModelError e = parse_error_of(text + ",0]");
  CHECK(e.message() == "more than 10000000 JSON values (the limit of a model file)");
  CHECK(e.pointer() == "/9999999");
}

TEST_CASE("json_reader: an object with many keys is read in linear time, in file order",
          "[geometry][io][limits]") {
  // ordered_json inserts a key after a linear search for it: 5 million keys (a 64 MB file)
  // took hours. The reader appends (duplicates are excluded by its own hash set).
  constexpr int n = 300000;
  std::string text = "{";
  for (int i = 0; i < n; ++i)
    text += (i ? ",\"k" : "\"k") + std::to_string(n - i) + "\": " + std::to_string(i);
  text += "}";
  const Json j = parse_json_text(text, "keys.json");  // (its time: bench/bench_model_setup.cpp)
  REQUIRE(j.size() == static_cast<std::size_t>(n));
  CHECK(j.begin().key() == "k300000");  // file order, not sorted
  CHECK(j.at("k1") == n - 1);
  CHECK(parse_error_of(text.substr(0, text.size() - 1) + ", \"k17\": 0}")
            .message()
            .find("duplicate key \"k17\"") == 0);
}

TEST_CASE("json_reader: messages serialize only what they show of a value",
          "[geometry][io][errors][limits]") {
  // A large array as the root: the type error shows about 60 characters of it.
  Json big = Json::array();
  for (int i = 0; i < 1000000; ++i) big.push_back(i);
  try {
    JsonCursor(big, "big.json").expect_object({"geometry"});
    FAIL("accepted an array as an object");
  } catch (const ModelError& e) {
    CHECK(std::string(e.what()).size() < 120);
    CHECK_THAT(e.what(), Catch::StartsWith("big.json: expected an object, got array [0,1,2,3,"));
  }
  // A huge string and a value nested deeper than any parsed document (built in memory).
  const Json s(std::string(50'000'000, 'x'));
  CHECK(short_dump(s) == std::string("\"").append(56, 'x').append("..."));
  Json deep = 0;
  for (int i = 0; i < 10000; ++i) deep = Json::array({std::move(deep)});
  CHECK(short_dump(deep) == std::string(57, '[') + "...");
  CHECK(describe_json(deep).size() <= 66);
  // Cutting never splits a UTF-8 character.
  std::string accents;
  for (int i = 0; i < 10; ++i) accents += "\xC3\xA9";  // e acute
  CHECK(short_dump(Json(accents), 9) == "\"\xC3\xA9\xC3\xA9...");
  // A huge duplicate key and a huge bad token are cut in the message.
  const std::string key(1'000'000, 'k');
  const ModelError dup = parse_error_of("{\"" + key + "\": 1, \"" + key + "\": 2}");
  CHECK(dup.message().size() < 200);
  CHECK(std::string(dup.what()).size() < 500);
  const ModelError bad = parse_error_of("[\"" + std::string(1'000'000, 'z'));  // unterminated
  CHECK(bad.message().size() < 300);
}

TEST_CASE("json_reader: a UTF-8 byte-order mark is skipped and positions stay right",
          "[geometry][io]") {
  const Json j = parse_json_text("\xEF\xBB\xBF{\"a\": [1, 2]}", "bom.json");
  CHECK(j.at("a").size() == 2);
  try {
    parse_json_text("\xEF\xBB\xBF{\"a\": [1,, 2]}", "bom.json");
    FAIL("accepted malformed JSON");
  } catch (const ModelError& e) {
    CHECK(e.pointer() == "/a/1");
    CHECK(e.message().find("line 1, column 10") != std::string::npos);  // the BOM is no column
  }
  const std::filesystem::path d = scratch_dir("bom");
  std::ofstream(d / "bom.json") << "\xEF\xBB\xBF{\"geometry\": {}}";
  CHECK(read_json_file((d / "bom.json").string()).contains("geometry"));
  std::filesystem::remove_all(d);
}

TEST_CASE("json_reader: model files must be regular files within 64 MiB",
          "[geometry][io][errors][limits]") {
  namespace fs = std::filesystem;
  static_assert(kMaxModelFileBytes == 64u << 20);
  const fs::path d = scratch_dir("files");
  auto error_of = [](const std::string& path) {
    try {
      read_json_file(path);
    } catch (const ModelError& e) {
      CHECK(e.file() == path);
      return std::string(e.what());
    }
    FAIL("read " << path);
    return std::string();
  };
  // A directory: said so, not "malformed JSON".
  CHECK(error_of(d.string()) == d.string() + ": is a directory, not a model file");
  // A FIFO would block forever once opened, /dev/zero never ends: refused before reading.
  const fs::path fifo = d / "fifo.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // (opened, it would hang: the test's timeout)
  CHECK(
      error_of(fifo.string()) ==
      fifo.string() +
          ": is not a regular file (a FIFO, socket or device); model files must be regular files");
  if (fs::exists("/dev/zero"))
    CHECK_THAT(error_of("/dev/zero"), Catch::StartsWith("/dev/zero: is not a regular file"));
  // Over the limit: refused from its size, before reading (a sparse file costs no disk).
  const fs::path huge = d / "huge.json";
  std::ofstream(huge) << "{}";
  fs::resize_file(huge, kMaxModelFileBytes + 1);
  CHECK(error_of(huge.string()) ==
        huge.string() +
            ": file of 67108865 bytes is larger than the limit of 64 MiB for a model file");
  std::ofstream(d / "small.json") << "[1, 2, 3]";
  CHECK(read_model_text((d / "small.json").string(), 9) == "[1, 2, 3]");
  CHECK_THROWS_WITH(
      read_model_text((d / "small.json").string(), 8),
      Catch::EndsWith("file of 9 bytes is larger than the limit of 8 bytes for a model file"));
  CHECK_THAT(error_of((d / "missing.json").string()),
             Catch::EndsWith("missing.json: cannot open file: No such file or directory"));
  fs::remove_all(d);
}

TEST_CASE("geometry_io: coordinates, lengths, weights and domains are bounded at read time",
          "[geometry][io][errors][limits]") {
  struct Case {
    std::string entity, pointer, fragment;
  };
  const std::string curve = R"({"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1], )";
  const std::vector<Case> cases = {
      {curve + R"("control_points": [[0, 0, 0], [1, 0, -1e101]]})",
       "/geometry/s/control_points/1/2", "must lie within +-1e+100"},
      {curve + R"("control_points": [[0, 0, 0], [1, 0, 0]], "weights": [1e300, 1e300]})",
       "/geometry/s/weights/0", "weight must lie in [1e-100, 1e+100], got 1e+300"},
      {curve + R"("control_points": [[0, 0, 0], [1, 0, 0]], "weights": [1e-5, 1e6]})",
       "/geometry/s/weights/1", "smallest is 1e-05 (index 0), got 1000000.0"},
      {R"({"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1e300, 1e300], "control_points": [[0, 0, 0], [1, 0, 0]]})",
       "/geometry/s/knots/2", "must lie within +-1e+100"},
      {R"({"type": "sphere", "center": [1e308, 0, 0], "radius": 1})", "/geometry/s/center/0",
       "must lie within +-1e+100"},
      {R"({"type": "cylinder", "center": [0, 0, 0], "axis": [0, 0, 1], "radius": 1e-300})",
       "/geometry/s/radius", "must lie in [1e-100, 1e+100]"},
      {R"({"type": "torus", "center": [0, 0, 0], "axis": [0, 0, 1], "major_radius": 1e308, "minor_radius": 1})",
       "/geometry/s/major_radius", "must lie in [1e-100, 1e+100]"},
      {R"({"type": "plane", "center": [0, 0, 0], "axis": [0, 0, 1e308]})", "/geometry/s/axis/2",
       "must lie within +-1e+100"},
      {R"({"type": "cylinder", "center": [0, 0, 0], "axis": [0, 0, 1], "radius": 1, "domain": {"v": [0, 1e308]}})",
       "/geometry/s/domain/v/1", "must lie within +-1e+100"},
      {R"({"type": "hyperboloid", "a": 1e200})", "/geometry/s/a", "must lie within +-1e+100"},
      {R"({"type": "revolution", "profile": [1, -1e300]})", "/geometry/s/profile/1",
       "must lie within +-1e+100"},
      {R"({"type": "construction", "shape": "sphere", "center": [0, 0, 0], "radius": 1e308})",
       "/geometry/s/radius", "must lie in [1e-100, 1e+100]"},
  };
  for (const Case& c : cases) {
    INFO(c.entity);
    const ModelError e = iga::test::geometry_error("{\"s\": " + c.entity + "}");
    INFO(e.what());
    CHECK(e.pointer() == c.pointer);
    CHECK(e.message().find(c.fragment) != std::string::npos);
  }
  // The bounds themselves are accepted, and so are unbounded (null) domain ends.
  const GeometryModel ok = parse_geometry(
      parse_json_text(R"({"c": {"type": "nurbs_curve", "degree": 1, "knots": [0, 0, 1, 1],
          "control_points": [[-1e100, 0, 0], [1e100, 0, 0]], "weights": [1, 1e10]},
          "b": {"type": "sphere", "center": [0, 0, 0], "radius": 1e-100},
          "p": {"type": "plane", "center": [0, 0, 0], "axis": [0, 0, 1],
                "domain": {"u": [-1e100, 1e100], "v": [null, 1]}}})",
                      "ok.json"),
      "ok.json", JsonPointer("/geometry"));
  CHECK(ok.entities.size() == 3);
}

TEST_CASE("make_storable: every homogeneous coordinate reads back from its written Cartesian value",
          "[geometry][io]") {
  // fl(w x) does not reach every double y: for about a fifth of random (y, w) no Cartesian x
  // gives y back. make_storable moves such y by an ulp to fl(w fl(y / w)), which does.
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> coord(-300, 300), weight(0.1, 3.0);
  std::vector<Vector4d> pw(20000);
  for (Vector4d& q : pw) q << coord(gen), coord(gen), coord(gen), weight(gen);
  std::vector<Vector4d> once = pw;
  make_storable(once);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < pw.size(); ++i) {
    CHECK(once[i].w() == pw[i].w());
    for (int k = 0; k < 3; ++k) {
      if (once[i][k] != pw[i][k]) ++moved;
      CHECK(std::abs(once[i][k] - pw[i][k]) <= std::abs(pw[i][k]) * 2.3e-16);  // one ulp
    }
  }
  CHECK(moved > 0);  // the case arises: the test exercises it
  std::vector<Vector4d> twice = once;
  make_storable(twice);
  CHECK(twice == once);  // idempotent
  // Through the writer and the reader: bit for bit.
  std::vector<double> U = {0, 0};
  for (std::size_t k = 1; k < pw.size() - 1; ++k) U.push_back(static_cast<double>(k));
  U.insert(U.end(), {static_cast<double>(pw.size() - 1), static_cast<double>(pw.size() - 1)});
  GeometryModel m;
  m.entities.emplace_back("c", NurbsCurve(KnotVector(1, U), pw));
  CHECK(text_round_trip(m) == m);
}

}  // namespace test_geometry_io
