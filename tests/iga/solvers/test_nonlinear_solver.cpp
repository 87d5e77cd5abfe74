// Tests of the load-stepping Newton solver (iga/solvers/nonlinear_solver.hpp) on small problems
// with closed-form solutions: the von Mises truss (2 DOF, geometrically nonlinear, before its limit
// point), chains of hardening (sinh) and softening (atan) springs, and a non-symmetric system.
// Properties: solution against the closed form, measured quadratic convergence, cutback on
// divergence, min_step_reached beyond a limit load with the last converged state kept, the
// UMFPACK path for non-symmetric tangents, progress output and the step callback.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "iga/solvers/nonlinear_solver.hpp"
#include "iga/solvers/roundoff_probe.hpp"
#include "von_mises_truss.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_nonlinear_solver {

using namespace iga;

namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using iga::test::VonMisesTruss;

/// A chain of n springs, node 0 fixed, the end node loaded by t F; spring i joins nodes i-1
/// and i with the force s_i(D) = k_i g(D) of its elongation D = u_i - u_{i-1}. Every spring
/// carries t F, so D_i = g^-1(t F / k_i) in closed form. Tridiagonal SPD tangent (g' > 0).
class SpringChain : public NonlinearProblem {
 public:
  enum class Law { hardening_sinh, softening_atan };
  SpringChain(Law law, std::vector<double> k, double F) : law_(law), k_(std::move(k)), F_(F) {}
  int num_dofs() const override { return static_cast<int>(k_.size()); }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    const int n = num_dofs();
    R.setZero(n);
    std::vector<Eigen::Triplet<double>> tr;
    for (int i = 0; i < n; ++i) {
      const double D = u(i) - (i > 0 ? u(i - 1) : 0.0);
      const double s = k_[i] * g(D);
      const double ds = k_[i] * dg(D);
      R(i) += s;
      if (i > 0) R(i - 1) -= s;
      if (K) {
        tr.emplace_back(i, i, ds);
        if (i > 0) {
          tr.emplace_back(i - 1, i - 1, ds);
          tr.emplace_back(i - 1, i, -ds);
          tr.emplace_back(i, i - 1, -ds);
        }
      }
    }
    R(n - 1) -= t * F_;
    if (K) {
      K->resize(n, n);
      K->setFromTriplets(tr.begin(), tr.end());
    }
    ++assemblies;
  }
  void commit(const VectorXd& u, double t) override {
    committed_t.push_back(t);
    (void)u;
  }

  /// The closed-form state at time t.
  VectorXd exact(double t) const {
    VectorXd u(num_dofs());
    double sum = 0.0;
    for (int i = 0; i < num_dofs(); ++i) {
      const double f = t * F_ / k_[i];
      sum += law_ == Law::hardening_sinh ? std::asinh(f) : std::tan(f);
      u(i) = sum;
    }
    return u;
  }
  /// Spring forces of a state (all equal to t F at equilibrium).
  VectorXd spring_forces(const VectorXd& u) const {
    VectorXd s(num_dofs());
    for (int i = 0; i < num_dofs(); ++i) s(i) = k_[i] * g(u(i) - (i > 0 ? u(i - 1) : 0.0));
    return s;
  }

  int assemblies = 0;
  std::vector<double> committed_t;

 private:
  double g(double D) const { return law_ == Law::hardening_sinh ? std::sinh(D) : std::atan(D); }
  double dg(double D) const {
    return law_ == Law::hardening_sinh ? std::cosh(D) : 1.0 / (1.0 + D * D);
  }
  Law law_;
  std::vector<double> k_;
  double F_;
};

/// R(u, t) = M sinh(u) - t f with a non-symmetric M: K = M diag(cosh u) is not symmetric.
/// Closed form: u_i = asinh(t (M^-1 f)_i).
class NonSymmetricSystem : public NonlinearProblem {
 public:
  NonSymmetricSystem() {
    M_ << 2.0, 1.0, 0.0, -0.5, 3.0, 1.0, 0.3, -1.0, 2.5;
    f_ << 4.0, -2.0, 6.0;
  }
  int num_dofs() const override { return 3; }
  bool symmetric() const override { return false; }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    const Eigen::Vector3d s = u.array().sinh().matrix();
    R = M_ * s - t * f_;
    if (K) {
      const Eigen::Matrix3d k = M_ * u.array().cosh().matrix().asDiagonal();
      *K = k.sparseView();
    }
  }
  VectorXd exact(double t) const {
    const Eigen::Vector3d y = M_.lu().solve(t * f_);
    return y.array().asinh().matrix();
  }

 private:
  Eigen::Matrix3d M_;
  Eigen::Vector3d f_;
};

