// The rational basis of curves and surfaces (geometry/rational_basis.hpp) against the NURBS
// evaluation of geometry/nurbs_*: sum_j R_j P_j and its derivatives reproduce the point and
// derivatives of a rational curve (circle) and surface (torus), and sum_j R_j = 1; the basis
// formed from per-direction tables (SpanBasisTable, rational_basis_first) is the same.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "geometry/constructions.hpp"
#include "geometry/rational_basis.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_rational_basis {

using namespace iga;

TEST_CASE("rational_basis: a circle's point, first and second derivatives from sum R_j P_j",
          "[geometry][basis]") {
  const NurbsCurve c = make_circle(Vector3d(0.1, -0.2, 0.3), Vector3d(0.0, 0.6, 0.8), 1.5);
  const Interval dom = c.domain();
  for (int k = 0; k <= 40; ++k) {
    const double xi = dom.lo + (dom.hi - dom.lo) * (k + 0.37) / 41.0;
    const RationalBasis B = rational_basis(c, xi);
    const CurveDerivs d = c.derivs(xi, 2);
    Vector3d x = Vector3d::Zero(), x1 = Vector3d::Zero(), x2 = Vector3d::Zero();
    double sum = 0.0, dsum = 0.0;
    for (int j = 0; j < B.count; ++j) {
      const Vector3d P = c.control_point(B.first + j);
      x += B.N[j] * P;
      x1 += B.dN[j] * P;
      x2 += B.ddN[j] * P;
      sum += B.N[j];
      dsum += B.dN[j];
    }
    INFO("xi = " << xi);
    CHECK(sum == Approx(1.0).epsilon(1e-14));
    CHECK(std::abs(dsum) < 1e-12);
    CHECK((x - d.d[0]).norm() < 1e-13);
    CHECK((x1 - d.d[1]).norm() < 1e-12 * (1.0 + d.d[1].norm()));
    CHECK((x2 - d.d[2]).norm() < 1e-11 * (1.0 + d.d[2].norm()));
  }
}

TEST_CASE("rational_basis: a torus's point and derivatives up to the second from sum R_k P_k",
          "[geometry][basis]") {
  const NurbsSurface s = make_torus(Vector3d(0.2, 0.0, -0.1), Vector3d(0.0, 0.0, 1.0), 2.0, 0.5);
  const Domain2 dom = s.domain();
  SurfaceBasis B;
  for (int k = 0; k <= 12; ++k)
    for (int l = 0; l <= 12; ++l) {
      const double u = dom.u.lo + (dom.u.hi - dom.u.lo) * (k + 0.29) / 13.0;
      const double v = dom.v.lo + (dom.v.hi - dom.v.lo) * (l + 0.61) / 13.0;
      rational_basis(s, u, v, B);
      const SurfaceDerivs d = s.derivs(u, v, 2);
      Vector3d x = Vector3d::Zero(), xu = x, xv = x, xuu = x, xvv = x, xuv = x;
      double sum = 0.0;
      for (int m = 0; m < B.count(); ++m) {
        const Vector3d P = s.control_point(B.first_u() + m % B.nu, B.first_v() + m / B.nu);
        const auto q = static_cast<std::size_t>(m);
        CHECK(B.global_index(m) == s.index(B.first_u() + m % B.nu, B.first_v() + m / B.nu));
        x += B.R[q] * P;
        xu += B.d1[q] * P;
        xv += B.d2[q] * P;
        xuu += B.d11[q] * P;
        xvv += B.d22[q] * P;
        xuv += B.d12[q] * P;
        sum += B.R[q];
      }
      INFO("(u, v) = (" << u << ", " << v << ")");
      CHECK(sum == Approx(1.0).epsilon(1e-14));
      CHECK((x - d.S).norm() < 1e-13);
      CHECK((xu - d.Su).norm() < 1e-12 * (1.0 + d.Su.norm()));
      CHECK((xv - d.Sv).norm() < 1e-12 * (1.0 + d.Sv.norm()));
      CHECK((xuu - d.Suu).norm() < 1e-11 * (1.0 + d.Suu.norm()));
      CHECK((xvv - d.Svv).norm() < 1e-11 * (1.0 + d.Svv.norm()));
      CHECK((xuv - d.Suv).norm() < 1e-11 * (1.0 + d.Suv.norm()));
    }
}

