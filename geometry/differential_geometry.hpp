// Differential geometry at a point of a surface or a curve.
// Notation ([KS15] / EQUATIONS.md -> code): rho_i -> a1, a2 (covariant basis), a_ij -> a
// (metric), a^ij -> a_inv, h_ij = rho_ij . n -> h (curvature tensor), n -> n,
// Serret-Frenet (tau, nu, beta) -> tangent, normal, binormal.
// Sign convention: h_ij = rho_ij . n, so a sphere with the outward normal has principal
// curvatures -1/R (the surface bends away from n); principal curvatures are the eigenvalues
// of the shape operator a^ij h_jk, k1 >= k2. With the outward normals of analytic_surfaces.hpp
// and constructions.hpp: cylinder k1 = 0 (along the axis), k2 = -1/R; torus -1/r along the
// tube's meridian and -cos v/(R + r cos v) along the parallel; cone 0 and -sin(alpha)/s;
// "inward" (normal_sign = -1) flips every sign. Gauss curvature K = k1 k2 is sign-independent.
#pragma once

#include "geometry/derivatives.hpp"

namespace iga {

/// The cross product matrix [v]x: [v]x w = v x w (skew-symmetric).
inline Matrix3d skew(const Vector3d& v) {
  Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

struct SurfaceFrame {
  Vector3d a1 = Vector3d::Zero(), a2 = Vector3d::Zero();                ///< rho_1, rho_2
  Vector3d n = Vector3d::Zero();                                        ///< unit normal (oriented)
  double jacobian = 0.0;                                                ///< |rho_1 x rho_2|
  Matrix2d a = Matrix2d::Zero();                                        ///< a_ij = rho_i . rho_j
  Matrix2d a_inv = Matrix2d::Zero();                                    ///< a^ij
  Vector3d a1_contra = Vector3d::Zero(), a2_contra = Vector3d::Zero();  ///< rho^i = a^ij rho_j
  Matrix2d h = Matrix2d::Zero();                              ///< h_ij = rho_ij . n (needs order 2)
  double mean_curvature = 0.0;                                ///< H = (k1 + k2)/2
  double gauss_curvature = 0.0;                               ///< K = k1 k2 = det h / det a
  double k1 = 0.0, k2 = 0.0;                                  ///< principal curvatures, k1 >= k2
  Vector3d dir1 = Vector3d::Zero(), dir2 = Vector3d::Zero();  ///< unit principal directions
};

/// Frame from derivatives of order >= 1 (curvatures need order 2). normal_sign = +1 or -1.
/// Throws GeometryError at a singular point (|rho_1 x rho_2| <= 1e-14 max(|rho_1|, |rho_2|)^2,
/// e.g. rho_1 ~ 0 at a pole).
/// At umbilic points (k1 == k2) dir1, dir2 are still an orthonormal tangent pair.
SurfaceFrame surface_frame(const SurfaceDerivs& d, int normal_sign = 1);

struct CurveFrame {
  Vector3d tangent = Vector3d::Zero();   ///< tau, unit
  Vector3d normal = Vector3d::Zero();    ///< nu, unit (zero where curvature vanishes)
  Vector3d binormal = Vector3d::Zero();  ///< beta = tau x nu
  double speed = 0.0;                    ///< |C'|
  double curvature = 0.0;                ///< kappa = |C' x C''| / |C'|^3
  double torsion = 0.0;                  ///< (C' x C'') . C''' / |C' x C''|^2 (needs order 3)
};

/// Serret-Frenet frame, curvature and torsion from derivatives (order >= 2; 3 for torsion).
/// Where |C' x C''| <= 1e-12 |C'| |C''| (curvature ~ 0) curvature, normal, binormal and
/// torsion are 0. Throws GeometryError for order < 1 or at a singular point (C' = 0).
CurveFrame curve_frame(const CurveDerivs& d);

}  // namespace iga
