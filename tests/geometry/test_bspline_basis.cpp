// Tests of the B-spline basis kernels (A2.1-A2.3) and knot vector validation.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geometry/bspline_basis.hpp"
#include "geometry/knot_vector.hpp"
#include "tests/support/random_nurbs.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_bspline_basis {

using namespace iga;

TEST_CASE("basis_funs: The NURBS Book Example 2.3 values at u = 5/2", "[geometry][basis]") {
  // BENCHMARKS.md: U = {0,0,0,1,2,3,4,4,5,5,5}, p = 2, u = 5/2:
  // N_{2,2} = 1/8, N_{3,2} = 6/8, N_{4,2} = 1/8.
  const std::vector<double> U = {0, 0, 0, 1, 2, 3, 4, 4, 5, 5, 5};
  const int p = 2, n_basis = 8;
  const int span = find_span(n_basis, p, 2.5, U);
  REQUIRE(span == 4);
  BasisValues N;
  basis_funs(span, 2.5, p, U, N);
  CHECK(N[0] == Approx(1.0 / 8).epsilon(1e-15));
  CHECK(N[1] == Approx(6.0 / 8).epsilon(1e-15));
  CHECK(N[2] == Approx(1.0 / 8).epsilon(1e-15));
}

TEST_CASE("find_span: U[span] <= u < U[span+1], last non-empty span at the end",
          "[geometry][basis]") {
  const std::vector<double> U = {0, 0, 0, 1, 2, 3, 4, 4, 5, 5, 5};
  const int p = 2, n = 8;
  for (double u = 0.0; u < 5.0; u += 0.01) {
    const int s = find_span(n, p, u, U);
    CHECK(U[s] <= u);
    CHECK(u < U[s + 1]);
  }
  CHECK(find_span(n, p, 5.0, U) == 7);
  CHECK(find_span(n, p, 4.0, U) == 7);  // u at a double knot: the span starting there
  CHECK(find_span(n, p, 0.0, U) == 2);
}

TEST_CASE("basis_funs: partition of unity and non-negativity for p = 1..5 with repeated knots",
          "[geometry][basis]") {
  std::mt19937 rng(42);
  for (int p = 1; p <= 5; ++p) {
    for (int trial = 0; trial < 20; ++trial) {
      const int n = p + 1 + trial % 7;
      const std::vector<double> U = test::random_knots(rng, p, n, p);
      std::uniform_real_distribution<double> unif(0.0, 1.0);
      for (int k = 0; k < 200; ++k) {
        // include the knots themselves
        const double u = k < static_cast<int>(U.size()) ? U[k] : unif(rng);
        const int span = find_span(n, p, u, U);
        BasisValues N;
        basis_funs(span, u, p, U, N);
        double sum = 0.0;
        for (int j = 0; j <= p; ++j) {
          CHECK(N[j] >= 0.0);
          sum += N[j];
        }
        CHECK(sum == Approx(1.0).epsilon(1e-14));
      }
    }
  }
}

TEST_CASE("ders_basis_funs: order 0 equals basis_funs, derivatives sum to zero",
          "[geometry][basis]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  for (int p = 1; p <= 5; ++p) {
    const int n = p + 6;
    const std::vector<double> U = test::random_knots(rng, p, n, p);
    for (int k = 0; k < 100; ++k) {
      const double u = unif(rng);
      const int span = find_span(n, p, u, U);
      BasisValues N;
      BasisDerivs D;
      basis_funs(span, u, p, U, N);
      ders_basis_funs(span, u, p, kMaxDerivOrder, U, D);
      double scale = 0.0;
      for (int j = 0; j <= p; ++j) {
        CHECK(D[0][j] == Approx(N[j]).margin(1e-15));
        scale = std::max(scale, std::abs(D[1][j]));
      }
      for (int d = 1; d <= kMaxDerivOrder; ++d) {
        double sum = 0.0, mag = 0.0;
        for (int j = 0; j <= p; ++j) {
          sum += D[d][j];
          mag += std::abs(D[d][j]);
        }
        CHECK(std::abs(sum) <= 1e-12 * std::max(1.0, mag));
        if (d > p)
          for (int j = 0; j <= p; ++j) CHECK(D[d][j] == 0.0);
      }
    }
  }
}

TEST_CASE("ders_basis_funs: derivatives agree with central finite differences",
          "[geometry][basis]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  const double h = 1e-6;
  for (int p = 1; p <= 5; ++p) {
    const int n = p + 5;
    const std::vector<double> U = test::random_knots(rng, p, n, 1);
    for (int k = 0; k < 200; ++k) {
      const double u = unif(rng);
      const int span = find_span(n, p, u, U);
      // stay away from knots so that the span (and smoothness) is the same at u +- h
      if (u - h <= U[span] || u + h >= U[span + 1]) continue;
      BasisDerivs D, Dp, Dm;
      ders_basis_funs(span, u, p, kMaxDerivOrder, U, D);
      ders_basis_funs(span, u + h, p, kMaxDerivOrder, U, Dp);
      ders_basis_funs(span, u - h, p, kMaxDerivOrder, U, Dm);
      for (int d = 1; d <= std::min(p, kMaxDerivOrder); ++d) {
        double mag = 1.0;
        for (int j = 0; j <= p; ++j) mag = std::max(mag, std::abs(D[d][j]));
        for (int j = 0; j <= p; ++j) {
          const double fd = (Dp[d - 1][j] - Dm[d - 1][j]) / (2 * h);
          CHECK(std::abs(fd - D[d][j]) <= 1e-5 * mag);
        }
      }
    }
  }
}

