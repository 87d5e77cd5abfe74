// Gauss-Legendre quadrature on [-1, 1], shared by the element and contact integrals.
// Reference: Abramowitz & Stegun 25.4.29 (nodes: roots of P_n; weights 2/((1-x^2) P_n'(x)^2)).
#pragma once

#include <array>

namespace iga {

inline constexpr int kMaxGaussPoints = 20;

/// n-point rule (1 <= n <= kMaxGaussPoints): nodes x ascending, weights w (entries past n
/// unused). Exact for polynomials of degree <= 2n - 1.
void gauss_legendre(int n, std::array<double, kMaxGaussPoints>& x,
                    std::array<double, kMaxGaussPoints>& w);

}  // namespace iga