/// Observed orders of convergence p = log(r_k / r_{k-1}) / log(r_{k-1} / r_{k-2}) from the last
/// three residual norms of each step that lie above `floor` (round-off level excluded).
std::vector<double> observed_orders(const NonlinearSolverResult& r, double floor) {
  std::vector<double> p;
  for (const StepAttempt& a : r.attempts) {
    if (a.outcome != NewtonOutcome::converged) continue;
    const std::vector<double>& h = a.residual_norms;
    int k = static_cast<int>(h.size()) - 1;
    while (k >= 0 && h[k] <= floor) --k;
    if (k < 2) continue;
    p.push_back(std::log(h[k] / h[k - 1]) / std::log(h[k - 1] / h[k - 2]));
  }
  return p;
}

}  // namespace

TEST_CASE("NonlinearSolver: von Mises truss follows the closed-form load-deflection curve",
          "[iga][solver]") {
  // Probe off: this counts the step control's own steps, cutbacks and assemblies.
  const RoundoffProbeOff probe_off;
  const double P = 0.95 * VonMisesTruss(1.0, 0.5, 1.0, 0.0).P_max();
  VonMisesTruss truss(1.0, 0.5, 1.0, P);

  NonlinearSolverSettings s;
  s.initial_step = 0.2;
  s.max_step = 0.2;
  s.tol_residual_rel = 1e-12;  // the load error is below 1e-12 of the step's load increment
  NonlinearSolver solver(s);
  int calls = 0;
  VectorXd u = VectorXd::Zero(2);
  const NonlinearSolverResult r =
      solver.solve(truss, u, [&](const VectorXd& uc, double t, const StepAttempt& a) {
        ++calls;
        CHECK(a.outcome == NewtonOutcome::converged);
        CHECK(a.t == t);
        // The closed form at every converged step.
        const double w = -uc(1);
        CHECK(truss.load(w) == Approx(t * P).epsilon(1e-9));
        CHECK(w == Approx(truss.deflection(t * P)).epsilon(1e-8));
        CHECK(uc(0) == Approx(0.0).margin(1e-14));
        return true;
      });
  REQUIRE(r.status == NonlinearSolverStatus::converged);
  CHECK(r.converged());
  CHECK(r.t == 1.0);
  CHECK(r.steps == 5);
  CHECK(calls == r.steps);
  CHECK(r.cutbacks == 0);
  CHECK(static_cast<int>(r.step_iterations.size()) == r.steps);
  CHECK(-u(1) == Approx(truss.deflection(P)).epsilon(1e-8));
  CHECK(r.cholmod_factorizations == r.total_iterations);
  CHECK(r.umfpack_factorizations == 0);
  CHECK(r.assemblies == r.total_iterations + r.steps);
  CHECK(r.time_assembly + r.time_linear_solve <= r.time_total);
}

