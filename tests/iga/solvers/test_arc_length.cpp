// Tests of the arc-length path following of NonlinearSolver (PathControl::arc_length, Crisfield's
// cylindrical constraint) on the von Mises truss, whose load-deflection curve has two limit
// points (closed form in von_mises_truss.hpp), and on the truss loaded through a soft spring,
// whose loaded point snaps back. Every converged state is checked against the closed form; the
// path must pass both limit points, land on t1 and on hit times, and take load steps where
// nothing depends on t.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "iga/solvers/nonlinear_solver.hpp"
#include "iga/solvers/roundoff_probe.hpp"
#include "von_mises_truss.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_arc_length {

using namespace iga;
using iga::test::TrussWithSpring;
using iga::test::VonMisesTruss;

namespace {

NonlinearSolverSettings arc_settings(double initial_step) {
  NonlinearSolverSettings s;
  s.control = PathControl::arc_length;
  s.initial_step = initial_step;
  s.max_step = 4.0 * initial_step;
  s.min_step = 1e-4 * initial_step;
  s.tol_residual_rel = 1e-10;
  s.max_steps = 2000;
  return s;
}

}  // namespace

TEST_CASE("Arc length: the von Mises truss passes both limit points and snaps through to t1",
          "[iga][solver][arc_length]") {
  // P = 1.5 P_max: the load factor t climbs to 2/3 (the first limit point), falls to -2/3 (the
  // second) and climbs again to 1 on the far branch (w > 2h). Load control stops at 2/3.
  const VonMisesTruss unit(1.0, 0.5, 1.0, 0.0);
  const double P = 1.5 * unit.P_max();
  VonMisesTruss truss(1.0, 0.5, 1.0, P);
  const double h = 0.5;

  NonlinearSolver solver(arc_settings(0.1));
  std::ostringstream log;
  solver.set_log(&log);
  VectorXd u = VectorXd::Zero(2);
  double t_max = -1e9, t_min = 1e9, w_last = 0.0;
  bool w_monotone = true;
  const NonlinearSolverResult r =
      solver.solve(truss, u, [&](const VectorXd& uc, double t, const StepAttempt& a) {
        const double w = -uc(1);
        // Every converged state is on the closed-form path, the symmetric one.
        CHECK(truss.load(w) == Approx(t * P).margin(1e-9 * P));
        CHECK(uc(0) == Approx(0.0).margin(1e-12));
        CHECK(a.arc_length > 0.0);
        w_monotone = w_monotone && w > w_last;
        w_last = w;
        if (w < h) t_max = std::max(t_max, t);  // before the top of the unstable branch
        t_min = std::min(t_min, t);
        return true;
      });
  INFO(log.str());
  REQUIRE(r.status == NonlinearSolverStatus::converged);
  CHECK(r.t == 1.0);
  // Both limit points passed: the load factor rose to near 2/3, fell to near -2/3.
  CHECK(t_max <= 2.0 / 3.0 + 1e-9);
  CHECK(t_max > 0.95 * 2.0 / 3.0);
  CHECK(t_min >= -2.0 / 3.0 - 1e-9);
  CHECK(t_min < -0.95 * 2.0 / 3.0);
  CHECK(w_monotone);  // the deflection grows along the whole path: no turning back
  // The end on the far branch: P(w) = P with w > 2h.
  CHECK(-u(1) > 2.0 * h);
  CHECK(truss.load(-u(1)) == Approx(P).epsilon(1e-9));
  CHECK(r.attempts.back().landed);
  // No step failed. A converged step refused by the round-off probe (IGA_ROUNDOFF_PROBE, tests
  // only) is cut back too; it is no failure of the arc-length control and is not counted.
  int failed = 0;
  for (const StepAttempt& a : r.attempts)
    if (a.outcome != NewtonOutcome::converged && a.outcome != NewtonOutcome::probe_refused)
      ++failed;
  CHECK(failed == 0);
  // Newton on the constraint keeps its quadratic rate: a handful of iterations per step.
  CHECK(*std::max_element(r.step_iterations.begin(), r.step_iterations.end()) <= 6);
  CHECK_THAT(log.str(), Catch::Contains("arc-length steps") && Catch::Contains(" arc "));

  // Load control cannot follow the falling branch: its Newton jumps from below the first limit
  // point to the far branch in one step (a gap in w wider than the unstable branch).
  NonlinearSolverSettings load = arc_settings(0.1);
  load.control = PathControl::load;
  load.min_step = 1e-4;
  VectorXd u2 = VectorXd::Zero(2);
  double w_prev = 0.0, widest_jump = 0.0;
  // Probe off for this run: the jump of load control's own step across the limit point is the
  // step control's behaviour under test, and the probe's refusals cut that very step back.
  const RoundoffProbeOff probe_off;
  const NonlinearSolverResult r2 =
      NonlinearSolver(load).solve(truss, u2, [&](const VectorXd& uc, double, const StepAttempt&) {
        widest_jump = std::max(widest_jump, -uc(1) - w_prev);
        w_prev = -uc(1);
        return true;
      });
  CHECK(r2.steps > 0);
  CHECK(widest_jump > 2.0 * h / std::sqrt(3.0));
}

