// B-spline basis functions: [PT97] Algorithms A2.1, A2.2, A2.3.
#include "geometry/bspline_basis.hpp"

#include <algorithm>
#include <cassert>

namespace iga {

int find_span(int n_basis, int p, double u, std::span<const double> U) {
  // A2.1 (p. 68), with n = n_basis - 1: binary search for U[i] <= u < U[i+1] in [p, n].
  const int n = n_basis - 1;
  if (u >= U[n + 1]) {
    int s = n;  // the last non-empty span: step back over repeated end knots
    while (s > p && U[s] == U[s + 1]) --s;
    return s;
  }
  if (u <= U[p]) {
    int s = p;
    while (s < n && U[s + 1] == U[s]) ++s;
    return s;
  }
  int low = p, high = n + 1;
  int mid = (low + high) / 2;
  while (u < U[mid] || u >= U[mid + 1]) {
    if (u < U[mid])
      high = mid;
    else
      low = mid;
    mid = (low + high) / 2;
  }
  return mid;
}

void basis_funs(int span, double u, int p, std::span<const double> U, BasisValues& N) {
  // A2.2 (p. 70): triangular scheme with left/right knot differences.
  assert(p <= kMaxDegree);
  double left[kMaxDegree + 1], right[kMaxDegree + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

namespace {

// A2.3 (p. 72). ndu holds basis functions (upper triangle) and knot differences (lower).
// PF = p for the common degrees (the loops unroll), 0 when p is known at run time only; the
// helpers below take PF too, so that each of them unrolls where the kernel did. They are forced
// inline: GCC inlines them anyway, but only after its early passes, which then no longer see
// that nd > 2 on the general path for p = 2 (its loops stay rolled and ndu goes to the stack).
constexpr int kM = kMaxDegree + 1;
using Ndu = double[kM][kM];

/// A2.3's triangular scheme: the basis functions of degrees 0..p at u (upper triangle of ndu,
/// column j degree j) and the knot differences right + left (lower triangle).
template <int PF>
[[gnu::always_inline]] inline void basis_triangle(int span, double u, int p_rt,
                                                  std::span<const double> U, Ndu& ndu) {
  const int p = PF > 0 ? PF : p_rt;
  double left[kM], right[kM];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // lower triangle
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;  // upper triangle
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
}

/// Derivatives of orders 1 and 2 (nd <= 2, p >= 2) with A2.3's coefficients a_{k,j} written
/// out (the hot path of surface evaluation); ndu[j][p-k] are the basis functions of degree
/// p-k, ndu[p-k+1][.] the knot differences. Terms whose indices leave the triangle are absent
/// (zero).
template <int PF>
[[gnu::always_inline]] inline void low_order_ders(int p_rt, int nd, const Ndu& ndu,
                                                  BasisDerivs& ders) {
  const int p = PF > 0 ? PF : p_rt;
  // Reciprocal knot differences, each computed once (divisions dominate this kernel).
  double inv_p[kMaxDegree + 1], inv_q[kMaxDegree + 1];
  for (int r = 0; r < p; ++r) inv_p[r] = 1.0 / ndu[p][r];
  if (nd >= 2)
    for (int r = 0; r < p - 1; ++r) inv_q[r] = 1.0 / ndu[p - 1][r];
  for (int r = 0; r <= p; ++r) {
    const double a10 = r >= 1 ? inv_p[r - 1] : 0.0;
    const double a11 = r <= p - 1 ? -inv_p[r] : 0.0;
    double d1 = 0.0;
    if (r >= 1) d1 += a10 * ndu[r - 1][p - 1];
    if (r <= p - 1) d1 += a11 * ndu[r][p - 1];
    if (nd >= 1) ders[1][r] = p * d1;
    if (nd >= 2) {
      double d2 = 0.0;
      if (r >= 2) d2 += a10 * inv_q[r - 2] * ndu[r - 2][p - 2];
      if (r >= 1 && r <= p - 1) d2 += (a11 - a10) * inv_q[r - 1] * ndu[r - 1][p - 2];
      if (r <= p - 2) d2 += -a11 * inv_q[r] * ndu[r][p - 2];
      ders[2][r] = p * (p - 1) * d2;
    }
  }
}

/// Derivatives of orders 1..n (n = min(nd, p)) by A2.3's recurrence for the coefficients
/// a_{k,j} (two rows, alternating), then scaled by p!/(p-k)!.
template <int PF>
[[gnu::always_inline]] inline void general_ders(int p_rt, int n, const Ndu& ndu,
                                                BasisDerivs& ders) {
  const int p = PF > 0 ? PF : p_rt;
  double a[2][kM];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = (rk >= -1) ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  // Multiply by p!/(p-k)!.
  double r = p;
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= r;
    r *= (p - k);
  }
}

template <int PF>
void ders_basis_funs_impl(int span, double u, int p_rt, int nd, std::span<const double> U,
                          BasisDerivs& ders) {
  const int p = PF > 0 ? PF : p_rt;
  assert(p <= kMaxDegree && nd <= kMaxDerivOrder);
  Ndu ndu;
  basis_triangle<PF>(span, u, p, U, ndu);
  for (int k = 0; k <= nd; ++k)
    for (int j = 0; j <= p; ++j) ders[k][j] = 0.0;
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  if (nd <= 2 && p >= 2)
    low_order_ders<PF>(p, nd, ndu, ders);
  else
    general_ders<PF>(p, std::min(nd, p), ndu, ders);
}

/// Degree 1 (bilinear patches: planes and the saddle's hyperboloid as NURBS): A2.3's operations
/// for p = 1 written out, the same numbers bit for bit (h = right + left, N_0 = right / h,
/// N_1 = left / h as temp = 1 / h times each; N_0' = -1 / h, N_1' = 1 / h; higher orders 0).
/// The general scheme's loops and zeroing cost several times these few operations, and the
/// warm projections onto such a rigid surface evaluate it at every contact point.
void ders_basis_funs_linear(int span, double u, int nd, std::span<const double> U,
                            BasisDerivs& ders) {
  const double left = u - U[span], right = U[span + 1] - u;
  const double h = right + left;
  const double temp = 1.0 / h;
  for (int k = 0; k <= nd; ++k) ders[k][0] = ders[k][1] = 0.0;
  ders[0][0] = 0.0 + right * temp;
  ders[0][1] = left * temp;
  if (nd >= 1) {
    ders[1][0] = -1.0 / h;
    ders[1][1] = 1.0 / h;
  }
}

}  // namespace

void ders_basis_funs(int span, double u, int p, int nd, std::span<const double> U,
                     BasisDerivs& ders) {
  switch (p) {
    case 1:
      return ders_basis_funs_linear(span, u, nd, U, ders);
    case 2:
      return ders_basis_funs_impl<2>(span, u, p, nd, U, ders);
    case 3:
      return ders_basis_funs_impl<3>(span, u, p, nd, U, ders);
    default:
      return ders_basis_funs_impl<0>(span, u, p, nd, U, ders);
  }
}

}  // namespace iga
