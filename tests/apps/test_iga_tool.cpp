// Runs the `iga` executable as a user would: on every model in data/, on bad input, and with
// bad command lines; checks exit codes, messages and the numbers it prints.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "tests/support/files.hpp"
#include "tests/support/vtk_xml_read.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_iga_tool {

namespace fs = std::filesystem;

namespace {

struct Run {
  int status = -1;
  std::string out, err;
};

using iga::test::csv_rows;
using iga::test::slurp;

// Runs `EXE ARGS`, capturing standard output and error in temporary files.
Run run_program(const std::string& exe, const std::string& args) {
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("iga_tool_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / ("out" + std::to_string(counter) + ".txt");
  const fs::path err = dir / ("err" + std::to_string(counter++) + ".txt");
  const std::string cmd = "\"" + exe + "\" " + args + " >\"" + out.string() + "\" 2>\"" +
                          err.string() + "\" </dev/null";
  const int raw = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// Runs `iga ARGS`.
Run run_iga(const std::string& args) {
  return run_program(IGA_EXE, args);
}

// The geometry models of data/ (app models such as capstan.json have a format of their own).
std::vector<fs::path> data_models() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(IGA_SOURCE_DIR) / "data"))
    if (e.path().extension() == ".json" &&
        slurp(e.path()).find("\"format\": \"iga-contact-model\"") != std::string::npos)
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// `iga run data/MODEL --out OUT EXTRA` into a fresh folder OUT.
Run run_data_model(const std::string& model, const fs::path& out, const std::string& extra = "") {
  fs::remove_all(out);
  return run_iga("run \"" + std::string(IGA_SOURCE_DIR) + "/data/" + model + "\" --out \"" +
                 out.string() + "\" " + extra);
}

}  // namespace

TEST_CASE("iga --help and subcommand help describe the commands", "[apps][iga]") {
  const Run r = run_iga("--help");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("eval") && Catch::Contains("make") && Catch::Contains("info"));
  const Run e = run_iga("eval --help");
  CHECK(e.status == 0);
  CHECK_THAT(e.out, Catch::Contains("--uv") && Catch::Contains("--grid") && Catch::Contains("--u"));
}

TEST_CASE("iga eval --center runs on every model in data/", "[apps][iga]") {
  const auto models = data_models();
  REQUIRE(models.size() >= 5);
  for (const fs::path& m : models) {
    INFO(m);
    const Run info = run_iga("info \"" + m.string() + "\"");
    CHECK(info.status == 0);
    const Run r = run_iga("eval \"" + m.string() + "\" --center");
    CHECK(r.status == 0);
    CHECK(r.err.empty());
    CHECK_THAT(r.out, Catch::Contains("point"));
    CHECK_THAT(r.out, !Catch::Contains("nan") && !Catch::Contains("inf"));
  }
}

TEST_CASE("iga eval --grid on the NURBS cylinder: points on the radius, normals outward",
          "[apps][iga]") {
  const std::string model = std::string(IGA_SOURCE_DIR) + "/data/cylinder_patch.json";
  const Run r = run_iga("eval \"" + model + "\" --grid 11");
  REQUIRE(r.status == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 1 + 11 * 11);
  CHECK(rows[0].front() == "entity");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    REQUIRE(rows[i].size() == 14);
    CHECK(rows[i][13] == "0");  // no singular point on a cylinder
    const double x = std::stod(rows[i][3]), y = std::stod(rows[i][4]);
    const double nx = std::stod(rows[i][6]), ny = std::stod(rows[i][7]);
    CHECK(std::hypot(x, y) == Approx(1.0).epsilon(1e-13));  // data/cylinder_patch.json: R = 1
    CHECK(nx * x + ny * y == Approx(1.0).epsilon(1e-12));   // outward unit normal
    // principal curvatures of a cylinder with the outward normal: 0 and -1/R
    CHECK(std::stod(rows[i][9]) == Approx(0.0).margin(1e-10));
    CHECK(std::stod(rows[i][10]) == Approx(-1.0).epsilon(1e-10));
  }
}

TEST_CASE("iga eval --u on the helix: curvature and torsion of the helix", "[apps][iga]") {
  // data/helix_cubic.json: R = 1, pitch 1 -> c = 1/2pi, kappa = R/(R^2+c^2), tau = c/(R^2+c^2)
  const std::string model = std::string(IGA_SOURCE_DIR) + "/data/helix_cubic.json";
  const Run r = run_iga("eval \"" + model + "\" --grid 5");
  REQUIRE(r.status == 0);
  const double c = 1.0 / (2 * M_PI);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 6);
  // interior samples (the interpolant's end spans are less accurate)
  for (std::size_t i = 2; i <= 4; ++i) {
    CHECK(std::stod(rows[i][8]) == Approx(1.0 / (1 + c * c)).epsilon(2e-3));
    CHECK(std::stod(rows[i][9]) == Approx(c / (1 + c * c)).epsilon(2e-2));
  }
}

TEST_CASE("iga eval: bad models exit 1 with file, JSON path and value on stderr",
          "[apps][iga][errors]") {
  const std::string bad = std::string(IGA_SOURCE_DIR) + "/tests/data/bad/";
  const Run r = run_iga("eval \"" + bad + "decreasing_knots.json\" --center");
  CHECK(r.status == 1);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("decreasing_knots.json") && Catch::Contains("/geometry/"));
  const Run m = run_iga("eval \"" + bad + "malformed_json.json\" --center");
  CHECK(m.status == 1);
  CHECK_THAT(m.err, Catch::Contains("line") && Catch::Contains("column"));
  const Run missing = run_iga("eval /nonexistent/model.json --center");
  CHECK(missing.status == 1);
  CHECK_THAT(missing.err, Catch::Contains("/nonexistent/model.json"));
}

TEST_CASE("iga eval: bad command lines are rejected", "[apps][iga][errors]") {
  const std::string model = std::string(IGA_SOURCE_DIR) + "/data/torus_patch.json";
  CHECK(run_iga("eval \"" + model + "\"").status != 0);              // no mode
  CHECK(run_iga("eval \"" + model + "\" --uv 0.5").status != 0);     // one value
  CHECK(run_iga("eval \"" + model + "\" --uv 99,0.5").status == 1);  // outside domain
  CHECK(run_iga("eval \"" + model + "\" --u 0.5").status == 1);      // surface needs --uv
  CHECK(run_iga("eval \"" + model + "\" --uv 0.5,0.5 --entity nope").status == 1);
  CHECK(run_iga("frobnicate").status != 0);
  CHECK(run_iga("").status != 0);
}