TEST_CASE("NonlinearSolver: Newton converges quadratically (observed order >= 1.8)",
          "[iga][solver]") {
  // Probe off: its 1e-10 perturbation of every correction is a floor for the residual history
  // (the order is measured down to 1e-13), and its refusals change the steps counted.
  const RoundoffProbeOff probe_off;
  // Big steps close to the limit point make Newton take several iterations.
  NonlinearSolverSettings s;
  s.initial_step = 0.5;
  s.max_step = 0.5;
  s.tol_residual_rel = 1e-14;
  s.tol_residual_abs = 1e-17;
  s.tol_residual_scaled = 0.0;
  s.tol_energy_rel = 0.0;  // residual test only: the residual history runs to round-off
  s.tol_energy_abs = 0.0;
  s.max_iterations = 30;
  s.max_residual_increases = 0;

  SECTION("von Mises truss (symmetric, CHOLMOD)") {
    const double P = 0.98 * VonMisesTruss(1.0, 0.5, 1.0, 0.0).P_max();
    VonMisesTruss truss(1.0, 0.5, 1.0, P);
    NonlinearSolver solver(s);
    VectorXd u = VectorXd::Zero(2);
    const NonlinearSolverResult r = solver.solve(truss, u);
    REQUIRE(r.converged());
    const std::vector<double> p = observed_orders(r, 1e-13 * P);
    REQUIRE(p.size() == 2);
    for (double order : p) CHECK(order >= 1.8);
  }
  SECTION("chain of hardening springs (tridiagonal, CHOLMOD)") {
    SpringChain chain(SpringChain::Law::hardening_sinh, {1.0, 2.0, 0.5, 3.0, 1.5}, 4.0);
    NonlinearSolver solver(s);
    VectorXd u = VectorXd::Zero(5);
    const NonlinearSolverResult r = solver.solve(chain, u);
    REQUIRE(r.converged());
    CHECK((u - chain.exact(1.0)).norm() <= 1e-12 * chain.exact(1.0).norm());
    const std::vector<double> p = observed_orders(r, 1e-12);
    REQUIRE(p.size() == 2);
    for (double order : p) CHECK(order >= 1.8);
  }
  SECTION("non-symmetric system (UMFPACK)") {
    NonSymmetricSystem sys;
    NonlinearSolver solver(s);
    VectorXd u = VectorXd::Zero(3);
    const NonlinearSolverResult r = solver.solve(sys, u);
    REQUIRE(r.converged());
    const std::vector<double> p = observed_orders(r, 1e-12);
    REQUIRE(p.size() == 2);
    for (double order : p) CHECK(order >= 1.8);
  }
}

TEST_CASE("NonlinearSolver: a step that diverges is cut back and the run still converges",
          "[iga][solver]") {
  // Hardening springs: one full step overshoots to sinh(~70) and diverges.
  SpringChain chain(SpringChain::Law::hardening_sinh, {1.0, 2.0, 0.5, 3.0}, 150.0);
  NonlinearSolverSettings s;
  s.initial_step = 1.0;
  s.max_step = 1.0;
  NonlinearSolver solver(s);
  VectorXd u = VectorXd::Zero(4);
  std::ostringstream log;
  solver.set_log(&log);
  const NonlinearSolverResult r = solver.solve(chain, u);
  INFO(log.str());
  REQUIRE(r.converged());
  CHECK(r.cutbacks >= 1);
  CHECK(r.attempts.front().outcome != NewtonOutcome::converged);
  CHECK(r.attempts.front().dt == 1.0);
  CHECK(static_cast<int>(r.attempts.size()) == r.steps + r.cutbacks);
  const VectorXd exact = chain.exact(1.0);
  CHECK((u - exact).norm() <= 1e-10 * exact.norm());
  // Commits only at converged steps, at their times, ending at t1.
  REQUIRE(static_cast<int>(chain.committed_t.size()) == r.steps);
  CHECK(chain.committed_t.back() == 1.0);
  // After the cutbacks, easy steps grow again.
  double dt_first = 0.0, dt_max = 0.0;
  for (const StepAttempt& a : r.attempts) {
    if (a.outcome != NewtonOutcome::converged) continue;
    if (dt_first == 0.0) dt_first = a.dt;
    dt_max = std::max(dt_max, a.dt);
  }
  CHECK(dt_max > dt_first);
  CHECK_THAT(log.str(), Catch::Contains("failed at t = 1"));
}

