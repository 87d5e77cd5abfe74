// Tests that the Bezier-element evaluation of a NURBS patch is the patch: point and derivatives
// up to order 2 against NurbsSurface::derivs (the B-spline basis of the knot spans) on random
// patches of every degree 1..4, rational or not, with repeated knots (C0 borders), inside the
// elements, on their borders and at the ends of the domain.
#include <catch2/catch.hpp>

#include <random>

#include "geometry/bezier_surface.hpp"
#include "tests/support/random_nurbs.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_bezier_surface {

using namespace iga;

namespace {

// Largest difference of the derivatives up to `order`, relative to the size of each.
double derivs_diff(const SurfaceDerivs& a, const SurfaceDerivs& b, int order) {
  auto rel = [](const Vector3d& x, const Vector3d& y) {
    return (x - y).norm() / std::max(1.0, y.norm());
  };
  double e = rel(a.S, b.S);
  if (order >= 1) e = std::max({e, rel(a.Su, b.Su), rel(a.Sv, b.Sv)});
  if (order >= 2) e = std::max({e, rel(a.Suu, b.Suu), rel(a.Suv, b.Suv), rel(a.Svv, b.Svv)});
  return e;
}

}  // namespace

TEST_CASE("bernstein_derivs: partition of unity and derivatives of t^r (1-t)^(p-r)",
          "[geometry][bezier]") {
  for (int p = 0; p <= 6; ++p)
    for (const double t : {0.0, 0.3, 0.77, 1.0}) {
      BasisDerivs B;
      bernstein_derivs(p, t, 2, B);
      double sum = 0, dsum = 0, ddsum = 0;
      for (int r = 0; r <= p; ++r) sum += B[0][r], dsum += B[1][r], ddsum += B[2][r];
      CHECK(sum == Approx(1.0).epsilon(1e-14));
      CHECK(std::abs(dsum) < 1e-12);
      CHECK(std::abs(ddsum) < 1e-11);
      // central differences of the values (a cubic error in h: 1e-6 at h = 1e-4)
      const double h = 1e-4;
      if (t > 0.0 && t < 1.0) {
        BasisDerivs Bp, Bm;
        bernstein_derivs(p, t + h, 0, Bp);
        bernstein_derivs(p, t - h, 0, Bm);
        for (int r = 0; r <= p; ++r) {
          CHECK(B[1][r] == Approx((Bp[0][r] - Bm[0][r]) / (2 * h)).margin(1e-6));
          CHECK(B[2][r] == Approx((Bp[0][r] - 2 * B[0][r] + Bm[0][r]) / (h * h)).margin(1e-4));
        }
      }
    }
}

TEST_CASE("BezierSurface: the NURBS patch's point and derivatives, in elements and on borders",
          "[geometry][bezier]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  int cases = 0;
  for (int p = 1; p <= 4; ++p)
    for (int q = 1; q <= 4; ++q)
      for (const bool rational : {false, true})
        for (const int max_mult : {1, std::min(p, q)}) {
          NurbsSurface s = test::random_surface(rng, p, q, p + 4, q + 3, rational, max_mult);
          s.set_normal_sign(-1);
          const BezierSurface b(s);
          REQUIRE(b.normal_sign() == -1);
          REQUIRE(b.domain().u == s.domain().u);
          REQUIRE(b.domain().v == s.domain().v);
          std::vector<Vector2d> at;
          for (int k = 0; k < 40; ++k) at.emplace_back(unif(rng), unif(rng));
          for (const double u : b.breaks_u())  // borders, where a C0 patch's derivatives jump
            for (const double v : b.breaks_v()) at.emplace_back(u, v);
          at.emplace_back(-0.5, 1.5);  // clamped to the domain, as NurbsSurface
          for (const Vector2d& t : at)
            for (int order = 0; order <= 2; ++order) {
              const double e =
                  derivs_diff(b.derivs(t[0], t[1], order), s.derivs(t[0], t[1], order), order);
              INFO("p " << p << " q " << q << " rational " << rational << " at " << t.transpose()
                        << " order " << order);
              REQUIRE(e < 1e-9);
            }
          ++cases;
        }
  CHECK(cases == 64);
}

TEST_CASE("BezierSurface: element_of follows the knot spans (border to the element above)",
          "[geometry][bezier]") {
  const NurbsSurface s(2, {0, 0, 0, 0.25, 0.5, 1, 1, 1}, 1, {0, 0, 0.5, 1, 1},
                       std::vector<Vector3d>(5 * 3, Vector3d::Zero()));
  const BezierSurface b(s);
  REQUIRE(b.elements().size() == 6);  // 3 x 2, u fastest
  CHECK(b.element_of(0.0, 0.0) == 0);
  CHECK(b.element_of(0.25, 0.0) == 1);
  CHECK(b.element_of(0.2499, 0.5) == 3);
  CHECK(b.element_of(1.0, 1.0) == 5);
  CHECK(b.element_of(0.75, 0.49) == 2);
}

}  // namespace test_bezier_surface
