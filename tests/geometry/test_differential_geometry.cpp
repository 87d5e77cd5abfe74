// Tests of surface and curve frames: metric identities, principal curvatures and directions
// against closed forms (cylinder, sphere, torus, cone, the saddle z = a x y of [KS15] (11)) for
// the analytic surfaces and the NURBS constructions, and Serret-Frenet frames of helices and
// circles (the paper's Sect. 6.4 helix: kappa = R/(R^2 + c^2), c = H / 2 pi).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/differential_geometry.hpp"
#include "geometry/knot_vector.hpp"
#include "tests/support/geometry_checks.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_differential_geometry {

using namespace iga;
using namespace iga::test;

namespace {

constexpr double kPi = std::numbers::pi;
/// Exact derivatives of the helix H(t) = (R cos(lt), R sin(lt), c l t) (l rescales the
/// parameter; curvature and torsion must not depend on it).
CurveDerivs helix_derivs(double R, double c, double t, double l = 1.0) {
  const double ct = std::cos(l * t), st = std::sin(l * t);
  CurveDerivs d;
  d.order = 3;
  d.d[0] = Vector3d(R * ct, R * st, c * l * t);
  d.d[1] = l * Vector3d(-R * st, R * ct, c);
  d.d[2] = l * l * Vector3d(-R * ct, -R * st, 0.0);
  d.d[3] = l * l * l * Vector3d(R * st, -R * ct, 0.0);
  return d;
}

/// Checks the properties every SurfaceFrame must have, independently of the surface: unit
/// normal orthogonal to the tangents, duality of the bases, k1 >= k2, principal directions
/// unit, orthogonal, tangent and eigenvectors of h x = k a x, H and K consistent.
void check_frame_identities(const SurfaceFrame& f, double kscale) {
  CHECK(f.n.norm() == Approx(1.0).epsilon(1e-14));
  CHECK(std::abs(f.n.dot(f.a1)) <= 1e-14 * f.a1.norm());
  CHECK(std::abs(f.n.dot(f.a2)) <= 1e-14 * f.a2.norm());
  CHECK(f.jacobian == Approx(f.a1.cross(f.a2).norm()).epsilon(1e-14));
  // a a^-1 = I to the round-off of an inverse: a few ulps times the condition number of a
  // (a skewed parametrization makes it up to 3e4 here; measured: at most 1.8 eps kappa, with
  // and without fused multiply-adds; a flat 1e-12 failed with -ffp-contract=fast -mfma).
  const double kappa = f.a.norm() * f.a_inv.norm();
  CHECK((f.a * f.a_inv - Matrix2d::Identity()).norm() <= 1e-15 * kappa);
  CHECK(f.a1_contra.dot(f.a1) == Approx(1.0).epsilon(1e-12));
  CHECK(f.a2_contra.dot(f.a2) == Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(f.a1_contra.dot(f.a2)) <= 1e-12 * f.a2.norm() * f.a1_contra.norm());
  CHECK(std::abs(f.a2_contra.dot(f.a1)) <= 1e-12 * f.a1.norm() * f.a2_contra.norm());
  CHECK(f.k1 >= f.k2);
  CHECK(f.dir1.norm() == Approx(1.0).epsilon(1e-13));
  CHECK(f.dir2.norm() == Approx(1.0).epsilon(1e-13));
  CHECK(std::abs(f.dir1.dot(f.dir2)) <= 1e-13);
  CHECK(std::abs(f.dir1.dot(f.n)) <= 1e-13);
  CHECK(std::abs(f.dir2.dot(f.n)) <= 1e-13);
  // Eigen-consistency: with x^i = dir . rho^i (contravariant components), h x = k a x.
  for (int i = 0; i < 2; ++i) {
    const Vector3d& dir = i == 0 ? f.dir1 : f.dir2;
    const double k = i == 0 ? f.k1 : f.k2;
    const Vector2d x(dir.dot(f.a1_contra), dir.dot(f.a2_contra));
    const Vector2d res = f.h * x - k * (f.a * x);
    CHECK(res.norm() <= 1e-11 * (f.h.norm() + std::abs(k) * f.a.norm() + 1e-300) * x.norm());
  }
  CHECK(f.mean_curvature == Approx(0.5 * (f.k1 + f.k2)).margin(1e-12 * kscale));
  CHECK(f.gauss_curvature == Approx(f.k1 * f.k2).margin(1e-12 * kscale * kscale));
}

/// Sorted pair (max, min).
std::pair<double, double> sorted(double a, double b) {
  return {std::max(a, b), std::min(a, b)};
}

}  // namespace