TEST_CASE(
    "NonlinearSolver: the secant predictor starts each step on the extrapolated path, same "
    "answers in fewer Newton iterations",
    "[iga][solver]") {
  // Probe off: two step controls compared step by step (20 equal steps, iterations counted).
  const RoundoffProbeOff probe_off;
  // Hardening springs loaded in 20 equal steps (no growth): from the second step on, the
  // secant extrapolation u_n + (u_n - u_{n-1}) lies within O(dt^2) of the next state.
  SpringChain plain(SpringChain::Law::hardening_sinh, {1.0, 2.0, 0.5, 3.0, 1.5}, 4.0);
  SpringChain secant = plain;
  NonlinearSolverSettings s;
  s.initial_step = s.max_step = 0.05;
  s.growth_factor = 1.0;
  NonlinearSolver a(s);
  s.secant_predictor = true;
  NonlinearSolver b(s);
  VectorXd ua = VectorXd::Zero(5), ub = VectorXd::Zero(5);
  const NonlinearSolverResult ra = a.solve(plain, ua), rb = b.solve(secant, ub);
  REQUIRE(ra.converged());
  REQUIRE(rb.converged());
  REQUIRE(ra.steps == 20);
  REQUIRE(rb.steps == 20);
  const VectorXd exact = plain.exact(1.0);
  CHECK((ua - exact).norm() <= 1e-10 * exact.norm());
  CHECK((ub - exact).norm() <= 1e-10 * exact.norm());
  INFO("Newton iterations: plain " << ra.total_iterations << ", secant " << rb.total_iterations);
  CHECK(rb.total_iterations < ra.total_iterations);
  // The first step has no earlier one to extrapolate: the same iterations as without.
  CHECK(rb.step_iterations.front() == ra.step_iterations.front());
}

TEST_CASE("NonlinearSolver: beyond a limit load the run ends at min_step_reached, state kept",
          "[iga][solver]") {
  // Softening springs saturate at k pi/2: the weakest (k = 1) carries at most pi/2, reached at
  // t_lim = pi/2 / F. No equilibrium exists beyond.
  const double F = 2.0;
  const double t_lim = 0.5 * std::numbers::pi / F;
  SpringChain chain(SpringChain::Law::softening_atan, {3.0, 1.0, 2.0}, F);
  NonlinearSolverSettings s;
  s.initial_step = 0.1;
  s.max_step = 0.2;
  s.min_step = 1e-4;
  NonlinearSolver solver(s);
  std::ostringstream log;
  solver.set_log(&log);
  VectorXd u = VectorXd::Zero(3);
  VectorXd u_callback;
  double t_callback = -1.0;
  const NonlinearSolverResult r =
      solver.solve(chain, u, [&](const VectorXd& uc, double t, const StepAttempt&) {
        u_callback = uc;
        t_callback = t;
        return true;
      });
  INFO(log.str());
  REQUIRE(r.status == NonlinearSolverStatus::min_step_reached);
  CHECK_FALSE(r.converged());
  CHECK(r.t < t_lim);
  CHECK(r.t > t_lim - 0.01);
  CHECK_THAT(r.message, Catch::Contains("minimum step reached"));
  CHECK(r.attempts.back().outcome != NewtonOutcome::converged);
  CHECK(r.attempts.back().t > t_lim);
  // The state is the last converged one: the one handed to the callback, in equilibrium.
  CHECK(t_callback == r.t);
  CHECK(u == u_callback);
  const VectorXd forces = chain.spring_forces(u);
  for (int i = 0; i < 3; ++i) CHECK(forces(i) == Approx(r.t * F).epsilon(1e-8));
  CHECK(chain.committed_t.back() == r.t);
  CHECK_THAT(log.str(), Catch::Contains("minimum step reached") &&
                            Catch::Contains("load stepping: min_step_reached"));
}

TEST_CASE("NonlinearSolver: a non-symmetric tangent is solved by UMFPACK", "[iga][solver]") {
  NonSymmetricSystem sys;
  NonlinearSolverSettings s;
  s.initial_step = 0.25;
  NonlinearSolver solver(s);
  VectorXd u = VectorXd::Zero(3);
  const NonlinearSolverResult r = solver.solve(sys, u);
  REQUIRE(r.converged());
  CHECK((u - sys.exact(1.0)).norm() <= 1e-10 * sys.exact(1.0).norm());
  CHECK(r.umfpack_factorizations == r.total_iterations);
  CHECK(r.cholmod_factorizations == 0);
  CHECK(r.cholesky_fallbacks == 0);
  CHECK(solver.linear_solver().backend() == LinearBackend::umfpack);
}

