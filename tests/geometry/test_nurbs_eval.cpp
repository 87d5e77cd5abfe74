// Tests of NURBS curve and surface evaluation (A4.2, A4.4) against independent formulas and
// finite differences.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "tests/support/random_nurbs.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_nurbs_eval {

using namespace iga;

namespace {
// Rational Bezier curve by de Casteljau in homogeneous coordinates (independent of A2.2/A4.2).
Vector3d de_casteljau(std::vector<Vector4d> pw, double t) {
  for (std::size_t r = 1; r < pw.size(); ++r)
    for (std::size_t i = 0; i + r < pw.size(); ++i) pw[i] = (1 - t) * pw[i] + t * pw[i + 1];
  return pw[0].head<3>() / pw[0].w();
}
}  // namespace

TEST_CASE("NurbsCurve: a single-span curve equals rational de Casteljau", "[geometry][eval]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> c(-1, 1), w(0.3, 3.0);
  for (int p = 1; p <= 6; ++p) {
    std::vector<Vector3d> P(static_cast<std::size_t>(p + 1));
    std::vector<double> W(static_cast<std::size_t>(p + 1));
    std::vector<Vector4d> pw;
    for (int i = 0; i <= p; ++i) {
      P[i] = Vector3d(c(rng), c(rng), c(rng));
      W[i] = w(rng);
      pw.emplace_back(W[i] * P[i].x(), W[i] * P[i].y(), W[i] * P[i].z(), W[i]);
    }
    std::vector<double> U(static_cast<std::size_t>(p + 1), 0.0);
    U.insert(U.end(), static_cast<std::size_t>(p + 1), 1.0);
    const NurbsCurve curve(p, U, P, W);
    for (double t = 0.0; t <= 1.0; t += 0.01)
      CHECK((curve.point(t) - de_casteljau(pw, t)).norm() <= 1e-14);
  }
}

TEST_CASE("NurbsCurve: linear precision with control points at Greville abscissae",
          "[geometry][eval]") {
  std::mt19937 rng(5);
  for (int p = 1; p <= 5; ++p) {
    const std::vector<double> U = test::random_knots(rng, p, p + 8, p);
    const KnotVector K(p, U);
    std::vector<Vector3d> P;
    for (double g : K.greville()) P.emplace_back(g, 2 * g - 1, 0.5);
    const NurbsCurve c(p, U, P);
    for (double u = 0.0; u <= 1.0; u += 0.001) {
      const CurveDerivs d = c.derivs(u, 2);
      CHECK((d.d[0] - Vector3d(u, 2 * u - 1, 0.5)).norm() <= 1e-14);
      CHECK((d.d[1] - Vector3d(1, 2, 0)).norm() <= 1e-11);
      CHECK(d.d[2].norm() <= 1e-8);
    }
  }
}

TEST_CASE("NurbsCurve: derivatives up to order 3 agree with central finite differences",
          "[geometry][eval]") {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  const double h = 1e-5;
  for (int p = 2; p <= 5; ++p) {
    const NurbsCurve c = test::random_curve(rng, p, p + 5, true);
    for (int k = 0; k < 200; ++k) {
      const double u = unif(rng);
      const int span = c.knots().find_span(u);
      if (u - h <= c.knots()[span] || u + h >= c.knots()[span + 1]) continue;
      const CurveDerivs d = c.derivs(u, 3), dp = c.derivs(u + h, 3), dm = c.derivs(u - h, 3);
      for (int o = 1; o <= 3; ++o) {
        const Vector3d fd = (dp.d[o - 1] - dm.d[o - 1]) / (2 * h);
        CHECK((fd - d.d[o]).norm() <= 1e-5 * std::max(1.0, d.d[o].norm()));
      }
    }
  }
}

TEST_CASE("NurbsSurface: derivatives up to order 2 agree with central finite differences",
          "[geometry][eval]") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  const double h = 1e-5;
  for (int p = 1; p <= 4; ++p) {
    const NurbsSurface s = test::random_surface(rng, p, p + 1 > 4 ? 2 : p + 1, p + 4, p + 5, true);
    for (int k = 0; k < 200; ++k) {
      const double u = unif(rng), v = unif(rng);
      const int su = s.knots_u().find_span(u), sv = s.knots_v().find_span(v);
      if (u - h <= s.knots_u()[su] || u + h >= s.knots_u()[su + 1]) continue;
      if (v - h <= s.knots_v()[sv] || v + h >= s.knots_v()[sv + 1]) continue;
      const SurfaceDerivs d = s.derivs(u, v, 2);
      const SurfaceDerivs up = s.derivs(u + h, v, 2), um = s.derivs(u - h, v, 2);
      const SurfaceDerivs vp = s.derivs(u, v + h, 2), vm = s.derivs(u, v - h, 2);
      const double tol = 1e-5 * std::max({1.0, d.Suu.norm(), d.Svv.norm(), d.Suv.norm()});
      // point() and derivs() are two code paths: the same point to round-off.
      CHECK((d.S - s.point(u, v)).norm() <= 1e-14 * std::max(1.0, d.S.norm()));
      CHECK(((up.S - um.S) / (2 * h) - d.Su).norm() <= tol);
      CHECK(((vp.S - vm.S) / (2 * h) - d.Sv).norm() <= tol);
      CHECK(((up.Su - um.Su) / (2 * h) - d.Suu).norm() <= tol);
      CHECK(((vp.Sv - vm.Sv) / (2 * h) - d.Svv).norm() <= tol);
      CHECK(((vp.Su - vm.Su) / (2 * h) - d.Suv).norm() <= tol);
      CHECK(((up.Sv - um.Sv) / (2 * h) - d.Suv).norm() <= tol);
    }
  }
}

TEST_CASE("NurbsSurface: tensor product of two curves' bases (u fastest storage)",
          "[geometry][eval]") {
  // S(u,v) = C1(u) + C2(v) componentwise when P_ij = P1_i + P2_j (B-spline, weights 1).
  std::mt19937 rng(17);
  const NurbsCurve c1 = test::random_curve(rng, 3, 7, false);
  const NurbsCurve c2 = test::random_curve(rng, 2, 5, false);
  std::vector<Vector3d> P;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) P.push_back(c1.control_point(i) + c2.control_point(j));
  const NurbsSurface s(3, c1.knots().knots(), 2, c2.knots().knots(), P);
  for (double u = 0; u <= 1.0; u += 0.05)
    for (double v = 0; v <= 1.0; v += 0.05)
      CHECK((s.point(u, v) - c1.point(u) - c2.point(v)).norm() <= 1e-14);
}

TEST_CASE("NurbsSurface: constructor rejects inconsistent nets and weights",
          "[geometry][eval][errors]") {
  using Catch::Matchers::Contains;
  const std::vector<double> U = {0, 0, 1, 1};
  const std::vector<Vector3d> P(4, Vector3d::Zero());
  CHECK_NOTHROW(NurbsSurface(1, U, 1, U, P));
  CHECK_THROWS_WITH(NurbsSurface(1, U, 1, U, std::vector<Vector3d>(3)),
                    Contains("control net size must be 2 x 2 = 4"));
  CHECK_THROWS_WITH(NurbsSurface(1, U, 1, U, P, {1, 1, -1, 1}), Contains("weight 2"));
  CHECK_THROWS_AS(NurbsCurve(1, U, {Vector3d::Zero(), Vector3d(NAN, 0, 0)}), GeometryError);
}

}  // namespace test_nurbs_eval
