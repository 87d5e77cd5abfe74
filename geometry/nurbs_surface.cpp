// NURBS surface evaluation: [PT97] A3.6 (B-spline surface derivatives), A4.4 (rational surface
// derivatives, eq. 4.20), up to second order.
#include "geometry/nurbs_surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace iga {

NurbsSurface::NurbsSurface(int degree_u, std::vector<double> knots_u, int degree_v,
                           std::vector<double> knots_v, const std::vector<Vector3d>& points,
                           const std::vector<double>& weights) {
  validate_knots(degree_u, knots_u, -1);
  validate_knots(degree_v, knots_v, -1);
  ku_ = KnotVector(degree_u, std::move(knots_u));
  kv_ = KnotVector(degree_v, std::move(knots_v));
  if (static_cast<std::size_t>(num_u()) * static_cast<std::size_t>(num_v()) != points.size())
    throw GeometryError("control net size must be " + std::to_string(num_u()) + " x " +
                        std::to_string(num_v()) + " = " + std::to_string(num_u() * num_v()) +
                        " (from knots and degrees), got " + std::to_string(points.size()));
  pw_ = to_homogeneous(points, weights);
  detect_closed();
}

NurbsSurface::NurbsSurface(KnotVector knots_u, KnotVector knots_v, std::vector<Vector4d> pw)
    : ku_(std::move(knots_u)), kv_(std::move(knots_v)), pw_(std::move(pw)) {
  if (static_cast<std::size_t>(num_u()) * static_cast<std::size_t>(num_v()) != pw_.size())
    throw GeometryError("control net size must be " + std::to_string(num_u() * num_v()) + ", got " +
                        std::to_string(pw_.size()));
  check_homogeneous(pw_);
  make_storable(pw_);
  detect_closed();
}

void NurbsSurface::detect_closed() {
  // A clamped direction is closed when its first and last rows of control points coincide
  // (then S(lo, v) == S(hi, v) for all v). Tolerance relative to the net's size.
  double scale = 0.0;
  for (const Vector4d& q : pw_)
    scale = std::max(scale, (q.head<3>() / q.w()).cwiseAbs().maxCoeff());
  const double tol = 1e-12 * std::max(scale, 1.0);
  closed_u_ = closed_v_ = true;
  for (int j = 0; j < num_v(); ++j)
    if ((control_point(0, j) - control_point(num_u() - 1, j)).norm() > tol) closed_u_ = false;
  for (int i = 0; i < num_u(); ++i)
    if ((control_point(i, 0) - control_point(i, num_v() - 1)).norm() > tol) closed_v_ = false;
}

Vector3d NurbsSurface::control_point(int i, int j) const {
  const Vector4d& q = pw_[static_cast<std::size_t>(index(i, j))];
  return q.head<3>() / q.w();
}

std::vector<Vector3d> NurbsSurface::control_points() const {
  return from_homogeneous(pw_);
}

std::vector<double> NurbsSurface::weights() const {
  return weights_of(pw_);
}

bool NurbsSurface::is_rational() const {
  return any_weight_not_one(pw_);
}

Domain2 NurbsSurface::domain() const {
  const auto [u0, u1] = ku_.domain();
  const auto [v0, v1] = kv_.domain();
  return {{u0, u1}, {v0, v1}};
}

