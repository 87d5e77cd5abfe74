// Restart (issue 17, item 3): a run interrupted after k steps and continued from its restart
// file gives the results of the uninterrupted run, step for step: every cell of steps.csv and
// the final state, to round-off (on one machine they are the same bit for bit; the test allows
// 1e-12 of each column's scale). Should round-off cut a step back in one run and not in the
// other (another processor; the round-off probe IGA_ROUNDOFF_PROBE), the step paths differ and
// the runs are compared at the times both reached instead, within a tolerance per model (the
// friction history and the multipliers depend a little on the path). The models cover what a
// restart must carry: friction history and multipliers of exact enforcement (capstan), several
// bodies and pairs (two ropes), a rod's committed triads and twists (helix with end couples), the
// arc-length state through a limit point (shallow arch), a frictional shell on a rigid tool (block
// on a saddle), a tool that moves (ring crushed between plates). A restart file of another model is
// refused, naming the file and what differs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_restart {

using namespace iga;
namespace fs = std::filesystem;

namespace {

std::string data(const std::string& model) {
  return std::string(IGA_SOURCE_DIR) + "/data/" + model;
}

struct Case {
  std::string model;
  int stop_after = 0;  ///< attempted steps of the interrupted run (solver.max_steps)
  std::function<void(Json&)> edit = [](Json&) {};
  /// The largest difference of a steps.csv column relative to its scale when the restarted run
  /// took other steps than the whole one (compared at common times; see check_restart). The
  /// models with friction use exact enforcement (penetration_tol 1e-4): its multipliers stop at
  /// another point on another path, 1e-4 of T/T0 measured in test_moving_tools.cpp.
  double path_tol = 3e-4;
};

/// Runs the model whole, then interrupted after `stop_after` attempts and continued from its
/// restart file by a fresh Analysis (as a new process would); compares steps.csv and u.
void check_restart(const Case& c) {
  Json doc = read_json_file(data(c.model));
  doc["output"]["vtk"] = "none";
  c.edit(doc);
  const std::string stem = fs::path(c.model).stem().string();
  const std::string whole = test::fresh_out_dir("restart", stem + "_whole");
  const std::string parts = test::fresh_out_dir("restart", stem + "_parts");

  Analysis a = Analysis::from_json(doc, c.model);
  const AnalysisResult full = a.run(nullptr, whole);
  // t1, or the end of the capstan's sliding plateau (stopped as the model asks)
  REQUIRE((full.solver.converged() || full.full_slip));
  REQUIRE(full.restart_file.empty());  // a run that reaches t1 writes none unless asked

  Json first = doc;
  first["solver"]["max_steps"] = c.stop_after;
  Analysis b = Analysis::from_json(first, c.model);
  const AnalysisResult stopped = b.run(nullptr, parts);
  REQUIRE(stopped.solver.status == NonlinearSolverStatus::max_steps_reached);
  REQUIRE(stopped.restart_file == (fs::path(parts) / "restart.bin").string());
  const auto done = static_cast<std::size_t>(stopped.solver.steps);
  REQUIRE(done >= 2);
  REQUIRE(done + 2 <= full.steps.size());  // something is left to do

  Analysis resumed = Analysis::from_json(doc, c.model);
  const AnalysisResult rest = resumed.run(nullptr, parts, {}, stopped.restart_file);
  REQUIRE(rest.solver.status == full.solver.status);
  REQUIRE(rest.full_slip == full.full_slip);

  const auto rows_whole = test::csv_rows(test::slurp(fs::path(whole) / "steps.csv"));
  const auto rows_parts = test::csv_rows(test::slurp(fs::path(parts) / "steps.csv"));
  REQUIRE(rows_parts.front() == rows_whole.front());
  // The same step path (the same times row by row): the same computation, so every cell agrees
  // to round-off. Another path: round-off decided a cutback differently in one of the runs (on
  // another processor, or with the round-off probe IGA_ROUNDOFF_PROBE); then the runs are
  // compared at the times both reached.
  bool same_path = rows_parts.size() == rows_whole.size();
  for (std::size_t i = 1; same_path && i < rows_whole.size(); ++i)
    same_path = rows_whole[i].at(1) == rows_parts[i].at(1);  // column t
  if (!same_path) {
    const test::CommonTimes common = test::compare_at_common_times(rows_whole, rows_parts);
    INFO(c.model << ": another step path after the restart; " << common.common
                 << " common times up to t = " << common.last_t << ", worst " << common.worst
                 << " of a column's scale at " << common.where);
    // Both runs' steps land on the model's hit times (or its steps of 0.1 without cutback): at
    // least those up to t = 1 are common.
    CHECK(common.common >= 10);
    CHECK(common.last_t >= 1.0);
    // A different path through stick and slip leaves a different friction history and, with
    // exact enforcement, multipliers converged to another point within the penetration
    // tolerance: c.path_tol of a column's scale. (With the hit times the restarted two-rope run
    // took the whole run's steps for the probe's seeds 1, 2, 3: steps.csv identical.)
    CHECK(common.worst <= c.path_tol);
    WARN(c.model << ": restarted after step " << done << " of " << full.steps.size()
                 << ": another step path, compared at " << common.common << " common times, worst "
                 << common.worst << " of a column's scale");
    return;
  }
  REQUIRE(rest.steps.size() == full.steps.size() - done);
  bool bitwise = true;
  double worst = 0.0;  // largest difference relative to its column's scale
  for (std::size_t j = 0; j < rows_whole.front().size(); ++j) {
    double scale = 0.0;
    for (std::size_t i = 1; i < rows_whole.size(); ++i)
      if (!rows_whole[i][j].empty()) scale = std::max(scale, std::abs(std::stod(rows_whole[i][j])));
    for (std::size_t i = 1; i < rows_whole.size(); ++i) {
      const std::string& x = rows_whole[i][j];
      const std::string& y = rows_parts[i][j];
      bitwise = bitwise && x == y;
      INFO(c.model << ": step " << i << ", column " << rows_whole.front()[j] << ": " << x
                   << " (whole run) vs " << y << " (restarted after step " << done << ")");
      REQUIRE(x.empty() == y.empty());
      if (x.empty()) continue;
      const double d = std::abs(std::stod(x) - std::stod(y));
      worst = std::max(worst, scale > 0.0 ? d / scale : d);
      CHECK(d <= 1e-12 * scale + 1e-300);
    }
  }
  const double du = (rest.u - full.u).norm() / std::max(full.u.norm(), 1e-300);
  CHECK(du <= 1e-12);
  WARN(c.model << ": restarted after step " << done << " of " << full.steps.size() << ": "
               << (bitwise ? "steps.csv identical" : "steps.csv differs") << ", worst " << worst
               << " of a column's scale, |u - u_whole| / |u| " << du);
}

}  // namespace

