// The non-zero rational basis functions of a NURBS curve or surface at a parameter and their
// derivatives up to the second: one implementation for the rod, the shell and the contact
// integrals (which evaluate them at fixed quadrature points).
// References: [PT97] Piegl & Tiller, The NURBS Book, 2nd ed.: A2.3 (B-spline basis and
// derivatives), eq. 4.8 and 4.20 (rational basis, here differentiated by the quotient rule).
//
// Notation (symbol -> code):
//   N_j, N_j', N_j''      B-spline basis and derivatives (A2.3)
//   w_j                   weights
//   W = sum N_j w_j       weight function, W', W''
//   R_j = N_j w_j / W     rational basis                          N (curve), R (surface)
//   R_j' = (N_j' w_j - R_j W') / W                                 dN; d1, d2
//   R_j'' = (N_j'' w_j - 2 R_j' W' - R_j W'') / W                  ddN; d11, d22
//   R_uv = (N_uv w - R_u W_v - R_v W_u - R W_uv) / W                d12
#pragma once

#include <array>
#include <span>
#include <vector>

#include "geometry/bspline_basis.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"

namespace iga {

/// The p+1 rational basis functions of a curve, R_j = N_{first+j} w / W, and their first two
/// derivatives at xi.
struct RationalBasis {
  int first = 0;  ///< index of the first non-zero function (span - p)
  int count = 0;  ///< p + 1
  BasisValues N{}, dN{}, ddN{};
};
/// xi is clamped to the curve's domain.
RationalBasis rational_basis(const NurbsCurve& c, double xi);

/// Largest degree per direction that SurfaceBasis holds (fixed capacity, no heap allocation).
inline constexpr int kMaxSurfaceBasisDegree = 5;
inline constexpr int kMaxSurfaceBasisPoints =
    (kMaxSurfaceBasisDegree + 1) * (kMaxSurfaceBasisDegree + 1);

/// The (p+1)(q+1) non-zero rational basis functions of a surface at (u, v) and their first and
/// second derivatives; local function k = i + (p+1) j is control point global_index(k).
struct SurfaceBasis {
  int span_u = 0, span_v = 0;  ///< knot spans; the first control point is (span_u-p, span_v-q)
  int nu = 0, nv = 0;          ///< p + 1, q + 1
  int num_u_total = 0;         ///< control points in u of the patch (for global indices)
  std::array<double, kMaxSurfaceBasisPoints> R{}, d1{}, d2{}, d11{}, d22{}, d12{};
  int count() const { return nu * nv; }
  int first_u() const { return span_u - nu + 1; }
  int first_v() const { return span_v - nv + 1; }
  int global_index(int k) const {
    return (first_u() + k % nu) + num_u_total * (first_v() + k / nu);
  }
};
/// (u, v) is clamped to the domain. Throws GeometryError for a degree above
/// kMaxSurfaceBasisDegree.
void rational_basis(const NurbsSurface& s, double u, double v, SurfaceBasis& B);

/// The B-spline basis of one direction at one parameter: its knot span and N, N', N'' (A2.3).
/// A surface's basis at (u, v) is the rational combination of the two directions' (below), so
/// a tensor-product rule evaluates each direction once per point of its rule and span instead
/// of once per point of the surface (quadrature and contact points keep no basis of their own).
struct SpanBasis {
  int span = 0;
  BasisDerivs N{};  ///< rows 0..2; rows past the degree's are 0
};
/// t is clamped to the knots' domain [U_p, U_n].
SpanBasis span_basis(const KnotVector& U, int p, double t);
/// The surface basis from the directions' (bu for u, bv for v): the same numbers, bit for bit,
/// as rational_basis(s, u, v, B) at the parameters bu and bv were made at. Throws GeometryError
/// for a degree above kMaxSurfaceBasisDegree.
void rational_basis(const NurbsSurface& s, const SpanBasis& bu, const SpanBasis& bv,
                    SurfaceBasis& B);

/// The values and first derivatives only, for k = i + (p+1) j: rows[3k] = R_k, rows[3k+1] =
/// R_k,u, rows[3k+2] = R_k,v (rational_basis' to round-off: 1/W is taken once), with w[k] the
/// weights of the (p+1)(q+1) control points (span_u - p + i, span_v - q + j): an element's
/// points share them.
void rational_basis_first(const SpanBasis& bu, const SpanBasis& bv, int p, int q, const double* w,
                          double* rows);

/// A rule's points x (on [-1, 1]) mapped into each span between consecutive breaks, span after
/// span: m + h x, with m and h the span's midpoint and half length (the parameters a
/// tensor-product quadrature's SpanBasisTable is made at).
std::vector<double> span_rule_points(std::span<const double> breaks, std::span<const double> x);

/// span_basis at a list of parameters of one direction (a tensor-product rule's points, the
/// same n in each non-empty span, in order): the table a surface's grid of points is formed from.
class SpanBasisTable {
 public:
  SpanBasisTable() = default;
  SpanBasisTable(const KnotVector& U, int p, std::span<const double> params);
  const SpanBasis& operator[](std::size_t i) const { return rows_[i]; }
  std::size_t size() const { return rows_.size(); }

 private:
  std::vector<SpanBasis> rows_;
};

/// sum_k dR[k] x_k over the basis functions of B (x: the patch's control points, global
/// indices): with dR = B.d1 or B.d2 the base vector a_1 or a_2 of the surface of points x.
inline Vector3d combine(const SurfaceBasis& B, const std::array<double, kMaxSurfaceBasisPoints>& dR,
                        std::span<const Vector3d> x) {
  Vector3d r = Vector3d::Zero();
  for (int k = 0; k < B.count(); ++k)
    r.noalias() += dR[static_cast<std::size_t>(k)] * x[static_cast<std::size_t>(B.global_index(k))];
  return r;
}

}  // namespace iga
