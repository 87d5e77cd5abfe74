// The rational basis of curves and surfaces (geometry/rational_basis.hpp) against the NURBS
// evaluation of geometry/nurbs_*: sum_j R_j P_j and its derivatives reproduce the point and
// derivatives of a rational curve (circle) and surface (torus), and sum_j R_j = 1.
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

}  // namespace test_rational_basis
