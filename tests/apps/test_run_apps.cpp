// `iga run` and `capstan` as a user runs them, under failure (issue 11, items 4, 5, 8, 11): a
// failure during a run is a reported status (exit 2) with summary.json; the capstan's CSV names
// each case, keeps failed cases with their status and never holds nan or inf; T0 = 0 is refused
// at read time naming the value's path.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include "geometry/json_reader.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_run_apps {

namespace fs = std::filesystem;

namespace {

using iga::Json;
using iga::read_json_file;
using iga::test::csv_rows;
using iga::test::slurp;

struct Result {
  int status = -1;
  std::string out;  ///< standard output and error
};

Result run(const std::string& exe, const std::string& args) {
  static int counter = 0;
  const fs::path log = fs::temp_directory_path() / ("run_apps_" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(counter++) + ".txt");
  const std::string cmd = "\"" + exe + "\" " + args + " >\"" + log.string() + "\" 2>&1 </dev/null";
  const int raw = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(log);
  fs::remove(log);
  return r;
}

fs::path fresh(const std::string& name) {
  return iga::test::fresh_out_dir("run_apps", name);
}

bool has_non_finite_text(const std::string& s) {
  for (const char* w : {"nan", "inf", "NaN", "Inf"})
    if (s.find(w) != std::string::npos) return true;
  return false;
}

const std::string kModel = std::string(IGA_SOURCE_DIR) + "/data/";

}  // namespace

TEST_CASE("iga run: a failure while writing the results exits 2 with summary.json and the rows",
          "[apps][iga][run]") {
  const fs::path out = fresh("iga_vtk_fails");
  fs::create_directories(out / "last_rod.vtu");  // a folder where the last VTK file goes
  const Result r = run(IGA_EXE, "run \"" + kModel + "rollup.json\" --quiet --out \"" +
                                    out.string() + "\" --set /output/vtk='\"last\"'");
  INFO(r.out);
  CHECK(r.status == 2);
  CHECK_THAT(r.out, Catch::Contains("last_rod.vtu"));
  const std::string summary = slurp(out / "summary.json");
  CHECK_THAT(summary, Catch::Contains("\"status\": \"failed\""));
  CHECK(csv_rows(slurp(out / "steps.csv")).size() >= 11);  // header and every converged step
}

namespace {

/// `iga run` of data/<model> into out with one --set: it must succeed, write steps.csv and
/// draw `png`.
void run_plotted(const std::string& model, const fs::path& out, const std::string& set,
                 const char* png) {
  const Result r = run(IGA_EXE, "run \"" + kModel + model + "\" --quiet --out \"" + out.string() +
                                    "\" --set " + set);
  INFO(r.out);
  CHECK(r.status == 0);
  CHECK(fs::exists(out / "steps.csv"));
  CHECK(fs::exists(out / png));
  CHECK_THAT(r.out, Catch::Contains("iga run: plot "));
}

}  // namespace

TEST_CASE("iga run: the model's plots of steps.csv columns are drawn (ring between plates)",
          "[apps][iga][run][moving_tools]") {
  const fs::path out = fresh("iga_ring_plots");
  run_plotted("ring_between_plates.json", out, "/output/vtk='\"last\"'", "force_travel.png");
  for (const char* f : {"diameters.png", "last_rod.vtu", "last_rigid.vts", "rigid.pvd"})
    CHECK(fs::exists(out / f));
  // The ring's plot has no published points: no reference file.
  CHECK_FALSE(fs::exists(out / "force_travel_reference.json"));
  // The moving plate is written where it is: its last position 0.4 below the first.
  CHECK(slurp(out / "last_rigid.vts") != slurp(out / "rigid.vts"));
}

TEST_CASE("iga run: a plot's published points go beside it and onto it (hinged roof)",
          "[apps][iga][run]") {
  const fs::path out = fresh("iga_roof_reference");
  run_plotted("hinged_roof.json", out, "/geometry/roof/refine/subdivide=4", "load_deflection.png");
  const Json ref = read_json_file((out / "load_deflection_reference.json").string());
  REQUIRE(ref.size() == 2);
  CHECK(ref[0].at("label") == "Sze et al. 2004: first maximum, h = 12.7");
  CHECK(ref[0].at("points").at(0).at(0).get<double>() == 11.293);
  CHECK(ref[0].at("points").at(0).at(1).get<double>() == 2226.3);
  // summary.json lists the path's two load limit points.
  const Json summary = read_json_file((out / "summary.json").string());
  REQUIRE(summary.at("limit_points").size() == 2);
  CHECK(summary["limit_points"][0].at("kind") == "maximum");
}