TEST_CASE("Arc length: the loaded point of a truss behind a soft spring snaps back",
          "[iga][solver][arc_length]") {
  // k_s = 0.1 < max(-dP/dw) = EA h^2 / L0^3 = 0.179: the loaded point's deflection
  // W = w + t P / k_s turns back between the limit points.
  const VonMisesTruss unit(1.0, 0.5, 1.0, 0.0);
  const double P = 1.5 * unit.P_max();
  TrussWithSpring problem(1.0, 0.5, 1.0, P, 0.1);
  NonlinearSolver solver(arc_settings(0.05));
  std::ostringstream log;
  solver.set_log(&log);
  VectorXd u = VectorXd::Zero(3);
  std::vector<double> W;
  double t_min = 1e9;
  const NonlinearSolverResult r =
      solver.solve(problem, u, [&](const VectorXd& uc, double t, const StepAttempt&) {
        const double w = -uc(1);
        CHECK(problem.truss().load(w) == Approx(t * P).margin(1e-9 * P));
        CHECK(-uc(2) == Approx(w + t * P / problem.k_s()).margin(1e-9));
        W.push_back(-uc(2));
        t_min = std::min(t_min, t);
        return true;
      });
  INFO(log.str());
  REQUIRE(r.status == NonlinearSolverStatus::converged);
  CHECK(r.t == 1.0);
  CHECK(t_min < -0.95 * 2.0 / 3.0);
  // The snap-back: the loaded point's deflection rises, falls back by a clear amount, rises.
  double W_peak = -1e9, drop = 0.0;
  for (double x : W) {
    W_peak = std::max(W_peak, x);
    drop = std::max(drop, W_peak - x);
  }
  CHECK(drop > 0.05);
  CHECK(W.back() > W_peak - 1e-12);
}

TEST_CASE("Arc length: steps land on hit times each time the path crosses them",
          "[iga][solver][arc_length]") {
  // t = 0.5 is crossed three times: rising, falling after the first limit point, rising again
  // on the far branch; three states with three different deflections, each on the closed form.
  const VonMisesTruss unit(1.0, 0.5, 1.0, 0.0);
  const double P = 1.5 * unit.P_max();
  VonMisesTruss truss(1.0, 0.5, 1.0, P);
  NonlinearSolverSettings s = arc_settings(0.1);
  s.hit_times = {0.5};
  std::vector<double> w_at_hit;
  VectorXd u = VectorXd::Zero(2);
  const NonlinearSolverResult r =
      NonlinearSolver(s).solve(truss, u, [&](const VectorXd& uc, double t, const StepAttempt& a) {
        if (t == 0.5) {
          CHECK(a.landed);
          w_at_hit.push_back(-uc(1));
          CHECK(truss.load(-uc(1)) == Approx(0.5 * P).epsilon(1e-9));
        }
        return true;
      });
  REQUIRE(r.converged());
  REQUIRE(w_at_hit.size() == 3);
  CHECK(w_at_hit[0] < w_at_hit[1]);
  CHECK(w_at_hit[1] < w_at_hit[2]);
}

TEST_CASE("Arc length: where nothing depends on t the steps are load steps, settings validated",
          "[iga][solver][arc_length]") {
  // P = 0: dR/dt = 0 (as for a tool that has not reached the body yet): load steps of
  // initial_step, growing on easy steps, no arc length.
  VonMisesTruss unloaded(1.0, 0.5, 1.0, 0.0);
  VectorXd u = VectorXd::Zero(2);
  NonlinearSolver solver(arc_settings(0.1));
  const NonlinearSolverResult r = solver.solve(unloaded, u);
  REQUIRE(r.converged());
  CHECK(r.t == 1.0);
  CHECK(r.attempts.front().t == Approx(0.1));
  for (const StepAttempt& a : r.attempts) CHECK(a.arc_length == 0.0);
  CHECK(u.norm() == 0.0);
  NonlinearSolverSettings s = arc_settings(0.1);
  s.desired_iterations = 0;
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("desired_iterations"));
  s.desired_iterations = 5;
  for (double bad : {0.0, -10.0, 180.5}) {
    s.max_turn_deg = bad;
    CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("max_turn_deg"));
  }
  CHECK(std::string(to_string(PathControl::arc_length)) == "arc_length");
}

