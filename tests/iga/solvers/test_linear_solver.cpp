// Tests of the sparse direct solvers (iga/solvers/linear_solver.hpp): CHOLMOD and UMFPACK against
// Eigen's SparseLU on random systems, reuse of the symbolic analysis, the fallback from Cholesky
// to LU on indefinite symmetric matrices, singular and non-finite matrices as statuses.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/SparseLU>

#include "iga/solvers/linear_solver.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_linear_solver {

using namespace iga;

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

/// Random sparse n x n matrix with about `per_col` off-diagonal entries per column, made
/// diagonally dominant (so non-singular): symmetric with a positive diagonal is SPD; `negative`
/// flips the sign of every third diagonal entry (symmetric: indefinite, still non-singular).
SparseMatrix random_matrix(int n, int per_col, bool symmetric, bool negative, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Triplets t;
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < per_col; ++k) {
      const int i = row(gen);
      if (i == j) continue;
      const double v = value(gen);
      t.emplace_back(i, j, v);
      if (symmetric) t.emplace_back(j, i, v);
    }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  // Diagonal dominance by rows and columns.
  Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd col_sum = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      row_sum(it.row()) += std::abs(it.value());
      col_sum(it.col()) += std::abs(it.value());
    }
  for (int i = 0; i < n; ++i) {
    const double d = 1.0 + std::max(row_sum(i), col_sum(i)) + 0.5 * std::abs(value(gen));
    t.emplace_back(i, i, (negative && i % 3 == 1) ? -d : d);
  }
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b(i) = value(gen);
  return b;
}

Eigen::VectorXd sparse_lu_solve(const SparseMatrix& A, const Eigen::VectorXd& b) {
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(A);
  REQUIRE(lu.info() == Eigen::Success);
  return lu.solve(b);
}

/// Solves with `solver` and checks the solution against SparseLU and the residual.
void check_solve(LinearSolver& solver, const SparseMatrix& A, unsigned seed) {
  const Eigen::VectorXd b = random_vector(static_cast<int>(A.rows()), seed);
  Eigen::VectorXd x;
  REQUIRE(solver.solve(A, b, x) == LinearSolveStatus::success);
  const Eigen::VectorXd x_ref = sparse_lu_solve(A, b);
  CHECK((x - x_ref).norm() <= 1e-12 * x_ref.norm());
  CHECK((A * x - b).norm() <= 1e-13 * b.norm() * (1.0 + A.cwiseAbs().sum() / A.rows()));
}

}  // namespace

TEST_CASE("LinearSolver: CHOLMOD solves random SPD systems as SparseLU does", "[iga][solver]") {
  // Small and sparse (simplicial LL^T) and larger with much fill (supernodal LL^T).
  for (const auto& [n, per_col] :
       std::vector<std::pair<int, int>>{{1, 0}, {8, 2}, {200, 3}, {600, 12}}) {
    CAPTURE(n, per_col);
    const SparseMatrix A = random_matrix(n, per_col, true, false, 17u + n);
    LinearSolver solver(true);
    check_solve(solver, A, 3u);
    CHECK(solver.backend() == LinearBackend::cholmod);
    CHECK_FALSE(solver.fell_back());
    CHECK(solver.message().empty());
    CHECK(solver.stats().cholesky_failures == 0);
    CHECK(solver.rcond() > 0.0);
    CHECK(solver.rcond() <= 1.0);
  }
}

TEST_CASE("LinearSolver: UMFPACK solves random non-symmetric systems as SparseLU does",
          "[iga][solver]") {
  for (const auto& [n, per_col] : std::vector<std::pair<int, int>>{{1, 0}, {8, 2}, {300, 5}}) {
    CAPTURE(n, per_col);
    const SparseMatrix A = random_matrix(n, per_col, false, true, 29u + n);
    LinearSolver solver(false);
    check_solve(solver, A, 5u);
    CHECK(solver.backend() == LinearBackend::umfpack);
    CHECK_FALSE(solver.fell_back());
    CHECK(solver.stats().cholesky_failures == 0);
    CHECK(solver.rcond() > 0.0);
  }
}

