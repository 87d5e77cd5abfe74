// Gauss-Legendre quadrature (Abramowitz & Stegun 25.4.29).
#include "iga/core/quadrature.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace iga {

/// Gauss-Legendre rule on [-1, 1]: Newton iteration on the roots of P_n from the initial guess
/// x_i ~ cos(pi (i + 3/4) / (n + 1/2)); weights 2 / ((1 - x_i^2) P_n'(x_i)^2) (Abramowitz &
/// Stegun 25.4.29).
void gauss_legendre(int n, std::array<double, kMaxGaussPoints>& x,
                    std::array<double, kMaxGaussPoints>& w) {
  if (n < 1 || n > kMaxGaussPoints)
    throw std::invalid_argument("Gauss-Legendre rule needs 1.." + std::to_string(kMaxGaussPoints) +
                                " points, got " + std::to_string(n));
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;  // P_0, P_1; recurrence (k+1) P_{k+1} = (2k+1) z P_k - k P_{k-1}
      for (int k = 1; k < n; ++k) {
        const double p2 = ((2.0 * k + 1.0) * z * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);  // P_n'
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) <= 1e-15) break;
    }
    x[static_cast<std::size_t>(i)] = -z;  // ascending order
    w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

}  // namespace iga
