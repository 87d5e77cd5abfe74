// Arc length [Cri81]: NonlinearSolver::solve_arc_length and its predictor, corrector and landing
// on t1 and hit times (nonlinear_solver.hpp: PathControl::arc_length). Notation as in
// nonlinear_solver.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <utility>

#include "iga/core/state_archive.hpp"
#include "iga/solvers/nonlinear_solver.hpp"
#include "iga/solvers/solver_steps.hpp"

namespace iga {

using namespace detail;

struct NonlinearSolver::ArcState {
  VectorXd u_last;      // the last converged state u_n
  double t = 0.0;       // its t_n
  VectorXd du_prev;     // the last converged step's increment (empty before the first)
  double dl = 0.0;      // the arc length of the next step (0: not yet set)
  double dl_min = 0.0;  // bounds of dl, set with it
  double dl_max = 0.0;
  bool flat = false;     // the last predictor found dR/dt = 0: a load step instead
  double dt_flat = 0.0;  // the size of such load steps (initial_step, cut back on failure)
  /// The size of the next step (dl, or dt_flat for a load step) and its minimum.
  double size() const { return flat ? dt_flat : dl; }
  double min_size(const NonlinearSolverSettings& s) const { return flat ? s.min_step : dl_min; }
  VectorXd R_h, R_t, du_R, du_t, du;  // workspace

