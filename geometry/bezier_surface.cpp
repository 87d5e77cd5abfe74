// Evaluation of a NURBS patch through its Bezier elements ([PT97] A5.6, A4.4).
#include "geometry/bezier_surface.hpp"

#include <algorithm>

#include "geometry/tensor_derivs.hpp"

namespace iga {

BezierSurface::BezierSurface(const NurbsSurface& s)
    : elements_(bezier_extract(s)),
      breaks_u_(s.knots_u().breaks()),
      breaks_v_(s.knots_v().breaks()),
      domain_(s.domain()),
      closed_u_(s.closed_u()),
      closed_v_(s.closed_v()) {
  set_normal_sign(s.normal_sign());
  per_u_ = static_cast<double>(breaks_u_.size() - 1) / (breaks_u_.back() - breaks_u_.front());
  per_v_ = static_cast<double>(breaks_v_.size() - 1) / (breaks_v_.back() - breaks_v_.front());
}

namespace {

// The interval [b_i, b_{i+1}) of the breaks that holds x (the last one holds the end; x is
// clamped to the breaks): from the guess of evenly spaced breaks (per: intervals per unit),
// stepped to the right one (no step where the breaks are even, as in most patches).
int interval_of(const std::vector<double>& b, double per, double x) {
  const int n = static_cast<int>(b.size()) - 1;  // intervals (b has two entries at least)
  const double g = (x - b.front()) * per;
  int i = g >= 1.0 ? (g < n ? static_cast<int>(g) : n - 1) : 0;  // NaN: 0
  while (i > 0 && x < b[static_cast<std::size_t>(i)]) --i;
  while (i < n - 1 && x >= b[static_cast<std::size_t>(i + 1)]) ++i;
  return i;
}

}  // namespace

int BezierSurface::element_of(double u, double v) const {
  const int nu = static_cast<int>(breaks_u_.size()) - 1;
  return interval_of(breaks_u_, per_u_, u) + nu * interval_of(breaks_v_, per_v_, v);
}

namespace {

// The Bernstein polynomials of degree p and
// their derivatives up to `order`, times scale^k for the k-th (the chain rule's 1 / h^k):
// B^d_r = (1 - t) B^(d-1)_r + t B^(d-1)_(r-1);
// B^p_r' = p (B^(p-1)_(r-1) - B^(p-1)_r);
// B^p_r'' = p (p - 1) (B^(p-2)_(r-2) - 2 B^(p-2)_(r-1) + B^(p-2)_r)
// (terms with an index outside 0..d are zero).
void bernstein_general(int p, double t, int order, double scale, BasisDerivs& B) {
  const double s = 1.0 - t;
  // b: degree d; lower1, lower2: degrees p - 1 and p - 2, shifted by 1 and 2 and padded with
  // zeros (lower1[r + 1] = B^(p-1)_r, lower2[r + 2] = B^(p-2)_r), so that the difference
  // formulas need no tests.
  double b[kMaxDegree + 1];
  double lower1[kMaxDegree + 3], lower2[kMaxDegree + 3];
  for (int r = 0; r < p + 3; ++r) lower1[r] = lower2[r] = 0.0;
  b[0] = 1.0;
  for (int d = 1; d <= p; ++d) {
    if (d == p - 1)
      for (int r = 0; r < d; ++r) lower2[r + 2] = b[r];
    if (d == p)
      for (int r = 0; r < d; ++r) lower1[r + 1] = b[r];
    double prev = 0.0;  // B^(d-1)_(r-1)
    for (int r = 0; r < d; ++r) {
      const double cur = b[r];
      b[r] = s * cur + t * prev;
      prev = cur;
    }
    b[d] = t * prev;
  }
  for (int r = 0; r <= p; ++r) B[0][static_cast<std::size_t>(r)] = b[r];
  if (order >= 1) {
    const double c1 = p * scale;
    for (int r = 0; r <= p; ++r)
      B[1][static_cast<std::size_t>(r)] = c1 * (lower1[r] - lower1[r + 1]);
  }
  if (order >= 2) {
    const double c2 = p * (p - 1) * scale * scale;
    for (int r = 0; r <= p; ++r)
      B[2][static_cast<std::size_t>(r)] = c2 * (lower2[r] - 2.0 * lower2[r + 1] + lower2[r + 2]);
  }
}

// The quadratic in closed form: B = (s^2, 2 t s, t^2), B' = 2 (-s, s - t, t), B'' = 2 (1, -2, 1).
void bernstein_quadratic(double t, int order, double scale, BasisDerivs& B) {
  const double s = 1.0 - t;
  auto set = [&B](int k, double b0, double b1, double b2) {
    BasisValues& row = B[static_cast<std::size_t>(k)];
    row[0] = b0, row[1] = b1, row[2] = b2;
  };
  set(0, s * s, 2.0 * t * s, t * t);
  if (order >= 1) set(1, -2.0 * scale * s, 2.0 * scale * (s - t), 2.0 * scale * t);
  if (order >= 2) {
    const double c2 = 2.0 * scale * scale;
    set(2, c2, -2.0 * c2, c2);
  }
}

// The cubic in closed form: B = (s^3, 3 t s^2, 3 t^2 s, t^3), s = 1 - t, B' = 3 (-s^2,
// s^2 - 2 t s, 2 t s - t^2, t^2), B'' = 6 (s, t - 2 s, s - 2 t, t) (the differences above).
void bernstein_cubic(double t, int order, double scale, BasisDerivs& B) {
  const double s = 1.0 - t, ss = s * s, tt = t * t, ts = t * s;
  auto set = [&B](int k, double b0, double b1, double b2, double b3) {
    BasisValues& row = B[static_cast<std::size_t>(k)];
    row[0] = b0, row[1] = b1, row[2] = b2, row[3] = b3;
  };
  set(0, ss * s, 3.0 * ts * s, 3.0 * ts * t, tt * t);
  if (order >= 1) {
    const double c1 = 3.0 * scale;
    set(1, -c1 * ss, c1 * (ss - 2.0 * ts), c1 * (2.0 * ts - tt), c1 * tt);
  }
  if (order >= 2) {
    const double c2 = 6.0 * scale * scale;
    set(2, c2 * s, c2 * (t - 2.0 * s), c2 * (s - 2.0 * t), c2 * t);
  }
}

void bernstein_any(int p, double t, int order, double scale, BasisDerivs& B) {
  switch (p) {
    case 2:
      return bernstein_quadratic(t, order, scale, B);
    case 3:
      return bernstein_cubic(t, order, scale, B);
    default:
      return bernstein_general(p, t, order, scale, B);
  }
}

}  // namespace

void bernstein_derivs(int p, double t, int order, BasisDerivs& B) {
  bernstein_any(p, t, std::clamp(order, 0, 2), 1.0, B);
}

SurfaceDerivs BezierSurface::derivs(double u, double v, int order) const {
  u = std::clamp(u, domain_.u.lo, domain_.u.hi);
  v = std::clamp(v, domain_.v.lo, domain_.v.hi);
  return derivs_on(element_of(u, v), u, v, order);
}

SurfaceDerivs BezierSurface::derivs_on(int element, double u, double v, int order) const {
  order = std::clamp(order, 0, 2);
  const BezierPatch& e = elements_[static_cast<std::size_t>(element)];
  u = std::clamp(u, e.range.u.lo, e.range.u.hi);
  v = std::clamp(v, e.range.v.lo, e.range.v.hi);
  const double hu = e.range.u.hi - e.range.u.lo, hv = e.range.v.hi - e.range.v.lo;
  BasisDerivs Bu, Bv;  // d/du = (1 / h_u) d/dt
  bernstein_any(e.degree_u, (u - e.range.u.lo) / hu, order, 1.0 / hu, Bu);
  bernstein_any(e.degree_v, (v - e.range.v.lo) / hv, order, 1.0 / hv, Bv);
  return detail::tensor_derivs(Bu, Bv, e.degree_u, e.degree_v, order, e.pw.data(), e.degree_u + 1);
}

}  // namespace iga
