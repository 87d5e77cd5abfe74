// Finite-difference check of a contact integral's tangent, shared by the contact tests: any
// class with assemble(x, R, triplets*) over control points x (3 unknowns each, dof 3 a + k).
#pragma once

#include <algorithm>
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

/// max |K - dR/dx| / max |K|, dR/dx by central differences with the absolute step h. The
/// contact is left evaluated at x.
template <class Contact>
double tangent_error(Contact& c, const std::vector<Vector3d>& x, double h) {
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  std::vector<Eigen::Triplet<double>> trip;
  c.assemble(x, R, &trip);
  Eigen::SparseMatrix<double> K(R.size(), R.size());
  K.setFromTriplets(trip.begin(), trip.end());
  const Eigen::MatrixXd Kd(K);
  double err = 0.0;
  for (Eigen::Index j = 0; j < R.size(); ++j) {
    std::vector<Vector3d> xp = x, xm = x;
    xp[static_cast<std::size_t>(j / 3)][j % 3] += h;
    xm[static_cast<std::size_t>(j / 3)][j % 3] -= h;
    const Eigen::VectorXd fd = (residual(c, xp) - residual(c, xm)) / (2 * h);
    err = std::max(err, (fd - Kd.col(j)).cwiseAbs().maxCoeff());
  }
  c.assemble(x, R, nullptr);
  return err / std::max(Kd.cwiseAbs().maxCoeff(), 1e-300);
}

}  // namespace iga::test
