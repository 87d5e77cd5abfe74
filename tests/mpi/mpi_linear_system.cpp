// Run by the suite under mpirun (tests/CMakeLists.txt): DistributedLinearSolver
// (iga/solvers/distributed_solver.hpp) on N ranks against the same system solved whole on each
// rank (Eigen's SparseLU). A chain of n unknowns assembled as finite elements: element e adds
// [[1, -1 + a], [-1 - a, 1]] at (e, e + 1), the elements in contiguous blocks per rank; the end
// springs and the shift -sigma of every diagonal entry come from other ranks than the rows'
// owners, so that entries cross ranks and several ranks add at one place. a = 0 is the
// shifted Laplacian tridiag(-1, 2, -1) - sigma I, whose negative eigenvalues are counted in
// closed form: MUMPS's inertia must match. Also: new values on the same pattern (reused), the
// non-symmetric LU, a singular matrix (the free chain) as a status on every rank; each rank's part
// handed in as a compressed matrix (as LinearSolver does) solves as its triplets do, keeps the
// pattern for new values, and a new pattern on one rank alone is a new analysis on every rank.
// Exit 0 on every rank when all hold.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/SparseLU>

#include "iga/parallel/communicator.hpp"
#include "iga/solvers/distributed_solver.hpp"

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

/// This rank's triplets of the chain (see the file's comment); `ends`: the end springs.
Triplets chain(int n, double sigma, double a, bool ends, int rank, int size) {
  Triplets t;
  const int elements = n - 1;
  for (int e = rank * elements / size; e < (rank + 1) * elements / size; ++e) {
    t.emplace_back(e, e, 1.0);
    t.emplace_back(e, e + 1, -1.0 + a);
    t.emplace_back(e + 1, e, -1.0 - a);
    t.emplace_back(e + 1, e + 1, 1.0);
  }
  for (int i = 0; i < n; ++i)
    if (i % size == (rank + 1) % size) t.emplace_back(i, i, -sigma);  // not the row's owner
  if (ends && rank == size - 1) {
    t.emplace_back(0, 0, 1.0);
    t.emplace_back(n - 1, n - 1, 1.0);
  }
  return t;
}

/// The whole matrix: every rank's triplets.
Eigen::SparseMatrix<double> whole(int n, double sigma, double a, bool ends, int size) {
  Triplets all;
  for (int r = 0; r < size; ++r) {
    const Triplets t = chain(n, sigma, a, ends, r, size);
    all.insert(all.end(), t.begin(), t.end());
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(all.begin(), all.end());
  return A;
}

}  // namespace

int main(int argc, char** argv) {
  const iga::ParallelSession session(argc, argv);
  const iga::Communicator& w = iga::world();
  const int r = w.rank(), p = w.size();
  int errors = 0;
  const auto expect = [&](bool ok, const std::string& what) {
    if (!ok) {
      std::fprintf(stderr, "[rank %d] %s\n", r, what.c_str());
      ++errors;
    }
  };
  const int n = 161;
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(1.0 + i);
  for (const double a : {0.0, 0.3}) {
    const bool symmetric = a == 0.0;
    iga::DistributedLinearSolver s(iga::LinearMethod::mumps);
    for (const double sigma : {0.05, 1.3}) {
      const Eigen::SparseMatrix<double> A = whole(n, sigma, a, true, p);
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
      const Eigen::VectorXd ref = lu.solve(b);
      Eigen::VectorXd x;
      const iga::LinearSolveStatus f = s.factorize(n, chain(n, sigma, a, true, r, p), symmetric);
      expect(f == iga::LinearSolveStatus::success, "factorize: " + s.message());
      if (f != iga::LinearSolveStatus::success) continue;
      expect(s.solve(b, x) == iga::LinearSolveStatus::success, "solve: " + s.message());
      expect((x - ref).norm() <= 1e-10 * ref.norm(),
             "solution differs from SparseLU's: " + std::to_string((x - ref).norm() / ref.norm()));
      expect(s.reused_analysis() == (sigma != 0.05), "pattern kept only for the second sigma");
      if (symmetric) {
        int below = 0;  // eigenvalues 2 - 2 cos(k pi / (n + 1)) below sigma
        for (int k = 1; k <= n; ++k)
          if (2.0 - 2.0 * std::cos(k * std::numbers::pi / (n + 1)) < sigma) ++below;
        expect(s.negative_pivots() == below, "inertia " + std::to_string(s.negative_pivots()) +
                                                 ", expected " + std::to_string(below));
      } else {
        expect(s.negative_pivots() == -1, "LU has no inertia");
      }
    }
    // The free symmetric chain without shift is singular (constants): a status on every rank,
    // by LDL^T and by LU.
    iga::DistributedLinearSolver singular(iga::LinearMethod::mumps);
    const iga::LinearSolveStatus st =
        singular.factorize(n, chain(n, 0.0, 0.0, false, r, p), symmetric);
    expect(st == iga::LinearSolveStatus::singular, "a singular matrix is reported");
    expect(!singular.message().empty(), "with a reason");
  }
  // The rows split in blocks over the ranks: together all n, each block after the one before.
  iga::DistributedLinearSolver s(iga::LinearMethod::mumps);
  expect(s.factorize(n, chain(n, 0.05, 0.0, true, r, p), true) == iga::LinearSolveStatus::success,
         "factorize");
  const auto [lo, hi] = s.owned_rows();
  expect(w.sum(static_cast<long long>(hi - lo)) == n, "the blocks hold every row once");
  expect(w.max(double(lo == 0 ? 0 : 1)) == (p > 1 ? 1.0 : 0.0) && hi <= n && lo <= hi,
         "the blocks are ordered ranges");
  // Parts as compressed matrices: the same solution as the triplets'; new values on the same
  // pattern keep it; an explicit zero added on rank 0 alone changes the pattern on every rank.
  {
    const Eigen::SparseMatrix<double> A = whole(n, 0.05, 0.0, true, p);
    const Eigen::VectorXd ref = Eigen::SparseLU<Eigen::SparseMatrix<double>>(A).solve(b);
    const auto part = [&](double sigma, bool extra) {
      Triplets t = chain(n, sigma, 0.0, true, r, p);
      if (extra && r == 0) t.emplace_back(0, n - 1, 0.0);
      Eigen::SparseMatrix<double> P(n, n);
      P.setFromTriplets(t.begin(), t.end());
      P.makeCompressed();
      return P;
    };
    iga::DistributedLinearSolver c(iga::LinearMethod::mumps);
    Eigen::VectorXd x;
    expect(c.factorize(part(0.05, false), true) == iga::LinearSolveStatus::success &&
               c.solve(b, x) == iga::LinearSolveStatus::success,
           "compressed parts: " + c.message());
    expect((x - ref).norm() <= 1e-10 * ref.norm(), "compressed parts: the triplets' solution");
    expect(!c.reused_analysis(), "compressed parts: the first factorization analyses");
    expect(c.factorize(part(0.7, false), true) == iga::LinearSolveStatus::success &&
               c.reused_analysis(),
           "compressed parts: new values keep the pattern");
    expect(c.factorize(part(0.05, true), true) == iga::LinearSolveStatus::success &&
               !c.reused_analysis() && c.solve(b, x) == iga::LinearSolveStatus::success &&
               (x - ref).norm() <= 1e-10 * ref.norm(),
           "compressed parts: a new pattern on rank 0 is a new analysis everywhere");
  }
  const long long failed = w.sum(static_cast<long long>(errors));
  if (r == 0) std::printf("mpi_linear_system: %d ranks, %lld failures\n", p, failed);
  return failed == 0 ? 0 : 1;
}
