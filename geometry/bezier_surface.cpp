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
}

namespace {

// The interval [b_i, b_{i+1}) of the breaks that holds x (the last one holds the end; x is
// clamped to the breaks).
int interval_of(const std::vector<double>& b, double x) {
  const auto last = b.end() - 1;  // b has two entries at least
  const auto it = std::upper_bound(b.begin() + 1, last, x);
  return static_cast<int>(it - b.begin()) - 1;
}

}  // namespace

int BezierSurface::element_of(double u, double v) const {
  const int nu = static_cast<int>(breaks_u_.size()) - 1;
  return interval_of(breaks_u_, u) + nu * interval_of(breaks_v_, v);
}

namespace {

// The Bernstein polynomials of degree p (P = p when known at compile time, 0 otherwise) and
// their derivatives up to `order`, times scale^k for the k-th (the chain rule's 1 / h^k):
// B^d_r = (1 - t) B^(d-1)_r + t B^(d-1)_(r-1);
// B^p_r' = p (B^(p-1)_(r-1) - B^(p-1)_r);
// B^p_r'' = p (p - 1) (B^(p-2)_(r-2) - 2 B^(p-2)_(r-1) + B^(p-2)_r)
// (terms with an index outside 0..d are zero).
template <int P>
void bernstein_scaled(int p_rt, double t, int order, double scale, BasisDerivs& B) {
  const int p = P > 0 ? P : p_rt;
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

void bernstein_any(int p, double t, int order, double scale, BasisDerivs& B) {
  switch (p) {
    case 2:
      return bernstein_scaled<2>(p, t, order, scale, B);
    case 3:
      return bernstein_scaled<3>(p, t, order, scale, B);
    default:
      return bernstein_scaled<0>(p, t, order, scale, B);
  }
}

}  // namespace

void bernstein_derivs(int p, double t, int order, BasisDerivs& B) {
  bernstein_any(p, t, std::clamp(order, 0, 2), 1.0, B);
}

SurfaceDerivs BezierSurface::derivs(double u, double v, int order) const {
  order = std::clamp(order, 0, 2);
  u = std::clamp(u, domain_.u.lo, domain_.u.hi);
  v = std::clamp(v, domain_.v.lo, domain_.v.hi);
  const BezierPatch& e = elements_[static_cast<std::size_t>(element_of(u, v))];
  const double hu = e.range.u.hi - e.range.u.lo, hv = e.range.v.hi - e.range.v.lo;
  BasisDerivs Bu, Bv;  // d/du = (1 / h_u) d/dt
  bernstein_any(e.degree_u, (u - e.range.u.lo) / hu, order, 1.0 / hu, Bu);
  bernstein_any(e.degree_v, (v - e.range.v.lo) / hv, order, 1.0 / hv, Bv);
  return detail::tensor_derivs(Bu, Bv, e.degree_u, e.degree_v, order, e.pw.data(), e.degree_u + 1);
}

}  // namespace iga