TEST_CASE("NonlinearSolver: progress lines, summary, callback stop, step growth", "[iga][solver]") {
  // Probe off: the step sizes, their growth and the lines per step are what is checked.
  const RoundoffProbeOff probe_off;
  SpringChain chain(SpringChain::Law::hardening_sinh, {1.0, 1.0}, 1.0);
  NonlinearSolverSettings s;
  s.initial_step = 0.1;
  s.max_step = 0.4;
  s.growth_factor = 2.0;
  s.easy_iterations = 10;
  NonlinearSolver solver(s);
  std::ostringstream log;
  solver.set_log(&log);
  VectorXd u = VectorXd::Zero(2);
  SECTION("one line per converged step and a summary") {
    const NonlinearSolverResult r = solver.solve(chain, u);
    REQUIRE(r.converged());
    // dt: 0.1, 0.2, 0.4 (max), 0.3 (to t1)
    REQUIRE(r.steps == 4);
    CHECK(r.attempts[1].dt == Approx(0.2));
    CHECK(r.attempts[2].dt == Approx(0.4));
    CHECK(r.attempts[3].t == 1.0);
    std::istringstream lines(log.str());
    std::string line;
    int step_lines = 0;
    while (std::getline(lines, line))
      if (line.rfind("step ", 0) == 0) ++step_lines;
    CHECK(step_lines == r.steps);
    CHECK_THAT(log.str(), Catch::Contains("load stepping: converged") &&
                              Catch::Contains("linear solves") && Catch::Contains("CHOLMOD"));
  }
  SECTION("steps land on the hit times, the step size carries on") {
    s.hit_times = {0.55, 0.25};
    solver.set_settings(s);
    const NonlinearSolverResult r = solver.solve(chain, u);
    REQUIRE(r.converged());
    std::vector<double> times;
    for (const StepAttempt& a : r.attempts) times.push_back(a.t);
    // dt 0.1; 0.2 -> 0.25 (hit); 0.4 -> 0.55 (hit, 0.3 taken); 0.4 -> 0.95; 1.0
    REQUIRE(times.size() == 5);
    CHECK(times[0] == Approx(0.1));
    CHECK(times[1] == 0.25);
    CHECK(times[2] == 0.55);
    CHECK(times[3] == Approx(0.95));
    CHECK(times[4] == 1.0);
    s.hit_times = {std::nan("")};
    CHECK_THROWS_WITH(solver.set_settings(s), Catch::Contains("hit_times"));
  }
  SECTION("the callback stops the run") {
    const NonlinearSolverResult r = solver.solve(
        chain, u, [](const VectorXd&, double, const StepAttempt& a) { return a.step < 2; });
    CHECK(r.status == NonlinearSolverStatus::stopped);
    CHECK(r.steps == 2);
    CHECK(r.t == Approx(0.3));
    CHECK((u - chain.exact(0.3)).norm() <= 1e-10);
  }
}

namespace {
/// A unit spring loaded by t that meets a stiff penalty "wall" at u = 1:
/// R = u + k_p max(0, u - 1) - t. Newton's first iterate of the step that reaches the wall
/// overshoots by about t - 1, where the residual jumps to k_p (t - 1), however small the step.
class SpringOnWall : public NonlinearProblem {
 public:
  int num_dofs() const override { return 1; }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    const bool touch = u[0] > 1.0;
    R.resize(1);
    R[0] = u[0] + (touch ? kp * (u[0] - 1.0) : 0.0) - t;
    if (K) {
      K->resize(1, 1);
      std::vector<Eigen::Triplet<double>> tr{{0, 0, 1.0 + (touch ? kp : 0.0)}};
      K->setFromTriplets(tr.begin(), tr.end());
    }
  }
  static constexpr double kp = 1e8;
};
}  // namespace