TEST_CASE("iga make writes models that load and evaluate exactly", "[apps][iga]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_make_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string torus = (dir / "torus.json").string();
  REQUIRE(run_iga("make torus --major-radius 3 --minor-radius 1 --out \"" + torus + "\"").status ==
          0);
  const Run r = run_iga("eval \"" + torus + "\" --grid 9");
  REQUIRE(r.status == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 82);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double x = std::stod(rows[i][3]), y = std::stod(rows[i][4]), z = std::stod(rows[i][5]);
    // (B.16): distance to the tube's centre circle equals the minor radius
    CHECK(std::hypot(std::hypot(x, y) - 3.0, z) == Approx(1.0).epsilon(1e-13));
  }
  const std::string cyl = (dir / "cyl4.json").string();
  REQUIRE(run_iga("make cylinder --patches 4 --out \"" + cyl + "\"").status == 0);
  const Run info = run_iga("info \"" + cyl + "\"");
  CHECK_THAT(info.out, Catch::Contains("patch_group of 4"));
  CHECK(run_iga("make klein-bottle --out x.json").status != 0);
  fs::remove_all(dir);
}

TEST_CASE("iga info and iga import on a STEP file: faces listed, written, read back without it",
          "[apps][iga][cad]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_import_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string step = std::string(IGA_SOURCE_DIR) + "/data/cad/sheave_v30.step";
  const Run info = run_iga("info \"" + step + "\"");
  REQUIRE(info.status == 0);
  CHECK_THAT(info.out, Catch::Contains("7 faces"));
  CHECK_THAT(info.out, Catch::Contains("face 2: cone -> cone (exact)"));
  CHECK_THAT(info.out, Catch::Contains("face 0: plane -> trimmed plane (exact)"));
  CHECK_THAT(info.out, Catch::Contains("2 boundary loops"));
  const std::string json = (dir / "groove.json").string();
  const Run imp =
      run_iga("import \"" + step + "\" --faces 2,3 --name groove --unit m --out \"" + json + "\"");
  REQUIRE(imp.status == 0);
  CHECK_THAT(imp.out, Catch::Contains("2 faces as the patch group \"groove\""));
  // The model written holds the two flanks as cones (lengths now in m) and the group.
  const Run back = run_iga("info \"" + json + "\"");
  REQUIRE(back.status == 0);
  CHECK_THAT(back.out, Catch::Contains("groove.face2: cone"));
  CHECK_THAT(back.out, Catch::Contains("v in [0.001, 0.0016]"));
  CHECK_THAT(back.out, Catch::Contains("groove: patch_group of 2: groove.face2 groove.face3"));
  // All faces, the trimmed side discs included.
  const Run all = run_iga("import \"" + step + "\" --out \"" + json + "\"");
  CHECK(all.status == 0);
  CHECK_THAT(all.out, Catch::Contains("face 5: plane -> trimmed plane (exact)"));
  CHECK_THAT(run_iga("info \"" + json + "\"").out,
             Catch::Contains("sheave_v30.face0: trimmed_surface"));
  CHECK(run_iga("import nothing.step --out x.json").status == 1);
  fs::remove_all(dir);
}

TEST_CASE("iga project: closest points and rays onto the 4-patch cylinder",
          "[apps][iga][project]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_project_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string model =
      std::string(IGA_SOURCE_DIR) + "/data/cylinder_4patch.json";  // R = 1, z in [0, 4]
  {
    std::ofstream pts(dir / "pts.csv");
    pts.precision(17);
    pts << "x,y,z\n";
    for (int k = 0; k < 50; ++k) {
      const double a = 0.37 * k, r = 0.3 + 0.05 * k;
      pts << r * std::cos(a) << "," << r * std::sin(a) << "," << 0.5 + 0.06 * k << "\n";
    }
    std::ofstream dirs(dir / "dirs.csv");
    dirs.precision(17);
    for (int k = 0; k < 50; ++k) {
      const double a = 0.37 * k;
      dirs << std::cos(a) << "," << std::sin(a) << ",0\n";  // radial: the ray meets the cylinder
    }
  }
  const Run r =
      run_iga("project \"" + model + "\" --points \"" + (dir / "pts.csv").string() + "\"");
  REQUIRE(r.status == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 51);
  CHECK(rows[0].size() == 12);
  for (int k = 0; k < 50; ++k) {
    const auto& row = rows[static_cast<std::size_t>(k + 1)];
    const double rad = 0.3 + 0.05 * k;
    CHECK(std::stod(row[8]) == Approx(rad - 1.0).margin(1e-10));  // (B.10): p = |d| - R
    CHECK(row[9] == "interior");
  }
  const Run ray =
      run_iga("project \"" + model + "\" --points \"" + (dir / "pts.csv").string() + "\" --ray \"" +
              (dir / "dirs.csv").string() + "\" --out \"" + (dir / "ray.csv").string() + "\"");
  REQUIRE(ray.status == 0);
  const auto ray_rows = csv_rows(slurp(dir / "ray.csv"));
  REQUIRE(ray_rows.size() == 51);
  for (int k = 0; k < 50; ++k) {
    const double rad = 0.3 + 0.05 * k;
    CHECK(std::stod(ray_rows[static_cast<std::size_t>(k + 1)][8]) ==
          Approx(1.0 - rad).margin(1e-10));
  }
  // bad input: a row with two values names the file and the line
  {
    std::ofstream bad(dir / "bad.csv");
    bad << "x,y,z\n1,2,3\n4,5\n";
  }
  const Run b =
      run_iga("project \"" + model + "\" --points \"" + (dir / "bad.csv").string() + "\"");
  CHECK(b.status == 1);
  CHECK_THAT(b.err, Catch::Contains("bad.csv:3"));
  fs::remove_all(dir);
}

TEST_CASE("iga info validates and summarizes the analysis sections", "[apps][iga][run]") {
  const Run r = run_iga("info \"" + std::string(IGA_SOURCE_DIR) + "/data/capstan.json\"");
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  // 10 arc + 2 x 3 span elements, the cubic fit elevated to degree 5 (C2: 3 new control points
  // an element), 6 contact points an element.
  CHECK(r.out.find("analysis: rod of 16 elements (degree 5, 53 control points)") !=
        std::string::npos);
  CHECK(r.out.find("96 contact points") != std::string::npos);
}

