// The pieces of a nonlinear step that load control (nonlinear_solver.cpp) and arc length
// (arc_length.cpp) share: the assembly and the linear solve of one Newton iteration, timed and
// counted; the divergence tests; the augmentation loop of exact enforcement; the failed and
// converged steps' log lines; the counts of a resumed run. Internal to iga/solvers.
//
// Notation as in nonlinear_solver.hpp: R(u, t) the residual, K its tangent, du the correction,
// rk = |R_k| the norm at iteration k, a the step's attempt, r the run's result.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <string>

#include "iga/solvers/nonlinear_solver.hpp"

namespace iga {

/// A Newton iteration's storage, kept over a run.
struct NonlinearSolver::Workspace {
  explicit Workspace(int size) : n(size), R(size), rhs(size), du(size) {}
  int n = 0;
  VectorXd R;    // residual at the current iterate
  VectorXd rhs;  // -R
  VectorXd du;   // Newton correction
  SparseMatrix K;
  double r0_max = 0.0;  // the largest |R_0| of the run's attempts so far (divergence scale)
};

namespace detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// printf-style formatting into a std::string (GCC 12 has no std::format).
template <class... Args>
std::string format(const char* fmt, Args... args) {
  const int size = std::snprintf(nullptr, 0, fmt, args...);
  if (size <= 0) return {};
  std::string s(static_cast<std::size_t>(size), '\0');
  std::snprintf(s.data(), s.size() + 1, fmt, args...);
  return s;
}

/// R(u, t) into R and the tangent into K, timed and counted in r. Returns |R|, or -1 with
/// `error` set when the problem threw.
double assemble_residual(NonlinearProblem& problem, const VectorXd& u, double t, int n, VectorXd& R,
                         SparseMatrix& K, NonlinearSolverResult& r, std::string& error);

/// R(u, t) alone (no tangent) into R, timed and counted in r. Returns |R|, or -1 with `error`
/// set when the problem threw.
double assemble_rhs(NonlinearProblem& problem, const VectorXd& u, double t, int n, VectorXd& R,
                    NonlinearSolverResult& r, std::string& error);

/// The Newton correction: K du = rhs, timed in r, the factorizations counted in a by backend.
LinearSolveStatus solve_correction(LinearSolver& linear, const SparseMatrix& K, const VectorXd& rhs,
                                   VectorXd& du, StepAttempt& a, NonlinearSolverResult& r);

/// A solve on the factorization linear holds (no new factorization), timed in r.
LinearSolveStatus solve_again(LinearSolver& linear, const VectorXd& rhs, VectorXd& x,
                              NonlinearSolverResult& r);

/// The absolute residual test's bound: tol_residual_abs, scaled to the run's forces r0_max
/// (a floor for unloaded starts), and the problem's round-off (contact forces from large
/// penalties: an augmented Lagrangian with a raised eps_N cannot get |R| below it).
inline double residual_floor(const NonlinearSolverSettings& s, double r0_max,
                             const NonlinearProblem& problem) {
  return std::max(
      {s.tol_residual_abs, s.tol_residual_scaled * r0_max, problem.residual_roundoff()});
}

/// Tests only: the round-off probe's refusal of a converged step (roundoff_probe.hpp) of the
/// given size, never at the minimum size.
void probe_refusal(StepAttempt& a, double size, double min_size);

/// The divergence tests after iteration k: |R_k| above r_div, or |R| grew in
/// max_residual_increases consecutive iterations (`increases` counts them). Returns why the
/// iterations diverged, or an empty string.
std::string divergence(const NonlinearSolverSettings& s, int k, double rk, double r_prev,
                       double r_div, double r0_max, int& increases);

/// Records |R_k| = rk of iteration k in a; false (a's outcome set) when the assembly failed
/// (rk < 0, `error` says why) or rk is not finite.
bool record_residual(double rk, int k, const std::string& error, StepAttempt& a);

/// The end of the step from t with nominal size dt.
double step_end(const NonlinearSolverSettings& s, double t, double dt, double t_eps);

/// Adds a re-solve after a multiplier update (b) to the step's attempt a: its iterations,
/// norms and factorizations.
void append_resolve(StepAttempt& a, const StepAttempt& b);

/// The run's totals of an attempt, converged or not.
void add_attempt_totals(NonlinearSolverResult& r, const StepAttempt& a);

/// A failed attempt a of size `size` ("dt = ..." or "arc ..."): the log line with what comes next
/// (`next`); at the minimum size the run's status and message. Returns at_min (the run ends).
bool report_failed_step(std::ostream* log, NonlinearSolverResult& r, const StepAttempt& a,
                        const std::string& size, const std::string& next, bool at_min,
                        double t_last);

/// The progress line of converged step r.steps, at time t, lambda the fraction of the span done.
void log_converged_step(std::ostream& log, const NonlinearSolverResult& r, const StepAttempt& a,
                        double t, double lambda, const NonlinearProblem& problem);

/// A checkpoint that cannot be resumed with n unknowns: std::invalid_argument.
void check_resume(const SolverCheckpoint& c, int n);

/// The counts of a resumed run: its time, steps, attempts and force scale from the checkpoint
/// (none: a fresh run, nothing changed).
void resume_counts(const SolverCheckpoint* resume, NonlinearSolverResult& r, int& attempted,
                   double& force_scale);

/// The checkpoint of a converged step at t with the run's counts (resume_counts reads them back);
/// the step sizes are the caller's to set.
SolverCheckpoint counted_checkpoint(double t, const NonlinearSolverResult& r, int attempted,
                                    double force_scale);

/// A saved step size within the (possibly new) bounds, or `fallback` where none was saved.
double resumed_step(double saved, double fallback, const NonlinearSolverSettings& s);

/// Exact enforcement after the step's converged Newton solve: update multipliers and solve
/// again (resolve(b, r0_step): Newton at the same t into b, r0_step the step's first |R_0|)
/// until the constraints hold, or a re-solve or augment fails (a's outcome). Returns the most
/// iterations of one re-solve (0 without any).
template <class Resolve>
int augment_until_satisfied(NonlinearProblem& problem, const VectorXd& u, double t, StepAttempt& a,
                            Resolve&& resolve) {
  int hardest_resolve = 0;
  while (a.outcome == NewtonOutcome::converged) {
    const AugmentResult ar = problem.augment(u, t);
    if (ar.status == AugmentStatus::satisfied) break;
    if (ar.status == AugmentStatus::failed || ar.status == AugmentStatus::passed_through) {
      a.outcome = ar.status == AugmentStatus::failed ? NewtonOutcome::augmentation_failed
                                                     : NewtonOutcome::passed_through;
      a.message = ar.message;
      break;
    }
    ++a.augmentations;
    StepAttempt b;
    resolve(b, a.residual_norms.front());
    hardest_resolve = std::max(hardest_resolve, b.iterations);
    append_resolve(a, b);
    if (b.outcome != NewtonOutcome::converged) {
      a.outcome = b.outcome;
      a.message = format("after augmentation %d (%s): %s", a.augmentations, ar.message.c_str(),
                         b.message.c_str());
    }
  }
  return hardest_resolve;
}

}  // namespace detail

}  // namespace iga
