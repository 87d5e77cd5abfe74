// Finite-difference check of a contact integral's tangent, shared by the contact tests: any
// class with assemble(x, R, triplets*) over control points x (3 unknowns each, dof 3 a + k).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/derivatives.hpp"

namespace iga::test {

/// The residual alone at x (a zero vector plus the contributions).
template <class Contact>
Eigen::VectorXd residual(Contact& c, const std::vector<Vector3d>& x) {
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  c.assemble(x, R, nullptr);
  return R;
}

/// max |K - dR/dx| / max |K| with dR/dx by central differences, column by column: each column
/// is compared with the differences of every step in `steps` (absolute), the nearest taken; a
/// difference whose residual at x + s e_j or x - s e_j fails `valid()` (called right after each
/// evaluation: e.g. a kink of the contact law crossed) is left out, and a column left with none
/// is counted in *skipped (if given). The contact is left evaluated at x.
template <class Contact, class Valid>
double tangent_error(Contact& c, const std::vector<Vector3d>& x, const std::vector<double>& steps,
                     Valid&& valid, int* skipped = nullptr) {
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  std::vector<Eigen::Triplet<double>> trip;
  c.assemble(x, R, &trip);
  Eigen::SparseMatrix<double> K(R.size(), R.size());
  K.setFromTriplets(trip.begin(), trip.end());
  const Eigen::MatrixXd Kd(K);
  double err = 0.0;
  if (skipped) *skipped = 0;
  for (Eigen::Index j = 0; j < R.size(); ++j) {
    double col = std::numeric_limits<double>::infinity();
    for (const double h : steps) {
      std::vector<Vector3d> xp = x, xm = x;
      xp[static_cast<std::size_t>(j / 3)][j % 3] += h;
      xm[static_cast<std::size_t>(j / 3)][j % 3] -= h;
      const Eigen::VectorXd rp = residual(c, xp);
      const bool valid_p = valid();
      const Eigen::VectorXd rm = residual(c, xm);
      if (!valid_p || !valid()) continue;
      col = std::min(col, ((rp - rm) / (2 * h) - Kd.col(j)).cwiseAbs().maxCoeff());
    }
    if (std::isinf(col)) {
      if (skipped) ++*skipped;
      continue;
    }
    err = std::max(err, col);
  }
  c.assemble(x, R, nullptr);
  return err / std::max(Kd.cwiseAbs().maxCoeff(), 1e-300);
}

/// The same with one step h and every difference taken.
template <class Contact>
double tangent_error(Contact& c, const std::vector<Vector3d>& x, double h) {
  return tangent_error(c, x, {h}, [] { return true; });
}

}  // namespace iga::test