TEST_CASE("iga run: the capstan model runs to full slip and writes its results",
          "[apps][iga][run]") {
  const fs::path out = fs::temp_directory_path() / ("iga_run_test_" + std::to_string(::getpid()));
  const Run r = run_data_model("capstan.json", out, "--set /contact/0/mu=0.2");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("full slip at t = ") != std::string::npos);
  for (const char* f : {"steps.csv", "summary.json", "model_used.json", "rod.pvd", "contact.pvd",
                        "last_rod.vtu", "last_contact.vtu"})
    CHECK(fs::exists(out / f));
  // The last row's reaction at the pulled end over T0 = 10 is the capstan ratio exp(0.2 pi).
  const auto rows = csv_rows(slurp(out / "steps.csv"));
  REQUIRE(rows.size() >= 12);
  const auto col = std::find(rows[0].begin(), rows[0].end(), "R52_norm");  // the last point
  REQUIRE(col != rows[0].end());
  CHECK(rows[0].back() == "pull");  // one column per load curve, after the reactions
  const double T_ratio =
      std::stod(rows.back()[static_cast<std::size_t>(col - rows[0].begin())]) / 10.0;
  CHECK(std::abs(T_ratio / std::exp(0.2 * M_PI) - 1.0) < 0.005);
  CHECK(slurp(out / "model_used.json").find("\"mu\": 0.2") != std::string::npos);
  CHECK(slurp(out / "summary.json").find("\"full_slip\": true") != std::string::npos);
  // Contact fields on the rod (per element, issue 12 item 6): the line pressure is finite, >= 0,
  // and peaks near the tight end at about T0 e^{mu phi} / rho (rho = 1.02; the last element is
  // partly in the lift-off zone, so a little below); the tool's side is written too.
  CHECK(fs::exists(out / "last_tool_contact.vtu"));
  const iga::test::VtkXmlFile vtk = iga::test::read_vtk_xml(out / "last_rod.vtu");
  const std::vector<double> pressure = vtk.field("contact_pressure");
  double largest = 0.0, smallest = 1e300;
  for (const double p : pressure) {
    REQUIRE(std::isfinite(p));
    largest = std::max(largest, p);
    smallest = std::min(smallest, p);
  }
  CHECK(pressure.size() == 257);
  CHECK(smallest >= 0.0);
  const double tight = 10.0 * std::exp(0.2 * M_PI) / 1.02;
  CHECK(largest <= 1.01 * tight);
  CHECK(largest >= 0.8 * tight);
  // The rod keeps its other contact fields, one value per sample, the state 0, 1 or 2 and some
  // of the arc sliding at full slip.
  for (const char* f : {"contact_traction_T", "contact_traction_B", "contact_state"})
    CHECK(vtk.field(f).size() == 257);
  const std::vector<double> state = vtk.field("contact_state");
  CHECK(std::all_of(state.begin(), state.end(),
                    [](double s) { return s == 0.0 || s == 1.0 || s == 2.0; }));
  CHECK(std::count(state.begin(), state.end(), 2.0) > 0);
}

TEST_CASE("iga run: the Scordelis-Lo roof (a shell) writes its monitor and the shell files",
          "[apps][iga][run][shell]") {
  const fs::path out = fs::temp_directory_path() / ("iga_run_shell_" + std::to_string(::getpid()));
  const Run r = run_data_model("scordelis_lo.json", out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("shell of 256 elements (degree 3 x 3, 361 control points)") !=
        std::string::npos);
  for (const char* f :
       {"steps.csv", "summary.json", "model_used.json", "shell.pvd", "last_shell.vts"})
    CHECK(fs::exists(out / f));
  // The linear analysis at the full self weight: -u_z at the free edge's mid-point is the
  // Scordelis-Lo value, 0.3006 within 0.1 % on this mesh, in one solve.
  const auto rows = csv_rows(slurp(out / "steps.csv"));
  REQUIRE(rows.size() == 2);
  const auto col = std::find(rows[0].begin(), rows[0].end(), "free_edge_mid_uz");
  REQUIRE(col != rows[0].end());
  CHECK(rows[0].back() == "load_factor");
  CHECK(std::stod(rows[1].back()) == Approx(1.0).epsilon(1e-12));
  CHECK(r.out.find("linear path: 1 step(s)") != std::string::npos);
  const double w = -std::stod(rows[1][static_cast<std::size_t>(col - rows[0].begin())]);
  CHECK(std::abs(w / 0.3006 - 1.0) < 1e-3);
  const Run bad =
      run_data_model("scordelis_lo.json", out, "--quiet --set /materials/concrete/thickness=-1");
  CHECK(bad.status == 1);
  CHECK(bad.err.find("scordelis_lo.json: /materials/concrete/thickness: must be > 0, got -1") !=
        std::string::npos);
  fs::remove_all(out);
}

TEST_CASE("iga run: the neo-Hookean tube names its law in the log and plots the closed form",
          "[apps][iga][run][shell]") {
  const fs::path out = fs::temp_directory_path() / ("iga_run_tube_" + std::to_string(::getpid()));
  const Run r = run_data_model("inflated_tube.json", out);
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("shell of 16 elements (degree 3 x 3, 55 control points, neo-Hookean, 5 points "
                   "through the thickness)") != std::string::npos);
  CHECK(fs::exists(out / "pressure_stretch_reference.json"));
  fs::remove_all(out);
}

TEST_CASE("iga run: bad analysis input exits 1 naming the file, JSON path and value",
          "[apps][iga][run][errors]") {
  const std::string model = std::string(IGA_SOURCE_DIR) + "/data/capstan.json";
  struct Case {
    std::string set, message;
  };
  const std::vector<Case> cases = {
      {"/materials/rope/EA=0", "/materials/rope/EA: must be > 0, got 0"},
      {"/contact/0/rigid=\\\"rope\\\"", "/contact/0/rigid: not a rigid surface"},
      {"/bodies/rope/material=\\\"steel\\\"",
       "/bodies/rope/material: names no entry of \\\"materials\\\""},
      {"/loads/0/curve=\\\"hold2\\\"",
       "/loads/0/curve: names no entry of \\\"load_curves\\\", got \\\"hold2\\\""},
      {"/loads/0/at=0.5",
       "/loads/0/direction: \\\"outward_tangent\\\" needs the point \\\"start\\\" or \\\"end\\\""},
      {"/boundary_conditions/0/components=[3]",
       "/boundary_conditions/0/components/0: component must be 0, 1 or 2, got 3"},
      {"/load_curves/pull/points=[[1,0],[1,1]]",
       "/load_curves/pull/points/1/0: times must increase, got 1"},
      {"/solver/max_step=-1", "/solver/max_step: must be > 0, got -1"},
      {"/geometry/rope/arc_elements=0", "/geometry/rope/arc_elements: must be in 1..100000, got 0"},
      {"/output/vtk=\\\"some\\\"",
       "/output/vtk: expected one of \\\"none\\\", \\\"last\\\", \\\"all\\\", got \\\"some\\\""},
  };
  for (const Case& c : cases) {
    const Run r =
        run_iga("run \"" + model + "\" --quiet --out /tmp/iga_bad_run --set \"" + c.set + "\"");
    INFO(c.set << "\n" << r.out << r.err);
    CHECK(r.status == 1);
    std::string msg = c.message;
    for (std::size_t k; (k = msg.find("\\\"")) != std::string::npos;) msg.replace(k, 2, 1, '"');
    CHECK(r.err.find("capstan.json: " + msg) != std::string::npos);
  }
}

