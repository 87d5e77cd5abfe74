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

#include "geometry/bspline_basis.hpp"
#include "geometry/derivatives.hpp"

namespace iga::detail {

// A3.6 on the homogeneous net gives A^(k,l), then A4.4 / eq. (4.20):
// S^(k,l) = (A^(k,l) - sum_{i=1..k} C(k,i) w^(i,0) S^(k-i,l)
//           - sum_{j=1..l} C(l,j) [w^(0,j) S^(k,l-j) + sum_{i=1..k} C(k,i) w^(i,j) S^(k-i,l-j)]) /
//           w
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
SurfaceDerivs dispatch_degrees(const BasisDerivs& Nu, const BasisDerivs& Nv, int p, int q,
                               const Vector4d* net, int stride) {
  if (p == 2 && q == 2) return eval_derivs<O, 2, 2>(Nu, Nv, p, q, net, stride);
  if (p == 3 && q == 3) return eval_derivs<O, 3, 3>(Nu, Nv, p, q, net, stride);
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
