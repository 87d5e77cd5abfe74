// Ray projection ("rigid surface is slave", [KS15] Sect. 2.1, eqs. 2-5): intersect the line
// r(xi^3) = x + xi^3 N with a surface by Newton on (alpha^1, alpha^2, xi^3), residual (3)
// F = rho(alpha) - x - xi^3 N, Jacobian (4) [rho_1 | rho_2 | -N], step (5). Statuses `miss`
// (no intersection within the domain) and `tangent` (n.N -> 0, eq. 9).
#pragma once

#include "contact/closest_point.hpp"
#include "contact/projection.hpp"

namespace iga {

/// Local ray projection from a parameter guess and a guess of xi^3, within the surface domain.
ProjectionResult ray_project_local(const Surface& s, const Vector3d& x, const Vector3d& N,
                                   const Vector2d& start, double xi3_start = 0.0,
                                   const ProjectionOptions& opt = {});

/// Global ray projection onto a NURBS patch: candidate elements are those whose box the line
/// crosses; each is seeded from its sample nearest to the line; the intersection with the
/// smallest |xi^3| is returned.
ProjectionResult ray_project(const PatchProjector& patch, const Vector3d& x, const Vector3d& N,
                             const ProjectionOptions& opt = {});

}  // namespace iga