namespace {

/// A fresh temporary folder for one test case.
fs::path temp_dir(const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / (tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

/// No cell of a CSV text is a non-finite number.
bool all_finite_cells(const std::string& csv) {
  for (const auto& row : csv_rows(csv))
    for (const std::string& c : row)
      if (c.find("inf") != std::string::npos || c.find("nan") != std::string::npos) return false;
  return true;
}

const std::string kAnalytic = std::string(IGA_SOURCE_DIR) + "/data/analytic_surfaces.json";

}  // namespace

TEST_CASE(
    "iga project: only a line of the expected names is a header, bad rows are errors with file and "
    "line",
    "[apps][iga][project][errors]") {
  const fs::path dir = temp_dir("iga_project_input");
  const std::string model = "project \"" + kAnalytic + "\" --entity ball --points ";
  auto project = [&](const std::string& name, const std::string& text) {
    write_file(dir / name, text);
    return run_iga(model + "\"" + (dir / name).string() + "\"");
  };
  // A header by its names (any case, blanks), or none: the same two points.
  for (const std::string head : {"x,y,z\n", " X , Y , Z \n", ""}) {
    const Run r = project("ok.csv", head + "0,0,3\n1,0,2\n");
    INFO(head << r.err);
    CHECK(r.status == 0);
    CHECK(csv_rows(r.out).size() == 3);
  }
  // A first line that is neither the names nor three numbers was once taken for a header and
  // the point lost; now each is an error at line 1 saying what is wrong.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"1,2\n0,0,3\n", "found 2 fields"},
      {"1e309,0,0\n0,0,3\n", "out of the range"},
      {"1;2;3\n0,0,3\n", "found 1 field"},
      {"0x1p3,0,0\n0,0,3\n", "not a decimal number"},
      {"inf,0,0\n0,0,3\n", "not a decimal number"},
      {"a,b,c\n0,0,3\n", "not a decimal number"},
      {"1,,3\n", "empty field"}};
  for (const auto& [text, what] : bad) {
    const Run r = project("bad.csv", text);
    INFO(text << " -> " << r.err);
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("bad.csv:1:") && Catch::Contains(what));
  }
  // Later lines too, with their line number.
  const Run late = project("late.csv", "x,y,z\n0,0,3\n1e309,0,0\n");
  CHECK(late.status == 1);
  CHECK_THAT(late.err, Catch::Contains("late.csv:3:"));
  // A directory, a missing file and a file without rows are errors, not 0 points.
  Run r = run_iga(model + "\"" + dir.string() + "\"");
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("not a regular file"));
  r = run_iga(model + "\"" + (dir / "none.csv").string() + "\"");
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("no such file"));
  r = project("empty.csv", "x,y,z\n");
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("no rows"));
  fs::remove_all(dir);
}