TEST_CASE("validate_knots: rejects inconsistent knot vectors with the index and value",
          "[geometry][basis][errors]") {
  using Catch::Matchers::Contains;
  const std::vector<double> good = {0, 0, 0, 0.5, 1, 1, 1};
  REQUIRE_NOTHROW(validate_knots(2, good, 4));
  CHECK_THROWS_WITH(validate_knots(0, good, 6), Contains("degree must be"));
  CHECK_THROWS_WITH(validate_knots(2, good, 5),
                    Contains("knot count must be control points + degree + 1 = 8, got 7"));
  const std::vector<double> decreasing = {0, 0, 0, 0.7, 0.5, 1, 1, 1};
  CHECK_THROWS_WITH(validate_knots(2, decreasing, 5), Contains("knot 4 = 0.5 < knot 3 = 0.7"));
  const std::vector<double> triple = {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1};
  CHECK_THROWS_WITH(validate_knots(2, triple, 6), Contains("multiplicity 3 > degree 2"));
  const std::vector<double> unclamped = {0, 0, 0.1, 0.5, 1, 1, 1};
  CHECK_THROWS_WITH(validate_knots(2, unclamped, 4), Contains("clamped"));
  const std::vector<double> nan = {0, 0, 0, std::nan(""), 1, 1, 1};
  CHECK_THROWS_WITH(validate_knots(2, nan, 4), Contains("not finite"));
}

TEST_CASE("KnotVector: breaks, multiplicity, Greville abscissae, uniform factory",
          "[geometry][basis]") {
  const KnotVector K = KnotVector::uniform(3, 4, 0.0, 2.0);
  CHECK(K.num_basis() == 7);
  CHECK(K.num_elements() == 4);
  CHECK(K.multiplicity(0.0) == 4);
  CHECK(K.multiplicity(0.5) == 1);
  const std::vector<double> g = K.greville();
  REQUIRE(g.size() == 7);
  CHECK(g.front() == 0.0);
  CHECK(g.back() == Approx(2.0).epsilon(1e-15));
  for (std::size_t i = 1; i < g.size(); ++i) CHECK(g[i] > g[i - 1]);
}

TEST_CASE("ders_basis_funs: degree 1 written out equals A2.2's values bit for bit, slopes 1/h",
          "[geometry][basis]") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  const std::vector<double> U = test::random_knots(rng, 1, 9, 1);
  for (int k = 0; k < 300; ++k) {
    const double u = k < static_cast<int>(U.size()) ? U[k] : unif(rng);
    const int span = find_span(9, 1, u, U);
    BasisValues N;
    BasisDerivs D;
    basis_funs(span, u, 1, U, N);
    for (int nd = 0; nd <= kMaxDerivOrder; ++nd) {
      ders_basis_funs(span, u, 1, nd, U, D);
      CHECK(D[0][0] == N[0]);  // the same operations as A2.2's: the same bits
      CHECK(D[0][1] == N[1]);
      const double h = U[span + 1] - U[span];
      if (nd >= 1) {
        CHECK(D[1][0] == Approx(-1.0 / h).epsilon(1e-14));
        CHECK(D[1][1] == Approx(1.0 / h).epsilon(1e-14));
      }
      for (int d = 2; d <= nd; ++d) CHECK((D[d][0] == 0.0 && D[d][1] == 0.0));
    }
  }
}

TEST_CASE("ders_basis_funs: the order <= 2 fast path equals the general A2.3 loop",
          "[geometry][basis]") {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  for (int p = 1; p <= 6; ++p) {
    const int n = p + 7;
    const std::vector<double> U = test::random_knots(rng, p, n, p);
    for (int k = 0; k < 300; ++k) {
      const double u = k < static_cast<int>(U.size()) ? U[k] : unif(rng);
      const int span = find_span(n, p, u, U);
      BasisDerivs fast, general;
      ders_basis_funs(span, u, p, 2, U, fast);     // fast path (p >= 2)
      ders_basis_funs(span, u, p, 3, U, general);  // general loop
      for (int d = 0; d <= 2; ++d)
        for (int j = 0; j <= p; ++j)
          CHECK(fast[d][j] ==
                Approx(general[d][j]).epsilon(1e-12).margin(1e-12 * (1 + std::abs(general[1][j]))));
    }
  }
}

}  // namespace test_bspline_basis