#ifdef CAPSTAN_EXE
TEST_CASE("capstan: --mu/--phi-deg lists name each case in the CSV and keep failed cases",
          "[apps][capstan]") {
  const fs::path out = fresh("capstan_lists");
  // Coarse rope (4 arc elements) so that the test stays fast.
  const std::string coarse =
      " --set /geometry/rope/arc_elements=4 --set /geometry/rope/span_elements=2";
  Result r =
      run(CAPSTAN_EXE, "--mu 0,0.3 --phi-deg 90" + coarse + " --out \"" + out.string() + "\"");
  INFO(r.out);
  CHECK(r.status == 0);
  auto rows = csv_rows(slurp(out / "capstan.csv"));
  REQUIRE(rows.size() == 3);
  CHECK(rows[0] == std::vector<std::string>{"case", "sweep", "mu", "phi", "T_ratio", "exact",
                                            "rel_error", "pull", "plateau_mean", "plateau_spread",
                                            "status"});
  CHECK(rows[1][0] == "c1");
  CHECK(rows[2][0] == "c2");
  CHECK(rows[1][1] == "c");
  CHECK(rows[2].back() == "full_slip");

  // Every case fails (one Newton iteration per step allowed): each keeps its row with the solver's
  // status and no ratio.
  r = run(CAPSTAN_EXE, "--mu 0.3 --phi-deg 90,180 --set /solver/max_iterations=1" + coarse +
                           " --out \"" + out.string() + "\"");
  INFO(r.out);
  CHECK(r.status == 2);
  const std::string csv = slurp(out / "capstan.csv");
  rows = csv_rows(csv);
  REQUIRE(rows.size() == 3);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    CHECK(rows[k].back() == "min_step_reached");
    CHECK(rows[k][4].empty());  // T_ratio
  }
  CHECK_FALSE(has_non_finite_text(csv));
}

TEST_CASE(
    "capstan: capstan_pressure.csv holds the line pressure along the arc, near "
    "T0 e^{mu theta} / rho, and its plot",
    "[apps][capstan][output]") {
  // Issue 12 item 6: per element the mean pressure at full slip against the closed form; the
  // end elements (centres within 0.2 rad of an end: lift-off zones of the bending rope) are
  // left out. The elements next to them (centres within 0.6 rad of an end) lie in the rope's
  // bending boundary layer, whose state at the detection of full slip depends on the steps the
  // run took, which round-off changes (issue 34): measured at mu 0.3, phi 180 on the default
  // mesh over 10 seeds of IGA_ROUNDOFF_PROBE, within 1.6 % there (2.5 % required) and within
  // 0.6 % on the rest of the arc (1 % required).
  const fs::path out = fresh("capstan_pressure");
  const Result r = run(CAPSTAN_EXE, "--mu 0.3 --phi-deg 180 --out \"" + out.string() + "\"");
  INFO(r.out);
  REQUIRE(r.status == 0);
  const std::string csv = slurp(out / "capstan_pressure.csv");
  CHECK_FALSE(has_non_finite_text(csv));
  const auto rows = csv_rows(csv);
  REQUIRE(rows.size() >= 9);
  CHECK(rows[0] == std::vector<std::string>{"case", "mu", "phi", "theta", "pressure", "exact"});
  int interior = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double theta = std::stod(rows[k][3]), p = std::stod(rows[k][4]),
                 exact = std::stod(rows[k][5]);
    CHECK(exact == Approx(10.0 * std::exp(0.3 * theta) / 1.02).epsilon(1e-9));
    if (theta < 0.2 || theta > M_PI - 0.2) continue;  // end elements: half an element + lift-off
    const bool boundary_layer = theta < 0.6 || theta > M_PI - 0.6;
    CHECK(p == Approx(exact).epsilon(boundary_layer ? 2.5e-2 : 1e-2));
    ++interior;
  }
  CHECK(interior >= 7);
  CHECK(fs::exists(out / "capstan_pressure.png"));
}

TEST_CASE("capstan: a case that reaches t_end without full slip is pulled on (mu 0.85, phi 270)",
          "[apps][capstan]") {
  const fs::path out = fresh("capstan_pull_on");
  const Result r = run(CAPSTAN_EXE, "--mu 0.85 --phi-deg 270 --out \"" + out.string() + "\"");
  INFO(r.out);
  CHECK(r.status == 0);
  // At the model's pull 0.05 the arc has not slid for the three steps of the sliding plateau
  // (solver/full_slip_steps) by t_end: pulled on to 0.1, where it has.
  CHECK_THAT(r.out, Catch::Contains("c1: no full slip at the pull 0.05: pulling on to 0.1"));
  CHECK_THAT(r.out, !Catch::Contains("pulling on to 0.2"));
  const auto rows = csv_rows(slurp(out / "capstan.csv"));
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].back() == "full_slip");
  CHECK(std::stod(rows[1][7]) == Approx(0.1));  // pull
  // T/T0 against e^(mu phi) = 54.90 (exact enforcement: -2.6e-5 measured)
  CHECK(std::abs(std::stod(rows[1][4]) / std::stod(rows[1][5]) - 1.0) < 5e-4);
}

TEST_CASE("capstan: T0 = 0 is refused at read time naming the value's path",
          "[apps][capstan][errors]") {
  const fs::path out = fresh("capstan_T0");
  const Result r =
      run(CAPSTAN_EXE, "--quick --set /loads/0/magnitude=0 --out \"" + out.string() + "\"");
  INFO(r.out);
  CHECK(r.status != 0);
  CHECK_THAT(r.out,
             Catch::Contains("capstan.json: /loads/0/magnitude: must be > 0 (app/T0: the result is "
                             "T / T0), got 0"));
  CHECK_FALSE(fs::exists(out / "capstan.csv"));
}
#endif

}  // namespace test_run_apps
