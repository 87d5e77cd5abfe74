// B-spline basis functions and their derivatives: the stateless kernels of the NURBS library.
// References: [PT97] L. Piegl, W. Tiller, The NURBS Book, 2nd ed., Springer 1997.
//   find_span        Algorithm A2.1 (p. 68)
//   basis_funs       Algorithm A2.2 (p. 70)
//   ders_basis_funs  Algorithm A2.3 (p. 72)
//
// Notation ([PT97] -> code): p -> p (degree), U -> U (knots, m+1 values), n+1 basis functions
// -> n_basis = m - p, N_{i,p}(u) -> N[j] with i = span - p + j, N^{(k)}_{i,p} -> ders[k][j].
//
// No heap allocation: scratch space is fixed-size, sized by kMaxDegree.
#pragma once

#include <array>
#include <span>

namespace iga {

/// Largest polynomial degree the kernels support (fixed-size scratch arrays).
inline constexpr int kMaxDegree = 10;
/// Largest derivative order the evaluation routines return.
inline constexpr int kMaxDerivOrder = 3;

/// Values of the p+1 non-zero basis functions at u (entries past p unused).
using BasisValues = std::array<double, kMaxDegree + 1>;
/// ders[k][j] = k-th derivative of N_{span-p+j,p}(u) for k <= the requested order (rows
/// beyond it are left untouched).
using BasisDerivs = std::array<BasisValues, kMaxDerivOrder + 1>;

/// A2.1: the knot span index i with U[i] <= u < U[i+1], for n_basis basis functions of degree
/// p. u is clamped to [U[p], U[n_basis]]; u == U[n_basis] returns the last non-empty span.
int find_span(int n_basis, int p, double u, std::span<const double> U);

/// A2.2: the p+1 non-vanishing basis functions N_{span-p..span, p}(u).
void basis_funs(int span, double u, int p, std::span<const double> U, BasisValues& N);

/// A2.3: the non-vanishing basis functions and their derivatives up to order nd
/// (nd <= kMaxDerivOrder; derivatives of order > p are zero).
void ders_basis_funs(int span, double u, int p, int nd, std::span<const double> U,
                     BasisDerivs& ders);

}  // namespace iga