TEST_CASE("NonlinearSolver: a contact that closes in a cut-back step is not taken for divergence",
          "[iga][solver]") {
  // Probe off: the cutbacks down to a few 1e-6 are the step control under test; the probe's
  // 1e-10 relative perturbation of u ~ 1 is k_p 1e-10 = 1e-2 in R, above tol_residual_abs.
  const RoundoffProbeOff probe_off;
  // Judged against the step's own |R_0| (~ dt), the jump k_p (t - 1) at the wall is always
  // > 1e4 |R_0| near the wall and the run ended at min_step; against the run's largest |R_0|
  // (0.1 here) the step passes once it is cut back to a few 1e-6.
  SpringOnWall p;
  NonlinearSolverSettings s;
  s.t1 = 2.0;
  s.initial_step = 0.1;
  s.max_step = 0.1;
  s.min_step = 1e-7;
  s.tol_residual_abs = 1e-6;  // above the round-off floor k_p |u| 1e-16 ~ 1e-8 of the penalty
  NonlinearSolver solver(s);
  VectorXd u = VectorXd::Zero(1);
  const NonlinearSolverResult r = solver.solve(p, u);
  INFO(r.message);
  REQUIRE(r.converged());
  CHECK(r.cutbacks > 0);
  CHECK(u[0] == Approx(1.0 + 1.0 / (1.0 + SpringOnWall::kp)).epsilon(1e-12));
}

TEST_CASE("NonlinearSolver: zero load increments converge without iterations", "[iga][solver]") {
  SpringChain chain(SpringChain::Law::hardening_sinh, {1.0, 1.0}, 0.0);
  NonlinearSolver solver;
  VectorXd u = VectorXd::Zero(2);
  const NonlinearSolverResult r = solver.solve(chain, u);
  REQUIRE(r.converged());
  CHECK(r.total_iterations == 0);
  CHECK(u.norm() == 0.0);
}

namespace {

/// The spring chain of the tests above, whose assembly throws as the contact search does on a
/// non-finite state ("broad_phase: ... -nan") whenever a step beyond t = 0.5 is longer than
/// 0.2: the solver must cut such steps back, not end the run.
class ThrowsOnLongSteps : public NonlinearProblem {
 public:
  ThrowsOnLongSteps() : chain_(SpringChain::Law::hardening_sinh, {1.0, 2.0}, 1.0) {}
  int num_dofs() const override { return chain_.num_dofs(); }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    if (t > 0.5 && t - committed_ > 0.2)
      throw std::invalid_argument("broad_phase: points 3 is not finite: (-nan, 0, 0)");
    chain_.assemble(u, t, R, K);
  }
  void commit(const VectorXd&, double t) override { committed_ = t; }

 private:
  SpringChain chain_;
  double committed_ = 0.0;
};

}  // namespace

TEST_CASE("NonlinearSolver: an exception in the assembly fails the attempt and cuts the step back",
          "[iga][solver]") {
  NonlinearSolverSettings s;
  s.initial_step = 0.3;
  s.max_step = 0.3;
  ThrowsOnLongSteps p;
  NonlinearSolver solver(s);
  VectorXd u = VectorXd::Zero(p.num_dofs());
  NonlinearSolverResult r;
  REQUIRE_NOTHROW(r = solver.solve(p, u));
  CHECK(r.converged());
  CHECK(r.cutbacks >= 1);
  bool seen = false;
  for (const StepAttempt& a : r.attempts)
    if (a.outcome == NewtonOutcome::assembly_failed) {
      seen = true;
      CHECK_THAT(a.message, Catch::Contains("broad_phase") && Catch::Contains("-nan"));
    }
  CHECK(seen);
  CHECK(std::string(to_string(NewtonOutcome::assembly_failed)) == "assembly_failed");
  CHECK(std::string(to_string(NonlinearSolverStatus::failed)) == "failed");
}

TEST_CASE("NonlinearSolver: hit_times outside (t0, t1) are refused", "[iga][solver]") {
  NonlinearSolverSettings s;
  s.hit_times = {0.5, 1.5};
  CHECK_THROWS_WITH(NonlinearSolver(s),
                    Catch::Contains("hit_times: must be inside (t0, t1), got 1.5"));
  s.hit_times = {0.0};
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("hit_times"));
  s.tol_residual_scaled = -1.0;
  s.hit_times = {};
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("tol_residual_scaled"));
}

