// Tests of the model file (iga/model/model.hpp): load -> save -> load is exact and the saved text
// is stable; top-level keys, format/version and the types of the analysis sections are checked with
// errors that name the file, the JSON path and the value.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "iga/model/model.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_model_io {

using namespace iga;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/tests/data/";

std::string scratch(const std::string& name) {
  const fs::path dir = fs::path(IGA_BINARY_DIR) / "test_output" / "model_io";
  fs::create_directories(dir);
  return (dir / name).string();
}

ModelError model_error(const std::string& path) {
  try {
    load_model(path);
  } catch (const ModelError& e) {
    return e;
  }
  FAIL("no ModelError for " << path);
  return ModelError("", "", "");
}

}  // namespace

TEST_CASE("model: load -> save -> load is exact and the saved text is stable", "[iga][io][model]") {
  const Model m1 = load_model(kData + "models/all_entities.json");
  CHECK(m1.name == "all entities");
  CHECK(m1.geometry.entities.size() == 10);

  const std::string first = scratch("all_entities_1.json");
  save_model(m1, first);
  const Model m2 = load_model(first);
  CHECK(m2 == m1);

  const std::string second = scratch("all_entities_2.json");
  save_model(m2, second);
  CHECK(iga::test::slurp(second) == iga::test::slurp(first));
  CHECK(load_model(second) == m1);
}

TEST_CASE("model: saved files carry format and version and keep the entity order",
          "[iga][io][model]") {
  const Model m = load_model(kData + "models/all_entities.json");
  const Json j = model_to_json(m);
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  CHECK(keys == std::vector<std::string>{"format", "version", "name", "description", "geometry"});
  CHECK(j["format"] == kModelFormat);
  CHECK(j["version"] == kModelFormatVersion);
  CHECK(j["geometry"].begin().key() == "rail");
  CHECK(j["geometry"].back()["type"] == "patch_group");
}

TEST_CASE("model: only \"geometry\" is required and name and description default to empty",
          "[iga][io][model]") {
  const Model m = parse_model(Json::parse(R"({"geometry": {}})"), "min.json");
  CHECK(m.name.empty());
  CHECK(m.description.empty());
  CHECK(m.geometry.entities.empty());
  CHECK(parse_model(model_to_json(m), "again.json") == m);
}

TEST_CASE("model: a plain nlohmann::json document is accepted", "[iga][io][model]") {
  nlohmann::json j;
  j["name"] = "plain";
  j["geometry"]["floor"] = {{"type", "plane"}, {"center", {0, 0, 0}}, {"axis", {0, 0, 1}}};
  const Model m = parse_model(j, "plain.json");
  CHECK(m.name == "plain");
  CHECK(m.geometry.surface("floor") != nullptr);
}

TEST_CASE("model: analysis sections are kept in file order and saved back unchanged",
          "[iga][io][model]") {
  Json j = parse_json_text(R"({"format": "iga-contact-model", "geometry": {},
    "solver": {"t_end": 2}, "bodies": {"b": {"type": "rod"}}, "app": {"x": [1, 2]},
    "loads": [{"type": "point_force"}]})",
                           "sections.json");
  const Model m = parse_model(j, "sections.json");
  CHECK(m.has_analysis());
  REQUIRE(m.sections.size() == 4);
  CHECK(m.sections.items().begin().key() == "solver");  // file order
  const Json back = model_to_json(m);
  for (const char* k : {"solver", "bodies", "app", "loads"}) CHECK(back[k] == j[k]);
  CHECK(parse_model(back, "back.json") == m);
  // A list section given as an object, and an object section given as a list, are errors.
  Json bad = j;
  bad["loads"] = Json::object();
  CHECK_THROWS_WITH(parse_model(bad, "b.json"), Catch::Contains("/loads: expected an array"));
}

TEST_CASE("model: bad model files name the file and the JSON path and the value",
          "[iga][io][model][errors]") {
  struct Case {
    const char* file;
    const char* pointer;
    std::vector<std::string> fragments;
  };
  const std::vector<Case> cases = {
      {"section_wrong_type.json", "/materials", {"expected an object", "got array"}},
      {"unknown_top_level_key.json", "/solvr", {"unknown key \"solvr\"", "geometry"}},
      {"wrong_version.json", "/version", {"unsupported format version", "got 2"}},
      {"wrong_format.json", "/format", {"iga-contact-model", "got \"stl\""}},
      {"missing_geometry.json", "", {"missing required key \"geometry\""}},
      {"negative_radius.json", "/geometry/drum/radius", {"must be > 0, got -3"}},
      {"overflow_number.json", "/geometry/rail/control_points/1/2", {"1e999"}},
      {"malformed_json.json", "/geometry", {"line 5, column 5"}},
  };
  for (const Case& c : cases) {
    const std::string path = kData + "bad/" + c.file;
    INFO(c.file);
    const ModelError e = model_error(path);
    const std::string what = e.what();
    INFO(what);
    CHECK(e.file() == path);
    CHECK(e.pointer() == c.pointer);
    const std::string prefix =
        std::string(c.pointer).empty() ? path + ": " : path + ": " + c.pointer + ": ";
    CHECK(what.rfind(prefix, 0) == 0);
    for (const std::string& f : c.fragments) CHECK(what.find(f) != std::string::npos);
  }
}

TEST_CASE("model: every file in tests/data/bad is rejected with a message naming it",
          "[iga][io][model][errors]") {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kData + "bad")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const std::string path = entry.path().string();
    INFO(path);
    const ModelError e = model_error(path);
    CHECK(std::string(e.what()).rfind(path + ": ", 0) == 0);
  }
  CHECK(count >= 12);
}

TEST_CASE("model: a missing file and an unwritable path are reported", "[iga][io][model]") {
  const std::string missing = kData + "models/does_not_exist.json";
  const ModelError e = model_error(missing);
  CHECK(e.file() == missing);
  CHECK(e.message().find("cannot open file") != std::string::npos);
  CHECK_THROWS_AS(save_model(Model{}, kData + "no_such_dir/x.json"), std::runtime_error);
}

TEST_CASE("model: save -> load is bit for bit for every model in data/", "[iga][io][model]") {
  // data/pinched_cylinder.json lost an ulp in 263 of 1225 control points: its rational net is
  // computed in homogeneous form, and not every w P is fl(w x) for some double x. The
  // constructed net is now stored so that it is (make_storable), and the writer finds that x.
  // Within one machine this is a property of the I/O code, so the comparison is exact.
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(IGA_SOURCE_DIR) / "data")) {
    if (entry.path().extension() != ".json") continue;
    const std::string path = entry.path().string();
    INFO(path);
    const Model m1 = load_model(path);
    const std::string first = scratch("data_1_" + entry.path().filename().string());
    save_model(m1, first);
    const Model m2 = load_model(first);
    CHECK(m2 == m1);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < m1.geometry.entities.size(); ++i) {
      const auto* s1 = std::get_if<NurbsSurface>(&m1.geometry.entities[i].second);
      const auto* s2 = std::get_if<NurbsSurface>(&m2.geometry.entities[i].second);
      if (s1 == nullptr || s2 == nullptr) continue;
      for (std::size_t k = 0; k < s1->homogeneous().size(); ++k)
        if (s1->homogeneous()[k] != s2->homogeneous()[k]) ++differing;
    }
    CHECK(differing == 0);
    const std::string second = scratch("data_2_" + entry.path().filename().string());
    save_model(m2, second);
    CHECK(iga::test::slurp(second) == iga::test::slurp(first));
    ++count;
  }
  CHECK(count >= 15);
}

}  // namespace test_model_io
