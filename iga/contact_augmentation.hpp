// Exact enforcement of the normal contact constraint by an augmented Lagrangian with Uzawa
// updates between Newton solves of a load step (docs/contact.md, "Enforcement"), shared by the
// CTRS (iga/curve_contact.hpp) and STAS (iga/surface_contact.hpp) integrals.
//
// Notation: lambda_N <= 0 the multiplier of a contact point (a force per unit length or area,
// like N), xi^3 its gap (52), eps_N the penalty, N = min(0, lambda_N + eps_N xi^3) ((34)
// augmented, contact/contact_law.hpp).
//
// After Newton has converged at a load step (the integral's points hold the state of that
// assembly), the largest penetration p = max(-xi^3) over the active points is compared with
// the tolerance; if p > tol, every point's multiplier becomes its current force,
// lambda_N <- N (0 where the point is apart), and the step is solved again. A point that stays
// in contact then carries lambda_N from the start of the re-solve and its gap shrinks to
// (N_new - lambda_N) / eps_N, the change of its force between solves over eps_N. Multipliers
// are committed with the history at converged steps and restored when a step is cut back.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "contact/contact_law.hpp"
#include "iga/nonlinear_problem.hpp"

namespace iga {

/// The multipliers' bookkeeping of one contact integral.
struct NormalAugmentation {
  int step_updates = 0;          ///< updates since the last commit or restore
  int total_updates = 0;         ///< updates since construction
  double max_penetration = 0.0;  ///< at the last augment() call

  /// The Uzawa step over `points`: active(cp), gap(cp), N(cp) read the state of the last
  /// assembly; lambda(cp) is the multiplier (a reference).
  template <class Point, class Active, class Gap, class Force, class Lambda>
  AugmentResult update(std::vector<Point>& points, const ContactEnforcement& e, Active active,
                       Gap gap, Force N, Lambda lambda) {
    if (!e.augmented) return {};
    max_penetration = 0.0;
    for (const Point& cp : points)
      if (active(cp)) max_penetration = std::max(max_penetration, -gap(cp));
    char buf[160];
    if (max_penetration <= e.penetration_tol) return {};
    if (step_updates >= e.max_augmentations) {
      std::snprintf(buf, sizeof buf,
                    "contact penetration %.3e above penetration_tol %.3e after %d augmentations "
                    "(max_augmentations)",
                    max_penetration, e.penetration_tol, step_updates);
      return {AugmentStatus::failed, buf};
    }
    ++step_updates;
    ++total_updates;
    for (Point& cp : points) lambda(cp) = active(cp) ? std::min(0.0, N(cp)) : 0.0;
    std::snprintf(buf, sizeof buf, "contact penetration %.3e > penetration_tol %.3e",
                  max_penetration, e.penetration_tol);
    return {AugmentStatus::updated, buf};
  }
};

}  // namespace iga
