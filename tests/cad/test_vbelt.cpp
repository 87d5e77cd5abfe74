// Issue 15, item 4 and its verification: several contacts per contact point. A rope of radius r
// in the V-groove of a sheave read from STEP touches both flanks at once, at the same distance
// (the closest point is not unique, [KS15] Sect. 2.2); with "per_face" every face of the tool is
// a contact pair of its own, so each flank has its own gap, normal and friction history. Wrapped
// over phi on the sheave and pulled to full slip, the rope obeys the V-belt law
//   T / T0 = exp(mu phi / sin alpha),
// alpha the angle between a flank and the groove's mid-plane (the wedge multiplies the normal
// force by 1 / sin alpha: 2 N sin alpha = T dphi). A flat-bottomed groove wider than the rope
// gives the plain exp(mu phi) back. The sheaves are made by OpenCASCADE's modelling API
// (tests/support/cad_samples.hpp) and written as STEP; the model is data/capstan.json with the
// sheave as its tool.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "iga/model/analysis.hpp"
#include "iga/solvers/roundoff_probe.hpp"
#include "tests/support/cad_samples.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_vbelt {

using namespace iga;

namespace {

constexpr double kPi = std::numbers::pi;
const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

/// T/T0 at full slip of the capstan's rope (radius r, centre line at radius rho) wrapped by pi
/// in the sheave of `step` (every face a pair of its own), mu = 0.2: the mean over the three
/// steps of the sliding plateau that stop the run (T/T0 swings as points enter and leave the
/// lift-off zones, issue 12 item 3; measured at alpha = 20 deg: +0.42 % with steps of 0.1,
/// +0.02 % with 0.025, which the stiff wedge does not always allow). A run that does not reach
/// full slip (Newton stalls in the stiff wedge and the step size collapses; which run does
/// depends on the last bits of the arithmetic: tried with glibc's FMA paths masked) is run again
/// with half the largest step, as the capstan app pulls again; the first that reaches full slip
/// counts, none fails the test.
double belt_ratio(const std::string& step, double r, double rho, int& pairs, bool wedge = true) {
  Json doc = read_json_file(kData + "capstan.json");
  doc["geometry"]["sheave"] = {{"type", "cad"}, {"file", step}};
  doc["geometry"]["rope"]["radius"] = rho;
  Json& c = doc["contact"][0];
  c["rigid"] = "sheave";
  c["radius"] = r;
  c["mu"] = 0.2;
  c["per_face"] = true;
  // Penalty, 100 times the capstan's: the wedge multiplies the normal force by 1 / sin alpha,
  // and the penalty's error (T / (R^2 eps_N), issue 12) with it (measured at alpha = 20 deg:
  // +0.52 % with eps = 2.1e4, +0.41 % with 2.1e5, +0.22 % with 2.1e6). With the augmented
  // Lagrangian the two flanks' multipliers do not converge once the rope is pulled (open; see
  // the note of issue 15). On the flat bottom alone: the capstan's own settings (exact
  // enforcement).
  if (wedge) {
    c.erase("enforcement");
    c.erase("penetration_tol");
    c["eps_N"] = 2.1e6;
    c["eps_T"] = 2.1e6;
  }
  doc["boundary_conditions"][1]["magnitude"] = 0.1;  // enough pull to slide at T/T0 ~ 6
  for (const double max_step : {0.1, 0.05, 0.025, 0.0125}) {
    doc["solver"]["max_step"] = max_step;
    doc["solver"]["initial_step"] = max_step;
    Analysis a = Analysis::from_json(doc, kData + "sheave.json");
    pairs = a.num_pairs();
    const AnalysisResult res = a.run();
    if (res.full_slip) {  // the mean over the sliding plateau (the stop rule's last 3 steps)
      REQUIRE(res.steps.size() >= 3);
      double T = 0.0;
      for (std::size_t k = res.steps.size() - 3; k < res.steps.size(); ++k)
        T += res.steps[k].reactions.at(0).norm() / 3.0;
      return T / 10.0;
    }
    WARN("no full slip with max_step " << max_step << " (" << res.solver.message
                                       << "): again with half of it");
  }
  FAIL("no full slip");
  return 0.0;
}

}  // namespace

TEST_CASE("V-belt: a rope in a V-groove read from STEP reaches exp(mu phi / sin alpha)",
          "[cad][vbelt][analysis]") {
  // Probe off (not a test of the step control; a known weakness, docs/portability.md): this
  // model's start depends on the last bits. Under the round-off probe its first steps are cut
  // back, and at small steps the rope, touching both flanks, hunts between contact states
  // (seed 1: no convergence at dt = 1e-5, t = 0.003, |R| 7 times |R_0|); its steps take 6 to 17
  // Newton iterations whatever their size, so a step cut back never grows again
  // (easy_iterations = 4). With steps of a fixed size the first step still fails for some
  // seeds. To be made robust (a start that does not hunt), then the probe back on.
  const RoundoffProbeOff probe_off;
  const std::string dir = test::fresh_out_dir("cad_vbelt", "v");
  std::filesystem::create_directories(dir);
  const double r = 0.05, R_root = 1.0, mu = 0.2;
  for (const double alpha_deg : {20.0, 30.0, 45.0}) {
    const double alpha = alpha_deg * kPi / 180.0;
    const std::string step = dir + "/sheave_" + std::to_string(int(alpha_deg)) + ".step";
    test::write_step(test::sheave(1.6, 0.8, R_root, alpha), step);
    // The rope's centre touches both flanks: at r from each, on the mid-plane; 1e-6 inside,
    // so that every point is in contact from the start (a rope that only touches at zero gap
    // makes Newton hunt between contact states in the first steps, more or less so depending
    // on the last bits of the arithmetic: tried).
    const double rho = R_root + r / std::sin(alpha) - 1e-6;
    int pairs = 0;
    const double ratio = belt_ratio(step, r, rho, pairs);
    const double law = std::exp(mu * kPi / std::sin(alpha));
    INFO("alpha = " << alpha_deg << " deg: T/T0 = " << ratio << ", exp(mu phi / sin alpha) = "
                    << law << ", error " << 100 * (ratio / law - 1) << " %");
    CHECK(pairs == 7);  // the sheave's faces, each a pair
    CHECK(std::abs(ratio / law - 1.0) < 0.005);
  }
}

TEST_CASE("V-belt: in a flat-bottomed groove wider than the rope the plain exp(mu phi) returns",
          "[cad][vbelt][analysis]") {
  const std::string dir = test::fresh_out_dir("cad_vbelt", "flat");
  std::filesystem::create_directories(dir);
  const double r = 0.05, R_root = 1.0, mu = 0.2;
  const std::string step = dir + "/sheave_flat.step";
  test::write_step(test::sheave(1.6, 0.8, R_root, 30.0 * kPi / 180.0, 0.15), step);
  int pairs = 0;
  const double ratio = belt_ratio(step, r, R_root + r, pairs, false);
  const double law = std::exp(mu * kPi);
  INFO("T/T0 = " << ratio << ", exp(mu phi) = " << law);
  CHECK(pairs == 8);
  CHECK(std::abs(ratio / law - 1.0) < 0.005);
}

}  // namespace test_vbelt
