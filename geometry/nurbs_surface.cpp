// NURBS surface evaluation: [PT97] A3.6 (B-spline surface derivatives), A4.4 (rational surface
// derivatives, eq. 4.20), up to second order.
#include "geometry/nurbs_surface.hpp"

#include "geometry/tensor_derivs.hpp"

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
  // The (p + 1) x (q + 1) block of the net that the basis functions of the spans reach.
  const Vector4d* net = &pw_[static_cast<std::size_t>((sv - q) * num_u() + su - p)];
  return detail::tensor_derivs(Nu, Nv, p, q, order, net, num_u());
}

std::vector<int> edge_points(const NurbsSurface& S, SurfaceEdge edge, int row) {
  const int nu = S.num_u(), nv = S.num_v();
  const bool u_edge = edge == SurfaceEdge::kUMin || edge == SurfaceEdge::kUMax;
  if (row < 0 || row >= (u_edge ? nu : nv))
    throw GeometryError("edge_points: row " + std::to_string(row) + " is outside the control net");
  std::vector<int> pts;
  if (u_edge) {
    const int i = edge == SurfaceEdge::kUMin ? row : nu - 1 - row;
    for (int j = 0; j < nv; ++j) pts.push_back(S.index(i, j));
  } else {
    const int j = edge == SurfaceEdge::kVMin ? row : nv - 1 - row;
    for (int i = 0; i < nu; ++i) pts.push_back(S.index(i, j));
  }
  return pts;
}

}  // namespace iga
