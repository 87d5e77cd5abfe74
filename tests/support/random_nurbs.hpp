// Random NURBS curves and surfaces for property tests (seeded, reproducible).
#pragma once

#include <algorithm>
#include <random>
#include <vector>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"

namespace iga::test {

/// A clamped knot vector on [0, 1] of degree p with n_basis functions and random interior
/// knots, some repeated (multiplicity up to max_mult <= p).
inline std::vector<double> random_knots(std::mt19937& rng, int p, int n_basis, int max_mult = 1) {
  std::uniform_real_distribution<double> unif(0.02, 0.98);
  std::uniform_int_distribution<int> mult_dist(1, std::max(1, max_mult));
  std::vector<double> interior;
  while (static_cast<int>(interior.size()) < n_basis - p - 1) {
    const double x = unif(rng);
    const int m = std::min(mult_dist(rng), n_basis - p - 1 - static_cast<int>(interior.size()));
    interior.insert(interior.end(), static_cast<std::size_t>(m), x);
  }
  std::sort(interior.begin(), interior.end());
  std::vector<double> U(static_cast<std::size_t>(p + 1), 0.0);
  U.insert(U.end(), interior.begin(), interior.end());
  U.insert(U.end(), static_cast<std::size_t>(p + 1), 1.0);
  return U;
}

inline NurbsCurve random_curve(std::mt19937& rng, int p, int n, bool rational, int max_mult = 1) {
  std::uniform_real_distribution<double> coord(-1.0, 1.0), wdist(0.5, 2.0);
  std::vector<Vector3d> P(static_cast<std::size_t>(n));
  std::vector<double> w(static_cast<std::size_t>(n), 1.0);
  for (int i = 0; i < n; ++i) {
    P[i] = Vector3d(coord(rng), coord(rng), coord(rng));
    if (rational) w[i] = wdist(rng);
  }
  return NurbsCurve(p, random_knots(rng, p, n, max_mult), P, w);
}

inline NurbsSurface random_surface(std::mt19937& rng, int p, int q, int nu, int nv, bool rational,
                                   int max_mult = 1) {
  std::uniform_real_distribution<double> coord(-1.0, 1.0), wdist(0.5, 2.0);
  std::vector<Vector3d> P(static_cast<std::size_t>(nu * nv));
  std::vector<double> w(P.size(), 1.0);
  for (std::size_t i = 0; i < P.size(); ++i) {
    P[i] = Vector3d(coord(rng), coord(rng), coord(rng));
    if (rational) w[i] = wdist(rng);
  }
  return NurbsSurface(p, random_knots(rng, p, nu, max_mult), q, random_knots(rng, q, nv, max_mult),
                      P, w);
}

}  // namespace iga::test
