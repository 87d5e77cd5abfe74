// A follower pressure on a NURBS surface whose control points are the unknowns (shells,
// membranes), one quadrature point at a time: the force p (a_1 x a_2) du dv along the current
// normal and its load stiffness.
//
// Notation: R_k, R_k,a the rational basis and its first derivatives at the point (SurfaceBasis;
// local k, control point B.global_index(k)); a_a = sum R_k,a x_k the current base vectors;
// w = p times the Gauss weight and the parametric Jacobian (integrates p du dv); [v]x the cross
// product matrix; g the Cartesian residual (3 per control point, f_int - f_ext).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "geometry/differential_geometry.hpp"
#include "geometry/rational_basis.hpp"
#include "iga/core/dof_map.hpp"

namespace iga {

/// g_k -= R_k w (a_1 x a_2); with K, the load stiffness d g_k / d x_l = -R_k w (R_l,2 [a_1]x -
/// R_l,1 [a_2]x) appended as triplets (not symmetric in general: only for a closed surface or a
/// boundary held fixed).
inline void add_follower_pressure(const SurfaceBasis& B, double w, std::span<const Vector3d> x,
                                  Eigen::VectorXd& g, std::vector<Triplet>* K) {
  const Vector3d a1 = combine(B, B.d1, x), a2 = combine(B, B.d2, x);
  const Vector3d f = w * a1.cross(a2);
  const int np = B.count();
  for (int k = 0; k < np; ++k)
    g.segment<3>(3 * B.global_index(k)) -= B.R[static_cast<std::size_t>(k)] * f;
  if (!K) return;
  const Matrix3d S1 = w * skew(a1), S2 = w * skew(a2);
  for (int l = 0; l < np; ++l) {
    const Matrix3d Dl =
        B.d2[static_cast<std::size_t>(l)] * S1 - B.d1[static_cast<std::size_t>(l)] * S2;
    const int cl = 3 * B.global_index(l);
    for (int k = 0; k < np; ++k) {
      const double Rk = B.R[static_cast<std::size_t>(k)];
      const int rk = 3 * B.global_index(k);
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a) K->emplace_back(rk + a, cl + b, -Rk * Dl(a, b));
    }
  }
}

}  // namespace iga
