// Thread-count independence checks (issue 17, item 4): how many entries of two assemblies
// (residual and tangent triplets) differ, bit for bit.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iga::test {

/// The entries of a and b that differ, and the triplets of A and B that differ in row, column
/// or value (the sizes must agree).
inline int count_differences(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                             const std::vector<Eigen::Triplet<double>>& A,
                             const std::vector<Eigen::Triplet<double>>& B) {
  int differ = 0;
  for (Eigen::Index i = 0; i < a.size(); ++i) differ += a[i] != b[i];
  for (std::size_t k = 0; k < A.size(); ++k)
    differ += A[k].row() != B[k].row() || A[k].col() != B[k].col() || A[k].value() != B[k].value();
  return differ;
}

}  // namespace iga::test