TEST_CASE(
    "rational_basis: formed from a tensor-product rule's per-direction tables, the torus's "
    "basis is the one evaluated at each point, bit for bit, and its first derivatives to round-off",
    "[geometry][basis]") {
  // A rational surface with distinct weights in both directions, refined so that it has many
  // spans; the rule's points of every span per direction, as the shell and contact build them.
  const NurbsSurface s = make_torus(Vector3d(0.2, 0.0, -0.1), Vector3d(0.0, 0.0, 1.0), 2.0, 0.5);
  const std::vector<double> bu = s.knots_u().breaks(), bv = s.knots_v().breaks();
  const std::array<double, 3> rule{-0.7745966692414834, 0.0, 0.7745966692414834};
  const auto points = [&](const std::vector<double>& b) {
    std::vector<double> t;
    for (std::size_t e = 0; e + 1 < b.size(); ++e)
      for (const double x : rule)
        t.push_back(0.5 * (b[e] + b[e + 1]) + 0.5 * (b[e + 1] - b[e]) * x);
    return t;
  };
  const std::vector<double> tu = points(bu), tv = points(bv);
  const SpanBasisTable TU(s.knots_u(), s.degree_u(), tu), TV(s.knots_v(), s.degree_v(), tv);
  REQUIRE(TU.size() == tu.size());
  REQUIRE(TV.size() == tv.size());
  SurfaceBasis A, B;
  std::array<double, 3 * kMaxSurfaceBasisPoints> rows{};
  std::array<double, kMaxSurfaceBasisPoints> w{};
  int differ = 0;
  double worst = 0.0;
  for (std::size_t j = 0; j < tv.size(); ++j)
    for (std::size_t i = 0; i < tu.size(); ++i) {
      rational_basis(s, tu[i], tv[j], A);
      rational_basis(s, TU[i], TV[j], B);
      REQUIRE(B.span_u == A.span_u);
      REQUIRE(B.span_v == A.span_v);
      for (int k = 0; k < A.count(); ++k) {
        const auto q = static_cast<std::size_t>(k);
        differ += A.R[q] != B.R[q] || A.d1[q] != B.d1[q] || A.d2[q] != B.d2[q] ||
                  A.d11[q] != B.d11[q] || A.d22[q] != B.d22[q] || A.d12[q] != B.d12[q];
        w[q] = s.weight(A.first_u() + k % A.nu, A.first_v() + k / A.nu);
      }
      rational_basis_first(TU[i], TV[j], s.degree_u(), s.degree_v(), w.data(), rows.data());
      for (int k = 0; k < A.count(); ++k) {
        const auto q = static_cast<std::size_t>(k);
        worst = std::max({worst, std::abs(rows[3 * q] - A.R[q]),
                          std::abs(rows[3 * q + 1] - A.d1[q]) / (1.0 + std::abs(A.d1[q])),
                          std::abs(rows[3 * q + 2] - A.d2[q]) / (1.0 + std::abs(A.d2[q]))});
      }
    }
  CHECK(differ == 0);
  CHECK(worst <= 1e-14);
  // Parameters outside the domain are clamped as rational_basis(s, u, v) clamps them.
  rational_basis(s, -1.0, 10.0, A);
  rational_basis(s, span_basis(s.knots_u(), s.degree_u(), -1.0),
                 span_basis(s.knots_v(), s.degree_v(), 10.0), B);
  CHECK(A.span_u == B.span_u);
  CHECK(A.span_v == B.span_v);
  CHECK(A.R == B.R);
}

}  // namespace test_rational_basis
