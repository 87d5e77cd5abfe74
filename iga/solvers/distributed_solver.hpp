// K du = b over the ranks of the run (world(), iga/parallel/communicator.hpp): each rank hands
// in its part of the tangent, the sum of its own elements' entries (global free DOF numbers, any
// rows: the parts of several ranks at one place are summed), as a compressed sparse matrix
// (or as triplets). PETSc assembles the parts into one distributed AIJ matrix (coordinate
// assembly: MatSetPreallocationCOO once per pattern, then MatSetValuesCOO straight from the
// part's value array, no copy), and b into a PETSc vector; then
// - the direct method (mumps): MUMPS itself (with_petsc/mumps_direct.hpp) takes each rank's rows
//   of that matrix (a symmetric matrix's lower triangle), ordered by METIS's nested dissection of
//   the whole pattern, computed once per pattern on rank 0 (Debian's MUMPS has PORD alone, 27 %
//   more work on shell tangents); LDL^T with the inertia for a symmetric K, LU otherwise; b and x
//   pass through rank 0 (PETSc's scatters). The PETSc option -iga_mumps_through_petsc takes
//   PETSc's MUMPS interface instead (MUMPS's own ordering);
// - the Krylov method: GMRES with GAMG, or PETSc's options.
// With a DofLayout (set_layout: the model's), a rank's rows are the unknowns it owns (numbered by
// owner), it gives b at those, and gets x at its own unknowns and its ghosts (0 elsewhere).
// Without one, the rows are split in even blocks, b is the same on every rank and every rank
// gets the whole x.
// While no rank's pattern changed, the matrix keeps its pattern and the solver its analysis;
// what a rank keeps to tell is its part's pattern (4 bytes an entry). MUMPS's controls pass in
// PETSc's options (-mat_mumps_icntl_<k>, -mat_mumps_cntl_<k>) on either path. In a build without
// PETSc the constructor throws: one process needs no distribution (LinearSolver).
// References: [MUMPS], [PETSc] as in petsc_engine.hpp; [METIS] Karypis, Kumar, SIAM J. Sci.
// Comput. 20(1), 1998.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "iga/parallel/dof_layout.hpp"
#include "iga/solvers/linear_solver.hpp"

namespace iga {

class DistributedLinearSolver {
 public:
  /// `method`: mumps or krylov (std::invalid_argument for suitesparse).
  explicit DistributedLinearSolver(LinearMethod method);
  ~DistributedLinearSolver();
  DistributedLinearSolver(const DistributedLinearSolver&) = delete;
  DistributedLinearSolver& operator=(const DistributedLinearSolver&) = delete;

  /// Collective: the n x n matrix summed from every rank's part `local` (square, compressed,
  /// column major; its value array is read, not copied, by PETSc), factorized (MUMPS) or its
  /// preconditioner set up (Krylov). A failure is a status, the same on every rank, with the
  /// reason in message().
  [[nodiscard]] LinearSolveStatus factorize(const Eigen::SparseMatrix<double>& local,
                                            bool symmetric);
  /// The same with this rank's part as triplets (summed where they repeat a place).
  [[nodiscard]] LinearSolveStatus factorize(int n, const std::vector<Eigen::Triplet<double>>& local,
                                            bool symmetric);
  /// Collective: x = K^-1 b (b and x of size n): without a layout, b the same on every rank and
  /// x, the whole solution, on every rank; with one, b read at this rank's own unknowns and x
  /// current at its own unknowns and its ghosts (0 elsewhere).
  [[nodiscard]] LinearSolveStatus solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The Krylov method's near null space for the next factorize()s: columns of the whole
  /// matrix's rows, the same on every rank (NonlinearProblem::near_null_space); ignored by
  /// MUMPS.
  void set_near_null_space(const Eigen::MatrixXd& Z);
  /// The ownership of the unknowns (not owned; it must outlive the solver), or null: rows split
  /// evenly, b and x replicated. A new layout takes effect at the next factorize().
  void set_layout(const DofLayout* layout);
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
