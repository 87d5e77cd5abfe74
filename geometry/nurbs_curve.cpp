// NURBS curve evaluation: [PT97] A3.2 (B-spline derivatives), A4.2 (rational derivatives).
#include "geometry/nurbs_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace iga {

namespace {
constexpr double kBinomial[kMaxDerivOrder + 1][kMaxDerivOrder + 1] = {
    {1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};

}  // namespace

std::vector<Vector4d> to_homogeneous(const std::vector<Vector3d>& P, const std::vector<double>& w) {
  if (!w.empty() && w.size() != P.size())
    throw GeometryError("weights count " + std::to_string(w.size()) + " != control point count " +
                        std::to_string(P.size()));
  std::vector<Vector4d> pw(P.size());
  for (std::size_t i = 0; i < P.size(); ++i) {
    const double wi = w.empty() ? 1.0 : w[i];
    if (!(wi > 0.0) || !std::isfinite(wi))
      throw GeometryError("weight " + std::to_string(i) + " must be finite and > 0, got " +
                          std::to_string(wi));
    if (!P[i].allFinite())
      throw GeometryError("control point " + std::to_string(i) + " is not finite");
    pw[i] << wi * P[i], wi;
  }
  return pw;
}

std::vector<Vector3d> from_homogeneous(const std::vector<Vector4d>& pw) {
  std::vector<Vector3d> P(pw.size());
  for (std::size_t i = 0; i < pw.size(); ++i) P[i] = pw[i].head<3>() / pw[i].w();
  return P;
}

std::vector<double> weights_of(const std::vector<Vector4d>& pw) {
  std::vector<double> w(pw.size());
  for (std::size_t i = 0; i < pw.size(); ++i) w[i] = pw[i].w();
  return w;
}

bool any_weight_not_one(const std::vector<Vector4d>& pw) {
  return std::any_of(pw.begin(), pw.end(), [](const Vector4d& q) { return q.w() != 1.0; });
}

void check_homogeneous(const std::vector<Vector4d>& pw) {
  for (std::size_t i = 0; i < pw.size(); ++i)
    if (!(pw[i].w() > 0.0) || !pw[i].allFinite())
      throw GeometryError("homogeneous control point " + std::to_string(i) +
                          " must be finite with weight > 0");
}

void make_storable(std::vector<Vector4d>& pw) {
  for (Vector4d& q : pw) {
    const double w = q.w();
    if (w == 1.0) continue;
    for (int k = 0; k < 3; ++k) {
      const double y = q[k], x0 = y / w;
      // Any x with fl(w x) == y lies within two ulps of x0 (|w x - y| <= ulp(y) / 2).
      bool storable = w * x0 == y;
      double up = x0, down = x0;
      for (int i = 0; i < 3 && !storable; ++i) {
        up = std::nextafter(up, std::numeric_limits<double>::infinity());
        down = std::nextafter(down, -std::numeric_limits<double>::infinity());
        storable = w * up == y || w * down == y;
      }
      if (!storable) q[k] = w * x0;
    }
  }
}

NurbsCurve::NurbsCurve(int degree, std::vector<double> knots, const std::vector<Vector3d>& points,
                       const std::vector<double>& weights) {
  validate_knots(degree, knots, static_cast<int>(points.size()));
  knots_ = KnotVector(degree, std::move(knots));
  pw_ = to_homogeneous(points, weights);
}

NurbsCurve::NurbsCurve(KnotVector knots, std::vector<Vector4d> pw)
    : knots_(std::move(knots)), pw_(std::move(pw)) {
  validate_knots(knots_.degree(), knots_.span(), static_cast<int>(pw_.size()));
  check_homogeneous(pw_);
  make_storable(pw_);
}

Vector3d NurbsCurve::control_point(int i) const {
  const Vector4d& q = pw_[static_cast<std::size_t>(i)];
  return q.head<3>() / q.w();
}

std::vector<Vector3d> NurbsCurve::control_points() const {
  return from_homogeneous(pw_);
}

std::vector<double> NurbsCurve::weights() const {
  return weights_of(pw_);
}

bool NurbsCurve::is_rational() const {
  return any_weight_not_one(pw_);
}

Interval NurbsCurve::domain() const {
  const auto [a, b] = knots_.domain();
  return {a, b};
}

Vector3d NurbsCurve::point(double u) const {
  return derivs(u, 0).d[0];
}

CurveDerivs NurbsCurve::derivs(double u, int order) const {
  // A4.2 (p. 127): derivatives of the homogeneous curve A(u), w(u), then
  // C^(k) = (A^(k) - sum_{i=1..k} binom(k,i) w^(i) C^(k-i)) / w   (eq. 4.8).
  const int p = degree();
  order = std::clamp(order, 0, kMaxDerivOrder);
  const Interval dom = domain();
  u = std::clamp(u, dom.lo, dom.hi);
  const int span = knots_.find_span(u);
  BasisDerivs N;
  ders_basis_funs(span, u, p, order, knots_.span(), N);

  Vector4d A[kMaxDerivOrder + 1];
  for (int k = 0; k <= order; ++k) {
    A[k].setZero();
    if (k > p) continue;
    for (int j = 0; j <= p; ++j)
      A[k].noalias() += N[k][j] * pw_[static_cast<std::size_t>(span - p + j)];
  }
  CurveDerivs out;
  out.order = order;
  for (int k = 0; k <= order; ++k) {
    Vector3d v = A[k].head<3>();
    for (int i = 1; i <= k; ++i) v -= kBinomial[k][i] * A[i].w() * out.d[k - i];
    out.d[k] = v / A[0].w();
  }
  for (int k = order + 1; k <= kMaxDerivOrder; ++k) out.d[k].setZero();
  return out;
}

}  // namespace iga
