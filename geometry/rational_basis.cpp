// The rational basis of NURBS curves and surfaces (geometry/rational_basis.hpp).
#include "geometry/rational_basis.hpp"

#include <algorithm>
#include <string>

namespace iga {

RationalBasis rational_basis(const NurbsCurve& c, double xi) {
  // [PT97] A2.3 for N, N', N''; R_j = N_j w_j / W with W = sum N_j w_j, then the quotient rule:
  // R_j' = (N_j' w_j - R_j W') / W,  R_j'' = (N_j'' w_j - 2 R_j' W' - R_j W'') / W.
  const int p = c.degree();
  const Interval dom = c.domain();
  xi = std::clamp(xi, dom.lo, dom.hi);
  const int span = c.knots().find_span(xi);
  BasisDerivs ders;
  ders_basis_funs(span, xi, p, 2, c.knots().span(), ders);
  RationalBasis B;
  B.first = span - p;
  B.count = p + 1;
  double W = 0.0, W1 = 0.0, W2 = 0.0;
  for (int j = 0; j <= p; ++j) {
    const double wj = c.weight(B.first + j);
    W += ders[0][j] * wj;
    W1 += ders[1][j] * wj;
    W2 += (p >= 2 ? ders[2][j] : 0.0) * wj;
  }
  for (int j = 0; j <= p; ++j) {
    const double wj = c.weight(B.first + j);
    const std::size_t k = static_cast<std::size_t>(j);
    B.N[k] = ders[0][j] * wj / W;
    B.dN[k] = (ders[1][j] * wj - B.N[k] * W1) / W;
    B.ddN[k] = ((p >= 2 ? ders[2][j] : 0.0) * wj - 2.0 * B.dN[k] * W1 - B.N[k] * W2) / W;
  }
  return B;
}

SpanBasis span_basis(const KnotVector& U, int p, double t) {
  const std::span<const double> k = U.span();
  t = std::clamp(t, k[static_cast<std::size_t>(p)], k[k.size() - 1 - static_cast<std::size_t>(p)]);
  SpanBasis b;
  b.span = U.find_span(t);
  ders_basis_funs(b.span, t, p, 2, k, b.N);
  return b;
}

std::vector<double> span_rule_points(std::span<const double> breaks, std::span<const double> x) {
  std::vector<double> t;
  if (breaks.size() < 2) return t;
  t.reserve((breaks.size() - 1) * x.size());
  for (std::size_t e = 0; e + 1 < breaks.size(); ++e) {
    const double m = 0.5 * (breaks[e] + breaks[e + 1]), h = 0.5 * (breaks[e + 1] - breaks[e]);
    for (const double xi : x) t.push_back(m + h * xi);
  }
  return t;
}

SpanBasisTable::SpanBasisTable(const KnotVector& U, int p, std::span<const double> params) {
  rows_.reserve(params.size());
  for (const double t : params) rows_.push_back(span_basis(U, p, t));
}

void rational_basis(const NurbsSurface& s, double u, double v, SurfaceBasis& B) {
  const Domain2 dom = s.domain();
  u = std::clamp(u, dom.u.lo, dom.u.hi);
  v = std::clamp(v, dom.v.lo, dom.v.hi);
  rational_basis(s, span_basis(s.knots_u(), s.degree_u(), u),
                 span_basis(s.knots_v(), s.degree_v(), v), B);
}

void rational_basis(const NurbsSurface& s, const SpanBasis& bu, const SpanBasis& bv,
                    SurfaceBasis& B) {
  const int p = s.degree_u(), q = s.degree_v();
  if (p > kMaxSurfaceBasisDegree || q > kMaxSurfaceBasisDegree)
    throw GeometryError("rational_basis: surface degree " + std::to_string(p) + " x " +
                        std::to_string(q) + " above the supported " +
                        std::to_string(kMaxSurfaceBasisDegree));
  B.span_u = bu.span;
  B.span_v = bv.span;
  B.nu = p + 1;
  B.nv = q + 1;
  B.num_u_total = s.num_u();
  const BasisDerivs &Nu = bu.N, &Nv = bv.N;
  // Weighted tensor products and the weight function W with its derivatives ([PT97] eq. 4.20).
  double W = 0, Wu = 0, Wv = 0, Wuu = 0, Wvv = 0, Wuv = 0;
  const int fu = B.span_u - p, fv = B.span_v - q;
  for (int j = 0; j <= q; ++j)
    for (int i = 0; i <= p; ++i) {
      const std::size_t k = static_cast<std::size_t>(i + B.nu * j);
      const double w = s.weight(fu + i, fv + j);
      B.R[k] = Nu[0][i] * Nv[0][j] * w;
      B.d1[k] = Nu[1][i] * Nv[0][j] * w;
      B.d2[k] = Nu[0][i] * Nv[1][j] * w;
      B.d11[k] = Nu[2][i] * Nv[0][j] * w;
      B.d22[k] = Nu[0][i] * Nv[2][j] * w;
      B.d12[k] = Nu[1][i] * Nv[1][j] * w;
      W += B.R[k];
      Wu += B.d1[k];
      Wv += B.d2[k];
      Wuu += B.d11[k];
      Wvv += B.d22[k];
      Wuv += B.d12[k];
    }
  // Quotient rule: R = N/W, R_a = (N_a - R W_a)/W, R_aa = (N_aa - 2 R_a W_a - R W_aa)/W,
  // R_uv = (N_uv - R_u W_v - R_v W_u - R W_uv)/W.
  for (int k = 0; k < B.count(); ++k) {
    const std::size_t l = static_cast<std::size_t>(k);
    const double R = B.R[l] / W;
    const double Ru = (B.d1[l] - R * Wu) / W;
    const double Rv = (B.d2[l] - R * Wv) / W;
    B.d11[l] = (B.d11[l] - 2.0 * Ru * Wu - R * Wuu) / W;
    B.d22[l] = (B.d22[l] - 2.0 * Rv * Wv - R * Wvv) / W;
    B.d12[l] = (B.d12[l] - Ru * Wv - Rv * Wu - R * Wuv) / W;
    B.R[l] = R;
    B.d1[l] = Ru;
    B.d2[l] = Rv;
  }
}

void rational_basis_first(const SpanBasis& bu, const SpanBasis& bv, int p, int q, const double* w,
                          double* rows) {
  const BasisDerivs &Nu = bu.N, &Nv = bv.N;
  double W = 0, Wu = 0, Wv = 0;
  for (int j = 0, k = 0; j <= q; ++j)
    for (int i = 0; i <= p; ++i, ++k) {
      double* r = rows + 3 * k;
      r[0] = Nu[0][i] * Nv[0][j] * w[k];
      r[1] = Nu[1][i] * Nv[0][j] * w[k];
      r[2] = Nu[0][i] * Nv[1][j] * w[k];
      W += r[0];
      Wu += r[1];
      Wv += r[2];
    }
  const double iW = 1.0 / W;  // one division (these rows are formed at every assembly)
  for (int k = 0; k < (p + 1) * (q + 1); ++k) {
    double* r = rows + 3 * k;
    const double R = r[0] * iW;
    r[1] = (r[1] - R * Wu) * iW;
    r[2] = (r[2] - R * Wv) * iW;
    r[0] = R;
  }
}

}  // namespace iga