namespace {

// A3.6 on the homogeneous net gives A^(k,l), then A4.4 / eq. (4.20):
// S^(k,l) = (A^(k,l) - sum_{i=1..k} C(k,i) w^(i,0) S^(k-i,l)
//           - sum_{j=1..l} C(l,j) [w^(0,j) S^(k,l-j) + sum_{i=1..k} C(k,i) w^(i,j) S^(k-i,l-j)]) /
//           w
// The order O, and for the common degrees also PF = p and QF = q (0: known at run time only),
// are template parameters so that the loops unroll.
template <int O, int PF, int QF>
SurfaceDerivs eval_derivs(const BasisDerivs& Nu, const BasisDerivs& Nv, int p_rt, int q_rt, int su,
                          int sv, int nu, const std::vector<Vector4d>& pw) {
  const int p = PF > 0 ? PF : p_rt;
  const int q = QF > 0 ? QF : q_rt;
  // First the u-sums of every row of the element's net, T[k] = sum_r Nu[k][r] Pw[.][.], then
  // the v-sums A[k][l] = sum_s Nv[l][s] T_s[k], k + l <= O.
  Vector4d A[O + 1][O + 1];
  for (int k = 0; k <= O; ++k)
    for (int l = 0; l <= O; ++l) A[k][l].setZero();
  for (int s = 0; s <= q; ++s) {
    const Vector4d* P = &pw[static_cast<std::size_t>((sv - q + s) * nu + su - p)];
    Vector4d T[O + 1];
    for (int k = 0; k <= O; ++k) {
      T[k] = Nu[k][0] * P[0];
      for (int r = 1; r <= p; ++r) T[k].noalias() += Nu[k][r] * P[r];
    }
    for (int l = 0; l <= O; ++l)
      for (int k = 0; k + l <= O; ++k) A[k][l].noalias() += Nv[l][s] * T[k];
  }
  constexpr double bin[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 2, 1}};
  Vector3d S[O + 1][O + 1];
  const double inv_w = 1.0 / A[0][0].w();
  for (int k = 0; k <= O; ++k) {
    for (int l = 0; k + l <= O; ++l) {
      Vector3d x = A[k][l].template head<3>();
      for (int j = 1; j <= l; ++j) x -= bin[l][j] * A[0][j].w() * S[k][l - j];
      for (int i = 1; i <= k; ++i) {
        x -= bin[k][i] * A[i][0].w() * S[k - i][l];
        for (int j = 1; j <= l; ++j) x -= bin[k][i] * bin[l][j] * A[i][j].w() * S[k - i][l - j];
      }
      S[k][l] = x * inv_w;
    }
  }
  SurfaceDerivs d;
  d.order = O;
  d.S = S[0][0];
  if constexpr (O >= 1) {
    d.Su = S[1][0];
    d.Sv = S[0][1];
  }
  if constexpr (O >= 2) {
    d.Suu = S[2][0];
    d.Suv = S[1][1];
    d.Svv = S[0][2];
  }
  return d;
}

template <int O>
SurfaceDerivs dispatch_degrees(const BasisDerivs& Nu, const BasisDerivs& Nv, int p, int q, int su,
                               int sv, int nu, const std::vector<Vector4d>& pw) {
  if (p == 2 && q == 2) return eval_derivs<O, 2, 2>(Nu, Nv, p, q, su, sv, nu, pw);
  if (p == 3 && q == 3) return eval_derivs<O, 3, 3>(Nu, Nv, p, q, su, sv, nu, pw);
  return eval_derivs<O, 0, 0>(Nu, Nv, p, q, su, sv, nu, pw);
}

}  // namespace

SurfaceDerivs NurbsSurface::derivs(double u, double v, int order) const {
  const int p = degree_u(), q = degree_v();
  order = std::clamp(order, 0, 2);
  const std::vector<double>& U = ku_.knots();
  const std::vector<double>& V = kv_.knots();
  u = std::clamp(u, U[static_cast<std::size_t>(p)], U[U.size() - 1 - static_cast<std::size_t>(p)]);
  v = std::clamp(v, V[static_cast<std::size_t>(q)], V[V.size() - 1 - static_cast<std::size_t>(q)]);
  const int su = ku_.find_span(u), sv = kv_.find_span(v);
  BasisDerivs Nu, Nv;
  ders_basis_funs(su, u, p, order, U, Nu);
  ders_basis_funs(sv, v, q, order, V, Nv);
  switch (order) {
    case 0:
      return dispatch_degrees<0>(Nu, Nv, p, q, su, sv, num_u(), pw_);
    case 1:
      return dispatch_degrees<1>(Nu, Nv, p, q, su, sv, num_u(), pw_);
    default:
      return dispatch_degrees<2>(Nu, Nv, p, q, su, sv, num_u(), pw_);
  }
}

}  // namespace iga
