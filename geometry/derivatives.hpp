// Small aggregates carrying a point and its parametric derivatives, shared by NURBS and
// analytic curves and surfaces.
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/bspline_basis.hpp"

namespace iga {

using Eigen::Matrix2d;
using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::Vector4d;

/// d[k] = k-th derivative of C(u) with respect to u, k = 0..order (d[0] is the point).
struct CurveDerivs {
  int order = 0;
  std::array<Vector3d, kMaxDerivOrder + 1> d{};
};

/// A surface point and its derivatives up to order 2 (entries above `order` are zero).
/// Index convention: S = rho, Su = rho_1, Sv = rho_2, Suu = rho_11, Suv = rho_12, Svv = rho_22.
struct SurfaceDerivs {
  int order = 0;
  Vector3d S = Vector3d::Zero();
  Vector3d Su = Vector3d::Zero();
  Vector3d Sv = Vector3d::Zero();
  Vector3d Suu = Vector3d::Zero();
  Vector3d Suv = Vector3d::Zero();
  Vector3d Svv = Vector3d::Zero();
};

/// A closed parameter interval [lo, hi] (infinite bounds allowed for analytic surfaces).
struct Interval {
  double lo = 0.0;
  double hi = 1.0;
  bool operator==(const Interval&) const = default;
};

/// Rectangular parameter domain of a surface.
struct Domain2 {
  Interval u;
  Interval v;
  bool operator==(const Domain2&) const = default;
};

}  // namespace iga
