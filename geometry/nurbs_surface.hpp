// Tensor-product NURBS surface patches: evaluation of points and derivatives up to order 2.
// References: [PT97] The NURBS Book: A3.6 (B-spline surface derivatives), A4.3, A4.4 (rational
// surface point and derivatives, eq. 4.20).
#pragma once

#include <vector>

#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/surface.hpp"

namespace iga {

/// S(u,v) = sum_ij N_i,p(u) N_j,q(v) w_ij P_ij / sum_ij N_i,p(u) N_j,q(v) w_ij.
/// Control points are stored flat with u running fastest: index(i, j) = i + n_u * j.
/// Invariant: knots_u().num_basis() * knots_v().num_basis() == number of control points,
/// weights > 0 and finite.
class NurbsSurface : public Surface {
 public:
  NurbsSurface() = default;
  /// Throws GeometryError on inconsistent data. Empty `weights` means all 1 (B-spline).
  NurbsSurface(int degree_u, std::vector<double> knots_u, int degree_v, std::vector<double> knots_v,
               const std::vector<Vector3d>& points, const std::vector<double>& weights = {});
  /// From homogeneous control points (w P, w), u fastest.
  NurbsSurface(KnotVector knots_u, KnotVector knots_v, std::vector<Vector4d> pw);

  int degree_u() const { return ku_.degree(); }
  int degree_v() const { return kv_.degree(); }
  const KnotVector& knots_u() const { return ku_; }
  const KnotVector& knots_v() const { return kv_; }
  int num_u() const { return ku_.num_basis(); }
  int num_v() const { return kv_.num_basis(); }
  int index(int i, int j) const { return i + num_u() * j; }
  Vector3d control_point(int i, int j) const;
  double weight(int i, int j) const { return pw_[static_cast<std::size_t>(index(i, j))].w(); }
  std::vector<Vector3d> control_points() const;
  std::vector<double> weights() const;
  const std::vector<Vector4d>& homogeneous() const { return pw_; }
  bool is_rational() const;

  // Surface interface
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  Domain2 domain() const override;
  bool closed_u() const override { return closed_u_; }
  bool closed_v() const override { return closed_v_; }
  std::string type_name() const override { return "nurbs_surface"; }

  bool operator==(const NurbsSurface& o) const {
    return ku_ == o.ku_ && kv_ == o.kv_ && pw_ == o.pw_ && normal_sign() == o.normal_sign();
  }

 private:
  void detect_closed();

  KnotVector ku_, kv_;
  std::vector<Vector4d> pw_;
  bool closed_u_ = false, closed_v_ = false;
};

/// The four edges of a patch's parameter rectangle.
enum class SurfaceEdge { kUMin, kUMax, kVMin, kVMax };

/// The control points of a row along an edge (row 0: on the edge, 1: the next inward, ...), in
/// the order of the edge's parameter; indices i + n_u j. GeometryError if the row is outside the
/// net.
std::vector<int> edge_points(const NurbsSurface& S, SurfaceEdge edge, int row = 0);

}  // namespace iga
