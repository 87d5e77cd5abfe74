// Thread-count independence checks (issue 17, item 4): how many entries of two assemblies
// (residual and tangent triplets) differ, bit for bit; running a piece of code on n threads.
#pragma once

#include <cstddef>
#include <vector>

#include <omp.h>
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

/// Runs f() with n OpenMP threads, then restores the thread count it found.
template <class F>
void on_threads(int n, F&& f) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(n);
  f();
  omp_set_num_threads(saved);
}

}  // namespace iga::test
