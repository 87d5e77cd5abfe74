// Bound-constrained Newton minimization in 1 or 2 parameters, shared by the closest point
// projections onto curves and surfaces ([KS15] eqs. 12, 16-18; Sect. 2.2 for the bounds).
// Internal header of contact/.
//
// The model supplies, at a parameter t, the objective f = 1/2 |x - rho(t)|^2 (12), its gradient
// g (16), Hessian H (17) and, per parameter, the scale |rho_i| |x - rho| that turns g_i into
// the cosine of the angle between x - rho and the tangent rho_i (the orthogonality residual).
// Algorithm: active set (a parameter at a bound whose gradient points out of the box is held),
// Newton step on the free parameters, Levenberg-Marquardt shift where the reduced Hessian is
// not positive definite (far points, concave sides), projection onto the box, and an Armijo
// backtracking line search; closed directions wrap around instead of being bounded.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "contact/projection.hpp"

namespace iga::detail {

template <int D>
struct LocalModel {
  using Vec = Eigen::Matrix<double, D, 1>;
  using Mat = Eigen::Matrix<double, D, D>;
  double f = 0.0;
  Vec g = Vec::Zero();
  Mat H = Mat::Zero();
  Vec scale = Vec::Ones();  ///< |rho_i| |x - rho| (> 0)
  bool has_hessian = true;  ///< false when evaluated with first derivatives only
};

template <int D>
struct NewtonOutcome {
  Eigen::Matrix<double, D, 1> t;
  int iterations = 0;
  int at_bound = 0;  ///< parameters resting on a bound at the end
  bool converged = false;
  double residual = 0.0;
};

template <int D>
struct Box {
  Eigen::Matrix<double, D, 1> lo, hi;
  bool wrap[D] = {};  ///< closed direction: periodic with period hi - lo
};

/// Symmetric positive definite test and a shift making it so (Levenberg-Marquardt).
template <int D>
Eigen::Matrix<double, D, D> make_positive(const Eigen::Matrix<double, D, D>& H, double floor) {
  double min_eig;
  if constexpr (D == 1) {
    min_eig = H(0, 0);
  } else {
    const double tr = H(0, 0) + H(1, 1);
    const double det = H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0);
    const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
    min_eig = 0.5 * tr - disc;
  }
  if (min_eig >= floor) return H;
  Eigen::Matrix<double, D, D> Hs = H;
  Hs.diagonal().array() += (floor - min_eig);
  return Hs;
}

/// H^-1 g for a symmetric positive definite H (make_positive's): the closed form (Cramer's
/// rule; as accurate as a factorization for a 2 x 2 whose condition number make_positive
/// keeps below 1e10); not finite when H is singular to round-off.
template <int D>
Eigen::Matrix<double, D, 1> solve_spd(const Eigen::Matrix<double, D, D>& H,
                                      const Eigen::Matrix<double, D, 1>& g) {
  if constexpr (D == 1) {
    return Eigen::Matrix<double, 1, 1>(g[0] / H(0, 0));
  } else {
    const double det = H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0);
    return Eigen::Vector2d(H(1, 1) * g[0] - H(0, 1) * g[1], H(0, 0) * g[1] - H(1, 0) * g[0]) / det;
  }
}
/// Parameter i rests at a bound with the gradient pointing out of the box (a closed direction
/// has no bounds): the active set, held fixed in the step.
template <int D>
bool held_at_bound(const LocalModel<D>& m, const Eigen::Matrix<double, D, 1>& t, const Box<D>& box,
                   int i) {
  return !box.wrap[i] &&
         ((t[i] <= box.lo[i] && m.g[i] > 0.0) || (t[i] >= box.hi[i] && m.g[i] < 0.0));
}

/// Largest |g_i| / scale_i over the parameters not held at a bound.
template <int D>
double projected_residual(const LocalModel<D>& m, const Eigen::Matrix<double, D, 1>& t,
                          const Box<D>& box) {
  double res = 0.0;
  for (int i = 0; i < D; ++i) {
    const bool held = held_at_bound<D>(m, t, box, i);
    if (!held) res = std::max(res, std::abs(m.g[i]) / m.scale[i]);
  }
  return res;
}