TEST_CASE("NonlinearSolver: invalid settings and state sizes throw with the field name",
          "[iga][solver]") {
  NonlinearSolverSettings s;
  s.min_step = 0.0;
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("NonlinearSolverSettings.min_step"));
  s = {};
  s.cutback_factor = 1.5;
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("cutback_factor"));
  s = {};
  s.t1 = s.t0;
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("t1"));
  NonlinearSolver solver;
  CHECK_THROWS_WITH(solver.set_settings(s), Catch::Contains("t1"));

  SpringChain chain(SpringChain::Law::hardening_sinh, {1.0, 1.0}, 1.0);
  VectorXd u = VectorXd::Zero(3);
  CHECK_THROWS_AS((void)solver.solve(chain, u), std::invalid_argument);
}

namespace {

/// R(u, t) = A u + c u^3 (componentwise) - t f, A SPD tridiagonal: linear for c = 0 (u = t A^-1
/// f), else hardening; counts its assemblies with and without the tangent. With `singular` A
/// has a zero row and column (no stiffness at the last unknown).
class CubicSystem : public NonlinearProblem {
 public:
  explicit CubicSystem(double c, bool singular = false) : c_(c) {
    const int n = 4;
    A_ = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      A_(i, i) = 4.0 + i;
      if (i + 1 < n) A_(i, i + 1) = A_(i + 1, i) = -1.0;
    }
    if (singular) A_.row(n - 1).setZero(), A_.col(n - 1).setZero();
    f_ = Eigen::Vector4d(1.0, -2.0, 3.0, 0.5);
  }
  int num_dofs() const override { return 4; }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    R = A_ * u + c_ * u.array().cube().matrix() - t * f_;
    if (K) {
      ++tangents;
      const Eigen::MatrixXd k =
          A_ + Eigen::MatrixXd((3.0 * c_ * u.array().square()).matrix().asDiagonal());
      *K = k.sparseView();
    } else {
      ++residuals;
    }
  }
  /// The linear solution t A^-1 f.
  VectorXd linear(double t) const { return A_.ldlt().solve(t * f_); }
  int tangents = 0, residuals = 0;

 private:
  double c_;
  Eigen::MatrixXd A_;
  VectorXd f_;
};

}  // namespace

TEST_CASE(
    "NonlinearSolver: the linear analysis solves every step on one assembly and factorization "
    "of the start tangent",
    "[iga][solver][linear]") {
  NonlinearSolverSettings s;
  s.analysis = AnalysisKind::linear;
  s.initial_step = 0.25;
  s.max_step = 1.0;  // the linear path keeps initial_step: no growth
  for (const double c : {0.0, 2.0}) {
    CubicSystem p(c);
    NonlinearSolver solver(s);
    VectorXd u = VectorXd::Zero(4);
    std::vector<double> times;
    const NonlinearSolverResult r =
        solver.solve(p, u, [&](const VectorXd& uc, double t, const StepAttempt& a) {
          times.push_back(t);
          CHECK(a.linear);
          // Linear theory at every step: t A^-1 f, whatever c (the tangent at u = 0 is A).
          CHECK((uc - p.linear(t)).norm() <= 1e-10 * p.linear(1.0).norm());
          return true;
        });
    INFO("c = " << c << ": " << r.message);
    REQUIRE(r.converged());
    CHECK(times == std::vector<double>{0.25, 0.5, 0.75, 1.0});
    CHECK(r.linear_steps == 4);
    CHECK(r.total_iterations == 4);  // one solve per step
    CHECK(p.tangents == 1);          // one tangent ...
    CHECK(r.cholmod_factorizations + r.ldlt_factorizations + r.umfpack_factorizations == 1);
    CHECK(p.residuals == 3);  // ... and the later steps' R(u_0, t)
    CHECK(r.assemblies == 4);
    CHECK(r.residual_assemblies == 3);
  }
  // A singular start tangent ends the run, at once and saying so (no cutbacks: a smaller step
  // has the same tangent).
  CubicSystem singular(0.0, true);
  NonlinearSolver solver(s);
  VectorXd u = VectorXd::Zero(4);
  const NonlinearSolverResult r = solver.solve(singular, u);
  CHECK(r.status == NonlinearSolverStatus::failed);
  CHECK_THAT(r.message, Catch::Contains("linear analysis: the step to t = 0.25 failed"));
  CHECK(r.cutbacks == 0);
  CHECK(r.steps == 0);
  CHECK(u.isZero(0.0));
}

