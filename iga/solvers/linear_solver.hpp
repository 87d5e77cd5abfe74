// Sparse direct solution of K du = -R, behind one interface: CHOLMOD supernodal/simplicial LL^T
// for symmetric positive definite tangents; for symmetric indefinite ones (past a limit point,
// at contact onset) CHOLMOD's simplicial LDL^T, accepted when its solution's residual is at
// round-off (no pivoting: a small pivot shows as a large residual); UMFPACK LU otherwise (the
// frictional tangent is not symmetric, [KS15] eqs. 38-39, 76-78) and as the last fallback. The
// symbolic analysis is kept and reused while the sparsity pattern is unchanged. Singular
// matrices are a status, not an exception.
// References: [CHOLMOD] Chen, Davis, Hager, Rajamanickam, ACM TOMS 35(3), 2008;
// [UMFPACK] Davis, ACM TOMS 30(2), 2004; [KS15] see ../shared/paper/EQUATIONS.md.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "iga/parallel/dof_layout.hpp"
#include "iga/solvers/petsc_engine.hpp"

namespace iga {

using Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double>;  // column major

/// The factorization that holds the current solution operator.
enum class LinearBackend {
  none,     ///< no successful factorization
  cholmod,  ///< CHOLMOD LL^T (symmetric positive definite)
  ldlt,     ///< CHOLMOD simplicial LDL^T (symmetric indefinite, no pivoting)
  umfpack,  ///< UMFPACK LU (general, or the fallback)
  mumps,    ///< MUMPS through PETSc (LinearMethod::mumps): LDL^T with pivoting, or LU
  krylov,   ///< a PETSc Krylov solver (LinearMethod::krylov)
};

/// How the last factorize()/solve() ended.
enum class LinearSolveStatus {
  success,
  singular,        ///< zero pivot in the LU factorization, or a solution that is not finite
  invalid_input,   ///< non-finite matrix entries, or the library rejected the matrix
  not_factorized,  ///< solve() without a successful factorize()
};

/// Short lower-case names ("cholmod", "singular", ...) for messages and logs.
const char* to_string(LinearBackend b);
const char* to_string(LinearSolveStatus s);

/// Counters and wall times (seconds), cumulative since construction or reset().
struct LinearSolverStats {
  int analyses = 0;             ///< symbolic analyses (fill-reducing ordering), both backends
  int factorizations = 0;       ///< numeric factorizations attempted (a fallback counts two)
  int cholesky_failures = 0;    ///< Cholesky attempts that found the matrix not positive definite
  int ldlt_factorizations = 0;  ///< LDL^T factorizations (successful or not)
  int ldlt_rejected = 0;        ///< LDL^T factorizations or solutions rejected (then UMFPACK)
  int solves = 0;               ///< triangular solves
  double time_analyze = 0.0;
  double time_factorize = 0.0;
  double time_solve = 0.0;
};

/// A sparse direct solver for square Eigen::SparseMatrix<double>.
///
/// symmetric() == true: the matrix is taken as symmetric (the full matrix is passed; CHOLMOD
/// reads its lower triangle) and factorized by CHOLMOD LL^T; if that fails (not positive
/// definite: indefinite or singular), by CHOLMOD simplicial LDL^T, and if that fails too (a zero
/// pivot, or at solve time a residual above 1e-10 (|A| |x| + |b|) after one step of iterative
/// refinement: the growth of an unpivoted factorization), by UMFPACK LU. After an LDL^T with
/// negative pivots the next factorize() starts with LDL^T (the matrices of a Newton sequence
/// keep their inertia from one iteration to the next, and a failing LL^T costs a factorization
/// up to its failing pivot); one without negative pivots goes back to LL^T.
/// symmetric() == false: UMFPACK only.
///
/// The pattern of the last matrix is kept as its signature; a matrix with the same pattern
/// (same size, column pointers and row indices; explicit zeros count as entries) reuses each
/// backend's symbolic analysis. The solver keeps its own copy of the matrix (UMFPACK's
/// iterative refinement reads it at solve time), so the caller's matrix may change afterwards.
class LinearSolver {
 public:
  explicit LinearSolver(bool symmetric = true);
  ~LinearSolver();
  LinearSolver(LinearSolver&&) noexcept;
  LinearSolver& operator=(LinearSolver&&) noexcept;
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Picks CHOLMOD (with UMFPACK fallback) or UMFPACK for the next factorize().
  void set_symmetric(bool symmetric);
  /// The library: SuiteSparse (default; as described above) or PETSc's MUMPS or Krylov solvers
  /// (petsc_engine.hpp; symmetric() picks MUMPS's LDL^T or LU). Forgets the factorization.
  /// Throws std::runtime_error for a PETSc method in a build without PETSc.
  void set_method(LinearMethod method);
  LinearMethod method() const;
  /// Distributed (NonlinearProblem::distributed): factorize() takes this rank's part of the
  /// matrix, summed over the ranks of the run by DistributedLinearSolver (MUMPS, or the Krylov
  /// method), and solve() is collective: without a layout, b is the same on every rank and every
  /// rank gets the whole solution; with the problem's (NonlinearProblem::layout, not owned),
  /// b is read at the rank's own unknowns and x is current at its own and its ghosts
  /// (DistributedLinearSolver::set_layout). Needs a PETSc method (std::invalid_argument
  /// otherwise). Forgets the factorization.
  void set_distributed(bool distributed, const DofLayout* layout = nullptr);
  bool distributed() const;
  bool symmetric() const;
  /// The Krylov method's near null space (the columns of Z, one entry per unknown: the
  /// bodies' rigid-body motions, NonlinearProblem::near_null_space) for its algebraic
  /// multigrid preconditioner (PETSc's GAMG), used from the next factorize() on; the direct
  /// solvers ignore it. Empty: none.
  void set_near_null_space(const Eigen::MatrixXd& Z);

