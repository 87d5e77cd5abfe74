// The tensor-product part of rational surface evaluation, shared by the NURBS patch (basis
// functions of its knot spans) and its Bezier elements (Bernstein polynomials): from the
// univariate basis functions and their derivatives in u and v and the (p + 1) x (q + 1) block
// of homogeneous control points they weight, the point and derivatives up to order 2.
// Internal header of geometry/. References: [PT97] The NURBS Book, A3.6 (B-spline surface
// derivatives), A4.4 and eq. (4.20) (rational surface derivatives).
//
// Notation: Nu[k][r] = k-th derivative of the r-th basis function in u (r = 0..p), Nv[l][s]
// likewise in v; net + s * stride = the first of the p + 1 points of row s (u fastest);
// A^(k,l) = sum_rs Nu[k][r] Nv[l][s] Pw_rs (homogeneous), S^(k,l) the derivatives of S.
#pragma once

#include <cstddef>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "geometry/bspline_basis.hpp"
#include "geometry/cpu_features.h"
#include "geometry/derivatives.hpp"

namespace iga::detail {

// The rational surface's derivatives from the homogeneous ones A[k][l] = A^(k,l), k + l <= O:
// A4.4 / eq. (4.20),
// S^(k,l) = (A^(k,l) - sum_{i=1..k} C(k,i) w^(i,0) S^(k-i,l)
//           - sum_{j=1..l} C(l,j) [w^(0,j) S^(k,l-j) + sum_{i=1..k} C(k,i) w^(i,j) S^(k-i,l-j)]) /
//           w
template <int O>
SurfaceDerivs rational_derivs(const Vector4d (&A)[O + 1][O + 1]) {
  // Written out for k + l <= 2, in the order of the sums above (the same rounding).
  const double inv_w = 1.0 / A[0][0].w();
  SurfaceDerivs d;
  d.order = O;
  d.S = A[0][0].template head<3>() * inv_w;
  if constexpr (O >= 1) {
    const double w10 = A[1][0].w(), w01 = A[0][1].w();
    d.Su = (A[1][0].template head<3>() - w10 * d.S) * inv_w;
    d.Sv = (A[0][1].template head<3>() - w01 * d.S) * inv_w;
    if constexpr (O >= 2) {
      d.Suu = (A[2][0].template head<3>() - 2.0 * w10 * d.Su - A[2][0].w() * d.S) * inv_w;
      d.Suv = (A[1][1].template head<3>() - w01 * d.Su - w10 * d.Sv - A[1][1].w() * d.S) * inv_w;
      d.Svv = (A[0][2].template head<3>() - 2.0 * w01 * d.Sv - A[0][2].w() * d.S) * inv_w;
    }
  }
  return d;
}

// A3.6 on the homogeneous net gives A^(k,l), then rational_derivs.
// The order O, and for the common degrees also PF = p and QF = q (0: known at run time only),
// are template parameters so that the loops unroll.
template <int O, int PF, int QF>
SurfaceDerivs eval_derivs(const BasisDerivs& Nu, const BasisDerivs& Nv, int p_rt, int q_rt,
                          const Vector4d* net, int stride) {
  const int p = PF > 0 ? PF : p_rt;
  const int q = QF > 0 ? QF : q_rt;
  // First the u-sums of every row of the element's net, T[k] = sum_r Nu[k][r] Pw[.][.], then
  // the v-sums A[k][l] = sum_s Nv[l][s] T_s[k], k + l <= O.
  Vector4d A[O + 1][O + 1];
  for (int k = 0; k <= O; ++k)
    for (int l = 0; l <= O; ++l) A[k][l].setZero();
  for (int s = 0; s <= q; ++s) {
    const Vector4d* P = net + static_cast<std::ptrdiff_t>(s) * stride;
    Vector4d T[O + 1];
    for (int k = 0; k <= O; ++k) {
      T[k] = Nu[k][0] * P[0];
      for (int r = 1; r <= p; ++r) T[k].noalias() += Nu[k][r] * P[r];
    }
    for (int l = 0; l <= O; ++l)
      for (int k = 0; k + l <= O; ++k) A[k][l].noalias() += Nv[l][s] * T[k];
  }
  return rational_derivs<O>(A);
}

// The homogeneous sums A^(k,l) = sum_rs Nu[k][r] Nv[l][s] Pw_rs, k + l <= O, for degree P in
// both directions (2 or 3: the patches of most models) on whole homogeneous points: a point
// (x, y, z, w) is one 4-wide vector (AVX2 with fused multiply-adds where the processor has
// them, else two SSE2 halves, which every x86-64 has), so the sums take a quarter (or half) of
// the scalar instructions. The sums run in the order of eval_derivs (u first, then v); with
// fused multiply-adds they round differently, within round-off. The path is chosen once per
// process by the processor's features as glibc sees them (cpu_features.h: a run with
// GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA takes the path of a processor without them).
// A[q] = A^(kSumK[q], kSumL[q]): 00, 10, 01, 20, 11, 02.
inline constexpr int kSumK[6] = {0, 1, 0, 2, 1, 0}, kSumL[6] = {0, 0, 1, 0, 1, 2};
constexpr int sums_of(int order) {
  return (order + 1) * (order + 2) / 2;
}

#if defined(__x86_64__)
template <int P, int O>
void net_sums_sse2(const Vector4d* net, int stride, const BasisDerivs& Nu, const BasisDerivs& Nv,
                   double (*A)[4]) {
  constexpr int NQ = sums_of(O);
  __m128d a[NQ][2];
  for (int q = 0; q < NQ; ++q) a[q][0] = a[q][1] = _mm_setzero_pd();
  for (int s = 0; s <= P; ++s) {
    const double* row = net[static_cast<std::ptrdiff_t>(s) * stride].data();
    __m128d T[O + 1][2];
    const __m128d p0 = _mm_loadu_pd(row), p1 = _mm_loadu_pd(row + 2);
    for (int k = 0; k <= O; ++k) {
      const __m128d b = _mm_set1_pd(Nu[k][0]);
      T[k][0] = _mm_mul_pd(b, p0);
      T[k][1] = _mm_mul_pd(b, p1);
    }
    for (int r = 1; r <= P; ++r) {
      const __m128d q0 = _mm_loadu_pd(row + 4 * r), q1 = _mm_loadu_pd(row + 4 * r + 2);
      for (int k = 0; k <= O; ++k) {
        const __m128d b = _mm_set1_pd(Nu[k][static_cast<std::size_t>(r)]);
        T[k][0] = _mm_add_pd(T[k][0], _mm_mul_pd(b, q0));
        T[k][1] = _mm_add_pd(T[k][1], _mm_mul_pd(b, q1));
      }
    }
    for (int q = 0; q < NQ; ++q) {
      const __m128d b = _mm_set1_pd(Nv[kSumL[q]][static_cast<std::size_t>(s)]);
      a[q][0] = _mm_add_pd(a[q][0], _mm_mul_pd(b, T[kSumK[q]][0]));
      a[q][1] = _mm_add_pd(a[q][1], _mm_mul_pd(b, T[kSumK[q]][1]));
    }
  }
  for (int q = 0; q < NQ; ++q) {
    _mm_storeu_pd(A[q], a[q][0]);
    _mm_storeu_pd(A[q] + 2, a[q][1]);
  }
}

template <int P, int O>
__attribute__((target("avx2,fma"))) void net_sums_avx2(const Vector4d* net, int stride,
                                                       const BasisDerivs& Nu, const BasisDerivs& Nv,
                                                       double (*A)[4]) {
  constexpr int NQ = sums_of(O);
  __m256d a[NQ];
  for (int q = 0; q < NQ; ++q) a[q] = _mm256_setzero_pd();
  for (int s = 0; s <= P; ++s) {
    const double* row = net[static_cast<std::ptrdiff_t>(s) * stride].data();
    __m256d T[O + 1];
    const __m256d p0 = _mm256_loadu_pd(row);
    for (int k = 0; k <= O; ++k) T[k] = _mm256_mul_pd(_mm256_set1_pd(Nu[k][0]), p0);
    for (int r = 1; r <= P; ++r) {
      const __m256d p = _mm256_loadu_pd(row + 4 * r);
      for (int k = 0; k <= O; ++k)
        T[k] = _mm256_fmadd_pd(_mm256_set1_pd(Nu[k][static_cast<std::size_t>(r)]), p, T[k]);
    }
    for (int q = 0; q < NQ; ++q)
      a[q] = _mm256_fmadd_pd(_mm256_set1_pd(Nv[kSumL[q]][static_cast<std::size_t>(s)]), T[kSumK[q]],
                             a[q]);
  }
  for (int q = 0; q < NQ; ++q) _mm256_storeu_pd(A[q], a[q]);
}

inline bool avx2_fma_active() {
  static const bool active = iga_avx2_fma_active() != 0;
  return active;
}

// eval_derivs for p = q = P by the vector sums above.
template <int O, int P>
SurfaceDerivs vector_derivs(const BasisDerivs& Nu, const BasisDerivs& Nv, const Vector4d* net,
                            int stride) {
  double sums[sums_of(O)][4];
  if (avx2_fma_active())
    net_sums_avx2<P, O>(net, stride, Nu, Nv, sums);
  else
    net_sums_sse2<P, O>(net, stride, Nu, Nv, sums);
  Vector4d A[O + 1][O + 1];
  for (int q = 0; q < sums_of(O); ++q) A[kSumK[q]][kSumL[q]] = Eigen::Map<const Vector4d>(sums[q]);
  return rational_derivs<O>(A);
}
#endif

template <int O>
SurfaceDerivs dispatch_degrees(const BasisDerivs& Nu, const BasisDerivs& Nv, int p, int q,
                               const Vector4d* net, int stride) {
#if defined(__x86_64__)
  if (p == 2 && q == 2) return vector_derivs<O, 2>(Nu, Nv, net, stride);
  if (p == 3 && q == 3) return vector_derivs<O, 3>(Nu, Nv, net, stride);
#else
  if (p == 2 && q == 2) return eval_derivs<O, 2, 2>(Nu, Nv, p, q, net, stride);
  if (p == 3 && q == 3) return eval_derivs<O, 3, 3>(Nu, Nv, p, q, net, stride);
#endif
  return eval_derivs<O, 0, 0>(Nu, Nv, p, q, net, stride);
}

/// Point and derivatives up to `order` (0..2) from the basis functions of both directions and
/// the block of the net they weight (see the notation above). No heap allocation.
inline SurfaceDerivs tensor_derivs(const BasisDerivs& Nu, const BasisDerivs& Nv, int p, int q,
                                   int order, const Vector4d* net, int stride) {
  switch (order) {
    case 0:
      return dispatch_degrees<0>(Nu, Nv, p, q, net, stride);
    case 1:
      return dispatch_degrees<1>(Nu, Nv, p, q, net, stride);
    default:
      return dispatch_degrees<2>(Nu, Nv, p, q, net, stride);
  }
}

}  // namespace iga::detail
