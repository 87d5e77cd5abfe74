// Shared helpers of the geometry tests: random directions and parameters, and the check of a
// surface's exact derivatives against central finite differences of its points.
#pragma once

#include <algorithm>
#include <random>
#include <vector>

#include "geometry/knot_vector.hpp"
#include "geometry/surface.hpp"

namespace iga::test {

inline Vector3d random_unit(std::mt19937& g) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vector3d v;
  do v = Vector3d(n(g), n(g), n(g));
  while (v.norm() < 1e-3);
  return v.normalized();
}

inline double uniform(std::mt19937& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}

inline Vector3d random_vector(std::mt19937& g, double s = 1.0) {
  return Vector3d(uniform(g, -s, s), uniform(g, -s, s), uniform(g, -s, s));
}

/// A random parameter strictly inside a random element (away from C^0 knots, so that
/// central differences with steps <= 1e-4 stay in one element).
inline double inside_element(std::mt19937& g, const KnotVector& k) {
  const std::vector<double> br = k.breaks();
  const std::size_t e = std::uniform_int_distribution<std::size_t>(0, br.size() - 2)(g);
  return br[e] + uniform(g, 0.1, 0.9) * (br[e + 1] - br[e]);
}

/// Largest deviation of the exact derivatives (orders 0..2) from central differences of
/// point(), relative to |exact| + L (L = size of the surface, for derivatives that vanish).
/// h1: step of the first differences, h2: of the second.
inline double surface_fd_error(const Surface& s, double u, double v, double L, double h1 = 1e-5,
                               double h2 = 1e-4) {
  const SurfaceDerivs d = s.derivs(u, v, 2);
  auto P = [&s](double a, double b) { return s.point(a, b); };
  auto rel = [L](const Vector3d& fd, const Vector3d& ex) {
    return (fd - ex).norm() / (ex.norm() + L);
  };
  const Vector3d fu = (P(u + h1, v) - P(u - h1, v)) / (2 * h1);
  const Vector3d fv = (P(u, v + h1) - P(u, v - h1)) / (2 * h1);
  const Vector3d fuu = (P(u + h2, v) - 2 * P(u, v) + P(u - h2, v)) / (h2 * h2);
  const Vector3d fvv = (P(u, v + h2) - 2 * P(u, v) + P(u, v - h2)) / (h2 * h2);
  const Vector3d fuv =
      (P(u + h2, v + h2) - P(u + h2, v - h2) - P(u - h2, v + h2) + P(u - h2, v - h2)) /
      (4 * h2 * h2);
  return std::max({rel(P(u, v), d.S), rel(fu, d.Su), rel(fv, d.Sv), rel(fuu, d.Suu),
                   rel(fvv, d.Svv), rel(fuv, d.Suv)});
}

}  // namespace iga::test
