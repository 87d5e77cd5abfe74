// Results and options shared by every projection onto a rigid surface or curve.
// References: [KS15] (see ../shared/paper/EQUATIONS.md) Sect. 2.2 (surfaces, then edges, then
// vertices), eqs. (2)-(5) ray projection, (10)-(18) closest point projection.
//
// Notation ([KS15] -> code): alpha^1, alpha^2 -> uv; rho(alpha) -> point; n -> normal;
// p = xi^3 = (r - rho).n -> signed distance / ray parameter.
#pragma once

#include <string>

#include <Eigen/Core>

#include "geometry/derivatives.hpp"

namespace iga {

/// How a projection ended. Non-convergence is a status, never an exception.
enum class ProjectionStatus {
  interior,       ///< closest point inside the patch (gradient zero, eq. 16)
  edge,           ///< on a patch boundary curve (one parameter at its bound)
  vertex,         ///< at a patch corner (both parameters at a bound)
  not_converged,  ///< iteration limit reached; the best iterate is returned
  miss,           ///< ray projection: the ray does not meet the surface (in its domain)
  tangent,        ///< ray projection: the ray is tangent to the surface, n.N -> 0 (eq. 9)
  far,            ///< no surface within the search distance (contact search said none)
};

/// A short lower-case name ("interior", "edge", ...), as written in CSV output.
const char* to_string(ProjectionStatus s);

/// True for the statuses that carry a valid foot point (interior, edge, vertex).
inline bool found(ProjectionStatus s) {
  return s == ProjectionStatus::interior || s == ProjectionStatus::edge ||
         s == ProjectionStatus::vertex;
}

struct ProjectionResult {
  Vector2d uv = Vector2d::Zero();      ///< surface parameters (alpha^1, alpha^2)
  Vector3d point = Vector3d::Zero();   ///< rho(uv), the foot point
  Vector3d normal = Vector3d::Zero();  ///< oriented unit normal n at uv
  /// Closest point: signed distance, |x - rho| with the sign of (x - rho).n (eq. 10: p along
  /// n in the interior). Ray: the ray parameter xi^3 with x + xi^3 N = rho (eqs. 2-3).
  double distance = 0.0;
  ProjectionStatus status = ProjectionStatus::not_converged;
  int iterations = 0;  ///< Newton iterations used (summed over seeds for cold starts)
  int patch = 0;       ///< index of the patch within a multi-patch rigid surface
  /// Scaled optimality residual at the end. Closest point: max_i |rho_i.(x - rho)| /
  /// (|rho_i| max(|x - rho|, L)) over the parameters not held at a bound, L = |rho_1| du +
  /// |rho_2| dv a length of the patch: the foot point's tangential error relative to the model
  /// size near the surface, the cosine of the angle between x - rho and rho_i far from it.
  /// Ray: |F| relative to the local patch size.
  double residual = 0.0;
  /// Closest point onto a NURBS patch (PatchProjector): proven the global minimum over the
  /// patch, to 1e-11 of the patch's size, by the bounds of its Bezier control nets.
  bool certified = false;
};

/// Convergence and iteration controls.
struct ProjectionOptions {
  int max_iterations = 30;
  double tol_residual = 1e-13;  ///< on the scaled orthogonality residual
  double tol_step = 1e-14;      ///< on the parameter step, relative to the domain size
  /// Projections onto NURBS patches (PatchProjector, RigidSurface): prove the answer the
  /// global minimum by the bounds of the Bezier control nets (subdividing where they are not
  /// tight enough) and check every warm start the same way. false: the sampled search of
  /// earlier versions (seeded Newtons per element, warm starts accepted as they converge),
  /// faster but able to miss a global minimum when two lie closer than the samples.
  bool certify = true;
};

}  // namespace iga
