// Least-squares fitting of B-spline curves to sampled points with a prescribed knot vector
// ([PT97] Sect. 9.4.1, global least-squares approximation with fixed end points).
#pragma once

#include <vector>

#include "geometry/nurbs_curve.hpp"

namespace iga {

struct CurveFit {
  NurbsCurve curve;
  double max_deviation = 0.0;  ///< largest |C(t_k) - Q_k| over the samples
};

/// The B-spline of the given degree and knots minimizing sum_k |C(t_k) - Q_k|^2, with
/// C(t_0) = Q_0 and C(t_last) = Q_last interpolated exactly. Parameters t must lie in the knot
/// domain and be non-decreasing; there must be more samples than control points, spread so
/// that every basis function is sampled (Schoenberg-Whitney), else GeometryError.
CurveFit fit_curve(const std::vector<Vector3d>& Q, const std::vector<double>& t, int degree,
                   const std::vector<double>& knots);

}  // namespace iga