TEST_CASE("iga project: far points and bad rays are per-point statuses, never inf in the output",
          "[apps][iga][project]") {
  const fs::path dir = temp_dir("iga_project_far");
  write_file(dir / "far.csv",
             "x,y,z\n1e154,1e154,1e154\n-1e154,3e153,2\n1e300,-1e300,1e300\n0,0,3\n");
  for (const std::string e :
       {"ball", "drum", "ring", "funnel", "saddle", "bowl", "floor", "roof"}) {
    const Run r = run_iga("project \"" + kAnalytic + "\" --entity " + e + " --points \"" +
                          (dir / "far.csv").string() + "\"");
    INFO(e << ": " << r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(all_finite_cells(r.out));
    const auto rows = csv_rows(r.out);
    REQUIRE(rows.size() == 5);
    for (std::size_t k = 1; k < rows.size(); ++k) {
      REQUIRE(rows[k].size() >= 10);
      const std::string& status = rows[k][9];
      const bool foot = status == "interior" || status == "edge" || status == "vertex";
      // A foot point's distance is a finite number; out_of_range has empty cells.
      if (foot) CHECK(std::isfinite(std::stod(rows[k][8])));
      if (status == "out_of_range") CHECK(rows[k][8].empty());
    }
  }
  // On the sphere the far distance is right: |x - c| - R (c = (0, 0, 2), R = 0.5).
  const Run ball = run_iga("project \"" + kAnalytic + "\" --entity ball --points \"" +
                           (dir / "far.csv").string() + "\"");
  const auto rows = csv_rows(ball.out);
  CHECK(std::stod(rows[1][8]) == Approx(std::sqrt(3.0) * 1e154).epsilon(1e-12));
  CHECK(rows[1][9] == "interior");

  // Rays: a zero direction is bad_direction for its point, a huge one is rescaled, the batch
  // goes on (it aborted on analytic surfaces; NURBS patches said miss).
  write_file(dir / "pts.csv", "x,y,z\n0,0,3\n0,0,3\n0,0,3\n5,5,5\n");
  write_file(dir / "dirs.csv", "dx,dy,dz\n0,0,0\n0,0,-1e300\n0,0,-1\n1,0,0\n");
  for (const std::string e : {"ball", "roof", "obstacle"}) {
    const Run r =
        run_iga("project \"" + kAnalytic + "\" --entity " + e + " --points \"" +
                (dir / "pts.csv").string() + "\" --ray \"" + (dir / "dirs.csv").string() + "\"");
    INFO(e << ": " << r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(all_finite_cells(r.out));
    const auto rr = csv_rows(r.out);
    REQUIRE(rr.size() == 5);
    CHECK(rr[1][9] == "bad_direction");
    CHECK(rr[2][9] == rr[3][9]);
    CHECK(rr[2][8] == rr[3][8]);
    CHECK((rr[4][9] == "miss" || rr[4][9] == "tangent"));  // the floor plane is parallel
    for (int c = 0; c < 9; ++c) CHECK(rr[4][static_cast<std::size_t>(c)].empty());
  }
  const Run ray =
      run_iga("project \"" + kAnalytic + "\" --entity ball --points \"" +
              (dir / "pts.csv").string() + "\" --ray \"" + (dir / "dirs.csv").string() + "\"");
  CHECK(std::stod(csv_rows(ray.out)[2][8]) == Approx(0.5).epsilon(1e-12));  // z = 3 to z = 2.5
  fs::remove_all(dir);
}

TEST_CASE("iga eval: singular points (poles, apex, axis) are written with a flag, the grid goes on",
          "[apps][iga]") {
  const fs::path dir = temp_dir("iga_eval_singular");
  const Run r =
      run_iga("eval \"" + kAnalytic + "\" --grid 5 --out \"" + (dir / "g.csv").string() + "\"");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string text = slurp(dir / "g.csv");
  CHECK(all_finite_cells(text));
  const auto rows = csv_rows(text);
  REQUIRE(rows.size() > 1);
  CHECK(rows[0].back() == "singular");
  int ball_poles = 0, bowl_axis = 0;
  for (const auto& row : rows) {
    if (row.size() < 14 || row[13] != "1") continue;
    if (row[0] == "ball") {
      // The sphere's poles (v = +-pi/2): the limit normal is the axis, +-e_z, the curvatures
      // those of the sphere, 1/R = 2.
      ++ball_poles;
      const double v = std::stod(row[2]);
      CHECK(std::stod(row[8]) == Approx(v > 0 ? 1.0 : -1.0).epsilon(1e-6));
      CHECK(std::abs(std::stod(row[9])) == Approx(2.0).epsilon(1e-4));
      CHECK(std::stod(row[12]) == Approx(4.0).epsilon(1e-4));
    }
    if (row[0] == "bowl") {
      // z = r^2/2 at r = 0: normal along the axis, both curvatures 1.
      ++bowl_axis;
      CHECK(std::abs(std::stod(row[8])) == Approx(1.0).epsilon(1e-6));
      CHECK(std::abs(std::stod(row[9])) == Approx(1.0).epsilon(1e-4));
    }
  }
  CHECK(ball_poles == 10);
  CHECK(bowl_axis == 5);
  // A cone's apex has no limit normal (the normals circle the axis): empty cells, flag 1.
  write_file(dir / "cone.json", R"({"format": "iga-contact-model", "version": 1, "name": "c",
    "geometry": {"tip": {"type": "cone", "center": [0, 0, 0], "axis": [0, 0, 1], "alpha": 0.5,
                         "domain": {"v": [0, 1]}}}})");
  const Run cone = run_iga("eval \"" + (dir / "cone.json").string() + "\" --grid 3");
  INFO(cone.err);
  REQUIRE(cone.status == 0);
  int apex = 0;
  for (const auto& row : csv_rows(cone.out)) {
    if (row.size() < 14 || row[13] != "1") continue;
    ++apex;
    CHECK(std::stod(row[2]) == 0.0);  // v = 0
    for (int c = 6; c <= 12; ++c) CHECK(row[static_cast<std::size_t>(c)].empty());
  }
  CHECK(apex == 3);
  // One point: --uv at the pole prints the limit normal instead of failing.
  const Run uv = run_iga("eval \"" + kAnalytic + "\" --entity ball --uv 0,1.5707963267948966");
  INFO(uv.err);
  CHECK(uv.status == 0);
  CHECK_THAT(uv.out, Catch::Contains("singular point") && Catch::Contains("(limit)"));
  fs::remove_all(dir);
}

TEST_CASE("iga info: every line ends with a newline, patch groups included", "[apps][iga]") {
  for (const std::string f : {"analytic_surfaces.json", "cylinder_4patch.json", "capstan.json"}) {
    const Run r = run_iga("info \"" + std::string(IGA_SOURCE_DIR) + "/data/" + f + "\"");
    INFO(f << ": " << r.out << r.err);
    CHECK(r.status == 0);
    REQUIRE(!r.out.empty());
    CHECK(r.out.back() == '\n');
    const bool newline_after_group =
        r.out.find("patch_group") == std::string::npos ||
        r.out.find('\n', r.out.find("patch_group")) != std::string::npos;
    CHECK(newline_after_group);
  }
}

// ---- issue 11: command-line contract, --set, limits of the reader ---------------------------

namespace {

/// A fresh scratch folder for one test case.
fs::path scratch(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("iga_tool_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string quoted(const fs::path& p) {
  std::string q = "\"";  // not "\"" + s: GCC 12 warns falsely (-Wrestrict) on that form
  q += p.string();
  q += '"';
  return q;
}

const std::string kCapstan = std::string(IGA_SOURCE_DIR) + "/data/capstan.json";

}  // namespace

TEST_CASE("iga and the apps exit 2 on a bad command line, 1 on bad input, 0 on --help",
          "[apps][iga][errors]") {
  // CLI11's own codes were 105 (unknown option), 106 (missing required), 109 (extra), ...
  const std::vector<std::string> bad_lines = {"",
                                              "frobnicate",
                                              "--bogus",
                                              "eval",
                                              "info",
                                              "run",
                                              "run \"" + kCapstan + "\" --bogus",
                                              "run \"" + kCapstan + "\" extra_argument",
                                              "eval \"" + kCapstan + "\" --grid abc",
                                              "project \"" + kCapstan + "\""};
  for (const std::string& args : bad_lines) {
    const Run r = run_iga(args);
    INFO("iga " << args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(!r.err.empty());
  }
  for (const char* args : {"--help", "run --help", "--version"}) {
    INFO(args);
    CHECK(run_iga(args).status == 0);
  }
  // A missing model file is bad input, reported by the reader: 1, not a command-line error.
  const Run missing = run_iga("run /nonexistent/model.json --quiet");
  CHECK(missing.status == 1);
  CHECK_THAT(missing.err, Catch::Contains("/nonexistent/model.json: cannot open file"));
  // The apps.
  for (const auto& [exe, args] :
       std::vector<std::pair<std::string, std::string>>{{CAPSTAN_EXE, "--bogus"},
                                                        {CAPSTAN_EXE, "--mu abc"},
                                                        {HELIX_EXE, "--pitch"},
                                                        {HELIX_EXE, "a.json b.json"},
                                                        {SADDLE_EXE, "--strategy sideways"},
                                                        {SADDLE_EXE, "--frobnicate"}}) {
    const Run r = run_program(exe, args);
    INFO(exe << " " << args << "\n" << r.err);
    CHECK(r.status == 2);
  }
  for (const char* exe : {CAPSTAN_EXE, HELIX_EXE, SADDLE_EXE})
    CHECK(run_program(exe, "--help").status == 0);
  const Run bad_model = run_program(CAPSTAN_EXE, "/nonexistent/capstan.json");
  CHECK(bad_model.status == 1);
  CHECK_THAT(bad_model.err, Catch::Contains("/nonexistent/capstan.json: cannot open file"));
}

TEST_CASE("iga run --set adds a key whose parent object exists and names a bad pointer itself",
          "[apps][iga][run][errors]") {
  const fs::path out = scratch("set");
  // /solver has no max_steps in capstan.json: it is added, and the run stops after 2 steps.
  // Probe off for this child: max_steps counts attempts, and "steps": 2 converged ones.
  const Run added = run_program("env", "-u IGA_ROUNDOFF_PROBE \"" + std::string(IGA_EXE) +
                                           "\" run \"" + kCapstan + "\" --quiet --out " +
                                           quoted(out) + " --set /solver/max_steps=2");
  INFO(added.out << added.err);
  CHECK(added.status == 2);  // the solver stopped early, as asked
  CHECK(added.err.empty());
  CHECK(slurp(out / "model_used.json").find("\"max_steps\": 2") != std::string::npos);
  CHECK(slurp(out / "summary.json").find("\"steps\": 2") != std::string::npos);
  struct Case {
    std::string set, message;
  };
  const std::vector<Case> cases = {
      // a new key the schema does not know: the loader's own message, with the allowed keys
      {"/solver/max_stepz=3",
       "capstan.json: /solver/max_stepz: unknown key \"max_stepz\" (allowed here: t_end"},
      {"/solver/a~2b=1",
       "iga: error: --set: \"/solver/a~2b\" is not a JSON pointer: '~' must be followed by 0 or 1"},
      {"/solver/a~=1", "--set: \"/solver/a~\" is not a JSON pointer"},
      {"solver/max_steps=3",
       "iga: error: --set: expected /json/pointer=value (e.g. /solver/max_steps=50), got "
       "\"solver/max_steps=3\""},
      {"/solver/max_steps", "--set: expected /json/pointer=value"},
      {"/nosuch/key=1",
       "capstan.json: /nosuch/key: --set: no such entry, and its parent /nosuch does not exist "
       "either"},
      {"/contact/7=1",
       "capstan.json: /contact/7: --set: no such entry; a new key can only be added to an object, "
       "and /contact is array"},
      {"/contact/99999999999999999999999=1",
       "capstan.json: /contact/99999999999999999999999: --set: no such entry; a new key"},
      {"/solver/max_steps=[", "--set /solver/max_steps: /0: malformed JSON at line 1, column 2"},
  };
  for (const Case& c : cases) {
    const Run r =
        run_iga("run \"" + kCapstan + "\" --quiet --out " + quoted(out) + " --set '" + c.set + "'");
    INFO(c.set << "\n" << r.err);
    CHECK(r.status == 1);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK(r.err.find("json.exception") == std::string::npos);  // never the library's message
  }
  // The apps share the override: a new key is taken, a bad pointer gets the same message.
  const Run app =
      run_program(CAPSTAN_EXE, "--mu 0.3 --phi-deg 90 --out " + quoted(out / "capstan") +
                                   " --set /solver/max_steps=2");
  INFO(app.out << app.err);
  CHECK(app.status == 2);  // the case did not reach full slip in 2 steps
  CHECK(app.err.find("error") == std::string::npos);
  CHECK(slurp(out / "capstan" / "model_used.json").find("\"max_steps\": 2") != std::string::npos);
  const Run app_bad =
      run_program(CAPSTAN_EXE, "--out " + quoted(out / "capstan") + " --set '/solver/a~2b=1'");
  CHECK(app_bad.status == 1);
  CHECK_THAT(app_bad.err,
             Catch::Contains("capstan: error: --set: \"/solver/a~2b\" is not a JSON pointer"));
  const Run app_unknown = run_program(
      HELIX_EXE, "--quick --out " + quoted(out / "helix") + " --set /geometry/rope/pich=1");
  CHECK(app_unknown.status == 1);
  CHECK_THAT(app_unknown.err,
             Catch::Contains("helix.json: /geometry/rope/pich: unknown key \"pich\""));
  fs::remove_all(out);
}

TEST_CASE(
    "iga: deep nesting, non-regular files and a byte-order mark end in a message, not a crash",
    "[apps][iga][errors][limits]") {
  const fs::path d = scratch("limits");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(d / name, std::ios::binary) << text;
    return quoted(d / name);
  };
  auto nested = [](std::size_t levels, bool closed) {
    return std::string(levels, '[') + "0" + (closed ? std::string(levels, ']') : std::string());
  };
  const std::string head =
      "{\"format\": \"iga-contact-model\", \"version\": 1, \"geometry\": {}, \"app\": ";
  struct Case {
    std::string command, message;
  };
  const std::vector<Case> cases = {
      // crashed (exit 139) writing model_used.json, in the error message, and while loading
      {"run " + write("app40k.json", head + nested(40000, true) + "}") + " --quiet --out " +
           quoted(d / "o"),
       "app40k.json: /app/0/0/0/0/0/0/0/0"},
      {"info " + write("root60k.json", nested(60000, true)), "root60k.json: /0/0/0/0/"},
      {"eval " + write("app300k.json", head + nested(300000, true) + "}") + " --center",
       "app300k.json: /app/0/0"},
      {"info " + write("unclosed.json", nested(std::size_t{1} << 20, false)),
       "unclosed.json: /0/0/0/0"},
      {"info " + quoted(d), ": is a directory, not a model file"},
      {"eval /dev/zero --center", "/dev/zero: is not a regular file"},
  };
  for (const Case& c : cases) {
    const Run r = run_iga(c.command);
    INFO(c.command.substr(0, 200) << "\n" << r.err);
    CHECK(r.status == 1);
    CHECK(r.err.find(c.message) != std::string::npos);
    if (c.message.find("/0/0") != std::string::npos)
      CHECK(r.err.find("nested deeper than 256 levels") != std::string::npos);
    CHECK(r.err.size() < 1000);
  }
  // A FIFO blocked forever when opened: it is refused before (timeout: a regression fails, not
  // hangs).
  const fs::path fifo = d / "fifo.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const Run f = run_program("timeout",
                            "20 \"" + std::string(IGA_EXE) + "\" run " + quoted(fifo) + " --quiet");
  CHECK(f.status == 1);
  CHECK_THAT(f.err, Catch::Contains("fifo.json: is not a regular file"));
  // A UTF-8 byte-order mark: accepted by info, eval and run alike.
  const std::string bom = write("bom.json", "\xEF\xBB\xBF" + slurp(kCapstan));
  CHECK(run_iga("info " + bom).status == 0);
  CHECK(run_iga("eval " + bom + " --center").status == 0);
  const Run run =
      run_iga("run " + bom + " --quiet --out " + quoted(d / "bom") + " --set /solver/max_steps=1");
  INFO(run.err);
  CHECK(run.status == 2);  // read and run; stopped after the one step asked for
  CHECK(run.err.empty());
  fs::remove_all(d);
}

TEST_CASE("iga run --restart continues a run that stopped early, as the uninterrupted run",
          "[apps][iga][run][restart]") {
  const fs::path whole = scratch("restart_whole"), parts = scratch("restart_parts");
  // Steps land on t = 0.1, 0.2, ..., 1.9 in every run, whatever cutbacks happen between: the
  // common times at which the runs are compared should their steps differ (below).
  std::string grid = " --set \"/solver/hit_times=[0.1";
  for (int k = 2; k < 20; ++k) grid += "," + std::to_string(k / 10.0);
  grid += "]\"";
  const Run full = run_iga("run \"" + kCapstan + "\" --quiet --out " + quoted(whole) + grid);
  REQUIRE(full.status == 0);
  CHECK_FALSE(fs::exists(whole / "restart.bin"));  // reached its end: none unless asked
  // Stopped after 5 attempted steps: exit 2, a restart file of the last converged step.
  const Run first = run_iga("run \"" + kCapstan + "\" --out " + quoted(parts) +
                            " --set /solver/max_steps=5" + grid);
  INFO(first.out << first.err);
  CHECK(first.status == 2);
  CHECK_THAT(first.out, Catch::Contains("restart file: " + (parts / "restart.bin").string()));
  CHECK_THAT(slurp(parts / "summary.json"), Catch::Contains("\"restart_file\""));
  const Run rest = run_iga("run \"" + kCapstan + "\" --out " + quoted(parts) + " --restart " +
                           quoted(parts / "restart.bin") + grid);
  INFO(rest.out << rest.err);
  CHECK(rest.status == 0);
  CHECK_THAT(rest.out, Catch::Contains("restart from " + (parts / "restart.bin").string()));
  // steps.csv: the rows before the restart and after it, those of the whole run (the same
  // computation on the same machine; test_restart.cpp compares with a tolerance). Unless
  // round-off cut a step back in one run and not in the other (the contact assembly's threads
  // sum in any order; another processor; the round-off probe IGA_ROUNDOFF_PROBE): then the runs
  // are compared at the times both reached.
  const std::string steps_parts = slurp(parts / "steps.csv"),
                    steps_whole = slurp(whole / "steps.csv");
  if (steps_parts != steps_whole) {
    const iga::test::CommonTimes c =
        iga::test::compare_at_common_times(csv_rows(steps_whole), csv_rows(steps_parts));
    INFO("another step path: " << c.common << " common times up to t = " << c.last_t << ", worst "
                               << c.worst << " of a column's scale at " << c.where);
    CHECK(c.common >= 10);
    CHECK(c.last_t >= 1.0);
    // Another path through stick and slip, and multipliers converged to another point within
    // the penetration tolerance (1e-4): 3e-4 of a column's scale, as test_moving_tools.cpp
    // measured for the same model. (With the hit times the restarted run took the whole run's
    // steps for the probe's seeds 1, 2, 3: steps.csv identical.)
    CHECK(c.worst <= 3e-4);
  }
  // A restart file of another model: bad input, exit 1, naming the file.
  const Run wrong =
      run_iga("run \"" + std::string(IGA_SOURCE_DIR) + "/data/two_ropes.json\" --quiet --out " +
              quoted(scratch("wrong")) + " --restart " + quoted(parts / "restart.bin"));
  CHECK(wrong.status == 1);
  CHECK_THAT(wrong.err, Catch::Contains("iga: error: " + (parts / "restart.bin").string()) &&
                            Catch::Contains("unknowns"));
}

// ---- issue 34: CAD files never kill the tool -------------------------------------------------

namespace {

std::string cad_source(const std::string& relative) {
  return slurp(fs::path(IGA_SOURCE_DIR) / relative);
}

/// The text without its first one-line CARTESIAN_POINT entity.
std::string without_a_point(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  bool removed = false;
  while (std::getline(in, line)) {
    if (!removed && line.rfind('#', 0) == 0 && line.find("CARTESIAN_POINT") != std::string::npos &&
        line.find(");") != std::string::npos) {
      removed = true;
      continue;
    }
    out += line + "\n";
  }
  REQUIRE(removed);
  return out;
}

/// data/cad/cylinder.step with its length unit declared as `factor` mm, named `name`.
std::string cylinder_with_unit(const std::string& name, const std::string& factor) {
  std::string text = cad_source("data/cad/cylinder.step");
  const std::string si = "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );";
  const std::size_t at = text.find(si);
  REQUIRE(at != std::string::npos);
  text.replace(at, si.size(),
               "( CONVERSION_BASED_UNIT('" + name +
                   "',#9001) LENGTH_UNIT() NAMED_UNIT(#9002) );\n#9001 = "
                   "LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(" +
                   factor + "),#9003);\n#9002 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n" +
                   "#9003 = " + si);
  return text;
}

/// `iga run` on data/plate_on_die.json with its die read from `cad` (and more --set options).
Run run_die_from(const fs::path& cad, const std::string& more = "") {
  const std::string model = std::string(IGA_SOURCE_DIR) + "/data/plate_on_die.json";
  return run_iga("run \"" + model + "\" --quiet --out \"" + (cad.parent_path() / "run").string() +
                 "\" --set \"/geometry/die/file=\\\"" + cad.string() + "\\\"\"" + more);
}

}  // namespace

TEST_CASE("iga info, import and run on broken CAD files: exit 1 naming the file, never a signal",
          "[apps][iga][cad][errors]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_cad_broken_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string cylinder = cad_source("data/cad/cylinder.step");
  const std::string screw = cad_source("tests/data/cad/occt/screw.step");
  std::string noise = "\xFF\xD8\xFF\xE0";
  for (int i = 0; i < 3000; ++i) noise += static_cast<char>((i * 7919 + 13) % 256);
  std::string wrong_type = cylinder;
  const std::string placement = "#26 = AXIS2_PLACEMENT_3D('',#27,";
  REQUIRE(wrong_type.find(placement) != std::string::npos);
  wrong_type.replace(wrong_type.find(placement), placement.size(),
                     "#26 = AXIS2_PLACEMENT_3D('',#28,");
  const std::vector<std::pair<std::string, std::string>> files = {
      {"truncated.step", screw.substr(0, screw.size() / 2)},
      {"truncated_closed.step",
       screw.substr(0, screw.size() / 2) + "\nENDSEC;\nEND-ISO-10303-21;\n"},
      {"cylinder_truncated_closed.step",
       cylinder.substr(0, cylinder.size() / 2) + "\nENDSEC;\nEND-ISO-10303-21;\n"},
      {"missing_point.step", without_a_point(cylinder)},
      // a placement's location given a direction: OpenCASCADE 7.6 crashes in the transfer
      {"wrong_type.step", wrong_type},
      {"photo.step", noise},
      {"empty.step", ""},
  };
  for (const auto& [name, text] : files) {
    const fs::path f = dir / name;
    write_file(f, text);
    const Run info = run_iga("info \"" + f.string() + "\"");
    INFO(name << "\ninfo: " << info.out << info.err);
    CHECK(info.status == 1);  // (-1: ended by a signal)
    CHECK_THAT(info.err, Catch::Contains(f.string()));
    const Run imp =
        run_iga("import \"" + f.string() + "\" --out \"" + (dir / "x.json").string() + "\"");
    INFO("import: " << imp.out << imp.err);
    CHECK(imp.status == 1);
    CHECK_THAT(imp.err, Catch::Contains(f.string()));
    const Run run = run_die_from(f);
    INFO("run: " << run.out << run.err);
    CHECK(run.status == 1);
    CHECK_THAT(run.err, Catch::Contains("/geometry/die/file") && Catch::Contains(f.string()));
    if (name == "wrong_type.step")  // (or the status a sanitizer's report ends the reader with)
      for (const Run* r : {&info, &imp, &run})
        CHECK_THAT(r->err,
                   Catch::Contains("OpenCASCADE crashed (signal 11, SIGSEGV) while reading " +
                                   f.string()) ||
                       Catch::Contains("reader process ended with status"));
  }
  fs::create_directories(dir / "folder.step");
  CHECK_THAT(run_iga("info \"" + (dir / "folder.step").string() + "\"").err,
             Catch::Contains("folder.step: is a directory"));
  // The good file runs as before up to its load (a run of 0 steps is not offered: info).
  CHECK(run_iga("info \"" + std::string(IGA_SOURCE_DIR) + "/data/plate_on_die.json\"").status == 0);
  fs::remove_all(dir);
}

TEST_CASE("iga info on a CAD file: every face listed, the file's unit and the factor shown",
          "[apps][iga][cad]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_cad_units_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Run screw =
      run_iga("info \"" + std::string(IGA_SOURCE_DIR) + "/tests/data/cad/occt/screw.step\"");
  REQUIRE(screw.status == 0);
  CHECK_THAT(screw.out, Catch::Contains("step file, 10 faces"));
  for (int k = 0; k < 10; ++k)
    CHECK_THAT(screw.out, Catch::Contains("  face " + std::to_string(k) + ": "));
  CHECK_THAT(screw.out, Catch::Contains("length unit of the file: millimetre (1 mm)"));

  // The same numbers, once in mm and once declared in inches: 25.4 times larger in mm.
  write_file(dir / "inch.step", cylinder_with_unit("INCH", "25.4"));
  const Run mm = run_iga("info \"" + std::string(IGA_SOURCE_DIR) + "/data/cad/cylinder.step\"");
  const Run in = run_iga("info \"" + (dir / "inch.step").string() + "\"");
  REQUIRE(mm.status == 0);
  REQUIRE(in.status == 0);
  CHECK_THAT(mm.out, Catch::Contains("converted to mm by the factor 1;"));
  CHECK_THAT(in.out, Catch::Contains("length unit of the file: INCH (25.4 mm), converted to mm "
                                     "by the factor 25.4;"));
  CHECK_THAT(mm.out, Catch::Contains("box 2 x 2 x 3 from (-1, -1, -1.5)"));
  CHECK_THAT(in.out, Catch::Contains("box 50.8 x 50.8 x 76.2 from (-25.4, -25.4, -38.1)"));
  const Run in_in = run_iga("info \"" + (dir / "inch.step").string() + "\" --unit in");
  CHECK_THAT(in_in.out, Catch::Contains("converted to in by the factor 1;"));
  // Units that are no lengths: refused, with the file and the value.
  for (const char* factor : {"1.E300", "0.", "-25.4"}) {
    const fs::path bad = dir / (std::string("unit") + factor + ".step");
    write_file(bad, cylinder_with_unit("FURLONG", factor));
    const Run r = run_iga("info \"" + bad.string() + "\"");
    INFO(r.out << r.err);
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains(bad.string() + ": the file's length unit \"FURLONG\" is"));
    CHECK(run_iga("import \"" + bad.string() + "\" --out \"" + (dir / "x.json").string() + "\"")
              .status == 1);
    CHECK(run_die_from(bad).status == 1);
  }
  fs::remove_all(dir);
}