  // A resumed run: the state of the checkpoint; the arc length and its bounds as the first
  // run set them (from its first tangent). None: a fresh run, nothing changed.
  void resume_from(const SolverCheckpoint* resume, const NonlinearSolverSettings& s) {
    if (resume == nullptr) return;
    const SolverCheckpoint& c = *resume;
    t = c.t;
    du_prev = c.du_prev;
    dl = c.dl;
    dl_min = c.dl_min;
    dl_max = c.dl_max;
    flat = c.flat;
    dt_flat = resumed_step(c.dt_flat, dt_flat, s);
  }
  // The checkpoint after a converged step (the step sizes of the next one).
  SolverCheckpoint checkpoint(const NonlinearSolverResult& r, int attempted,
                              double force_scale) const {
    SolverCheckpoint c = counted_checkpoint(t, r, attempted, force_scale);
    c.du_prev = du_prev;
    c.dl = dl;
    c.dl_min = dl_min;
    c.dl_max = dl_max;
    c.flat = flat;
    c.dt_flat = dt_flat;
    return c;
  }
};

namespace {

/// dR/dt at (u, t) by a one-sided difference of step h (exact where the loads and prescribed
/// values are linear in t) into R_t, then R and K at (u, t), so that the last assembly is the
/// state's own. The difference comes from the loads alone where the problem can give it
/// (NonlinearProblem::load_rate: counted in r.load_rates; `try_loads`), else from an assembly
/// at t + h.
/// Returns |R|, or -1 with `error` set.
double assemble_with_rate(NonlinearProblem& problem, const VectorXd& u, double t, double h, int n,
                          VectorXd& R_h, VectorXd& R, SparseMatrix& K, VectorXd& R_t,
                          NonlinearSolverResult& r, std::string& error, bool try_loads) {
  bool from_loads = false;
  const Clock::time_point start = Clock::now();
  try {
    from_loads = try_loads && problem.load_rate(u, t, h, R_t);
  } catch (const std::exception& e) {
    error = e.what();
    return -1.0;
  }
  r.time_assembly += seconds_since(start);
  if (from_loads) {
    ++r.load_rates;
    return assemble_residual(problem, u, t, n, R, K, r, error);
  }
  if (assemble_rhs(problem, u, t + h, n, R_h, r, error) < 0.0) return -1.0;
  const double rn = assemble_residual(problem, u, t, n, R, K, r, error);
  if (rn >= 0.0) R_t = (R_h - R) / h;
  return rn;
}

/// The load increment dt of a correction from the cylindrical constraint
/// |base + dt du_t|^2 = dl^2 (base = Delta u + du_R): a dt^2 + b dt + c = 0 [Cri81], the root
/// whose new increment is nearest the current Du. Returns why there is none, or an empty string.
std::string constraint_root(const NonlinearProblem& p, const VectorXd& base, const VectorXd& du_t,
                            const VectorXd& Du, double dl, double& dt) {
  const double qa = p.dot(du_t, du_t);
  const double qb = 2.0 * p.dot(du_t, base);
  const double qc = p.dot(base, base) - dl * dl;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (!std::isfinite(disc)) return "the constraint's coefficients are not finite";
  if (disc < 0.0) return "the arc-length constraint has no real root";
  // Roots without cancellation.
  const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
  const double root1 = q / qa, root2 = q != 0.0 ? qc / q : root1;
  const double score1 = p.dot(base + root1 * du_t, Du);
  const double score2 = p.dot(base + root2 * du_t, Du);
  dt = score1 >= score2 ? root1 : root2;
  return {};
}

/// A converged arc-length step in `a`: the angle (degrees) between its increment Du and its
/// predictor into a.turn_deg, and the outcome: converged, or refused (diverged, with why) if
/// the angle is above max_turn_deg and the arc can still be cut (`can_cut`).
void finish_arc_step(const NonlinearProblem& p, StepAttempt& a, const VectorXd& Du,
                     const VectorXd& predictor, double max_turn_deg, bool can_cut) {
  const double nn = p.norm(Du) * p.norm(predictor);
  const double c = nn > 0.0 ? std::clamp(p.dot(Du, predictor) / nn, -1.0, 1.0) : 1.0;
  a.turn_deg = std::acos(c) * 180.0 / std::numbers::pi;
  a.outcome = NewtonOutcome::converged;
  a.message.clear();
  if (a.turn_deg <= max_turn_deg || !can_cut) return;
  a.outcome = NewtonOutcome::diverged;
  a.message = format(
      "converged, but the increment turned %.1f degrees from the predictor (max_turn_deg %.1f): "
      "the arc is too long for the path's bend",
      a.turn_deg, max_turn_deg);
}

/// The energy test of an arc-length iteration (off when both tolerances are 0): E <=
/// tol_energy_rel E_1 or E <= tol_energy_abs; or, with |R| at its floor, E below its round-off
/// floor (machine epsilon times the step's work scale: its force scale times its increment Du,
/// whose norm, a reduction over the processes, is taken only there). Where E_1 is itself round-off
/// (a first correction all but orthogonal to the residual), E <= tol E_1 can never hold: the von
/// Mises truss under the round-off probe's seed 6 stalled at |R| = 1e-17 with E between 1e-36 and
/// 1e-34 for 20 iterations.
bool energy_passes(const NonlinearSolverSettings& s, double e, double e1, bool at_floor,
                   double scale, const NonlinearProblem& p, const VectorXd& Du) {
  if (!(s.tol_energy_rel > 0.0 || s.tol_energy_abs > 0.0)) return true;
  if (e <= s.tol_energy_rel * e1 || e <= s.tol_energy_abs) return true;
  return at_floor && e <= std::numeric_limits<double>::epsilon() * scale * p.norm(Du);
}

}  // namespace

bool NonlinearSolver::arc_predictor(NonlinearProblem& problem, VectorXd& u, ArcState& arc,
                                    Workspace& w, StepAttempt& a, NonlinearSolverResult& r,
                                    double& Dt) {
  const NonlinearSolverSettings& s = settings_;
  std::string error;
  const auto finish = [&a](NewtonOutcome outcome, std::string message) {
    a.outcome = outcome;
    a.message = std::move(message);
    return false;
  };
  const double h = 1e-7 * (s.t1 - s.t0);
  // Predictor: K du_t = -dR/dt at the converged state, Delta t = +-Delta l / |du_t|.
  u = arc.u_last;
  a.t = arc.t;
  if (assemble_with_rate(problem, u, arc.t, h, w.n, arc.R_h, w.R, w.K, arc.R_t, r, error,
                         s.rate_from_loads) < 0.0)
    return finish(NewtonOutcome::assembly_failed, "assembly at the step's start: " + error);
  w.rhs = -arc.R_t;
  const LinearSolveStatus ls = solve_correction(linear_, w.K, w.rhs, arc.du_t, a, r);
  if (ls != LinearSolveStatus::success)
    return finish(
        NewtonOutcome::linear_solve_failed,
        format("predictor: linear solve %s: %s", to_string(ls), linear_.message().c_str()));
  const double nt = problem.norm(arc.du_t);
  if (!std::isfinite(nt))
    return finish(NewtonOutcome::not_finite, "predictor: the tangent solution is not finite");
  arc.flat = !(nt > 0.0);
  if (arc.flat) {
    // Nothing depends on t here (e.g. a tool still away from the body): a load step of dt_flat.
    Dt = std::min(arc.dt_flat, s.t1 - arc.t);
    arc.du.setZero(w.n);
    return true;
  }
  if (arc.dl == 0.0) {
    arc.dl = s.initial_step * nt;
    arc.dl_min = arc.dl * s.min_step / s.initial_step;
    arc.dl_max = arc.dl * s.max_step / s.initial_step;
  }
  a.arc_length = arc.dl;
  // Forward at the first step; then on the side of the previous increment.
  const double side =
      arc.du_prev.size() == w.n && problem.dot(arc.du_t, arc.du_prev) < 0.0 ? -1.0 : 1.0;
  Dt = side * arc.dl / nt;
  arc.du = Dt * arc.du_t;
  return true;
}

void NonlinearSolver::arc_newton(NonlinearProblem& problem, VectorXd& u, ArcState& arc,
                                 Workspace& w, StepAttempt& a, NonlinearSolverResult& r) {
  const NonlinearSolverSettings& s = settings_;
  linear_.set_symmetric(problem.symmetric());
  linear_.set_distributed(problem.distributed(), problem.layout());
  if (linear_.method() == LinearMethod::krylov)  // the step's start (Newton's, there)
    linear_.set_near_null_space(problem.near_null_space(arc.u_last, arc.t));
  a.residual_norms.reserve(static_cast<std::size_t>(s.max_iterations) + 1);
  std::string error;
  const auto finish = [&a](NewtonOutcome outcome, std::string message) {
    a.outcome = outcome;
    a.message = std::move(message);
  };
  const double h_base = 1e-7 * (s.t1 - s.t0);
  const auto assemble = [&](double t, double direction) {
    return assemble_with_rate(problem, u, t, direction < 0.0 ? -h_base : h_base, w.n, arc.R_h, w.R,
                              w.K, arc.R_t, r, error, s.rate_from_loads);
  };
  // K x = b with the current factorization (factorized by the caller).
  const auto solve = [&](const VectorXd& b, VectorXd& x) { return solve_again(linear_, b, x, r); };

  double Dt = 0.0;
  if (!arc_predictor(problem, u, arc, w, a, r, Dt)) return;
  if (arc.flat) {  // a load-controlled step
    a.t = arc.t + Dt;
    a.dt = Dt;
    u = arc.u_last;
    return newton(problem, u, a.t, w, a, r);
  }
  VectorXd& Du = arc.du;
  const VectorXd predictor = Du;
  LinearSolveStatus ls = LinearSolveStatus::success;
  // A converged step, unless its increment turned too far from the predictor.
  const auto converged = [&] {
    finish_arc_step(problem, a, Du, predictor, s.max_turn_deg, arc.dl > arc.dl_min * (1.0 + 1e-12));
  };

  double r0 = 0.0, scale = 0.0, e1 = 0.0, r_prev = 0.0;
  int increases = 0;
  const auto r_abs = [&] { return residual_floor(s, w.r0_max, problem); };
  for (int k = 0;; ++k) {
    u = arc.u_last + Du;
    a.t = arc.t + Dt;
    a.dt = Dt;
    const double rk = assemble(a.t, Dt);
    if (!record_residual(rk, k, error, a)) return;
    if (k == 0) {
      r0 = rk;
      // The force scale of the step: the load increment along the predictor, not only the
      // predictor's residual (small by construction).
      scale = std::max(r0, std::abs(Dt) * problem.norm(arc.R_t));
      w.r0_max = std::max(w.r0_max, scale);
      if (rk <= r_abs()) return converged();
    } else {
      const bool at_floor = rk <= r_abs();
      const bool residual_ok = at_floor || rk <= s.tol_residual_rel * scale;
      if (residual_ok && energy_passes(s, a.energy_norms.back(), e1, at_floor, scale, problem, Du))
        return converged();
      if (const double floor = problem.residual_roundoff(); floor > 0.0 && rk <= floor)
        return converged();
      if (std::string why =
              divergence(s, k, rk, r_prev, s.divergence_ratio * w.r0_max, w.r0_max, increases);
          !why.empty())
        return finish(NewtonOutcome::diverged, std::move(why));
    }
    r_prev = rk;
    if (k == s.max_iterations) break;

    // K du_R = -R, K du_t = -dR/dt (one factorization), then the load increment from the
    // constraint |Du + du_R + dt du_t|^2 = Delta l^2: a dt^2 + b dt + c = 0 [Cri81].
    w.rhs = -w.R;
    ls = solve_correction(linear_, w.K, w.rhs, arc.du_R, a, r);
    if (ls == LinearSolveStatus::success) {
      w.rhs = -arc.R_t;
      ls = solve(w.rhs, arc.du_t);
    }
    if (ls != LinearSolveStatus::success)
      return finish(NewtonOutcome::linear_solve_failed,
                    format("iteration %d: linear solve %s: %s", k + 1, to_string(ls),
                           linear_.message().c_str()));
    a.iterations = k + 1;
    double dt = 0.0;
    if (std::string why = constraint_root(problem, Du + arc.du_R, arc.du_t, Du, arc.dl, dt);
        !why.empty())
      return finish(NewtonOutcome::diverged, format("iteration %d: %s", k + 1, why.c_str()));
    w.du = arc.du_R + dt * arc.du_t;
    const double e = std::abs(problem.dot(w.du, w.R));
    a.energy_norms.push_back(e);
    if (!std::isfinite(e))
      return finish(NewtonOutcome::not_finite, format("iteration %d: E is not finite", k + 1));
    if (k == 0) e1 = e;
    Du += w.du;
    Dt += dt;
  }
  finish(NewtonOutcome::max_iterations,
         format("no convergence in %d iterations (|R| = %.3e, |R|/|R_0| = %.3e)", s.max_iterations,
                a.residual_norms.back(), a.residual_norms.back() / std::max(scale, 1e-300)));
}

int NonlinearSolver::solve_fixed(NonlinearProblem& problem, VectorXd& u, double t, Workspace& w,
                                 StepAttempt& a, NonlinearSolverResult& r) {
  newton(problem, u, t, w, a, r);
  const int first_solve = a.iterations;
  const auto resolve = [&](StepAttempt& b, double r0_step) {
    newton(problem, u, t, w, b, r, /*break_cycles=*/true, r0_step);
  };
  return std::max(first_solve, augment_until_satisfied(problem, u, t, a, resolve));
}

namespace {

/// The message of an arc-length run that converged: on t1, or past it (a failed landing at the
/// minimum arc length).
std::string arc_end_message(const NonlinearSolverSettings& s, int steps, double t) {
  if (t > s.t1 + 1e-12 * (s.t1 - s.t0))
    return format(
        "passed t1 = %.9g in %d arc-length steps, ending at t = %.9g (landing on t1 failed at "
        "the minimum arc length)",
        s.t1, steps, t);
  return format("reached t1 = %.9g in %d arc-length steps", s.t1, steps);
}

}  // namespace

void NonlinearSolver::land(NonlinearProblem& problem, VectorXd& u, const ArcState& arc,
                           Workspace& w, StepAttempt& a, NonlinearSolverResult& r, int& hardest) {
  const NonlinearSolverSettings& s = settings_;
  const double t_eps = 1e-12 * (s.t1 - s.t0);
  const double lo = std::min(arc.t, a.t), hi = std::max(arc.t, a.t);
  double target = NAN;  // the first time crossed
  const auto consider = [&](double tau) {
    if (tau > lo + t_eps && tau < hi - t_eps &&
        (std::isnan(target) || std::abs(tau - arc.t) < std::abs(target - arc.t)))
      target = tau;
  };
  for (double h : s.hit_times) consider(h);
  if (a.t > s.t1 - t_eps && arc.t < s.t1 - t_eps) {
    if (a.t < s.t1 + t_eps)
      a.t = s.t1;  // on t1 already
    else
      consider(s.t1);
  }
  if (std::isnan(target)) return;
  const VectorXd u_arc = u;
  const double t_arc = a.t;
  problem.restore();
  u = arc.u_last + ((target - arc.t) / (t_arc - arc.t)) * (u_arc - arc.u_last);
  StepAttempt b;
  const int it = solve_fixed(problem, u, target, w, b, r);
  append_resolve(a, b);
  a.augmentations += b.augmentations;
  if (b.outcome == NewtonOutcome::converged) {
    a.t = target;
    a.landed = true;
    hardest = std::max(hardest, it);
    return;
  }
  if (!arc.flat && arc.dl > arc.dl_min * (1.0 + 1e-12)) {
    // Cut back (the caller restores u and the problem): a shorter arc ends before the time or
    // starts its landing from closer by. Before, the arc state was kept here, and a run whose
    // last step overshot t1 ended beyond it reporting "reached t1".
    a.outcome = NewtonOutcome::landing_failed;
    a.message = format("landing on t = %.9g failed: %s", target, b.message.c_str());
    return;
  }
  // At the minimum arc length: keep the arc state, solved again at its t (a few iterations).
  problem.restore();
  u = u_arc;
  StepAttempt c;
  solve_fixed(problem, u, t_arc, w, c, r);
  append_resolve(a, c);
  a.augmentations += c.augmentations;
  a.outcome = c.outcome;
  a.message = c.message;
}

NonlinearSolverResult NonlinearSolver::solve_arc_length(NonlinearProblem& problem, VectorXd& u,
                                                        const StepCallback& on_step,
                                                        const SolverCheckpoint* resume) {
  const Clock::time_point start = Clock::now();
  const NonlinearSolverSettings& s = settings_;
  const int n = problem.num_dofs();
  NonlinearSolverResult r;
  r.t = s.t0;
  Workspace w(n);
  ArcState arc;
  arc.u_last = u;
  arc.t = s.t0;
  arc.dt_flat = s.initial_step;
  const double span = s.t1 - s.t0;
  const double t_eps = 1e-12 * span;
  int attempted = 0;
  bool ended = false;
  resume_counts(resume, r, attempted, w.r0_max);
  arc.resume_from(resume, s);
  checkpoint_ = {};

  while (!ended) {
    if (attempted >= s.max_steps) {
      r.status = NonlinearSolverStatus::max_steps_reached;
      r.message =
          format("%d steps attempted (max_steps); last converged t = %.9g", attempted, arc.t);
      break;
    }
    ++attempted;
    StepAttempt a;
    a.step = r.steps + 1;
    a.t_start = arc.t;
    int hardest_solve = 0;
    try {
      arc_newton(problem, u, arc, w, a, r);
      hardest_solve = a.iterations;
      if (a.outcome == NewtonOutcome::converged) {
        const double t_arc = a.t;
        const auto resolve = [&](StepAttempt& b, double r0_step) {
          newton(problem, u, t_arc, w, b, r, /*break_cycles=*/true, r0_step);
        };
        hardest_solve =
            std::max(hardest_solve, augment_until_satisfied(problem, u, t_arc, a, resolve));
      }
      if (a.outcome == NewtonOutcome::converged) land(problem, u, arc, w, a, r, hardest_solve);
    } catch (...) {
      u = arc.u_last;
      problem.restore();
      throw;
    }
    add_attempt_totals(r, a);
    a.dt = a.t - arc.t;
    probe_refusal(a, arc.size(), arc.min_size(s));

    if (a.outcome == NewtonOutcome::converged) {
      problem.synchronize(u);  // current everywhere: the callback reads any point
      arc.du_prev = u - arc.u_last;
      arc.u_last = u;
      arc.t = a.t;
      ++r.steps;
      r.t = arc.t;
      r.step_iterations.push_back(a.iterations);
      const Clock::time_point t0 = Clock::now();
      problem.commit(u, arc.t);
      r.time_callback += seconds_since(t0);
      if (log_) log_converged_step(*log_, r, a, arc.t, (arc.t - s.t0) / span, problem);
      // [Cri81]: Delta l sqrt(desired / N), within the growth and cutback factors.
      const double f =
          std::sqrt(static_cast<double>(s.desired_iterations) / std::max(hardest_solve, 1));
      if (!arc.flat)
        arc.dl = std::clamp(arc.dl * std::clamp(f, s.cutback_factor, s.growth_factor), arc.dl_min,
                            arc.dl_max);
      else if (hardest_solve <= s.easy_iterations)  // load steps grow as under load control
        arc.dt_flat = std::min(arc.dt_flat * s.growth_factor, s.max_step);
      checkpoint_ = arc.checkpoint(r, attempted, w.r0_max);
      bool go_on = true;
      if (on_step) {
        const Clock::time_point tc = Clock::now();
        go_on = on_step(u, arc.t, a);
        r.time_callback += seconds_since(tc);
      }
      r.attempts.push_back(std::move(a));
      if (arc.t >= s.t1 - t_eps) {
        ended = true;
      } else if (!go_on) {
        r.status = NonlinearSolverStatus::stopped;
        r.message = format("stopped by the step callback at t = %.9g", arc.t);
        ended = true;
      }
    } else {
      u = arc.u_last;
      problem.restore();
      ++r.cutbacks;
      if (arc.flat) {  // a load step failed
        const bool at_min = arc.dt_flat <= s.min_step * (1.0 + 1e-12);
        const double dt_next = std::max(arc.dt_flat * s.cutback_factor, s.min_step);
        ended = report_failed_step(log_, r, a, format("dt = %.3e", a.dt),
                                   at_min ? "minimum step reached" : format("dt -> %.3e", dt_next),
                                   at_min, arc.t);
        arc.dt_flat = dt_next;
      } else {
        const bool at_min = arc.dl <= arc.dl_min * (1.0 + 1e-12);
        const double dl_next = std::max(arc.dl * s.cutback_factor, arc.dl_min);
        ended = report_failed_step(
            log_, r, a, format("arc %.3e", arc.dl),
            at_min ? "minimum arc length reached" : format("arc -> %.3e", dl_next), at_min, arc.t);
        arc.dl = dl_next;
      }
      r.attempts.push_back(std::move(a));
    }
  }
  if (r.status == NonlinearSolverStatus::converged) r.message = arc_end_message(s, r.steps, arc.t);
  r.time_total = seconds_since(start);
  if (log_) write_summary(*log_, r);
  return r;
}

}  // namespace iga