// ---- curves ---------------------------------------------------------------------------------

TEST_CASE(
    "curve_frame: helix curvature R/(R^2+c^2) and torsion c/(R^2+c^2) to 1e-12, "
    "independent of the parametrization speed",
    "[geometry][diffgeo]") {
  std::mt19937 g(21);
  for (int k = 0; k < 500; ++k) {
    const double R = uniform(g, 0.1, 5.0), c = uniform(g, -3.0, 3.0);
    const double t = uniform(g, -10, 10), l = std::pow(10.0, uniform(g, -1, 1));
    const double den = R * R + c * c;
    const CurveFrame f = curve_frame(helix_derivs(R, c, t, l));
    CHECK(f.speed == Approx(l * std::sqrt(den)).epsilon(1e-14));
    CHECK(f.curvature == Approx(R / den).epsilon(1e-12));
    CHECK(f.torsion == Approx(c / den).epsilon(1e-12).margin(1e-14));
    // Frame: nu points to the axis, beta = (c sin, -c cos, R)/sqrt(R^2 + c^2), right-handed.
    const double ct = std::cos(l * t), st = std::sin(l * t);
    CHECK((f.normal - Vector3d(-ct, -st, 0.0)).norm() <= 1e-13);
    CHECK((f.binormal - Vector3d(c * st, -c * ct, R) / std::sqrt(den)).norm() <= 1e-13);
    CHECK((f.tangent.cross(f.normal) - f.binormal).norm() <= 1e-14);
  }
}

TEST_CASE("curve_frame: straight line has zero curvature, no normal/binormal, zero torsion",
          "[geometry][diffgeo]") {
  CurveDerivs d;
  d.order = 3;
  d.d[1] = Vector3d(1, 2, 3);
  d.d[2] = 0.5 * d.d[1];  // a non-uniform speed along a straight line
  d.d[3] = Vector3d(1, -1, 4);
  const CurveFrame f = curve_frame(d);
  CHECK((f.tangent - d.d[1].normalized()).norm() <= 1e-15);
  // Exact zeros by design, not by arithmetic: |d1 x d2| is only round-off (with fused
  // multiply-adds it is a product's rounding error, not 0), below curve_frame's relative
  // threshold, which then leaves curvature and torsion at their initial 0.
  CHECK(f.curvature == 0.0);
  CHECK(f.torsion == 0.0);
  CHECK(f.normal.isZero(0.0));
  CHECK(f.binormal.isZero(0.0));
  CurveDerivs z;
  z.order = 2;
  CHECK_THROWS_AS(curve_frame(z), GeometryError);  // C' = 0: no tangent
}

TEST_CASE(
    "curve_frame: NURBS circle has curvature 1/R and torsion 0 to 1e-12, normal to the "
    "centre",
    "[geometry][diffgeo]") {
  std::mt19937 g(22);
  for (int k = 0; k < 10; ++k) {
    const double R = std::pow(10.0, uniform(g, -1, 1));
    const Vector3d c = random_vector(g, R), axis = random_unit(g);
    const NurbsCurve circ = make_circle(c, axis, R);
    for (int q = 0; q < 200; ++q) {
      const double u = uniform(g, 0, 1);
      const CurveDerivs d = circ.derivs(u, 3);
      const CurveFrame f = curve_frame(d);
      CHECK(f.curvature * R == Approx(1.0).epsilon(1e-12));
      CHECK(f.torsion * R == Approx(0.0).margin(1e-12));
      CHECK((f.normal - (c - d.d[0]) / R).norm() <= 1e-12);
      CHECK((f.binormal - axis).norm() <= 1e-12);  // counter-clockwise about the axis
    }
  }
}

