// Tests of PETSc's solvers behind LinearSolver (iga/solvers/petsc_engine.hpp): MUMPS's LDL^T
// and LU against SuiteSparse on the same systems, the inertia of a shifted Laplacian against
// its eigenvalues in closed form, the pattern kept with new values, a singular matrix as a
// status, a Krylov solver (GMRES with GAMG) on a 2-D Laplacian, with and without a near null
// space. In a build without PETSc the
// methods are refused with a clear message.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "iga/parallel/communicator.hpp"
#include "iga/solvers/linear_solver.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_petsc_solver {

using namespace iga;

namespace {

/// The 1-D Laplacian tridiag(-1, 2, -1) of size n minus sigma I: eigenvalues
/// 2 - 2 cos(k pi / (n + 1)) - sigma, k = 1..n.
SparseMatrix shifted_laplacian(int n, double sigma) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 - sigma);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

/// A random non-symmetric, diagonally dominant sparse matrix.
SparseMatrix random_general(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < 4; ++k) t.emplace_back(row(gen), j, value(gen));
    t.emplace_back(j, j, 6.0);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = value(gen);
  return b;
}

double relative_residual(const SparseMatrix& A, const VectorXd& x, const VectorXd& b) {
  return (A * x - b).norm() / b.norm();
}

}  // namespace

TEST_CASE("LinearSolver with PETSc: MUMPS LDL^T has the inertia of a shifted Laplacian",
          "[iga][solver][petsc]") {
  if (!parallel_build()) {
    LinearSolver s;
    CHECK_THROWS_WITH(s.set_method(LinearMethod::mumps), Catch::Contains("IGA_WITH_PETSC=OFF"));
    return;
  }
  const int n = 200;
  for (const double sigma : {0.0, 0.37, 1.1, 2.9}) {
    // Eigenvalues below sigma: 2 - 2 cos(k pi / (n + 1)) < sigma.
    int below = 0;
    for (int k = 1; k <= n; ++k)
      if (2.0 - 2.0 * std::cos(k * std::numbers::pi / (n + 1)) < sigma) ++below;
    const SparseMatrix A = shifted_laplacian(n, sigma);
    const VectorXd b = random_vector(n, 3);
    LinearSolver mumps(true), reference(true);
    mumps.set_method(LinearMethod::mumps);
    VectorXd x, y;
    const LinearSolveStatus st = mumps.solve(A, b, x);
    INFO("sigma " << sigma << ", " << below << " eigenvalues below: " << mumps.message());
    REQUIRE(st == LinearSolveStatus::success);
    CHECK(mumps.backend() == LinearBackend::mumps);
    CHECK(mumps.negative_pivots() == below);
    REQUIRE(reference.solve(A, b, y) == LinearSolveStatus::success);
    CHECK(relative_residual(A, x, b) < 1e-10);
    CHECK((x - y).norm() <= 1e-8 * y.norm());  // the shifts keep A far from singular
    if (reference.backend() == LinearBackend::ldlt) CHECK(reference.negative_pivots() == below);
  }
}

TEST_CASE("LinearSolver with PETSc: MUMPS LU as UMFPACK, the pattern kept with new values",
          "[iga][solver][petsc]") {
  if (!parallel_build()) return;  // the refusal: the test above
  const int n = 300;
  LinearSolver mumps(false), reference(false);
  mumps.set_method(LinearMethod::mumps);
  const SparseMatrix A = random_general(n, 7);
  const VectorXd b = random_vector(n, 8);
  VectorXd x, y;
  REQUIRE(mumps.solve(A, b, x) == LinearSolveStatus::success);
  CHECK_FALSE(mumps.reused_analysis());
  CHECK(mumps.negative_pivots() == -1);  // LU: no inertia
  REQUIRE(reference.solve(A, b, y) == LinearSolveStatus::success);
  CHECK((x - y).norm() <= 1e-10 * y.norm());
  // The same pattern with other values: kept (MUMPS's analysis reused), solved right.
  SparseMatrix B = A;
  for (int k = 0; k < B.nonZeros(); ++k) B.valuePtr()[k] *= 1.0 + 0.1 * std::sin(k);
  REQUIRE(mumps.solve(B, b, x) == LinearSolveStatus::success);
  CHECK(mumps.reused_analysis());
  CHECK(relative_residual(B, x, b) < 1e-12);
  // Another pattern: analysed again.
  const SparseMatrix C = random_general(n, 9);
  REQUIRE(mumps.solve(C, b, x) == LinearSolveStatus::success);
  CHECK_FALSE(mumps.reused_analysis());
  CHECK(relative_residual(C, x, b) < 1e-12);
  CHECK(mumps.stats().factorizations == 3);
  CHECK(mumps.stats().analyses == 2);
}

TEST_CASE("LinearSolver with PETSc: a singular matrix is a status with MUMPS's reason",
          "[iga][solver][petsc]") {
  if (!parallel_build()) return;
  // The free-free Laplacian (Neumann ends) is singular: constants are its null space.
  SparseMatrix A = shifted_laplacian(50, 0.0);
  A.coeffRef(0, 0) = 1.0;
  A.coeffRef(49, 49) = 1.0;
  for (const bool symmetric : {true, false}) {
    LinearSolver s(symmetric);
    s.set_method(LinearMethod::mumps);
    VectorXd x;
    const LinearSolveStatus st = s.solve(A, VectorXd::Ones(50), x);
    INFO("symmetric " << symmetric << ": " << s.message());
    CHECK(st == LinearSolveStatus::singular);
    CHECK_FALSE(s.message().empty());
  }
}

TEST_CASE("LinearSolver with PETSc: GMRES with GAMG solves a 2-D Laplacian",
          "[iga][solver][petsc]") {
  if (!parallel_build()) return;
  const int m = 40, n = m * m;  // the 5-point Laplacian on an m x m grid, Dirichlet
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const int r = i * m + j;
      t.emplace_back(r, r, 4.0);
      if (i > 0) t.emplace_back(r, r - m, -1.0);
      if (i + 1 < m) t.emplace_back(r, r + m, -1.0);
      if (j > 0) t.emplace_back(r, r - 1, -1.0);
      if (j + 1 < m) t.emplace_back(r, r + 1, -1.0);
    }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const VectorXd b = random_vector(n, 5);
  LinearSolver s(true);
  s.set_method(LinearMethod::krylov);
  VectorXd x;
  REQUIRE(s.solve(A, b, x) == LinearSolveStatus::success);
  CHECK(s.backend() == LinearBackend::krylov);
  CHECK(relative_residual(A, x, b) < 1e-9);  // the default relative tolerance, 1e-10
  // With a near null space for GAMG (the Laplacian's: the constants), given with a dependent
  // and a zero column that the orthonormalization leaves out: solved as well.
  Eigen::MatrixXd Z(n, 3);
  Z.col(0).setOnes();
  Z.col(1).setConstant(2.0);
  Z.col(2).setZero();
  s.set_near_null_space(Z);
  VectorXd y;
  REQUIRE(s.solve(A, b, y) == LinearSolveStatus::success);
  CHECK(relative_residual(A, y, b) < 1e-9);
}

}  // namespace test_petsc_solver
