// Static load stepping with Newton-Raphson, step growth and cutback ([Wri08]; [KS15] via
// ../shared/paper/EQUATIONS.md). Notation as in nonlinear_solver.hpp.
#include "iga/solvers/nonlinear_solver.hpp"

#include "iga/core/state_archive.hpp"
#include "iga/solvers/roundoff_probe.hpp"
#include "iga/solvers/solver_steps.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <utility>

namespace iga {

using namespace detail;

namespace {

[[noreturn]] void bad_setting(const char* field, const std::string& expected, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", value);
  throw std::invalid_argument(std::string("NonlinearSolverSettings.") + field + ": must be " +
                              expected + ", got " + buf);
}

}  // namespace

void NonlinearSolverSettings::validate() const {
  if (!std::isfinite(t0)) bad_setting("t0", "finite", t0);
  if (!std::isfinite(t1) || !(t1 > t0)) bad_setting("t1", "finite and > t0", t1);
  if (!(min_step > 0.0)) bad_setting("min_step", "> 0", min_step);
  if (!(max_step >= min_step)) bad_setting("max_step", ">= min_step", max_step);
  if (!(initial_step > 0.0)) bad_setting("initial_step", "> 0", initial_step);
  if (max_steps < 1) bad_setting("max_steps", ">= 1", max_steps);
  if (max_iterations < 1) bad_setting("max_iterations", ">= 1", max_iterations);
  if (!(tol_residual_rel >= 0.0)) bad_setting("tol_residual_rel", ">= 0", tol_residual_rel);
  if (!(tol_residual_abs >= 0.0)) bad_setting("tol_residual_abs", ">= 0", tol_residual_abs);
  if (!(tol_residual_scaled >= 0.0))
    bad_setting("tol_residual_scaled", ">= 0", tol_residual_scaled);
  if (!(tol_residual_rel > 0.0 || tol_residual_abs > 0.0))
    bad_setting("tol_residual_rel", "> 0 (or tol_residual_abs > 0)", tol_residual_rel);
  if (std::isnan(tol_energy_rel)) bad_setting("tol_energy_rel", "a number", tol_energy_rel);
  if (std::isnan(tol_energy_abs)) bad_setting("tol_energy_abs", "a number", tol_energy_abs);
  if (easy_iterations < 0) bad_setting("easy_iterations", ">= 0", easy_iterations);
  if (!(growth_factor >= 1.0)) bad_setting("growth_factor", ">= 1", growth_factor);
  if (!(cutback_factor > 0.0 && cutback_factor < 1.0))
    bad_setting("cutback_factor", "in (0, 1)", cutback_factor);
  if (!(divergence_ratio > 1.0)) bad_setting("divergence_ratio", "> 1", divergence_ratio);
  if (max_residual_increases < 0)
    bad_setting("max_residual_increases", ">= 0", max_residual_increases);
  for (double h : hit_times)
    if (!(h > t0 && h < t1)) bad_setting("hit_times", "inside (t0, t1)", h);
  if (desired_iterations < 1) bad_setting("desired_iterations", ">= 1", desired_iterations);
  if (!(max_turn_deg > 0.0 && max_turn_deg <= 180.0))
    bad_setting("max_turn_deg", "in (0, 180]", max_turn_deg);
  if (analysis != AnalysisKind::nonlinear && control == PathControl::arc_length)
    throw std::invalid_argument(std::string("NonlinearSolverSettings.analysis: must be nonlinear "
                                            "with arc length (a linear path has no limit "
                                            "points to follow), got ") +
                                to_string(analysis));
}

const char* to_string(AnalysisKind k) {
  switch (k) {
    case AnalysisKind::nonlinear:
      return "nonlinear";
    case AnalysisKind::linear:
      return "linear";
    case AnalysisKind::certified:
      return "certified";
  }
  return "?";
}

const char* to_string(PathControl c) {
  return c == PathControl::arc_length ? "arc_length" : "load";
}

const char* to_string(NewtonOutcome o) {
  switch (o) {
    case NewtonOutcome::converged:
      return "converged";
    case NewtonOutcome::diverged:
      return "diverged";
    case NewtonOutcome::not_finite:
      return "not_finite";
    case NewtonOutcome::max_iterations:
      return "max_iterations";
    case NewtonOutcome::linear_solve_failed:
      return "linear_solve_failed";
    case NewtonOutcome::assembly_failed:
      return "assembly_failed";
    case NewtonOutcome::augmentation_failed:
      return "augmentation_failed";
    case NewtonOutcome::landing_failed:
      return "landing_failed";
    case NewtonOutcome::passed_through:
      return "passed_through";
    case NewtonOutcome::probe_refused:
      return "probe_refused";
  }
  return "?";
}

const char* to_string(NonlinearSolverStatus s) {
  switch (s) {
    case NonlinearSolverStatus::converged:
      return "converged";
    case NonlinearSolverStatus::min_step_reached:
      return "min_step_reached";
    case NonlinearSolverStatus::max_steps_reached:
      return "max_steps_reached";
    case NonlinearSolverStatus::stopped:
      return "stopped";
    case NonlinearSolverStatus::failed:
      return "failed";
  }
  return "?";
}

namespace detail {

/// R(u, t) into R and the tangent into K, timed and counted in r. Returns |R|, or -1 with
/// `error` set when the problem threw.
double assemble_residual(NonlinearProblem& problem, const VectorXd& u, double t, int n, VectorXd& R,
                         SparseMatrix& K, NonlinearSolverResult& r, std::string& error) {
  const Clock::time_point t0 = Clock::now();
  try {
    problem.assemble(u, t, R, &K);
  } catch (const std::exception& e) {
    r.time_assembly += seconds_since(t0);
    ++r.assemblies;
    error = e.what();
    return -1.0;
  }
  r.time_assembly += seconds_since(t0);
  ++r.assemblies;
  if (R.size() != n || K.rows() != n || K.cols() != n)
    throw std::logic_error("NonlinearProblem::assemble: residual of size " +
                           std::to_string(R.size()) + " and tangent of size " +
                           std::to_string(K.rows()) + " x " + std::to_string(K.cols()) + " for " +
                           std::to_string(n) + " unknowns");
  return problem.norm(R);
}

/// R(u, t) alone (no tangent) into R, timed and counted in r. Returns |R|, or -1 with `error`
/// set when the problem threw.
double assemble_rhs(NonlinearProblem& problem, const VectorXd& u, double t, int n, VectorXd& R,
                    NonlinearSolverResult& r, std::string& error) {
  const Clock::time_point t0 = Clock::now();
  ++r.assemblies;
  ++r.residual_assemblies;
  try {
    problem.assemble(u, t, R, nullptr);
  } catch (const std::exception& e) {
    r.time_assembly += seconds_since(t0);
    error = e.what();
    return -1.0;
  }
  r.time_assembly += seconds_since(t0);
  if (R.size() != n)
    throw std::logic_error("NonlinearProblem::assemble: residual of size " +
                           std::to_string(R.size()) + " for " + std::to_string(n) + " unknowns");
  return problem.norm(R);
}

/// The Newton correction: K du = rhs, timed in r, the factorizations counted in a by backend.
LinearSolveStatus solve_correction(LinearSolver& linear, const SparseMatrix& K, const VectorXd& rhs,
                                   VectorXd& du, StepAttempt& a, NonlinearSolverResult& r) {
  const Clock::time_point t0 = Clock::now();
  LinearSolveStatus ls = linear.factorize(K);
  if (linear.fell_back()) ++a.cholesky_fallbacks;
  if (ls == LinearSolveStatus::success) {
    ls = linear.solve(rhs, du);  // may replace a grown LDL^T by UMFPACK
    roundoff_probe_perturb(du);  // test-only: IGA_ROUNDOFF_PROBE (roundoff_probe.hpp)
    if (linear.backend() == LinearBackend::cholmod)
      ++a.cholmod_factorizations;
    else if (linear.backend() == LinearBackend::ldlt)
      ++a.ldlt_factorizations;
    else if (linear.backend() == LinearBackend::umfpack)
      ++a.umfpack_factorizations;
    else
      ++a.petsc_factorizations;
  }
  r.time_linear_solve += seconds_since(t0);
  return ls;
}

LinearSolveStatus solve_again(LinearSolver& linear, const VectorXd& rhs, VectorXd& x,
                              NonlinearSolverResult& r) {
  const Clock::time_point t0 = Clock::now();
  const LinearSolveStatus ls = linear.solve(rhs, x);
  roundoff_probe_perturb(x);  // test-only: IGA_ROUNDOFF_PROBE (roundoff_probe.hpp)
  r.time_linear_solve += seconds_since(t0);
  return ls;
}

/// Tests only: the round-off probe's refusal of a converged step (roundoff_probe.hpp) of the
/// given size, never at the minimum size.
void probe_refusal(StepAttempt& a, double size, double min_size) {
  if (!roundoff_probe_enabled() || a.outcome != NewtonOutcome::converged ||
      size <= min_size * (1.0 + 1e-12))
    return;
  std::vector<double> state = {a.t_start, a.t, a.arc_length};
  state.insert(state.end(), a.residual_norms.begin(), a.residual_norms.end());
  if (!roundoff_probe_refuses(state)) return;
  a.outcome = NewtonOutcome::probe_refused;
  a.message = "refused by the round-off probe (IGA_ROUNDOFF_PROBE, tests only)";
}

/// The divergence tests after iteration k: |R_k| above r_div, or |R| grew in
/// max_residual_increases consecutive iterations (`increases` counts them). Returns why the
/// iterations diverged, or an empty string.
std::string divergence(const NonlinearSolverSettings& s, int k, double rk, double r_prev,
                       double r_div, double r0_max, int& increases) {
  if (rk > r_div)
    return format("iteration %d: |R| = %.3e > %.3g max |R_0| (max |R_0| = %.3e)", k, rk,
                  s.divergence_ratio, r0_max);
  increases = rk > r_prev ? increases + 1 : 0;
  if (s.max_residual_increases > 0 && increases >= s.max_residual_increases)
    return format("iteration %d: |R| grew in %d consecutive iterations (|R| = %.3e)", k, increases,
                  rk);
  return {};
}

/// Records |R_k| = rk of iteration k in a; false (a's outcome set) when the assembly failed
/// (rk < 0, `error` says why) or rk is not finite.
bool record_residual(double rk, int k, const std::string& error, StepAttempt& a) {
  if (rk < 0.0) {
    a.outcome = NewtonOutcome::assembly_failed;
    a.message = format("iteration %d: assembly: %s", k, error.c_str());
    return false;
  }
  a.residual_norms.push_back(rk);
  if (std::isfinite(rk)) return true;
  a.outcome = NewtonOutcome::not_finite;
  a.message = format("iteration %d: |R| is not finite", k);
  return false;
}

/// The end of the step from t with nominal size dt.
double step_end(const NonlinearSolverSettings& s, double t, double dt, double t_eps) {
  // The step ends at t1 if it would leave less than min_step to go.
  double t_new = t + dt;
  if (t_new > s.t1 - t_eps || s.t1 - t_new < s.min_step) t_new = s.t1;
  for (double h : s.hit_times)  // land on requested times (also one the step ends next to)
    if (h > t + t_eps && h < t_new + t_eps) t_new = h;
  return t_new;
}

/// Adds a re-solve after a multiplier update (b) to the step's attempt a: its iterations,
/// norms and factorizations.
void append_resolve(StepAttempt& a, const StepAttempt& b) {
  a.iterations += b.iterations;
  a.residual_norms.insert(a.residual_norms.end(), b.residual_norms.begin(), b.residual_norms.end());
  a.energy_norms.insert(a.energy_norms.end(), b.energy_norms.begin(), b.energy_norms.end());
  a.cholmod_factorizations += b.cholmod_factorizations;
  a.ldlt_factorizations += b.ldlt_factorizations;
  a.umfpack_factorizations += b.umfpack_factorizations;
  a.petsc_factorizations += b.petsc_factorizations;
  a.cholesky_fallbacks += b.cholesky_fallbacks;
}

/// The run's totals of an attempt, converged or not.
void add_attempt_totals(NonlinearSolverResult& r, const StepAttempt& a) {
  r.total_iterations += a.iterations;
  r.augmentations += a.augmentations;
  r.cholmod_factorizations += a.cholmod_factorizations;
  r.ldlt_factorizations += a.ldlt_factorizations;
  r.umfpack_factorizations += a.umfpack_factorizations;
  r.petsc_factorizations += a.petsc_factorizations;
  r.cholesky_fallbacks += a.cholesky_fallbacks;
}

/// A failed attempt a of size `size` ("dt = ..." or "arc ..."): the log line with what comes next
/// (`next`); at the minimum size the run's status and message. Returns at_min (the run ends).
bool report_failed_step(std::ostream* log, NonlinearSolverResult& r, const StepAttempt& a,
                        const std::string& size, const std::string& next, bool at_min,
                        double t_last) {
  if (log)
    *log << format("  step %d failed at t = %.9g (%s): %s (%d iterations): %s; ", a.step, a.t,
                   size.c_str(), to_string(a.outcome), a.iterations, a.message.c_str())
         << next << '\n';
  if (!at_min) return false;
  r.status = NonlinearSolverStatus::min_step_reached;
  r.message = format(
      "%s: the step from t = %.9g to %.9g (%s) failed (%s: %s); the state is the last converged "
      "one, t = %.9g",
      next.c_str(), a.t_start, a.t, size.c_str(), to_string(a.outcome), a.message.c_str(), t_last);
  return true;
}

/// Load control: a converged step's jump ratio (StepAttempt::jump_ratio) from the norm of its
/// increment, a jump counted in r.
void record_jump(StepAttempt& a, NonlinearSolverResult& r, double increment) {
  if (a.predicted > 0.0) a.jump_ratio = increment / a.predicted;
  if (a.jump_ratio > kJumpRatio) ++r.jumps;
}

/// Whether a run takes the linear path (AnalysisKind) from its start; a linear analysis does not
/// resume (std::invalid_argument), a certified one resumes with Newton.
bool linear_start(AnalysisKind kind, bool resumed) {
  if (resumed && kind == AnalysisKind::linear)
    throw std::invalid_argument(
        "NonlinearSolver::solve: a linear analysis does not resume a restart (its steps solve "
        "from the start state on one factorization): run it from the start");
  return kind != AnalysisKind::nonlinear && !resumed;
}

/// After an attempt of the given size: the round-off probe (not on the linear analysis's steps,
/// which have no convergence test to be at the edge of) and the linear path's count.
void settle_attempt(StepAttempt& a, NonlinearSolverResult& r, AnalysisKind kind, double size,
                    double min_size) {
  if (!a.linear || kind == AnalysisKind::certified) probe_refusal(a, size, min_size);
  if (a.outcome != NewtonOutcome::converged) a.linear = false;
  if (a.linear) ++r.linear_steps;
}

/// A failed step of the linear analysis ends the run (a smaller step has the same tangent),
/// the state that of the last solved step, at t.
void end_linear_run(std::ostream* log, NonlinearSolverResult& r, StepAttempt&& a, double t) {
  r.status = NonlinearSolverStatus::failed;
  r.message = format(
      "linear analysis: the step to t = %.9g failed (%s: %s); the state is the last solved one, "
      "t = %.9g",
      a.t, to_string(a.outcome), a.message.c_str(), t);
  if (log) *log << "  " << r.message << '\n';
  r.attempts.push_back(std::move(a));
}

/// The progress line of converged step r.steps, at time t, lambda the fraction of the span done.
void log_converged_step(std::ostream& log, const NonlinearSolverResult& r, const StepAttempt& a,
                        double t, double lambda, const NonlinearProblem& problem) {
  const double rn = a.residual_norms.back();
  const double en = a.energy_norms.empty() ? 0.0 : a.energy_norms.back();
  if (a.linear) {  // one solve on the start tangent; |R| after it only when certified
    log << format("step %4d  t = %-11.6g dt = %.3e  lambda = %.4f  linear  |R(u_0)| = %.3e",
                  r.steps, t, a.dt, lambda, a.residual_norms.front());
    if (a.residual_norms.size() > 1) log << format("  certified |R| = %.3e", rn);
    const std::string status = problem.status();
    if (!status.empty()) log << "  " << status;
    log << '\n';
    return;
  }
  log << format(
      "step %4d  t = %-11.6g dt = %.3e  lambda = %.4f  it = %2d  "
      "|R0| = %.3e  |R| = %.3e  E = %.3e",
      r.steps, t, a.dt, lambda, a.iterations, a.residual_norms.front(), rn, en);
  if (a.arc_length > 0.0)
    log << format("  arc %.3e turn %.1f", a.arc_length, a.turn_deg) << (a.landed ? " landed" : "");
  if (a.augmentations > 0) log << "  augmentations " << a.augmentations;
  if (a.cholesky_fallbacks > 0) log << "  lu-fallbacks " << a.cholesky_fallbacks;
  if (a.jump_ratio > kJumpRatio)
    log << format("  jump: %.0f times the tangent's prediction", a.jump_ratio);
  const std::string status = problem.status();
  if (!status.empty()) log << "  " << status;
  log << '\n';
}

}  // namespace detail

NonlinearSolver::NonlinearSolver(const NonlinearSolverSettings& settings) : settings_(settings) {
  settings_.validate();
  if (settings_.linear_method != LinearMethod::suitesparse)
    linear_.set_method(settings_.linear_method);
}

void NonlinearSolver::set_settings(const NonlinearSolverSettings& settings) {
  settings.validate();
  if (settings.linear_method != linear_.method()) linear_.set_method(settings.linear_method);
  settings_ = settings;
}

void NonlinearSolver::newton(NonlinearProblem& problem, VectorXd& u, double t, Workspace& w,
                             StepAttempt& a, NonlinearSolverResult& r, bool break_cycles,
                             double r0_step, double e1_step) {
  const NonlinearSolverSettings& s = settings_;
  a.residual_norms.reserve(static_cast<std::size_t>(s.max_iterations) + 1);
  a.energy_norms.reserve(static_cast<std::size_t>(s.max_iterations));
  linear_.set_symmetric(problem.symmetric());
  linear_.set_distributed(problem.distributed(), problem.layout());
  // The Krylov path's multigrid gets the bodies' rigid-body motions at the step's start (a
  // re-solve's start is current only at each process's own unknowns and ghosts: made current
  // everywhere first, since the motions are the whole body's).
  if (linear_.method() == LinearMethod::krylov) {
    problem.synchronize(u);
    linear_.set_near_null_space(problem.near_null_space(u, t));
  }

  // Returns |R|, or -1 with `error` set when the problem threw.
  std::string error;
  const auto assemble = [&] { return assemble_residual(problem, u, t, w.n, w.R, w.K, r, error); };
  const auto finish = [&a](NewtonOutcome outcome, std::string message) {
    a.outcome = outcome;
    a.message = std::move(message);
  };

  const double r0 = assemble();
  if (r0 < 0.0) return finish(NewtonOutcome::assembly_failed, "assembly of R_0: " + error);
  // Divergence is judged against the run's force scale, not only this step's |R_0|: after a
  // cutback |R_0| shrinks with dt, but a contact point that closes in the step adds a force of
  // the size of the penalty times its gap at once, however small dt is.
  w.r0_max = std::max(w.r0_max, r0);
  const double r_div = s.divergence_ratio * w.r0_max;
  a.residual_norms.push_back(r0);
  if (!std::isfinite(r0)) return finish(NewtonOutcome::not_finite, "|R_0| is not finite");
  // The absolute residual test (residual_floor), with the run's force scale so far.
  const auto r_abs = [&] { return residual_floor(s, w.r0_max, problem); };
  if (r0 <= r_abs()) return finish(NewtonOutcome::converged, {});

  const bool energy_test = s.tol_energy_rel > 0.0 || s.tol_energy_abs > 0.0;
  double e1 = 0.0;
  double r_prev = r0;
  int increases = 0;
  for (int k = 1; k <= s.max_iterations; ++k) {
    // K du_k = -R_{k-1}
    w.rhs = -w.R;
    const LinearSolveStatus ls = solve_correction(linear_, w.K, w.rhs, w.du, a, r);
    if (ls != LinearSolveStatus::success)
      return finish(
          NewtonOutcome::linear_solve_failed,
          format("iteration %d: linear solve %s: %s", k, to_string(ls), linear_.message().c_str()));
    if (k == 1 && a.iterations == 0) a.predicted = std::max(a.predicted, problem.norm(w.du));
    a.iterations = k;

    const double e = std::abs(problem.dot(w.du, w.R));  // E_k = |du_k . R_{k-1}|
    a.energy_norms.push_back(e);
    if (!std::isfinite(e))
      return finish(NewtonOutcome::not_finite, format("iteration %d: E is not finite", k));
    if (k == 1) e1 = std::max(e, e1_step);

    u += w.du;
    double rk = assemble();
    // Re-solves after a multiplier update: backtrack a correction that raises |R| (points
    // flipping between stick and slip can make full Newton steps cycle), halving it up to
    // four times while |R| stays above |R_{k-1}|.
    for (int half = 0; break_cycles && rk > r_prev && half < 4; ++half) {
      w.du *= 0.5;
      u -= w.du;
      rk = assemble();
    }
    if (!record_residual(rk, k, error, a)) return;

    const bool residual_ok = rk <= r_abs() || rk <= s.tol_residual_rel * std::max(r0, r0_step);
    const bool energy_ok = !energy_test || e <= s.tol_energy_rel * e1 || e <= s.tol_energy_abs;
    if (residual_ok && energy_ok) return finish(NewtonOutcome::converged, {});
    // At the round-off floor no iteration can do better: converged whatever the energy says.
    if (const double floor = problem.residual_roundoff(); floor > 0.0 && rk <= floor)
      return finish(NewtonOutcome::converged, {});

    if (std::string why = divergence(s, k, rk, r_prev, r_div, w.r0_max, increases); !why.empty())
      return finish(NewtonOutcome::diverged, std::move(why));
    r_prev = rk;
  }
  const double e_last = a.energy_norms.empty() ? 0.0 : a.energy_norms.back();
  finish(NewtonOutcome::max_iterations,
         format("no convergence in %d iterations (|R| = %.3e, |R|/|R_0| = %.3e, E/E_1 = %.3e)",
                s.max_iterations, a.residual_norms.back(), a.residual_norms.back() / r0,
                e1 > 0.0 ? e_last / e1 : 0.0));
}

bool NonlinearSolver::linear_step(NonlinearProblem& problem, VectorXd& u, const VectorXd& u_ref,
                                  double t, Workspace& w, StepAttempt& a, NonlinearSolverResult& r,
                                  bool& factorized, bool certify) {
  const NonlinearSolverSettings& s = settings_;
  std::string error;
  // R(u_0, t) (first step: with K_0, factorized below; later steps: R alone).
  double r0 = -1.0;
  if (!factorized) {
    linear_.set_symmetric(problem.symmetric());
    linear_.set_distributed(problem.distributed(), problem.layout());
    if (linear_.method() == LinearMethod::krylov)
      linear_.set_near_null_space(problem.near_null_space(u_ref, t));
    r0 = assemble_residual(problem, u_ref, t, w.n, w.R, w.K, r, error);
  } else {
    r0 = assemble_rhs(problem, u_ref, t, w.n, w.R, r, error);
  }
  if (!record_residual(r0, 0, error, a)) return true;
  w.r0_max = std::max(w.r0_max, r0);
  w.rhs = -w.R;
  LinearSolveStatus ls = LinearSolveStatus::success;
  if (!factorized) {
    ls = solve_correction(linear_, w.K, w.rhs, w.du, a, r);
    factorized = ls == LinearSolveStatus::success;
  } else {
    ls = solve_again(linear_, w.rhs, w.du, r);
  }
  if (ls != LinearSolveStatus::success) {
    a.outcome = NewtonOutcome::linear_solve_failed;
    a.message =
        format("linear path: linear solve %s: %s", to_string(ls), linear_.message().c_str());
    return true;
  }
  a.iterations = 1;
  a.predicted = problem.norm(w.du);
  a.energy_norms.push_back(std::abs(problem.dot(w.du, w.R)));
  u = u_ref + w.du;
  if (!w.du.allFinite()) {
    a.outcome = NewtonOutcome::not_finite;
    a.message = "linear path: the solution is not finite";
    return true;
  }
  if (!certify) {
    a.outcome = NewtonOutcome::converged;
    return true;
  }
  // The residual test of a Newton iteration (newton()) on R(u, t).
  const double rk = assemble_rhs(problem, u, t, w.n, w.R, r, error);
  if (!record_residual(rk, 1, error, a)) return true;
  const double r_abs = residual_floor(s, w.r0_max, problem);
  if (rk <= r_abs || rk <= s.tol_residual_rel * r0) {
    a.outcome = NewtonOutcome::converged;
    return true;
  }
  a.message = format("|R| = %.3e after the linear solve, above the residual test's %.3e", rk,
                     std::max(r_abs, s.tol_residual_rel * r0));
  return false;
}

namespace detail {

/// A checkpoint that cannot be resumed with n unknowns: std::invalid_argument.
void check_resume(const SolverCheckpoint& c, int n) {
  const auto bad = [](const std::string& what) {
    throw std::invalid_argument("NonlinearSolver::solve: resume: " + what);
  };
  if (c.u_prev.size() != 0 && c.u_prev.size() != n)
    bad("u_prev has size " + std::to_string(c.u_prev.size()) + ", the problem has " +
        std::to_string(n) + " unknowns");
  if (c.du_prev.size() != 0 && c.du_prev.size() != n)
    bad("du_prev has size " + std::to_string(c.du_prev.size()) + ", the problem has " +
        std::to_string(n) + " unknowns");
  if (!std::isfinite(c.t) || c.steps < 0 || c.attempted < c.steps || !(c.force_scale >= 0.0) ||
      !(c.dl >= 0.0) || !(c.dl_min >= 0.0) || !(c.dl_max >= c.dl_min) || !std::isfinite(c.dt))
    bad("its values are not those of a converged step (t " + format("%.9g", c.t) + ", steps " +
        std::to_string(c.steps) + ")");
}

/// The counts of a resumed run: its time, steps, attempts and force scale from the checkpoint
/// (none: a fresh run, nothing changed).
void resume_counts(const SolverCheckpoint* resume, NonlinearSolverResult& r, int& attempted,
                   double& force_scale) {
  if (resume == nullptr) return;
  const SolverCheckpoint& c = *resume;
  r.t = c.t;
  r.steps = c.steps;
  attempted = c.attempted;
  force_scale = c.force_scale;
}

/// The checkpoint of a converged step at t with the run's counts (resume_counts reads them back);
/// the step sizes are the caller's to set.
SolverCheckpoint counted_checkpoint(double t, const NonlinearSolverResult& r, int attempted,
                                    double force_scale) {
  SolverCheckpoint c;
  c.t = t;
  c.steps = r.steps;
  c.attempted = attempted;
  c.force_scale = force_scale;
  return c;
}

/// A saved step size within the (possibly new) bounds, or `fallback` where none was saved.
double resumed_step(double saved, double fallback, const NonlinearSolverSettings& s) {
  return saved > 0.0 ? std::clamp(saved, s.min_step, s.max_step) : fallback;
}

}  // namespace detail

void SolverCheckpoint::archive(StateArchive& a) {
  a.section("solver");
  a.io(t);
  a.io(steps);
  a.io(attempted);
  a.io(force_scale);
  a.io(dt);
  a.io(u_prev);
  a.io(t_prev);
  a.io(du_prev);
  a.io(dl);
  a.io(dl_min);
  a.io(dl_max);
  a.io(flat);
  a.io(dt_flat);
}

int NonlinearSolver::attempt_step(NonlinearProblem& problem, VectorXd& u, const VectorXd& u_ref,
                                  double t, Workspace& w, StepAttempt& a, NonlinearSolverResult& r,
                                  bool& linear_path, bool& factorized) {
  // Newton, then exact enforcement: multiplier updates and re-solves until they hold.
  if (!linear_path) return solve_fixed(problem, u, t, w, a, r);
  const bool certify = settings_.analysis == AnalysisKind::certified;
  if (linear_step(problem, u, u_ref, t, w, a, r, factorized, certify)) {
    a.linear = a.outcome == NewtonOutcome::converged;
    // A failure of the certified path leaves the step to Newton (cut back as any other).
    if (!a.linear && certify) linear_path = false;
    return 1;
  }
  // Not linear to the residual test: Newton from the linear state (the linear solve was its
  // first correction), in this step and the rest of the run.
  linear_path = false;
  r.linear_until = a.step;
  r.linear_message = a.message;
  if (log_)
    *log_ << format(
        "  step %d at t = %.9g: the linear path is not certified (%s); Newton from here on\n",
        a.step, t, a.message.c_str());
  // Its tests are those of the step's: against |R(u_0, t)| and the linear correction's
  // energy (from the linear state its own first ones are round-off).
  StepAttempt b;
  newton(problem, u, t, w, b, r, false, a.residual_norms.front(), a.energy_norms.front());
  const auto resolve = [&](StepAttempt& c, double r0) {
    newton(problem, u, t, w, c, r, /*break_cycles=*/true, r0);
  };
  const int hardest =
      1 + std::max(b.iterations, augment_until_satisfied(problem, u, t, b, resolve));
  append_resolve(a, b);
  a.augmentations += b.augmentations;
  a.outcome = b.outcome;
  a.message = b.message;
  return hardest;
}

NonlinearSolverResult NonlinearSolver::solve(NonlinearProblem& problem, VectorXd& u,
                                             const StepCallback& on_step,
                                             const SolverCheckpoint* resume) {
  const Clock::time_point start = Clock::now();
  const NonlinearSolverSettings& s = settings_;
  const int n = problem.num_dofs();
  if (u.size() != n)
    throw std::invalid_argument("NonlinearSolver::solve: u has size " + std::to_string(u.size()) +
                                ", the problem has " + std::to_string(n) + " unknowns");
  if (resume) check_resume(*resume, n);
  if (s.control == PathControl::arc_length) return solve_arc_length(problem, u, on_step, resume);

  NonlinearSolverResult r;
  r.t = s.t0;
  Workspace w(n);
  VectorXd u_last = u;  // the last converged state
  VectorXd u_prev;      // the one before it (secant predictor), at t_prev
  double t_prev = s.t0;

  const double span = s.t1 - s.t0;
  const double t_eps = 1e-12 * span;  // times closer than this to t1 are t1
  double t = s.t0;
  double dt = std::clamp(s.initial_step, s.min_step, s.max_step);
  int attempted = 0;
  bool ended = false;
  // The linear paths (AnalysisKind): every step from the start state, on one factorization.
  bool linear_path = linear_start(s.analysis, resume != nullptr);
  const VectorXd u_ref = linear_path ? u : VectorXd();
  bool factorized = false;
  if (resume) {
    resume_counts(resume, r, attempted, w.r0_max);
    t = resume->t;
    dt = resumed_step(resume->dt, dt, s);
    u_prev = resume->u_prev;
    t_prev = resume->t_prev;
  }
  checkpoint_ = {};

  while (!ended && s.t1 - t > t_eps) {
    if (attempted >= s.max_steps) {
      r.status = NonlinearSolverStatus::max_steps_reached;
      r.message = format("%d steps attempted (max_steps); last converged t = %.9g", attempted, t);
      break;
    }
    ++attempted;
    const double t_new = step_end(s, t, dt, t_eps);

    StepAttempt a;
    a.step = r.steps + 1;
    a.t_start = t;
    a.t = t_new;
    a.dt = t_new - t;
    int hardest_solve = 0;  // the most iterations of one Newton solve of the step
    if (s.secant_predictor && u_prev.size() == n && t > t_prev) {
      u = u_last + (a.dt / (t - t_prev)) * (u_last - u_prev);
      a.predicted = problem.norm(u - u_last);
    }
    const bool linear_try = linear_path;
    try {
      hardest_solve = attempt_step(problem, u, u_ref, t_new, w, a, r, linear_path, factorized);
    } catch (...) {
      u = u_last;
      problem.restore();
      throw;
    }
    add_attempt_totals(r, a);
    settle_attempt(a, r, s.analysis, std::min(dt, a.dt), s.min_step);

    if (a.outcome == NewtonOutcome::converged) {
      problem.synchronize(u);  // current everywhere: the callback reads any point
      record_jump(a, r, problem.norm(u - u_last));
      u_prev = u_last;
      t_prev = t;
      t = t_new;
      u_last = u;
      ++r.steps;
      r.t = t;
      r.step_iterations.push_back(a.iterations);
      const Clock::time_point t0 = Clock::now();
      problem.commit(u, t);
      r.time_callback += seconds_since(t0);
      if (log_) log_converged_step(*log_, r, a, t, (t - s.t0) / span, problem);
      // The linear paths keep initial_step: their steps are the output's times.
      if (!a.linear && hardest_solve <= s.easy_iterations)
        dt = std::min(dt * s.growth_factor, s.max_step);
      checkpoint_ = counted_checkpoint(t, r, attempted, w.r0_max);
      checkpoint_.dt = dt;
      checkpoint_.u_prev = u_prev;
      checkpoint_.t_prev = t_prev;
      bool go_on = true;
      if (on_step) {
        const Clock::time_point tc = Clock::now();
        go_on = on_step(u, t, a);
        r.time_callback += seconds_since(tc);
      }
      r.attempts.push_back(std::move(a));
      if (!go_on) {
        r.status = NonlinearSolverStatus::stopped;
        r.message = format("stopped by the step callback at t = %.9g", t);
        ended = true;
      }
    } else if (linear_try && s.analysis == AnalysisKind::linear) {
      // The linear analysis has no smaller step that could do better: the run ends.
      u = u_last;
      problem.restore();
      end_linear_run(log_, r, std::move(a), t);
      ended = true;
    } else {
      u = u_last;
      problem.restore();
      ++r.cutbacks;
      // The size tried: the nominal dt, or less where the step was cut at t1. (A step stretched
      // to t1 by less than min_step counts as its nominal size.)
      const double dt_tried = std::min(dt, a.dt);
      const bool at_min = dt_tried <= s.min_step * (1.0 + 1e-12);
      const double dt_next = std::max(dt_tried * s.cutback_factor, s.min_step);
      ended = report_failed_step(log_, r, a, format("dt = %.3e", a.dt),
                                 at_min ? "minimum step reached" : format("dt -> %.3e", dt_next),
                                 at_min, t);
      dt = dt_next;
      r.attempts.push_back(std::move(a));
    }
  }
  if (!ended && r.status == NonlinearSolverStatus::converged) {
    r.t = t;
    r.message = format("reached t1 = %.9g in %d steps", s.t1, r.steps);
  }
  r.time_total = seconds_since(start);
  if (log_) write_summary(*log_, r);
  return r;
}

void write_summary(std::ostream& os, const NonlinearSolverResult& r) {
  const int max_it = r.step_iterations.empty()
                         ? 0
                         : *std::max_element(r.step_iterations.begin(), r.step_iterations.end());
  int converged_iterations = 0;
  for (int it : r.step_iterations) converged_iterations += it;
  const double per_step = r.steps > 0 ? double(converged_iterations) / r.steps : 0.0;
  const double total = r.time_total > 0.0 ? r.time_total : 1.0;
  os << "load stepping: " << to_string(r.status) << ": " << r.message << '\n';
  os << format(
      "  steps %d, cutbacks %d, Newton iterations %d (%.2f per converged step, max %d), "
      "assemblies %d\n",
      r.steps, r.cutbacks, r.total_iterations, per_step, max_it, r.assemblies);
  os << format(
      "  wall time %.4f s: assembly %.4f s (%.1f %%), linear solves %.4f s (%.1f %%), "
      "commit and output %.4f s (%.1f %%)\n",
      r.time_total, r.time_assembly, 100.0 * r.time_assembly / total, r.time_linear_solve,
      100.0 * r.time_linear_solve / total, r.time_callback, 100.0 * r.time_callback / total);
  if (r.linear_steps > 0 || r.linear_until > 0) {
    os << format(
        "  linear path: %d step(s) on one tangent at the start state, assembled and factorized "
        "once (assemblies without the tangent %d)",
        r.linear_steps, r.residual_assemblies);
    if (r.linear_until > 0)
      os << format("; not certified at step %d (%s): Newton from there", r.linear_until,
                   r.linear_message.c_str());
    os << '\n';
  }
  if (r.augmentations > 0)
    os << format("  augmentations %d (multiplier updates, each followed by a Newton re-solve)\n",
                 r.augmentations);
  if (r.petsc_factorizations > 0)
    os << format("  factorizations: PETSc (MUMPS or a Krylov preconditioner) %d\n",
                 r.petsc_factorizations);
  else
    os << format("  factorizations: CHOLMOD %d, LDL^T %d, UMFPACK %d (Cholesky fallbacks %d)\n",
                 r.cholmod_factorizations, r.ldlt_factorizations, r.umfpack_factorizations,
                 r.cholesky_fallbacks);
  if (r.jumps > 0)
    os << format(
        "  warning: %d step(s) landed more than %.0f times beyond the tangent's prediction (see "
        "'jump' in the step lines): the path likely passes a limit point there and load control "
        "jumped to another branch; \"control\": \"arc_length\" follows the path through it\n",
        r.jumps, kJumpRatio);
}

}  // namespace iga