TEST_CASE("iga import and a model's cad entity: skipped entities warn, --strict refuses",
          "[apps][iga][cad]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_cad_skip_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::string die = cad_source("data/cad/die_fillet.step");
  // The second ADVANCED_FACE renamed to a type STEP does not know: 9 faces of 10 are left.
  std::size_t at = die.find("= ADVANCED_FACE(");
  REQUIRE(at != std::string::npos);
  at = die.find("= ADVANCED_FACE(", at + 1);
  REQUIRE(at != std::string::npos);
  die.replace(at, 16, "= ADVANCED_FACEX(");
  const fs::path damaged = dir / "damaged.step";
  write_file(damaged, die);
  const std::string out = (dir / "die.json").string();
  const Run lenient = run_iga("import \"" + damaged.string() + "\" --out \"" + out + "\"");
  INFO(lenient.out << lenient.err);
  CHECK(lenient.status == 0);
  CHECK_THAT(lenient.out, Catch::Contains("wrote " + out + ": 9 faces"));
  CHECK_THAT(lenient.err,
             Catch::Contains("warning: " + damaged.string()) && Catch::Contains("skipped"));
  const Run strict = run_iga("import \"" + damaged.string() + "\" --strict --out \"" + out + "\"");
  CHECK(strict.status == 1);
  CHECK_THAT(strict.err, Catch::Contains(damaged.string()) && Catch::Contains("strict"));
  // The undamaged file: no warning, strict or not.
  const std::string good = std::string(IGA_SOURCE_DIR) + "/data/cad/die_fillet.step";
  const Run whole = run_iga("import \"" + good + "\" --strict --out \"" + out + "\"");
  CHECK(whole.status == 0);
  CHECK(whole.err.empty());
  CHECK_THAT(whole.out, Catch::Contains("10 faces"));
  // The info listing warns too.
  CHECK_THAT(run_iga("info \"" + damaged.string() + "\"").err, Catch::Contains("skipped"));
  // A model's cad entity: strict makes it an error located at the entity.
  const Run run = run_die_from(damaged, " --set /geometry/die/strict=true");
  INFO(run.err);
  CHECK(run.status == 1);
  CHECK_THAT(run.err, Catch::Contains("/geometry/die/file") && Catch::Contains("strict"));
  fs::remove_all(dir);
}

}  // namespace test_iga_tool