  /// Analyzes (if the pattern changed) and factorizes A. Throws std::invalid_argument if A is
  /// not square; every numerical failure is a status, with a message.
  [[nodiscard]] LinearSolveStatus factorize(const SparseMatrix& A);
  /// x = A^-1 b with the last successful factorization. Throws std::invalid_argument if the size
  /// of b does not match. x need not be sized; b and x must not alias.
  [[nodiscard]] LinearSolveStatus solve(const VectorXd& b, VectorXd& x);
  /// factorize(A), then solve(b, x).
  [[nodiscard]] LinearSolveStatus solve(const SparseMatrix& A, const VectorXd& b, VectorXd& x);

  /// Status of the last factorize() or solve().
  LinearSolveStatus status() const;
  /// What happened, for logs: empty after a plain success; after a fallback, why the Cholesky
  /// failed ("not positive definite at column 3 of 10; factorized by UMFPACK"); after a failure,
  /// the reason.
  const std::string& message() const;
  /// The backend of the current factorization (none after a failed factorize()).
  LinearBackend backend() const;
  /// Whether the last factorize() tried CHOLMOD LL^T and found the matrix not positive definite
  /// (then LDL^T or UMFPACK holds the factorization).
  bool fell_back() const;
  /// The number of negative pivots of the last LDL^T factorization (its inertia: the number of
  /// negative eigenvalues, by Sylvester's law); 0 after LL^T, -1 after UMFPACK or a Krylov
  /// solver (unknown); MUMPS: its inertia if symmetric, else -1.
  int negative_pivots() const;
  /// Whether the last factorize() reused a symbolic analysis (pattern unchanged).
  bool reused_analysis() const;
  /// A cheap estimate of the reciprocal condition number of the current factorization
  /// (CHOLMOD: (min L_ii / max L_ii)^2; UMFPACK: min |U_ii| / max |U_ii|); 0 if none. A value
  /// near machine epsilon warns of a (nearly) singular matrix that the pivots did not catch.
  /// PETSc's solvers: not estimated, 1.
  double rcond() const;
  const LinearSolverStats& stats() const;

  /// Forgets the pattern, the analyses, the factorization and the statistics.
  void reset();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace iga