TEST_CASE(
    "curve_frame: interpolated helix curvature and torsion within bounds derived from "
    "the interpolation deviation",
    "[geometry][diffgeo][helix]") {
  const double R = 1.0, pitch = 2.0, angle = kPi, c = pitch / (2 * kPi);
  const double kappa = R / (R * R + c * c), tau = c / (R * R + c * c);
  for (const int n : {17, 33, 65}) {
    const HelixApproximation h = make_helix_cubic(R, pitch, angle, n);
    // With a parametric error e = O(dev) on elements of parametric size hs, e^(k) = O(dev / hs^k);
    // kappa depends on C', C'' and tau also on C'''. |C'| = angle sqrt(R^2+c^2),
    // |C''| = angle^2 R, |C'''| = angle^3 R for the exact curve.
    const double hs = 1.0 / (n - 1), dev = h.max_deviation;
    const double e1 = dev / hs / (angle * std::sqrt(R * R + c * c));
    const double e2 = dev / (hs * hs) / (angle * angle * R);
    const double e3 = dev / (hs * hs * hs) / (angle * angle * angle * R);
    // Away from the ends the constant is that of cubic spline interpolation (e'' / (e / h^2)
    // ~ (1/12) / (5/384) ~ 6); the end elements, where the averaged knots act as end
    // conditions, carry about 8 times larger derivative errors.
    const double tol_kappa_interior = 10.0 * (e2 + 3 * e1);
    const double tol_kappa = 50.0 * (e2 + 3 * e1);
    const double tol_tau = 10.0 * (e3 + 2 * e2 + 3 * e1);
    double worst_k = 0.0, worst_ki = 0.0, worst_t = 0.0;
    for (int q = 0; q <= 1000; ++q) {
      const double s = q / 1000.0;
      const CurveFrame f = curve_frame(h.curve.derivs(s, 3));
      const double ek = std::abs(f.curvature - kappa) / kappa;
      worst_k = std::max(worst_k, ek);
      if (s > 2 * hs && s < 1 - 2 * hs) worst_ki = std::max(worst_ki, ek);
      worst_t = std::max(worst_t, std::abs(f.torsion - tau) / tau);
    }
    INFO(n << " points: deviation " << dev << ", curvature error " << worst_k << " (tol "
           << tol_kappa << "), interior " << worst_ki << " (tol " << tol_kappa_interior
           << "), torsion error " << worst_t << " (tol " << tol_tau << ")");
    CHECK(worst_k <= tol_kappa);
    CHECK(worst_ki <= tol_kappa_interior);
    CHECK(worst_t <= tol_tau);
  }
}

// ---- surfaces: identities --------------------------------------------------------------------

TEST_CASE(
    "surface_frame: metric, dual basis and principal directions satisfy their identities "
    "for random derivatives",
    "[geometry][diffgeo]") {
  std::mt19937 g(23);
  for (int k = 0; k < 2000; ++k) {
    SurfaceDerivs d;
    d.order = 2;
    d.Su = random_vector(g, 2.0);
    d.Sv = random_vector(g, 2.0);
    if (d.Su.cross(d.Sv).norm() < 1e-2) continue;
    d.Suu = random_vector(g, 3.0);
    d.Suv = random_vector(g, 3.0);
    d.Svv = random_vector(g, 3.0);
    const SurfaceFrame f = surface_frame(d, 1);
    check_frame_identities(f, std::abs(f.k1) + std::abs(f.k2) + 1.0);
    // The oriented normal, and h_ij = rho_ij . n.
    CHECK((f.n - d.Su.cross(d.Sv).normalized()).norm() <= 1e-14);
    CHECK(f.h(0, 1) == Approx(d.Suv.dot(f.n)).margin(1e-14));
    // normal_sign = -1 flips n and h, so k1' = -k2, k2' = -k1 and H' = -H, K' = K.
    const SurfaceFrame m = surface_frame(d, -1);
    CHECK((m.n + f.n).norm() <= 1e-15);
    CHECK(m.k1 == Approx(-f.k2).margin(1e-13));
    CHECK(m.k2 == Approx(-f.k1).margin(1e-13));
    CHECK(m.gauss_curvature == Approx(f.gauss_curvature).margin(1e-13));
    // Rodrigues / Euler: the normal curvature along dir1 is k1 (II(x)/I(x) with x = dir).
    const Vector2d x(f.dir1.dot(f.a1_contra), f.dir1.dot(f.a2_contra));
    CHECK(x.dot(f.h * x) / x.dot(f.a * x) == Approx(f.k1).margin(1e-11 * (std::abs(f.k1) + 1)));
  }
}

