// K du = b over the ranks of the run (world(), iga/parallel/communicator.hpp): each rank hands
// in the tangent's triplets of its own elements (global free DOF numbers, any rows: entries of
// several ranks at one place are summed), PETSc assembles them into one distributed AIJ matrix
// (coordinate assembly: MatSetPreallocationCOO, MatSetValuesCOO; rows split in even blocks),
// MUMPS (LDL^T with the inertia for a symmetric K, LU otherwise) or a Krylov solver solves it,
// and every rank gets the whole solution. The right-hand side is the same on every rank (the
// residual summed over the ranks). While no rank's sequence of triplet positions changed, the
// matrix keeps its pattern and MUMPS its analysis. In a build without PETSc the constructor
// throws: one process needs no distribution (LinearSolver).
// References: [MUMPS], [PETSc] as in petsc_engine.hpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "iga/solvers/linear_solver.hpp"

namespace iga {

class DistributedLinearSolver {
 public:
  /// `method`: mumps or krylov (std::invalid_argument for suitesparse).
  explicit DistributedLinearSolver(LinearMethod method);
  ~DistributedLinearSolver();
  DistributedLinearSolver(const DistributedLinearSolver&) = delete;
  DistributedLinearSolver& operator=(const DistributedLinearSolver&) = delete;

  /// Collective: the matrix of n unknowns summed from every rank's `local` triplets, factorized
  /// (MUMPS) or its preconditioner set up (Krylov). A failure is a status, the same on every
  /// rank, with the reason in message().
  [[nodiscard]] LinearSolveStatus factorize(int n, const std::vector<Eigen::Triplet<double>>& local,
                                            bool symmetric);
  /// Collective: x = K^-1 b with b (size n) the same on every rank; x, the whole solution, on
  /// every rank.
  [[nodiscard]] LinearSolveStatus solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The Krylov method's near null space for the next factorize()s: columns of the whole
  /// matrix's rows, the same on every rank (NonlinearProblem::near_null_space); ignored by
  /// MUMPS.
  void set_near_null_space(const Eigen::MatrixXd& Z);
  const std::string& message() const;
  /// The inertia's negative count after a symmetric MUMPS factorization, else -1.
  int negative_pivots() const;
  /// Whether the last factorize() kept the pattern (every rank's triplet positions unchanged).
  bool reused_analysis() const;
  /// The rows this rank owns: [first, last).
  std::pair<int, int> owned_rows() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace iga