TEST_CASE(
    "NonlinearSolver: the certified linear path is taken where the residual test holds, and "
    "hands over to Newton where it does not",
    "[iga][solver][linear]") {
  // Probe off: the comparison with Newton counts iterations and assemblies.
  const RoundoffProbeOff probe_off;
  NonlinearSolverSettings s;
  s.initial_step = 0.5;
  s.max_step = 0.5;
  s.tol_residual_rel = 1e-10;
  const auto run = [&](double c, AnalysisKind kind, CubicSystem& p) {
    NonlinearSolverSettings sk = s;
    sk.analysis = kind;
    NonlinearSolver solver(sk);
    VectorXd u = VectorXd::Zero(4);
    NonlinearSolverResult r = solver.solve(p, u);
    INFO("c = " << c << ", " << to_string(kind) << ": " << r.message);
    REQUIRE(r.converged());
    return std::make_pair(r, u);
  };
  // Linear (c = 0) and linear within the test (c = 1e-9: |c u^3| ~ 1e-11 |f|): the linear path,
  // two assemblies per step (R(u_0, t), then R(u, t) for the test), one factorization.
  for (const double c : {0.0, 1e-9}) {
    CubicSystem p(c), q(c);
    const auto [r, u] = run(c, AnalysisKind::certified, p);
    const auto [rn, un] = run(c, AnalysisKind::nonlinear, q);
    CHECK(r.linear_steps == 2);
    CHECK(r.linear_until == 0);
    CHECK(p.tangents == 1);
    CHECK(p.residuals == 3);
    CHECK(r.cholmod_factorizations == 1);
    CHECK((u - un).norm() <= 1e-9 * un.norm());  // Newton's state to its tolerance
    CHECK(rn.cholmod_factorizations == 4);       // Newton: two per step (the energy test)
  }
  // Nonlinear (c = 2): the first step is not certified and Newton goes on from the linear
  // state, taking Newton's own path: its iterations, one assembly more (the test's).
  const double c = 2.0;
  CubicSystem p(c), q(c);
  const auto [r, u] = run(c, AnalysisKind::certified, p);
  const auto [rn, un] = run(c, AnalysisKind::nonlinear, q);
  CHECK(r.linear_steps == 0);
  CHECK(r.linear_until == 1);
  CHECK_THAT(r.linear_message, Catch::Contains("after the linear solve, above the residual test"));
  CHECK((u - un).norm() <= 1e-12 * un.norm());
  CHECK((u - p.linear(1.0)).norm() > 1e-2 * un.norm());  // not the linear solution
  CHECK(r.total_iterations == rn.total_iterations);
  CHECK(r.assemblies == rn.assemblies + 1);
  CHECK(r.residual_assemblies == 1);
  CHECK(r.step_iterations == rn.step_iterations);
}

TEST_CASE("NonlinearSolver: a linear analysis refuses arc length and a restart",
          "[iga][solver][linear]") {
  NonlinearSolverSettings s;
  s.analysis = AnalysisKind::linear;
  s.control = PathControl::arc_length;
  CHECK_THROWS_WITH(NonlinearSolver(s),
                    Catch::Contains("NonlinearSolverSettings.analysis: must be nonlinear with "
                                    "arc length"));
  s.analysis = AnalysisKind::certified;
  CHECK_THROWS_WITH(NonlinearSolver(s), Catch::Contains("got certified"));
  s.control = PathControl::load;
  s.analysis = AnalysisKind::linear;
  NonlinearSolver solver(s);
  CubicSystem p(0.0);
  VectorXd u = VectorXd::Zero(4);
  SolverCheckpoint c;
  c.t = 0.5;
  c.steps = 1;
  c.attempted = 1;
  c.dt = 0.5;
  CHECK_THROWS_WITH((void)solver.solve(p, u, {}, &c),
                    Catch::Contains("a linear analysis does not resume a restart"));
}

}  // namespace test_nonlinear_solver
