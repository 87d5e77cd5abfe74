// Exact enforcement of the normal contact constraint by an augmented Lagrangian with Uzawa
// updates between Newton solves of a load step (docs/contact.md, "Enforcement"), shared by the
// CTRS (iga/contact_integrals/curve_contact.hpp) and STAS
// (iga/contact_integrals/surface_contact.hpp) integrals.
//
// Notation: lambda_N <= 0 the multiplier of a contact point (a force per unit length or area,
// like N), xi^3 its gap (52), eps_N the penalty, N = min(0, lambda_N + eps_N xi^3) ((34)
// augmented, contact/contact_law.hpp).
//
// After Newton has converged at a load step (the integral's points hold the state of that
// assembly), the largest |xi^3| over the active points (N < 0) is compared with the tolerance:
// exact enforcement means xi^3 = 0 wherever there is a force, so a point held above the surface
// by its multiplier (xi^3 > 0, N < 0) violates the constraint as much as a penetrating one. If
// it is above the tolerance, every point's multiplier becomes its current force,
// lambda_N <- N (0 where the point is apart), and the step is solved again. A point that stays
// in contact then carries lambda_N from the start of the re-solve and its gap shrinks to
// (N_new - lambda_N) / eps_N, the change of its force between solves over eps_N. Multipliers
// are committed with the history at converged steps and restored when a step is cut back. The
// first solve of a step starts from multipliers extrapolated from the last two commits
// (NormalAugmentation::predict), which spares the update where the force grows steadily.
// With slip_tol > 0 the same updates augment the stick constraint: lambda_T <- T, so that a
// sticking point's slip since its anchor |g_T| shrinks to the change of its force between
// solves over eps_T (ContactEnforcement, contact/contact_law.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "contact/contact_law.hpp"
#include "iga/core/nonlinear_problem.hpp"

namespace iga {

/// The multipliers of one contact point (the point types of the integrals derive from it).
struct ContactMultipliers {
  double lambda_n = 0.0;            ///< normal multiplier lambda_N (augmented Lagrange), <= 0
  double lambda_n_committed = 0.0;  ///< lambda_N at the last converged step
  double lambda_n_before = 0.0;     ///< lambda_N at the commit before (predictor)
  /// Tangential multiplier lambda_T (slip_tol > 0), in the form the integral's law carries the
  /// tangential force (a 3-D vector, or covariant components in the first two entries).
  Vector3d lambda_t = Vector3d::Zero();
};

/// The multipliers' bookkeeping of one contact integral; Point derives from ContactMultipliers.
struct NormalAugmentation {
  int step_updates = 0;      ///< updates since the last commit or restore
  int total_updates = 0;     ///< updates since construction
  double max_gap = 0.0;      ///< max |xi^3| of the active points at the last augment() call
  double t_last = 0.0;       ///< time of the last prediction (assembly)
  double t_committed = 0.0;  ///< time of the last commit
  double t_before = 0.0;     ///< time of the commit before it
  int commits = 0;
  /// Factor on eps_N of the augmented law (1 at the start). An update that left the largest
  /// |gap| above half of its value at the update before (in the same step) multiplies it by 4,
  /// up to 1e3: where the body cannot follow the surface at every contact point, the updates
  /// shift force between neighbouring points by eps_N |gap| each and stall; a larger eps_N
  /// moves more force per update and leaves a smaller gap for the same imbalance (the method
  /// of multipliers with an increasing penalty, Bertsekas). Kept for the rest of the run.
  double eps_scale = 1.0;
  double previous_gap = 0.0;   ///< max |gap| at the last update of this step (0: none yet)
  double max_slip = 0.0;       ///< max |g_T| of the sticking points at the last augment() call
  double previous_slip = 0.0;  ///< max |g_T| at the last update of this step (0: none yet)
  /// Factor on eps_T of the augmented law, raised like eps_scale when the stick updates stall
  /// (a body much stiffer than eps_T per contact point moves little per update). Unlike
  /// eps_scale it goes back to 1 at every commit and restore: a stiff tangential law makes
  /// Newton fragile where points change between stick and slip (kept across steps, it made one
  /// capstan case of 23 fail at slip_tol 1e-6), so it is raised only within a step.
  double eps_t_scale = 1.0;
  /// The tangential multipliers lambda_T replace the committed forces in (66): set by an
  /// update with slip_tol > 0, cleared at a commit and a restore.
  bool tangential = false;

