// NonlinearProblem::load_rate (iga/core/nonlinear_problem.hpp): arc length's dR/dt taken from
// the loads alone. It must equal the one-sided difference of two assemblies,
// (R(u, t + h) - R(u, t)) / h, on every kind of body and load (dead point, surface and edge
// loads, follower pressures on shells and membranes, end moments on rods with and without
// torsion, springs whose stiffness follows a curve), and it must refuse where t enters the
// residual otherwise: a prescribed displacement along a curve, a moving tool, exact enforcement
// of contact (multipliers predicted along t).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_load_rate {

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

/// A state near the reference one: u = a r with r uniform in [-1, 1] per unknown.
VectorXd nearby_state(int n, double a) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  VectorXd u(n);
  for (int i = 0; i < n; ++i) u[i] = a * d(rng);
  return u;
}

/// |load_rate - (R(u, t + h) - R(u, t)) / h| / |difference|, or -1 where load_rate refuses.
/// The difference's own round-off is eps |R| / h: h is large enough for it to stay below 1e-9
/// of the rate here (the rates are exact for the models' linear curves; the exponential one of
/// the saddle's springs differs between the two by nothing but round-off, both being the same
/// difference quotient).
double rate_error(BodySystem& sys, const VectorXd& u, double t, double h, double* rate_norm) {
  VectorXd rate;
  if (!sys.load_rate(u, t, h, rate)) return -1.0;
  VectorXd R0, R1;
  sys.assemble(u, t + h, R1, nullptr);
  sys.assemble(u, t, R0, nullptr);
  const VectorXd diff = (R1 - R0) / h;
  if (rate_norm) *rate_norm = diff.norm();
  REQUIRE(rate.size() == diff.size());
  return (rate - diff).norm() / diff.norm();
}

}  // namespace

TEST_CASE("load_rate: the loads' change equals the difference of two assemblies, every body",
          "[iga][core][load_rate]") {
  // model, the state's size, t, h: loads of every kind on every body type
  struct Case {
    const char* file;
    double amplitude, t, h;
  };
  const Case cases[] = {
      {"saddle.json", 1e-3, 300.0, 1e-2},       // shell: surface load, springs c(t), contact
      {"inflated_tube.json", 1e-2, 0.5, 1e-4},  // shell: follower pressure (neo-Hookean)
      {"balloon.json", 1e-2, 0.5, 1e-4},        // membrane: follower pressure
      {"hinged_roof.json", 1e-1, 0.3, 1e-4},    // shell: point load
      {"arch_snap.json", 1e-2, 0.3, 1e-4},      // rod: point load
      {"rollup.json", 1e-2, 0.5, 1e-4},         // rod: end moment (follows the tangent)
      {"helix_couple.json", 1e-3, 0.5, 1e-4},   // rod with torsion: end couple
  };
  for (const Case& c : cases) {
    INFO(c.file);
    Analysis a = Analysis::from_json(read_json_file(kData + c.file), kData + c.file);
    BodySystem& sys = a.problem();
    const VectorXd u = nearby_state(sys.num_dofs(), c.amplitude);
    double norm = 0.0;
    const double err = rate_error(sys, u, c.t, c.h, &norm);
    CHECK(norm > 0.0);  // the loads change with t
    CHECK(err >= 0.0);  // taken from the loads
    CHECK(err < 1e-9);
    // a step back in t (arc length's predictor on a falling branch)
    CHECK(rate_error(sys, u, c.t, -c.h, nullptr) == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE("load_rate: refused where t moves a prescribed value, a tool or the multipliers",
          "[iga][core][load_rate]") {
  SECTION("a prescribed displacement along a curve") {
    Json doc = read_json_file(kData + "arch_snap.json");
    doc["boundary_conditions"].push_back(
        {{"type", "displacement"}, {"body", "arch"}, {"point", 3}, {"value", {0.0, 0.0, 0.1}}});
    Analysis a = Analysis::from_json(doc, "arch_prescribed.json");
    BodySystem& sys = a.problem();
    VectorXd rate;
    const VectorXd u = VectorXd::Zero(sys.num_dofs());
    CHECK_FALSE(sys.load_rate(u, 0.3, 1e-4, rate));
    // its curve is a ramp: fixed, the same displacement does not depend on t
    doc["boundary_conditions"].back()["curve"] = "one";
    doc["load_curves"]["one"] = {{"type", "constant"}, {"value", 1.0}};
    Analysis b = Analysis::from_json(doc, "arch_prescribed.json");
    CHECK(rate_error(b.problem(), u, 0.3, 1e-4, nullptr) == Approx(0.0).margin(1e-9));
  }
  SECTION("moving tools") {
    Analysis a = Analysis::from_json(read_json_file(kData + "ring_between_plates.json"),
                                     kData + "ring_between_plates.json");
    VectorXd rate;
    CHECK_FALSE(a.problem().load_rate(VectorXd::Zero(a.problem().num_dofs()), 0.5, 1e-4, rate));
  }
  SECTION("exact enforcement of contact") {
    Analysis a =
        Analysis::from_json(read_json_file(kData + "two_ropes.json"), kData + "two_ropes.json");
    VectorXd rate;
    CHECK_FALSE(a.problem().load_rate(VectorXd::Zero(a.problem().num_dofs()), 0.5, 1e-4, rate));
  }
}

}  // namespace test_load_rate