/// Moves s into the box: clamped to the bounds, wrapped around in a closed direction.
template <int D>
void into_box(Eigen::Matrix<double, D, 1>& s, const Box<D>& box) {
  for (int i = 0; i < D; ++i) {
    if (box.wrap[i]) {
      if (s[i] >= box.lo[i] && s[i] < box.hi[i]) continue;  // inside: as it is
      const double period = box.hi[i] - box.lo[i];
      double r = std::fmod(s[i] - box.lo[i], period);
      if (r < 0) r += period;
      s[i] = box.lo[i] + r;
    } else {
      s[i] = std::clamp(s[i], box.lo[i], box.hi[i]);
    }
  }
}

/// Step tolerance: relative to the box size (or to 1 + |t| where unbounded).
template <int D>
Eigen::Matrix<double, D, 1> step_tolerance(const Eigen::Matrix<double, D, 1>& t, const Box<D>& box,
                                           const ProjectionOptions& opt) {
  Eigen::Matrix<double, D, 1> step_tol;
  for (int i = 0; i < D; ++i) {
    const double w = box.hi[i] - box.lo[i];
    step_tol[i] = opt.tol_step * (std::isfinite(w) ? w : 1.0 + std::abs(t[i]));
  }
  return step_tol;
}

/// The gradient and Hessian restricted to the free parameters: a held parameter's row and
/// column become those of the identity and its gradient entry 0, so the step leaves it alone.
template <int D>
void reduce_to_free(const bool (&active)[D], Eigen::Matrix<double, D, D>& H,
                    Eigen::Matrix<double, D, 1>& g) {
  for (int i = 0; i < D; ++i)
    if (active[i]) {
      H.row(i).setZero();
      H.col(i).setZero();
      H(i, i) = 1.0;
      g[i] = 0.0;
    }
}

/// A point tried by the line search: its parameters, the step taken to it from the current
/// iterate, and its model.
template <int D>
struct Trial {
  Eigen::Matrix<double, D, 1> t;
  Eigen::Matrix<double, D, 1> taken = Eigen::Matrix<double, D, 1>::Zero();
  LocalModel<D> m;
};

/// Projected Armijo backtracking from t (model m) along dir; on success `trial` holds the
/// accepted point, whose model (of order trial_order) is reused as the next iterate's, so an
/// iteration costs one evaluation when the full step is taken.
template <int D, class Eval>
bool projected_line_search(Eval& eval, const LocalModel<D>& m, const Eigen::Matrix<double, D, 1>& t,
                           const Eigen::Matrix<double, D, 1>& dir, const Box<D>& box,
                           int trial_order, Trial<D>& trial) {
  double alpha = 1.0;
  for (int ls = 0; ls < 40; ++ls) {
    trial.t = t + alpha * dir;
    into_box<D>(trial.t, box);
    trial.taken = trial.t - t;
    for (int i = 0; i < D; ++i)  // a wrapped step is the short way round
      if (box.wrap[i]) trial.taken[i] = alpha * dir[i];
    const double slope = m.g.dot(trial.taken);
    if (slope < 0.0) {
      trial.m = eval(trial.t, trial_order);
      if (trial.m.f <= m.f + 1e-4 * slope) return true;
      // Near the solution the decrease (~ slope) drops below the round-off of f itself
      // and Armijo cannot see it; there the projected gradient is the merit instead.
      if (-slope <= 1e-10 * m.f &&
          projected_residual<D>(trial.m, trial.t, box) < projected_residual<D>(m, t, box))
        return true;
    }
    alpha *= 0.5;
  }
  return false;
}

/// Every component of the step is within its tolerance.
template <int D>
bool step_is_small(const Eigen::Matrix<double, D, 1>& taken,
                   const Eigen::Matrix<double, D, 1>& step_tol) {
  bool small = true;
  for (int i = 0; i < D; ++i) small = small && std::abs(taken[i]) <= step_tol[i];
  return small;
}

