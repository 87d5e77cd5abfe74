// NURBS (and B-spline) curves in 3-D: evaluation of points and derivatives.
// References: [PT97] The NURBS Book: A3.2 (B-spline curve derivatives), A4.1, A4.2 (rational
// curve point and derivatives, eq. 4.8).
#pragma once

#include <span>
#include <vector>

#include "geometry/derivatives.hpp"
#include "geometry/knot_vector.hpp"

namespace iga {

/// A NURBS curve C(u) = sum_i N_{i,p}(u) w_i P_i / sum_i N_{i,p}(u) w_i.
/// Invariant: knots().num_basis() == number of control points, weights > 0 and finite.
/// Control points are stored in homogeneous form Pw_i = (w_i P_i, w_i).
class NurbsCurve {
 public:
  NurbsCurve() = default;
  /// Throws GeometryError on inconsistent data. Empty `weights` means all 1 (B-spline).
  NurbsCurve(int degree, std::vector<double> knots, const std::vector<Vector3d>& points,
             const std::vector<double>& weights = {});
  /// From homogeneous control points (w P, w).
  NurbsCurve(KnotVector knots, std::vector<Vector4d> pw);

  int degree() const { return knots_.degree(); }
  const KnotVector& knots() const { return knots_; }
  int num_control_points() const { return static_cast<int>(pw_.size()); }
  Vector3d control_point(int i) const;
  double weight(int i) const { return pw_[static_cast<std::size_t>(i)].w(); }
  std::vector<Vector3d> control_points() const;
  std::vector<double> weights() const;
  const std::vector<Vector4d>& homogeneous() const { return pw_; }
  /// True when some weight differs from 1.
  bool is_rational() const;
  Interval domain() const;

  /// C(u); u is clamped to the domain.
  Vector3d point(double u) const;
  /// C(u) and its derivatives up to `order` <= kMaxDerivOrder (A4.2). No heap allocation.
  CurveDerivs derivs(double u, int order = 2) const;

  bool operator==(const NurbsCurve&) const = default;

 private:
  KnotVector knots_;
  std::vector<Vector4d> pw_;
};

/// Homogeneous control points (w P, w) from points and weights (empty = all 1); throws
/// GeometryError for a count mismatch, a weight <= 0 or a non-finite value.
std::vector<Vector4d> to_homogeneous(const std::vector<Vector3d>& P, const std::vector<double>& w);
std::vector<Vector3d> from_homogeneous(const std::vector<Vector4d>& pw);
std::vector<double> weights_of(const std::vector<Vector4d>& pw);
bool any_weight_not_one(const std::vector<Vector4d>& pw);
/// Throws GeometryError unless every point is finite with weight > 0.
void check_homogeneous(const std::vector<Vector4d>& pw);
/// Makes every homogeneous coordinate y = w P one that a file can hold. A file holds the
/// Cartesian P and w, and reading gives fl(w P); for a y computed in homogeneous form
/// (refinement, constructions) there is often no double P with fl(w P) == y. Such a y becomes
/// fl(w fl(y / w)), within an ulp of y: exactly what writing and reading it back gives, so that
/// save -> load reproduces the curve or surface bit for bit. Idempotent; weights unchanged.
void make_storable(std::vector<Vector4d>& pw);

}  // namespace iga