TEST_CASE("Arc length: a step that turns more than max_turn_deg from its predictor is cut back",
          "[iga][solver][arc_length]") {
  // The snap-back of the truss behind a soft spring with long arcs: without the limit some
  // converged steps turn far from their predictor (the path bends within one arc; here the run
  // then loses the path and ends at max_steps far below t = 0); with max_turn_deg = 10 those
  // are refused and repeated with shorter arcs, every accepted step turns at most 10 degrees,
  // and the run reaches t1 with every state on the closed form.
  const VonMisesTruss unit(1.0, 0.5, 1.0, 0.0);
  const double P = 1.5 * unit.P_max();
  const auto run = [&](double max_turn, double& worst_turn) {
    TrussWithSpring problem(1.0, 0.5, 1.0, P, 0.1);
    NonlinearSolverSettings s = arc_settings(0.2);
    s.max_turn_deg = max_turn;
    s.max_steps = 300;
    NonlinearSolver solver(s);
    VectorXd u = VectorXd::Zero(3);
    worst_turn = 0.0;
    NonlinearSolverResult r =
        solver.solve(problem, u, [&](const VectorXd& uc, double t, const StepAttempt& a) {
          CHECK(problem.truss().load(-uc(1)) == Approx(t * P).margin(1e-9 * P));
          worst_turn = std::max(worst_turn, a.turn_deg);
          return true;
        });
    return r;
  };
  double free_turn = 0.0, limited_turn = 0.0;
  const NonlinearSolverResult free = run(180.0, free_turn);
  const NonlinearSolverResult limited = run(10.0, limited_turn);
  INFO("without the limit: " << to_string(free.status) << " at t = " << free.t);
  CHECK(free_turn > 10.0);
  REQUIRE(limited.status == NonlinearSolverStatus::converged);
  CHECK(limited.t == 1.0);
  CHECK(limited_turn <= 10.0);
  int refused = 0;
  for (const StepAttempt& a : limited.attempts)
    refused += a.message.find("turned") != std::string::npos ? 1 : 0;
  CHECK(refused > 0);
}

namespace {

/// The von Mises truss whose residual at t = 1 is NaN the first `failures` times it is asked
/// for: the solve that lands an arc-length step on t1 fails.
class TrussFailingAtOne : public VonMisesTruss {
 public:
  TrussFailingAtOne(double P, int failures) : VonMisesTruss(1.0, 0.5, 1.0, P), left_(failures) {}
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    VonMisesTruss::assemble(u, t, R, K);
    if (t == 1.0 && left_ > 0) {
      --left_;
      R.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }

 private:
  int left_;
};

}  // namespace

TEST_CASE("Arc length: a step whose landing on t1 fails is cut back and ends on t1",
          "[iga][solver][arc_length]") {
  // Half the limit load: the path goes on beyond t = 1, the last arc crosses t1 and its landing
  // there fails once (NaN residual). The step is refused and repeated with a shorter arc, which
  // lands. (Before, the arc state beyond t1 was kept and the run said "reached t1".)
  const VonMisesTruss unit(1.0, 0.5, 1.0, 0.0);
  const double P = 0.5 * unit.P_max();
  TrussFailingAtOne truss(P, 1);
  NonlinearSolverSettings s = arc_settings(0.3);
  VectorXd u = VectorXd::Zero(2);
  const NonlinearSolverResult r =
      NonlinearSolver(s).solve(truss, u, [&](const VectorXd& uc, double t, const StepAttempt&) {
        CHECK(t <= 1.0);
        CHECK(truss.load(-uc(1)) == Approx(t * P).margin(1e-9 * P));
        return true;
      });
  REQUIRE(r.status == NonlinearSolverStatus::converged);
  CHECK(r.t == 1.0);
  CHECK(r.attempts.back().landed);
  // One cutback: the failed landing. Converged steps refused by the round-off probe
  // (IGA_ROUNDOFF_PROBE, tests only) are cut back too; they are not counted.
  int refused = 0;
  for (const StepAttempt& a : r.attempts) refused += a.outcome == NewtonOutcome::probe_refused;
  CHECK(r.cutbacks - refused == 1);
  int failed_landings = 0;
  for (const StepAttempt& a : r.attempts)
    if (a.outcome == NewtonOutcome::landing_failed) {
      ++failed_landings;
      CHECK_THAT(a.message, Catch::StartsWith("landing on t = 1 failed"));
    }
  CHECK(failed_landings == 1);
  CHECK_THAT(r.message, Catch::StartsWith("reached t1 = 1"));
}

}  // namespace test_arc_length