/// Parameters resting on a bound (closed directions have none).
template <int D>
int count_at_bound(const Eigen::Matrix<double, D, 1>& t, const Box<D>& box) {
  int n = 0;
  for (int i = 0; i < D; ++i)
    if (!box.wrap[i] && (t[i] <= box.lo[i] || t[i] >= box.hi[i])) ++n;
  return n;
}

/// Minimizes the model over the box from t0. `eval(t, order)` returns LocalModel<D> with the
/// Hessian when order == 2; with order == 1 only f, g and scale (has_hessian = false). The
/// solver asks for order 1 where quadratic convergence predicts that the trial point is the
/// answer (the residual before the step is below sqrt(tol) 10), and completes the Hessian
/// only if it is not.
template <int D, class Eval>
NewtonOutcome<D> bounded_newton(Eval&& eval, Eigen::Matrix<double, D, 1> t, const Box<D>& box,
                                const ProjectionOptions& opt) {
  using Vec = Eigen::Matrix<double, D, 1>;
  using Mat = Eigen::Matrix<double, D, D>;
  const Vec step_tol = step_tolerance<D>(t, box, opt);

  NewtonOutcome<D> out;
  into_box<D>(t, box);
  LocalModel<D> m = eval(t, 2);
  const double predict_tol = 10.0 * std::sqrt(opt.tol_residual);
  for (int it = 0; it < opt.max_iterations; ++it) {
    // Active set (held at a bound) and the projected-gradient (orthogonality) residual.
    bool active[D];
    for (int i = 0; i < D; ++i) active[i] = held_at_bound<D>(m, t, box, i);
    const double res = projected_residual<D>(m, t, box);
    out.residual = res;
    if (res <= opt.tol_residual) {
      out.converged = true;
      break;
    }
    if (!m.has_hessian) m = eval(t, 2);  // the prediction failed: complete the model
    out.iterations = it + 1;
    const int trial_order = res <= predict_tol ? 1 : 2;
    // Newton step on the free parameters, with a positive definite (shifted) Hessian.
    Mat H = m.H;
    Vec g = m.g;
    reduce_to_free<D>(active, H, g);
    const double hmax = H.cwiseAbs().maxCoeff();
    const Mat Hp = make_positive<D>(H, 1e-10 * hmax + 1e-300);
    Vec newton = -solve_spd<D>(Hp, g);
    if (!newton.allFinite()) newton = -g / (hmax + 1e-300);

    // Clamping can spoil the Newton direction at the bounds (coupled H); the projected
    // steepest descent direction always decreases f while the projected gradient is not zero.
    Trial<D> trial;
    trial.t = t;
    bool accepted = projected_line_search<D>(eval, m, t, newton, box, trial_order, trial);
    if (!accepted)
      accepted =
          projected_line_search<D>(eval, m, t, Vec(-g / (hmax + 1e-300)), box, trial_order, trial);
    if (!accepted) {
      // No decrease at this precision along either direction: a minimum to round-off.
      out.converged = true;
      break;
    }
    // A small step that brought a parameter onto a bound is no answer yet: with the active set
    // it changes, the next step may go on along the other parameter (seen: a start 1e-16
    // inside u's bound, the coupled Newton step clamped in u and in v at a corner that is no
    // minimum, 1e-7 of 1.7e-3 farther than the edge's minimum next to it).
    bool newly_bound = false;
    for (int i = 0; i < D; ++i)
      newly_bound = newly_bound || (!box.wrap[i] && trial.t[i] != t[i] &&
                                    (trial.t[i] <= box.lo[i] || trial.t[i] >= box.hi[i]));
    t = trial.t;
    m = trial.m;
    if (step_is_small<D>(trial.taken, step_tol) && !newly_bound) {
      out.converged = true;
      out.residual = projected_residual<D>(m, t, box);
      break;
    }
  }
  out.t = t;
  if (!out.converged) out.residual = projected_residual<D>(m, t, box);
  out.at_bound = count_at_bound<D>(t, box);
  return out;
}

}  // namespace iga::detail