TEST_CASE(
    "surface_frame: umbilic point with a skewed parametrization gives k1 == k2 and an "
    "orthonormal pair of directions",
    "[geometry][diffgeo]") {
  std::mt19937 g(24);
  for (int k = 0; k < 500; ++k) {
    const double lambda = uniform(g, -3, 3);
    SurfaceDerivs d;
    d.order = 2;
    d.Su = Vector3d(uniform(g, 0.5, 2), uniform(g, -1, 1), 0.0);
    d.Sv = Vector3d(uniform(g, -1, 1), uniform(g, 0.5, 2), 0.0);
    const Vector3d n = d.Su.cross(d.Sv).normalized();
    // rho_ij with normal part lambda a_ij (h = lambda a) plus arbitrary tangential parts.
    d.Suu = lambda * d.Su.dot(d.Su) * n + uniform(g, -1, 1) * d.Su;
    d.Suv = lambda * d.Su.dot(d.Sv) * n + uniform(g, -1, 1) * d.Sv;
    d.Svv = lambda * d.Sv.dot(d.Sv) * n + uniform(g, -1, 1) * d.Su;
    const SurfaceFrame f = surface_frame(d);
    CHECK(f.k1 == Approx(lambda).margin(1e-12));
    CHECK(f.k2 == Approx(lambda).margin(1e-12));
    CHECK(f.gauss_curvature == Approx(lambda * lambda).margin(1e-12));
    check_frame_identities(f, std::abs(lambda) + 1.0);
  }
}

TEST_CASE("surface_frame: throws at singular points", "[geometry][diffgeo][errors]") {
  SurfaceDerivs d;
  d.order = 1;
  d.Su = Vector3d(1, 0, 0);
  d.Sv = Vector3d(2, 0, 0);
  CHECK_THROWS_AS(surface_frame(d), GeometryError);
  d.Sv = Vector3d::Zero();
  CHECK_THROWS_AS(surface_frame(d), GeometryError);
  // The pole of the analytic sphere.
  const Sphere s(Placement{}, 1.0);
  CHECK_THROWS_AS(surface_frame(s.derivs(0.3, 0.5 * kPi)), GeometryError);
}

// ---- surfaces: closed-form curvatures ----------------------------------------------------------

// Sign convention (differential_geometry.hpp): h_ij = rho_ij . n, so with the outward normal a
// convex surface has negative principal curvatures:
//   cylinder   k1 = 0, k2 = -1/R
//   sphere     k1 = k2 = -1/R
//   torus      -1/r (along the tube's meridian) and -cos v/(R + r cos v) (along the parallel),
//              cos v = (s - R)/r with s the distance from the axis
//   cone       k1 = 0 (along the generator), k2 = -sin(alpha)/s

