// PETSc's solvers behind LinearSolver (linear_solver.hpp): MUMPS, a sparse direct solver with
// pivoting (LDL^T for symmetric matrices, with their inertia; LU otherwise), or a Krylov method
// with a preconditioner chosen by PETSc's options (e.g. -ksp_type gmres -pc_type gamg, or
// -pc_type hypre). The matrix is copied into a PETSc AIJ matrix, its pattern kept while it is
// unchanged, so that MUMPS keeps its analysis. PETSc's options come from the command line
// (after --petsc, iga/parallel/communicator.hpp) or PETSC_OPTIONS. In a build without PETSc
// (IGA_WITH_PETSC=OFF) make_petsc_engine throws.
// References: [MUMPS] Amestoy, Duff, L'Excellent, Koster, SIAM J. Matrix Anal. Appl. 23(1), 2001;
// [PETSc] Balay et al., PETSc/TAO Users Manual, ANL-21/39 (3.18).
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iga {

/// Which library solves the Newton systems.
enum class LinearMethod {
  suitesparse,  ///< CHOLMOD LL^T / LDL^T, UMFPACK LU (one process; the default there)
  mumps,        ///< MUMPS through PETSc: LDL^T with pivoting (symmetric), LU otherwise
  krylov,       ///< a PETSc Krylov solver and preconditioner from PETSc's options
};
const char* to_string(LinearMethod m);

class PetscEngine {
 public:
  virtual ~PetscEngine() = default;
  /// Copies A (square, compressed, column major; both triangles) and factorizes it (MUMPS) or
  /// sets up the preconditioner (Krylov). false with the reason in `why` on a failure (a zero
  /// pivot, a library error).
  virtual bool factorize(const Eigen::SparseMatrix<double>& A, bool symmetric,
                         std::string& why) = 0;
  /// x = A^-1 b; false with the reason (Krylov: not converged).
  virtual bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, std::string& why) = 0;
  /// Negative eigenvalues of the last symmetric MUMPS factorization (its inertia); -1 unknown.
  virtual int negative_pivots() const = 0;
  /// Whether the last factorize() kept the matrix's pattern (and MUMPS its analysis).
  virtual bool reused_analysis() const = 0;
  /// The Krylov method's near null space for the next factorize()s (algebraic multigrid: the
  /// rigid-body motions of the bodies, NonlinearProblem::near_null_space); ignored by MUMPS.
  virtual void set_near_null_space(const Eigen::MatrixXd& Z) { (void)Z; }
};

/// The engine of `method` (mumps or krylov; PETSc is started on first use, ensure_petsc).
/// Throws std::invalid_argument for suitesparse, std::runtime_error without PETSc.
std::unique_ptr<PetscEngine> make_petsc_engine(LinearMethod method);

}  // namespace iga