TEST_CASE("Restart: friction history and exact enforcement (capstan)", "[iga][model][restart]") {
  check_restart({"capstan.json", 6});
}

TEST_CASE("Restart: two bodies with their pairs (two ropes)", "[iga][model][restart]") {
  // Steps land on t = 0.1, 0.2, ..., 1.9 whatever cutbacks happen between: the common times of
  // the whole and the restarted run should their steps differ.
  check_restart({"two_ropes.json", 6, [](Json& d) {
                   Json grid = Json::array();
                   for (int k = 1; k < 20; ++k) grid.push_back(k / 10.0);
                   d["solver"]["hit_times"] = grid;
                 }});
}

TEST_CASE("Restart: a rod with torsion keeps its triads (helix with end couples)",
          "[iga][model][restart]") {
  check_restart({"helix_couple.json", 5, [](Json& d) { d["solver"]["t_end"] = 0.6; }});
}

TEST_CASE("Restart: arc length through the arch's limit point", "[iga][model][restart]") {
  check_restart({"arch_snap.json", 10});
}

TEST_CASE("Restart: a frictional shell on a rigid tool (block on a saddle)",
          "[iga][model][restart]") {
  check_restart({"saddle_block.json", 9});
}

TEST_CASE("Restart: a moving tool under arc length (ring between plates)",
          "[iga][model][restart]") {
  check_restart({"ring_between_plates.json", 10, [](Json& d) {
                   d["solver"]["control"] = "arc_length";
                   d["solver"]["t_end"] = 0.3;
                 }});
}

TEST_CASE("Restart: every N steps, and a file of another model is refused",
          "[iga][model][restart]") {
  Json doc = read_json_file(data("capstan.json"));
  doc["output"]["vtk"] = "none";
  doc["output"]["restart_every"] = 4;
  const std::string dir = test::fresh_out_dir("restart", "every");
  Analysis a = Analysis::from_json(doc, "capstan.json");
  // The step callback runs before the step's restart file is written: the file of step 4 is
  // first seen by the callback of step 5.
  int step = 0, first_seen = 0;
  const AnalysisResult r = a.run(nullptr, dir, [&](const VectorXd&, double, const AnalysisStep&) {
    ++step;
    if (first_seen == 0 && fs::exists(fs::path(dir) / "restart.bin")) first_seen = step;
    return true;
  });
  REQUIRE(r.full_slip);  // the capstan stops at the end of its sliding plateau
  REQUIRE(step >= 8);
  REQUIRE(r.restart_file == (fs::path(dir) / "restart.bin").string());
  CHECK(fs::exists(r.restart_file));
  CHECK(first_seen == 5);

  // capstan's file read by the two-rope model: other unknowns
  Analysis other = Analysis::load(data("two_ropes.json"));
  try {
    (void)other.run(nullptr, {}, {}, r.restart_file);
    FAIL("a restart file of another model was accepted");
  } catch (const RestartError& e) {
    const std::string msg = e.what();
    INFO(msg);
    CHECK(msg.find(r.restart_file) != std::string::npos);
    CHECK(msg.find("section \"analysis\"") != std::string::npos);
    CHECK(msg.find("unknowns") != std::string::npos);
  }
  // a truncated file
  const std::string cut = (fs::path(dir) / "cut.bin").string();
  {
    const std::string bytes = test::slurp(r.restart_file);
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  Analysis same = Analysis::from_json(doc, "capstan.json");
  CHECK_THROWS_WITH(same.run(nullptr, {}, {}, cut),
                    Catch::Contains("cut.bin") && Catch::Contains("ends early"));
  // not a restart file at all
  CHECK_THROWS_WITH(same.run(nullptr, {}, {}, data("capstan.json")),
                    Catch::Contains("not a restart file"));
}

}  // namespace test_restart