TEST_CASE(
    "principal curvatures: cylinder 0 and -1/R, directions along the axis and around, "
    "analytic and NURBS",
    "[geometry][diffgeo]") {
  std::mt19937 g(25);
  const double R = 0.8;
  Placement pl;
  pl.center = Vector3d(1, -2, 0.5);
  pl.axis = random_unit(g);
  pl.ref_dir = random_unit(g);
  const Cylinder ana(pl, R);
  const NurbsSurface nur = make_cylinder(pl.center, pl.axis, pl.ref_dir, R, 3.0);
  const Vector3d a = pl.axis;
  for (const Surface* s : {static_cast<const Surface*>(&ana), static_cast<const Surface*>(&nur)}) {
    INFO(s->type_name());
    double worst = 0.0, worst_dir = 0.0;
    for (int q = 0; q < 1000; ++q) {
      const double u = s == &ana ? uniform(g, 0, 2 * kPi) : uniform(g, 0, 1);
      const double v = s == &ana ? uniform(g, -2, 2) : uniform(g, 0, 1);
      const SurfaceFrame f = surface_frame(s->derivs(u, v, 2));
      worst =
          std::max({worst, std::abs(f.k1), std::abs(f.k2 + 1.0 / R) * R,
                    std::abs(f.gauss_curvature) * R * R, std::abs(f.mean_curvature + 0.5 / R) * R});
      worst_dir = std::max({worst_dir, 1.0 - std::abs(f.dir1.dot(a)), std::abs(f.dir2.dot(a))});
      if (q % 50 == 0) check_frame_identities(f, 1.0 / R);
    }
    CHECK(worst <= 1e-10);
    CHECK(worst_dir <= 1e-10);
  }
}

TEST_CASE("principal curvatures: sphere -1/R twice (outward), +1/R inward, analytic and NURBS",
          "[geometry][diffgeo]") {
  std::mt19937 g(26);
  const double R = 1.7;
  Placement pl;
  pl.center = Vector3d(0.3, 0.2, -1);
  pl.axis = random_unit(g);
  Sphere ana(pl, R);
  NurbsSurface nur = make_sphere(pl.center, R);
  for (Surface* s : {static_cast<Surface*>(&ana), static_cast<Surface*>(&nur)}) {
    INFO(s->type_name());
    for (const int sign : {1, -1}) {
      s->set_normal_sign(sign);
      double worst = 0.0;
      for (int q = 0; q < 1000; ++q) {
        const double u = s == &ana ? uniform(g, 0, 2 * kPi) : uniform(g, 0, 1);
        const double v = s == &ana ? uniform(g, -1.5, 1.5) : uniform(g, 0.02, 0.98);
        const SurfaceFrame f = surface_frame(s->derivs(u, v, 2), s->normal_sign());
        const double k = -sign / R;
        worst = std::max({worst, std::abs(f.k1 - k) * R, std::abs(f.k2 - k) * R,
                          std::abs(f.gauss_curvature - k * k) * R * R});
        if (q % 50 == 0) check_frame_identities(f, 1.0 / R);
      }
      INFO("normal sign " << sign << ": worst relative curvature error " << worst);
      CHECK(worst <= 1e-10);
    }
  }
}

