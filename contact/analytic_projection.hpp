// Closed-form projections onto the analytic rigid surfaces of [KS15]:
//   closest point: plane (8), sphere (B.4), cylinder (B.10), torus (B.16), cone (B.23),
//   hyperboloid z = a x y by the paper's Newton (16-22) from alpha(0) = (x, y) (20) (with a
//   global fallback over all critical points), surface of revolution (A.1) by a 1-D Newton in
//   the meridian plane;
//   ray: plane (8)-(9), sphere, cylinder, cone and hyperboloid (quadratics), torus (quartic),
//   surface of revolution by Newton (A.2a-e).
// Results follow the surface's normal_sign ("outward"/"inward"). Bounded domains are handled
// exactly: the constrained minimum of a surface of revolution lies on the meridian of the
// nearer angular bound and is found there in closed form; the hyperboloid's edges are straight
// lines (edge / vertex statuses, Sect. 2.2). The cone's apex is a vertex. Angles undefined on
// the axis are 0 (or the domain's lower bound). Ray directions are normalized, so xi3 is a
// length. See analytic_closest_point.cpp and analytic_ray.cpp for the details.
#pragma once

#include "contact/projection.hpp"
#include "geometry/analytic_surfaces.hpp"

namespace iga {

/// Closest point on an analytic surface (dispatch on the dynamic type); the global minimum over
/// the surface's domain. Throws GeometryError for an AnalyticSurface of another type.
ProjectionResult closest_point_analytic(const AnalyticSurface& s, const Vector3d& x,
                                        const ProjectionOptions& opt = {});
/// Ray projection x + xi3 N/|N| onto an analytic surface; the intersection with the smallest
/// |xi3| within the domain, or status miss (distance = +inf) / tangent (|n.N| < 1e-10, (9)).
/// A zero or non-finite N defines no ray: status miss (as for NURBS patches), no exception.
ProjectionResult ray_project_analytic(const AnalyticSurface& s, const Vector3d& x,
                                      const Vector3d& N, const ProjectionOptions& opt = {});

/// [KS15] (16)-(22) literally: Newton for the hyperboloid z = a x y in its local frame
/// (x, y, z local coordinates), from alpha(0) = (x, y) (20). Unbounded domain. The result is
/// local too: point rho (11), normal (22) (the +e_z side), distance (21); status interior when
/// the scaled residual (16) or the step reaches its tolerance, else not_converged (plain Newton
/// may wander for points at |p| ~ 1/|a|).
ProjectionResult hyperboloid_closest_point_ks(double a, const Vector3d& x_local,
                                              const ProjectionOptions& opt = {});

}  // namespace iga
