// The check that a converged step did not carry contact points through the rigid body, shared
// by the CTRS (curve_contact.hpp) and STAS (surface_contact.hpp) integrals.
//
// Notation: x_n a point's position at the last commit, x its position now, d = x - x_n; rho_n
// its committed foot (the closest point at the commit). A point apart from the body at the
// last commit (a foot within the search distance, no contact) and apart now, whose straight
// path from x_n to x enters the body (the ray x_n + s d/|d| hits the surface at 0 < s < |d|
// from outside: n . d < 0 at the hit), went through it in one step: a free body that falls, a
// step too large for the penalty to catch it. The converged state would be one without that
// contact, silently wrong; augment() reports the step as failed, so the solver cuts it. A path
// shorter than |x_n - rho_n| cannot reach the surface: only the others cast a ray.
#pragma once

#include <algorithm>
#include <cstdio>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "iga/core/nonlinear_problem.hpp"

namespace iga {

/// `points`: with members x, x_committed and history (ContactHistory); `active(p)`: whether
/// the point is in contact now.
template <class Point, class Active>
AugmentResult passed_through(const std::vector<Point>& points, const RigidSurface& rigid,
                             Active&& active) {
  int n = 0;
  double longest = 0.0;
  for (const Point& cp : points) {
    const ContactHistory& h = cp.history;
    if (active(cp) || h.active || h.patch < 0) continue;
    const Vector3d d = cp.x - cp.x_committed;
    const double len = d.norm();
    if (!(len > (cp.x_committed - h.foot).norm())) continue;
    const ProjectionResult hit = rigid.ray(cp.x_committed, d / len);
    if (!found(hit.status) || !(hit.distance > 0.0 && hit.distance < len)) continue;
    if (hit.normal.dot(d) >= 0.0) continue;  // leaving the body, not entering it
    ++n;
    longest = std::max(longest, len);
  }
  if (n == 0) return {};
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%d contact point(s) went through the rigid surface in one step (moved up to "
                "%.3g, across the surface)",
                n, longest);
  return {AugmentStatus::passed_through, buf};
}

}  // namespace iga