TEST_CASE(
    "principal curvatures: torus -1/r along the tube and -cos v/(R + r cos v) along the "
    "parallel, analytic and NURBS",
    "[geometry][diffgeo]") {
  std::mt19937 g(27);
  // R < 2r makes |cos v/(R + r cos v)| exceed 1/r near the inner equator, so the ordering of
  // k1, k2 switches over the surface.
  for (const auto& [R, r] : {std::pair{2.0, 0.6}, std::pair{1.5, 1.0}}) {
    Placement pl;
    pl.center = Vector3d(-1, 0.5, 2);
    pl.axis = random_unit(g);
    const Torus ana(pl, R, r);
    const NurbsSurface nur = make_torus(pl.center, pl.axis, R, r);
    const Vector3d a = pl.axis;
    for (const Surface* s :
         {static_cast<const Surface*>(&ana), static_cast<const Surface*>(&nur)}) {
      INFO(s->type_name() << " R = " << R << ", r = " << r);
      double worst = 0.0, worst_dir = 0.0;
      for (int q = 0; q < 2000; ++q) {
        const double u = s == &ana ? uniform(g, 0, 2 * kPi) : uniform(g, 0, 1);
        const double v = s == &ana ? uniform(g, 0, 2 * kPi) : uniform(g, 0, 1);
        const SurfaceDerivs d = s->derivs(u, v, 2);
        const SurfaceFrame f = surface_frame(d);
        const Vector3d x = d.S - pl.center;
        const Vector3d radial = x - x.dot(a) * a;
        const double cos_v = (radial.norm() - R) / r;  // from the geometry, not the parameter
        const double k_tube = -1.0 / r, k_par = -cos_v / (R + r * cos_v);
        const auto [kmax, kmin] = sorted(k_tube, k_par);
        worst = std::max({worst, std::abs(f.k1 - kmax) * r, std::abs(f.k2 - kmin) * r,
                          std::abs(f.gauss_curvature - k_tube * k_par) * r * r});
        // The direction of the tube curvature lies in the meridian plane (normal to e_phi).
        const Vector3d ephi = a.cross(radial).normalized();
        const Vector3d& dir_tube = (k_tube >= k_par) ? f.dir1 : f.dir2;
        if (std::abs(k_tube - k_par) > 1e-3 / r)
          worst_dir = std::max(worst_dir, std::abs(dir_tube.dot(ephi)));
        if (q % 100 == 0) check_frame_identities(f, 1.0 / r);
      }
      CHECK(worst <= 1e-10);
      CHECK(worst_dir <= 1e-9);
    }
  }
}

TEST_CASE("principal curvatures: cone 0 and -sin(alpha)/s, analytic and NURBS",
          "[geometry][diffgeo]") {
  std::mt19937 g(28);
  const double alpha = 0.6;
  Placement pl;
  pl.center = Vector3d(0.5, 0.5, 0.5);
  pl.axis = random_unit(g);
  pl.ref_dir = random_unit(g);
  const Cone ana(pl, alpha);
  const NurbsSurface nur = make_cone(pl.center, pl.axis, pl.ref_dir, alpha, 0.3, 2.0);
  for (const Surface* s : {static_cast<const Surface*>(&ana), static_cast<const Surface*>(&nur)}) {
    INFO(s->type_name());
    double worst = 0.0;
    for (int q = 0; q < 1000; ++q) {
      const double u = s == &ana ? uniform(g, 0, 2 * kPi) : uniform(g, 0, 1);
      const double v = s == &ana ? uniform(g, 0.3, 2.0) : uniform(g, 0, 1);
      const SurfaceDerivs d = s->derivs(u, v, 2);
      const SurfaceFrame f = surface_frame(d);
      const Vector3d x = d.S - pl.center;
      const double sr = (x - x.dot(pl.axis) * pl.axis).norm();
      worst = std::max({worst, std::abs(f.k1) * sr, std::abs(f.k2 + std::sin(alpha) / sr) * sr});
    }
    CHECK(worst <= 1e-10);
  }
}

TEST_CASE(
    "Gauss curvature of the saddle z = a x y is negative, -a^2/(1 + a^2(x^2+y^2))^2, "
    "analytic and bilinear NURBS",
    "[geometry][diffgeo]") {
  std::mt19937 g(29);
  for (const double a : {2.5e-2, 0.4, -1.3}) {
    const Hyperboloid ana(Placement{}, a);
    const NurbsSurface nur = make_bilinear_hyperboloid(a, -10, 10, -10, 10);
    for (const Surface* s :
         {static_cast<const Surface*>(&ana), static_cast<const Surface*>(&nur)}) {
      for (int q = 0; q < 500; ++q) {
        const double x = uniform(g, -10, 10), y = uniform(g, -10, 10);
        const SurfaceFrame f = surface_frame(s->derivs(x, y, 2));
        const double w = 1.0 + a * a * (x * x + y * y);
        CHECK(f.gauss_curvature < 0.0);
        CHECK(f.gauss_curvature == Approx(-a * a / (w * w)).epsilon(1e-10));
        CHECK(f.k1 > 0.0);
        CHECK(f.k2 < 0.0);
      }
    }
  }
}

}  // namespace test_differential_geometry