  /// Predictor for the first solve of a step at time t (before any update of the step): the
  /// multipliers extrapolated linearly in t from the last two commits, lambda_N = min(0,
  /// lambda_c + (t - t_c) / (t_c - t_b) (lambda_c - lambda_b)), so that a steadily growing
  /// contact force is met without an update; lambda_c at t = t_c (output, reactions).
  template <class Point>
  void predict(std::vector<Point>& points, const ContactEnforcement& e, double t) {
    if (!e.augmented || step_updates > 0) return;
    t_last = t;
    const double span = t_committed - t_before;
    const double ratio = commits >= 2 && span > 0.0 ? (t - t_committed) / span : 0.0;
    for (ContactMultipliers& m : points)
      m.lambda_n =
          std::min(0.0, m.lambda_n_committed + ratio * (m.lambda_n_committed - m.lambda_n_before));
  }
  /// At a commit: the points' multipliers and the times of the last two commits.
  template <class Point>
  void commit(std::vector<Point>& points) {
    for (ContactMultipliers& m : points) {
      m.lambda_n_before = m.lambda_n_committed;
      m.lambda_n_committed = m.lambda_n;
    }
    step_updates = 0;
    previous_gap = previous_slip = 0.0;
    tangential = false;
    eps_t_scale = 1.0;
    t_before = t_committed;
    t_committed = t_last;
    ++commits;
  }

  /// After a cut-back: the step starts again from the committed multipliers.
  template <class Point>
  void restore(std::vector<Point>& points) {
    for (ContactMultipliers& m : points) m.lambda_n = m.lambda_n_committed;
    step_updates = 0;
    previous_gap = previous_slip = 0.0;
    tangential = false;
    eps_t_scale = 1.0;
  }

  /// The integral is one part of a pair spread over several processes (its body is cut into
  /// blocks, BodySystem::distribute): takes each value to its maximum over the parts, on every
  /// process alike (a collective operation: every part calls it at the same update). Null: the
  /// pair is whole here.
  std::function<void(std::span<double>)> parts_max;

  /// The check after a converged Newton solve: `through`, the integral's pass-through check
  /// (pass_through.hpp), comes first; then the Uzawa step over `points`: active(cp), gap(cp),
  /// N(cp) read the state of the last assembly. Friction (slip_tol > 0): sticks(cp) and
  /// slip(cp) (|g_T|) of the last assembly, T(cp) its tangential force in the form the law
  /// carries (Vector3d). Over the parts of a spread pair (parts_max) the decisions are the
  /// whole pair's: the largest |gap| and slip of all parts, and a point through the surface
  /// on any part stops the update on all (the part that has it reports it).
  template <class Point, class Active, class Gap, class Force, class Sticks, class Slip,
            class Traction>
  AugmentResult update(std::vector<Point>& points, const ContactEnforcement& e,
                       const AugmentResult& through, Active active, Gap gap, Force N, Sticks sticks,
                       Slip slip, Traction T) {
    const bool through_here = through.status != AugmentStatus::satisfied;
    if (!e.augmented || (through_here && !parts_max)) return through;
    max_gap = max_slip = 0.0;
    for (const Point& cp : points) {
      if (!active(cp)) continue;
      max_gap = std::max(max_gap, std::abs(gap(cp)));
      if (e.slip_tol > 0.0 && sticks(cp)) max_slip = std::max(max_slip, slip(cp));
    }
    if (parts_max) {
      std::array<double, 3> whole{through_here ? 1.0 : 0.0, max_gap, max_slip};
      parts_max(whole);
      if (whole[0] > 0.0) return through;
      max_gap = whole[1];
      max_slip = whole[2];
    }
    const bool normal_ok = max_gap <= e.penetration_tol;
    const bool stick_ok = !(e.slip_tol > 0.0) || max_slip <= e.slip_tol;
    if (normal_ok && stick_ok) return {};
    char buf[240];
    if (step_updates >= e.max_augmentations) {
      if (!normal_ok)
        std::snprintf(buf, sizeof buf,
                      "contact gap %.3e (largest |gap| of a point carrying a force) above "
                      "penetration_tol %.3e after %d augmentations (max_augmentations)",
                      max_gap, e.penetration_tol, step_updates);
      else
        std::snprintf(buf, sizeof buf,
                      "stick slip %.3e (largest slip of a sticking point since its anchor) "
                      "above slip_tol %.3e after %d augmentations (max_augmentations)",
                      max_slip, e.slip_tol, step_updates);
      return {AugmentStatus::failed, buf};
    }
    if (!normal_ok && previous_gap > 0.0 && max_gap > 0.5 * previous_gap && eps_scale < 1e3)
      eps_scale *= 4.0;
    previous_gap = max_gap;
    if (!stick_ok && previous_slip > 0.0 && max_slip > 0.5 * previous_slip && eps_t_scale < 1e3)
      eps_t_scale *= 4.0;
    previous_slip = max_slip;
    ++step_updates;
    ++total_updates;
    for (Point& cp : points) cp.lambda_n = active(cp) ? std::min(0.0, N(cp)) : 0.0;
    if (e.slip_tol > 0.0) {
      for (Point& cp : points) cp.lambda_t = active(cp) ? Vector3d(T(cp)) : Vector3d::Zero();
      tangential = true;
    }
    if (!normal_ok)
      std::snprintf(buf, sizeof buf, "contact gap %.3e > penetration_tol %.3e", max_gap,
                    e.penetration_tol);
    else
      std::snprintf(buf, sizeof buf, "stick slip %.3e > slip_tol %.3e", max_slip, e.slip_tol);
    return {AugmentStatus::updated, buf};
  }
};

}  // namespace iga