TEST_CASE("LinearSolver: the symbolic analysis is reused while the pattern is unchanged",
          "[iga][solver]") {
  for (const bool symmetric : {true, false}) {
    CAPTURE(symmetric);
    const SparseMatrix A1 = random_matrix(120, 4, symmetric, !symmetric, 7u);
    // Same pattern, other values: a scaled copy plus a shifted diagonal.
    SparseMatrix A2 = 2.5 * A1;
    for (int i = 0; i < A2.rows(); ++i) A2.coeffRef(i, i) += 0.75;
    LinearSolver solver(symmetric);
    check_solve(solver, A1, 1u);
    CHECK_FALSE(solver.reused_analysis());
    CHECK(solver.stats().analyses == 1);
    check_solve(solver, A2, 2u);
    CHECK(solver.reused_analysis());
    CHECK(solver.stats().analyses == 1);
    CHECK(solver.stats().factorizations == 2);

    // The same pattern given in uncompressed storage is recognized.
    SparseMatrix A3 = A2;
    A3.uncompress();
    REQUIRE_FALSE(A3.isCompressed());
    check_solve(solver, A3, 4u);
    CHECK(solver.reused_analysis());
    CHECK(solver.stats().analyses == 1);

    // A new pattern (one more entry pair) triggers a new analysis.
    SparseMatrix A4 = A1;
    A4.coeffRef(0, 119) += 0.01;
    A4.coeffRef(119, 0) += 0.01;
    A4.makeCompressed();
    REQUIRE(A4.nonZeros() > A1.nonZeros());
    check_solve(solver, A4, 6u);
    CHECK_FALSE(solver.reused_analysis());
    CHECK(solver.stats().analyses == 2);
    CHECK(solver.stats().solves == 4);
    CHECK(solver.stats().time_factorize >= 0.0);
  }
}

TEST_CASE("LinearSolver: an indefinite symmetric matrix is factorized by LDL^T with its inertia",
          "[iga][solver]") {
  for (const auto& [n, per_col] : std::vector<std::pair<int, int>>{{9, 2}, {600, 12}}) {
    CAPTURE(n, per_col);
    const SparseMatrix indefinite = random_matrix(n, per_col, true, true, 41u);
    // the number of negative eigenvalues, from the dense symmetric eigensolver
    const Eigen::VectorXd lambda =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(indefinite)).eigenvalues();
    const int negative = static_cast<int>((lambda.array() < 0.0).count());
    REQUIRE(negative > 0);
    LinearSolver solver(true);
    check_solve(solver, indefinite, 8u);
    CHECK(solver.backend() == LinearBackend::ldlt);
    CHECK(solver.fell_back());
    CHECK(solver.negative_pivots() == negative);  // Sylvester's law of inertia
    CHECK(solver.stats().cholesky_failures == 1);
    CHECK(solver.stats().ldlt_factorizations == 1);
    CHECK(solver.stats().factorizations == 2);
    CHECK_THAT(solver.message(),
               Catch::Contains("not positive definite") && Catch::Contains("LDL^T"));
    // the next matrix of the pattern goes to LDL^T at once (no failing LL^T first)
    check_solve(solver, indefinite, 10u);
    CHECK(solver.backend() == LinearBackend::ldlt);
    CHECK_FALSE(solver.fell_back());
    CHECK(solver.stats().cholesky_failures == 1);

    // An SPD matrix with the same pattern: LDL^T finds no negative pivot, so the next
    // factorization is LL^T again.
    SparseMatrix spd = indefinite;
    for (int i = 0; i < n; ++i) spd.coeffRef(i, i) = std::abs(spd.coeff(i, i));
    check_solve(solver, spd, 9u);
    CHECK(solver.backend() == LinearBackend::ldlt);
    CHECK(solver.negative_pivots() == 0);
    check_solve(solver, spd, 11u);
    CHECK(solver.backend() == LinearBackend::cholmod);
    CHECK(solver.negative_pivots() == 0);
    CHECK(solver.reused_analysis());
    CHECK(solver.stats().analyses == 2);  // one per CHOLMOD factorization kind
  }
}

TEST_CASE("LinearSolver: where LDL^T without pivoting fails, UMFPACK solves", "[iga][solver]") {
  // A zero diagonal: every symmetric permutation leaves a zero first pivot.
  SparseMatrix zero(2, 2);
  zero.insert(0, 1) = 1.0;
  zero.insert(1, 0) = 1.0;
  zero.makeCompressed();
  LinearSolver solver(true);
  check_solve(solver, zero, 3u);
  CHECK(solver.backend() == LinearBackend::umfpack);
  CHECK(solver.negative_pivots() == -1);
  CHECK_THAT(solver.message(), Catch::Contains("zero pivot") && Catch::Contains("UMFPACK"));
  // A tiny pivot (element growth 1e20): the answer is right whichever path gives it (LDL^T
  // with one step of refinement, or UMFPACK after the residual check rejected it).
  SparseMatrix tiny = zero;
  tiny.coeffRef(0, 0) = 1e-20;
  LinearSolver other(true);
  check_solve(other, tiny, 4u);
  CHECK(other.backend() != LinearBackend::cholmod);
}

