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

#include <sys/wait.h>
#include "tests/support/files.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
  int status = -1;
  std::string out, err;
};

using iga::test::slurp;

// Runs `iga ARGS`, capturing standard output and error in temporary files.
Run run_iga(const std::string& args) {
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("iga_tool_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / ("out" + std::to_string(counter) + ".txt");
  const fs::path err = dir / ("err" + std::to_string(counter++) + ".txt");
  const std::string cmd = std::string("\"") + IGA_EXE + "\" " + args + " >\"" + out.string() +
                          "\" 2>\"" + err.string() + "\" </dev/null";
  const int raw = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
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

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
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
    REQUIRE(rows[i].size() == 13);
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
  CHECK(run_iga("eval \"" + model + "\"").status != 0);                    // no mode
  CHECK(run_iga("eval \"" + model + "\" --uv 0.5").status != 0);          // one value
  CHECK(run_iga("eval \"" + model + "\" --uv 99,0.5").status == 1);       // outside domain
  CHECK(run_iga("eval \"" + model + "\" --u 0.5").status == 1);           // surface needs --uv
  CHECK(run_iga("eval \"" + model + "\" --uv 0.5,0.5 --entity nope").status == 1);
  CHECK(run_iga("frobnicate").status != 0);
  CHECK(run_iga("").status != 0);
}

TEST_CASE("iga make writes models that load and evaluate exactly", "[apps][iga]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_make_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string torus = (dir / "torus.json").string();
  REQUIRE(run_iga("make torus --major-radius 3 --minor-radius 1 --out \"" + torus + "\"").status == 0);
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

TEST_CASE("iga project: closest points and rays onto the 4-patch cylinder", "[apps][iga][project]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_project_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string model = std::string(IGA_SOURCE_DIR) + "/data/cylinder_4patch.json";  // R = 1, z in [0, 4]
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
  const Run r = run_iga("project \"" + model + "\" --points \"" + (dir / "pts.csv").string() + "\"");
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
  const Run ray = run_iga("project \"" + model + "\" --points \"" + (dir / "pts.csv").string() +
                      "\" --ray \"" + (dir / "dirs.csv").string() + "\" --out \"" +
                      (dir / "ray.csv").string() + "\"");
  REQUIRE(ray.status == 0);
  const auto ray_rows = csv_rows(slurp(dir / "ray.csv"));
  REQUIRE(ray_rows.size() == 51);
  for (int k = 0; k < 50; ++k) {
    const double rad = 0.3 + 0.05 * k;
    CHECK(std::stod(ray_rows[static_cast<std::size_t>(k + 1)][8]) == Approx(1.0 - rad).margin(1e-10));
  }
  // bad input: a row with two values names the file and the line
  {
    std::ofstream bad(dir / "bad.csv");
    bad << "x,y,z\n1,2,3\n4,5\n";
  }
  const Run b = run_iga("project \"" + model + "\" --points \"" + (dir / "bad.csv").string() + "\"");
  CHECK(b.status == 1);
  CHECK_THAT(b.err, Catch::Contains("bad.csv:3"));
  fs::remove_all(dir);
}

TEST_CASE("iga info validates and summarizes the analysis sections", "[apps][iga][run]") {
  const Run r = run_iga("info \"" + std::string(IGA_SOURCE_DIR) + "/data/capstan.json\"");
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK(r.out.find("analysis: rod of 16 elements (degree 3, 21 control points)") != std::string::npos);
  CHECK(r.out.find("48 contact points") != std::string::npos);
}

TEST_CASE("iga run: the capstan model runs to full slip and writes its results",
          "[apps][iga][run]") {
  const fs::path out = fs::temp_directory_path() / ("iga_run_test_" + std::to_string(::getpid()));
  const Run r = run_data_model("capstan.json", out, "--set /contact/0/mu=0.2");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("full slip at t = ") != std::string::npos);
  for (const char* f : {"steps.csv", "summary.json", "model_used.json", "rod.pvd", "contact.pvd",
                        "last_rod.vtk", "last_contact.vtk"})
    CHECK(fs::exists(out / f));
  // The last row's reaction at the pulled end over T0 = 10 is the capstan ratio exp(0.2 pi).
  const auto rows = csv_rows(slurp(out / "steps.csv"));
  REQUIRE(rows.size() >= 12);
  const auto col = std::find(rows[0].begin(), rows[0].end(), "R20_norm");
  REQUIRE(col != rows[0].end());
  CHECK(rows[0].back() == "pull");  // one column per load curve, after the reactions
  const double T_ratio = std::stod(rows.back()[static_cast<std::size_t>(col - rows[0].begin())]) / 10.0;
  CHECK(std::abs(T_ratio / std::exp(0.2 * M_PI) - 1.0) < 0.005);
  CHECK(slurp(out / "model_used.json").find("\"mu\": 0.2") != std::string::npos);
  CHECK(slurp(out / "summary.json").find("\"full_slip\": true") != std::string::npos);
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
       {"steps.csv", "summary.json", "model_used.json", "shell.pvd", "last_shell.vtk"})
    CHECK(fs::exists(out / f));
  // The load is 1e-5 of the self weight (linear range): -1e5 u_z at the free edge's mid-point
  // is the Scordelis-Lo value, 0.3006 within 0.1 % on this mesh.
  const auto rows = csv_rows(slurp(out / "steps.csv"));
  REQUIRE(rows.size() == 2);
  const auto col = std::find(rows[0].begin(), rows[0].end(), "free_edge_mid_uz");
  REQUIRE(col != rows[0].end());
  CHECK(rows[0].back() == "load_factor");
  CHECK(std::stod(rows[1].back()) == Approx(1e-5).epsilon(1e-12));
  const double w = -1e5 * std::stod(rows[1][static_cast<std::size_t>(col - rows[0].begin())]);
  CHECK(std::abs(w / 0.3006 - 1.0) < 1e-3);
  const Run bad =
      run_data_model("scordelis_lo.json", out, "--quiet --set /materials/concrete/thickness=-1");
  CHECK(bad.status == 1);
  CHECK(bad.err.find("scordelis_lo.json: /materials/concrete/thickness: must be > 0, got -1") !=
        std::string::npos);
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
      {"/bodies/rope/material=\\\"steel\\\"", "/bodies/rope/material: names no entry of \\\"materials\\\""},
      {"/loads/0/curve=\\\"hold2\\\"", "/loads/0/curve: names no entry of \\\"load_curves\\\", got \\\"hold2\\\""},
      {"/loads/0/at=0.5", "/loads/0/direction: \\\"outward_tangent\\\" needs the point \\\"start\\\" or \\\"end\\\""},
      {"/boundary_conditions/0/components=[3]", "/boundary_conditions/0/components/0: component must be 0, 1 or 2, got 3"},
      {"/load_curves/pull/points=[[1,0],[1,1]]", "/load_curves/pull/points/1/0: times must increase, got 1"},
      {"/solver/max_step=-1", "/solver/max_step: must be > 0, got -1"},
      {"/geometry/rope/arc_elements=0", "/geometry/rope/arc_elements: must be in 1..100000, got 0"},
      {"/output/vtk=\\\"some\\\"", "/output/vtk: expected one of \\\"none\\\", \\\"last\\\", \\\"all\\\", got \\\"some\\\""},
  };
  for (const Case& c : cases) {
    const Run r = run_iga("run \"" + model + "\" --quiet --out /tmp/iga_bad_run --set \"" + c.set + "\"");
    INFO(c.set << "\n" << r.out << r.err);
    CHECK(r.status == 1);
    std::string msg = c.message;
    for (std::size_t k; (k = msg.find("\\\"")) != std::string::npos;) msg.replace(k, 2, "\"");
    CHECK(r.err.find("capstan.json: " + msg) != std::string::npos);
  }
}