TEST_CASE("LinearSolver: singular matrices are reported as a status with a message",
          "[iga][solver]") {
  SECTION("symmetric positive semi-definite: Cholesky fails, LU finds the zero pivot") {
    Triplets t{{0, 0, 1.0}, {0, 1, 1.0}, {1, 0, 1.0}, {1, 1, 1.0}, {2, 2, 3.0}};
    SparseMatrix A(3, 3);
    A.setFromTriplets(t.begin(), t.end());
    LinearSolver solver(true);
    CHECK(solver.factorize(A) == LinearSolveStatus::singular);
    CHECK(solver.status() == LinearSolveStatus::singular);
    CHECK(solver.backend() == LinearBackend::none);
    CHECK(solver.fell_back());
    CHECK_THAT(solver.message(), Catch::Contains("singular"));
    Eigen::VectorXd x;
    CHECK(solver.solve(Eigen::VectorXd::Ones(3), x) == LinearSolveStatus::not_factorized);
    CHECK(solver.rcond() == 0.0);
  }
  SECTION("non-symmetric with a zero column") {
    Triplets t{{0, 0, 2.0}, {1, 0, 1.0}, {2, 1, 4.0}, {0, 1, -1.0}};
    SparseMatrix A(3, 3);  // column 2 empty
    A.setFromTriplets(t.begin(), t.end());
    LinearSolver solver(false);
    CHECK(solver.factorize(A) == LinearSolveStatus::singular);
    CHECK_FALSE(solver.message().empty());
  }
  SECTION("numerically singular: two equal rows") {
    Triplets t{{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 1.0}, {1, 1, 2.0},
               {2, 2, 1.0}, {0, 2, 0.5}, {1, 2, 0.5}};
    SparseMatrix A(3, 3);
    A.setFromTriplets(t.begin(), t.end());
    LinearSolver solver(false);
    CHECK(solver.factorize(A) == LinearSolveStatus::singular);
  }
  SECTION("a good matrix after a singular one is solved") {
    Triplets t{{0, 0, 1.0}, {0, 1, 1.0}, {1, 0, 1.0}, {1, 1, 1.0}};
    SparseMatrix A(2, 2);
    A.setFromTriplets(t.begin(), t.end());
    LinearSolver solver(true);
    CHECK(solver.factorize(A) == LinearSolveStatus::singular);
    A.coeffRef(1, 1) = 2.0;
    check_solve(solver, A, 3u);
    CHECK(solver.backend() == LinearBackend::cholmod);
  }
}

TEST_CASE("LinearSolver: non-finite entries are invalid input, bad shapes throw", "[iga][solver]") {
  SparseMatrix A = random_matrix(5, 2, true, false, 3u);
  A.coeffRef(3, 3) = std::numeric_limits<double>::quiet_NaN();
  LinearSolver solver;
  CHECK(solver.factorize(A) == LinearSolveStatus::invalid_input);
  CHECK_THAT(solver.message(), Catch::Contains("(3, 3)"));
  CHECK(solver.backend() == LinearBackend::none);

  const SparseMatrix rectangular(3, 4);
  CHECK_THROWS_AS((void)solver.factorize(rectangular), std::invalid_argument);

  const SparseMatrix good = random_matrix(5, 2, true, false, 4u);
  REQUIRE(solver.factorize(good) == LinearSolveStatus::success);
  Eigen::VectorXd x;
  CHECK_THROWS_AS((void)solver.solve(Eigen::VectorXd::Ones(4), x), std::invalid_argument);

  // In-place solve (b and x the same vector) is allowed.
  Eigen::VectorXd bx = random_vector(5, 1u);
  const Eigen::VectorXd b = bx;
  REQUIRE(solver.solve(bx, bx) == LinearSolveStatus::success);
  CHECK((good * bx - b).norm() <= 1e-13 * b.norm() * 10.0);
}

TEST_CASE("LinearSolver: reset forgets pattern, factorization and statistics", "[iga][solver]") {
  LinearSolver solver(false);
  check_solve(solver, random_matrix(20, 3, false, false, 2u), 1u);
  REQUIRE(solver.stats().analyses == 1);
  solver.reset();
  CHECK_FALSE(solver.symmetric());
  CHECK(solver.backend() == LinearBackend::none);
  CHECK(solver.stats().analyses == 0);
  check_solve(solver, random_matrix(20, 3, false, false, 2u), 1u);
  CHECK_FALSE(solver.reused_analysis());
}

}  // namespace test_linear_solver
