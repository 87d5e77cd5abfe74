// Tests of the exact NURBS constructions ([PT97] A7.1, Sect. 7.5, Sect. 8.3, A8.1, A9.1): shape
// errors at round-off level at random points, derivatives against finite differences, normal
// orientation, surfaces of revolution, the bilinear saddle of [KS15] (11) and the convergence
// of the interpolated helix.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/fitting.hpp"
#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"
#include "geometry/knot_vector.hpp"
#include "tests/support/geometry_checks.hpp"
#include "tests/support/geometry_error.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_constructions {

using namespace iga;
using namespace iga::test;

namespace {

constexpr double kPi = std::numbers::pi;
/// A random parameter strictly inside a random element (away from C^0 knots, so that
/// central differences with steps <= 1e-4 stay in one element).
/// Largest relative deviation of the first and second derivatives of a surface from central
/// differences of point(), relative to |exact| + L.
/// Unit normal S_u x S_v / |S_u x S_v| (computed here, independently of surface_frame).
Vector3d raw_normal(const Surface& s, double u, double v) {
  const SurfaceDerivs d = s.derivs(u, v, 1);
  return d.Su.cross(d.Sv).normalized();
}

/// e_x, e_y of a frame with unit axis a and reference direction ref (computed here).
void in_plane_axes(const Vector3d& a, const Vector3d& ref, Vector3d& ex, Vector3d& ey) {
  ex = (ref - ref.dot(a) * a).normalized();
  ey = a.cross(ex);
}

Vector3d helix(double R, double pitch, double t) {
  return Vector3d(R * std::cos(t), R * std::sin(t), pitch * t / (2 * kPi));
}

}  // namespace

TEST_CASE("make_line: degree 1 segment with linear parametrization", "[geometry][constructions]") {
  const Vector3d a(1, -2, 3), b(-4, 0.5, 2);
  const NurbsCurve c = make_line(a, b);
  REQUIRE(c.degree() == 1);
  for (double u = 0.0; u <= 1.0; u += 0.125)
    CHECK((c.point(u) - (a + u * (b - a))).norm() <= 1e-15);
}

TEST_CASE("make_circle: 9 points, weights 1 and sqrt(2)/2, double knots at quarters",
          "[geometry][constructions]") {
  const NurbsCurve c = make_circle(Vector3d(1, 2, 3), Vector3d(0, 0, 1), 2.0);
  REQUIRE(c.degree() == 2);
  REQUIRE(c.num_control_points() == 9);
  const std::vector<double> U = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  CHECK(c.knots().knots() == U);
  for (int i = 0; i < 9; ++i)
    CHECK(c.weight(i) == Approx(i % 2 == 0 ? 1.0 : std::sqrt(2.0) / 2).epsilon(1e-15));
  // The corners of the control square lie at distance r sqrt(2) from the centre.
  for (int i = 1; i < 9; i += 2)
    CHECK((c.control_point(i) - Vector3d(1, 2, 3)).norm() ==
          Approx(2.0 * std::sqrt(2.0)).epsilon(1e-15));
}

TEST_CASE(
    "make_circle: radius error <= 1e-13 at random points, planar, closed, "
    "counter-clockwise about the normal",
    "[geometry][constructions]") {
  std::mt19937 g(1);
  double worst_r = 0.0, worst_plane = 0.0;
  for (int k = 0; k < 20; ++k) {
    const double r = std::pow(10.0, uniform(g, -2, 2));
    const Vector3d c = r * Vector3d(uniform(g, -3, 3), uniform(g, -3, 3), uniform(g, -3, 3));
    const Vector3d nrm = random_unit(g);
    const NurbsCurve circ = make_circle(c, nrm, r);
    const double size = r + c.norm();
    CHECK((circ.point(0.0) - circ.point(1.0)).norm() <= 1e-15 * size);
    for (int s = 0; s < 500; ++s) {
      const double u = uniform(g, 0.0, 1.0);
      const CurveDerivs d = circ.derivs(u, 1);
      worst_r = std::max(worst_r, std::abs((d.d[0] - c).norm() - r) / size);
      worst_plane = std::max(worst_plane, std::abs((d.d[0] - c).dot(nrm)) / size);
      CHECK((d.d[0] - c).cross(d.d[1]).dot(nrm) > 0.0);
    }
  }
  INFO("radius error " << worst_r << ", out-of-plane " << worst_plane);
  CHECK(worst_r <= 1e-13);
  CHECK(worst_plane <= 1e-13);
}

TEST_CASE(
    "make_circular_arc: ceil(theta / 90 deg) segments, exact end points, radius and "
    "monotone angle",
    "[geometry][constructions]") {
  const Vector3d c(0.5, -1, 2), X(1, 0, 0), Y(0, 0.6, 0.8);
  const double r = 1.7;
  for (const double deg : {10.0, 90.0, 91.0, 135.0, 180.0, 200.0, 270.0, 300.0, 360.0}) {
    const double start = -0.7, theta = deg * kPi / 180.0;
    const NurbsCurve a = make_circular_arc(c, X, Y, r, start, start + theta);
    const int narcs = static_cast<int>(std::ceil(deg / 90.0 - 1e-9));
    INFO("arc of " << deg << " degrees");
    CHECK(a.num_control_points() == 2 * narcs + 1);
    auto at = [&](double t) { return c + r * (std::cos(t) * X + std::sin(t) * Y); };
    CHECK((a.point(0.0) - at(start)).norm() <= 1e-14);
    CHECK((a.point(1.0) - at(start + theta)).norm() <= 1e-14);
    double prev = -1e300, worst = 0.0;
    for (int s = 0; s <= 2000; ++s) {
      const Vector3d p = a.point(s / 2000.0) - c;
      worst = std::max(worst, std::abs(p.norm() - r) / r);
      // Polar angle measured from the start direction, in [0, 2 pi).
      double phi = std::atan2(p.dot(Y), p.dot(X)) - start;
      while (phi < -1e-12) phi += 2 * kPi;
      if (s == 2000 && deg == 360.0) phi = 2 * kPi;
      CHECK(phi >= prev - 1e-12);
      CHECK(phi <= theta + 1e-12);
      prev = phi;
    }
    CHECK(worst <= 1e-13);
  }
}

TEST_CASE("make_circular_arc: rejects bad radius, angles and axes",
          "[geometry][constructions][errors]") {
  const Vector3d c = Vector3d::Zero(), X = Vector3d::UnitX(), Y = Vector3d::UnitY();
  CHECK_THROWS_AS(make_circular_arc(c, X, Y, 0.0, 0.0, 1.0), GeometryError);
  CHECK_THROWS_AS(make_circular_arc(c, X, Y, 1.0, 1.0, 1.0), GeometryError);
  CHECK_THROWS_AS(make_circular_arc(c, X, Y, 1.0, 0.0, 7.0), GeometryError);
  CHECK_THROWS_AS(make_circular_arc(c, X, 2 * Y, 1.0, 0.0, 1.0), GeometryError);
  CHECK_THROWS_AS(make_circular_arc(c, X, Vector3d(1, 1, 0).normalized(), 1.0, 0.0, 1.0),
                  GeometryError);
  CHECK_THROWS_AS(make_circle(c, Vector3d::Zero(), 1.0), GeometryError);
}

TEST_CASE("NURBS constructions: derivatives agree with central finite differences",
          "[geometry][constructions]") {
  std::mt19937 g(3);
  // Curves: circle and arc.
  const NurbsCurve circ = make_circle(Vector3d(1, 0, -1), random_unit(g), 1.5);
  const NurbsCurve arc =
      make_circular_arc(Vector3d::Zero(), Vector3d::UnitY(), Vector3d::UnitZ(), 0.7, 0.2, 4.0);
  for (const NurbsCurve* c : {&circ, &arc}) {
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {
      const double u = inside_element(g, c->knots());
      const CurveDerivs d = c->derivs(u, 2);
      const double h1 = 1e-6, h2 = 1e-4;
      const Vector3d fu = (c->point(u + h1) - c->point(u - h1)) / (2 * h1);
      const Vector3d fuu = (c->point(u + h2) - 2 * c->point(u) + c->point(u - h2)) / (h2 * h2);
      worst = std::max({worst, (fu - d.d[1]).norm() / (d.d[1].norm() + 1.0),
                        (fuu - d.d[2]).norm() / (d.d[2].norm() + 1.0)});
    }
    CHECK(worst <= 1e-6);
  }
  // Surfaces.
  const Vector3d axis = random_unit(g), ref = random_unit(g);
  const std::vector<std::pair<const char*, NurbsSurface>> surfaces = {
      {"cylinder", make_cylinder(Vector3d(1, 2, 3), axis, ref, 0.8, 2.0, 0.3, 5.0)},
      {"sphere", make_sphere(Vector3d(-1, 0, 2), 1.3)},
      {"torus", make_torus(Vector3d(0, 1, 0), axis, 2.0, 0.6)},
      {"cone", make_cone(Vector3d(0, 0, 1), axis, ref, 0.7, 0.2, 1.5)},
      {"hyperboloid", make_bilinear_hyperboloid(0.3, -2.0, 1.0, -1.0, 3.0)},
      {"plane", make_plane_patch(Vector3d(1, 1, 1), Vector3d(2, 0, 1), Vector3d(0, 3, -1))},
  };
  for (const auto& [name, s] : surfaces) {
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {
      const double u = inside_element(g, s.knots_u()), v = inside_element(g, s.knots_v());
      worst = std::max(worst, surface_fd_error(s, u, v, 1.0));
    }
    INFO(name << ": worst relative finite-difference error " << worst);
    CHECK(worst <= 1e-6);
  }
}

TEST_CASE(
    "make_cylinder: distance to the axis equals r (<= 1e-13), outward normal, angular "
    "range from ref_dir",
    "[geometry][constructions]") {
  std::mt19937 g(4);
  double worst_r = 0.0, worst_n = 0.0, worst_h = 0.0;
  for (int k = 0; k < 10; ++k) {
    const double r = std::pow(10.0, uniform(g, -1, 1)), h = uniform(g, 0.5, 3.0);
    const Vector3d base = r * Vector3d(uniform(g, -2, 2), uniform(g, -2, 2), uniform(g, -2, 2));
    const Vector3d a = random_unit(g), ref = random_unit(g);
    const double start = uniform(g, -1, 1);
    const double end = k % 2 == 0 ? start + 2 * kPi : start + uniform(g, 0.2, 6.0);
    const NurbsSurface s = make_cylinder(base, a, ref, r, h, start, end);
    const double size = r + base.norm() + h;
    Vector3d ex, ey;
    in_plane_axes(a, ref, ex, ey);
    for (double v : {0.0, 0.4, 1.0}) {
      CHECK(
          (s.point(0.0, v) - (base + r * (std::cos(start) * ex + std::sin(start) * ey) + v * h * a))
              .norm() <= 1e-13 * size);
      CHECK((s.point(1.0, v) - (base + r * (std::cos(end) * ex + std::sin(end) * ey) + v * h * a))
                .norm() <= 1e-13 * size);
    }
    for (int q = 0; q < 400; ++q) {
      const double u = uniform(g, 0, 1), v = uniform(g, 0, 1);
      const Vector3d x = s.point(u, v) - base;
      const Vector3d radial = x - x.dot(a) * a;
      worst_r = std::max(worst_r, std::abs(radial.norm() - r) / size);
      worst_h = std::max(worst_h, std::abs(x.dot(a) - v * h) / size);
      worst_n = std::max(worst_n, (raw_normal(s, u, v) - radial.normalized()).norm());
    }
  }
  INFO("radius error " << worst_r << ", axial error " << worst_h << ", normal error " << worst_n);
  CHECK(worst_r <= 1e-13);
  CHECK(worst_h <= 1e-13);
  CHECK(worst_n <= 1e-12);
}

TEST_CASE("make_sphere: |S - c| = r (<= 1e-13), poles at v = 0, 1, outward normal",
          "[geometry][constructions]") {
  std::mt19937 g(5);
  double worst_r = 0.0, worst_n = 0.0;
  for (int k = 0; k < 10; ++k) {
    const double r = std::pow(10.0, uniform(g, -1, 1));
    const Vector3d c = r * Vector3d(uniform(g, -2, 2), uniform(g, -2, 2), uniform(g, -2, 2));
    const NurbsSurface s = make_sphere(c, r);
    const double size = r + c.norm();
    for (double u : {0.0, 0.3, 0.9}) {
      CHECK((s.point(u, 0.0) - (c - r * Vector3d::UnitZ())).norm() <= 1e-14 * size);
      CHECK((s.point(u, 1.0) - (c + r * Vector3d::UnitZ())).norm() <= 1e-14 * size);
    }
    for (int q = 0; q < 400; ++q) {
      const double u = uniform(g, 0, 1), v = uniform(g, 0, 1);
      worst_r = std::max(worst_r, std::abs((s.point(u, v) - c).norm() - r) / size);
      if (v > 0.01 && v < 0.99)  // the normal is undefined at the poles
        worst_n = std::max(worst_n, (raw_normal(s, u, v) - (s.point(u, v) - c) / r).norm());
    }
  }
  INFO("radius error " << worst_r << ", normal error " << worst_n);
  CHECK(worst_r <= 1e-13);
  CHECK(worst_n <= 1e-11);
}

TEST_CASE("make_torus: (B.16) distance vanishes (<= 1e-13), closed both ways, outward normal",
          "[geometry][constructions]") {
  std::mt19937 g(6);
  double worst_p = 0.0, worst_n = 0.0;
  for (int k = 0; k < 10; ++k) {
    const double R = uniform(g, 1.0, 5.0), r = uniform(g, 0.1, 0.95) * R;
    const Vector3d c(uniform(g, -2, 2), uniform(g, -2, 2), uniform(g, -2, 2));
    const Vector3d a = random_unit(g);
    const NurbsSurface s = make_torus(c, a, R, r);
    const double size = R + r + c.norm();
    for (double t = 0.0; t <= 1.0; t += 0.1) {
      CHECK((s.point(0.0, t) - s.point(1.0, t)).norm() <= 1e-14 * size);
      CHECK((s.point(t, 0.0) - s.point(t, 1.0)).norm() <= 1e-14 * size);
    }
    for (int q = 0; q < 400; ++q) {
      const double u = uniform(g, 0, 1), v = uniform(g, 0, 1);
      const Vector3d x = s.point(u, v) - c;
      const double z = x.dot(a);
      const Vector3d radial = x - z * a;
      // (B.16): sqrt(x^2 + y^2 + z^2 + R^2 - 2 R s) - r = 0 on the surface.
      const double p = std::sqrt(x.squaredNorm() + R * R - 2 * R * radial.norm()) - r;
      worst_p = std::max(worst_p, std::abs(p) / size);
      const Vector3d tube_centre = R * radial.normalized();
      worst_n = std::max(worst_n, (raw_normal(s, u, v) - (x - tube_centre) / r).norm());
    }
  }
  INFO("distance error " << worst_p << ", normal error " << worst_n);
  CHECK(worst_p <= 1e-13);
  CHECK(worst_n <= 1e-11);
}

TEST_CASE(
    "make_cone: (B.23) s sin(a) - z cos(a) vanishes (<= 1e-13), s in [s1, s2], normal "
    "sin(a) e_r - cos(a) e_z",
    "[geometry][constructions]") {
  std::mt19937 g(7);
  double worst_p = 0.0, worst_n = 0.0;
  for (int k = 0; k < 10; ++k) {
    const double alpha = uniform(g, 0.05, 1.5), s1 = uniform(g, 0.0, 1.0);
    const double s2 = s1 + uniform(g, 0.2, 2.0);
    const Vector3d apex(uniform(g, -2, 2), uniform(g, -2, 2), uniform(g, -2, 2));
    const Vector3d a = random_unit(g), ref = random_unit(g);
    const NurbsSurface s = make_cone(apex, a, ref, alpha, s1, s2);
    const double size = s2 / std::cos(alpha) + apex.norm();
    Vector3d ex, ey;
    in_plane_axes(a, ref, ex, ey);
    CHECK((s.point(0.0, 0.0) - (apex + s1 * ex + s1 * std::tan(alpha) * a)).norm() <= 1e-13 * size);
    CHECK((s.point(0.0, 1.0) - (apex + s2 * ex + s2 * std::tan(alpha) * a)).norm() <= 1e-13 * size);
    for (int q = 0; q < 400; ++q) {
      const double u = uniform(g, 0, 1), v = uniform(g, 0, 1);
      const Vector3d x = s.point(u, v) - apex;
      const double z = x.dot(a);
      const Vector3d radial = x - z * a;
      const double sr = radial.norm();
      CHECK(sr >= s1 - 1e-13 * size);
      CHECK(sr <= s2 + 1e-13 * size);
      worst_p = std::max(worst_p, std::abs(sr * std::sin(alpha) - z * std::cos(alpha)) / size);
      if (sr > 1e-3 * s2) {
        const Vector3d n = std::sin(alpha) * radial / sr - std::cos(alpha) * a;
        worst_n = std::max(worst_n, (raw_normal(s, u, v) - n).norm());
      }
    }
  }
  INFO("(B.23) error " << worst_p << ", normal error " << worst_n);
  CHECK(worst_p <= 1e-13);
  CHECK(worst_n <= 1e-11);
}

TEST_CASE(
    "make_revolution: a NURBS profile keeps its distance to the axis and its height, "
    "u = 0 is the profile and u = 1 the profile rotated by the angle",
    "[geometry][constructions]") {
  std::mt19937 g(8);
  for (const double angle : {2 * kPi, 2.5, 0.5 * kPi, 4.0}) {
    // A random rational cubic profile in 3-D (not planar), partly on the axis side.
    std::vector<Vector3d> P;
    std::vector<double> W;
    for (int i = 0; i < 6; ++i) {
      P.emplace_back(uniform(g, -1, 2), uniform(g, -1, 2), uniform(g, -1, 2));
      W.push_back(uniform(g, 0.5, 2.0));
    }
    const NurbsCurve prof(3, {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1}, P, W);
    const Vector3d o(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1));
    const Vector3d a = random_unit(g);
    const NurbsSurface s = make_revolution(prof, o, 3.0 * a, angle);  // axis need not be unit
    const Eigen::AngleAxisd rot(angle, a);
    double worst = 0.0;
    for (int q = 0; q < 2000; ++q) {
      const double u = uniform(g, 0, 1), v = uniform(g, 0, 1);
      const Vector3d x = s.point(u, v) - o, y = prof.point(v) - o;
      const double hx = x.dot(a), hy = y.dot(a);
      worst =
          std::max({worst, std::abs((x - hx * a).norm() - (y - hy * a).norm()), std::abs(hx - hy)});
      if (q % 10 == 0) {
        CHECK((s.point(0.0, v) - prof.point(v)).norm() <= 1e-13);
        CHECK((s.point(1.0, v) - (o + rot * y)).norm() <= 1e-13);
      }
    }
    INFO("angle " << angle << ": worst distance/height error " << worst);
    CHECK(worst <= 1e-13);
  }
  CHECK_THROWS_AS(make_revolution(make_line(Vector3d(1, 0, 0), Vector3d(1, 0, 1)), Vector3d::Zero(),
                                  Vector3d::Zero()),
                  GeometryError);
  CHECK_THROWS_AS(make_revolution(make_line(Vector3d(1, 0, 0), Vector3d(1, 0, 1)), Vector3d::Zero(),
                                  Vector3d::UnitZ(), 7.0),
                  GeometryError);
}

TEST_CASE(
    "make_bilinear_hyperboloid: z == a x y (<= 1e-14) and equal to the analytic "
    "Hyperboloid with (u, v) = (x, y)",
    "[geometry][constructions]") {
  std::mt19937 g(9);
  const double a = 2.5e-2;  // the paper's saddle (Sect. 6.1)
  const NurbsSurface s = make_bilinear_hyperboloid(a, -10.0, 10.0, -10.0, 10.0);
  const Hyperboloid h(Placement{}, a);
  REQUIRE(s.degree_u() == 1);
  REQUIRE(s.degree_v() == 1);
  double worst_z = 0.0, worst_d = 0.0;
  for (int q = 0; q < 5000; ++q) {
    const double x = uniform(g, -10, 10), y = uniform(g, -10, 10);
    const SurfaceDerivs d = s.derivs(x, y, 2), e = h.derivs(x, y, 2);
    worst_z = std::max(
        {worst_z, std::abs(d.S.z() - a * d.S.x() * d.S.y()) / std::max(1.0, std::abs(d.S.z())),
         std::abs(d.S.x() - x) / 10, std::abs(d.S.y() - y) / 10});
    worst_d = std::max({worst_d, (d.S - e.S).norm(), (d.Su - e.Su).norm(), (d.Sv - e.Sv).norm(),
                        (d.Suu - e.Suu).norm(), (d.Suv - e.Suv).norm(), (d.Svv - e.Svv).norm()});
  }
  INFO("z - a x y: " << worst_z << ", derivatives vs analytic: " << worst_d);
  CHECK(worst_z <= 1e-14);
  CHECK(worst_d <= 1e-13);
  // (22): the normal points to the +z side.
  CHECK(raw_normal(s, 3.0, -4.0).z() > 0.0);
  CHECK_THROWS_AS(make_bilinear_hyperboloid(a, 1.0, 1.0, 0.0, 1.0), GeometryError);
}

TEST_CASE("make_plane_patch: corners and bilinear map", "[geometry][constructions]") {
  const Vector3d o(1, 2, 3), du(2, 0, 1), dv(0, 3, -1);
  const NurbsSurface s = make_plane_patch(o, du, dv);
  for (double u = 0; u <= 1; u += 0.25)
    for (double v = 0; v <= 1; v += 0.25)
      CHECK((s.point(u, v) - (o + u * du + v * dv)).norm() <= 1e-14);
  CHECK((raw_normal(s, 0.5, 0.5) - du.cross(dv).normalized()).norm() <= 1e-15);
}

TEST_CASE("make_helix_cubic: interpolates the data, reported deviation is honest and small",
          "[geometry][constructions][helix]") {
  const double R = 1.0, pitch = 2.0, angle = kPi;
  const HelixApproximation h = make_helix_cubic(R, pitch, angle, 33);
  REQUIRE(h.curve.degree() == 3);
  REQUIRE(h.curve.num_control_points() == 33);
  // Interpolation at t_k = k / 32.
  for (int k = 0; k <= 32; ++k)
    CHECK((h.curve.point(k / 32.0) - helix(R, pitch, angle * k / 32.0)).norm() <= 1e-13 * R);
  INFO("reported deviation " << h.max_deviation);
  CHECK(h.max_deviation > 0.0);
  CHECK(h.max_deviation < 1e-4 * R);
  // An independent random sampling never exceeds the reported maximum by more than a little.
  std::mt19937 g(10);
  double mine = 0.0;
  for (int q = 0; q < 20000; ++q) {
    const double s = uniform(g, 0, 1);
    mine = std::max(mine, (h.curve.point(s) - helix(R, pitch, s * angle)).norm());
  }
  CHECK(mine <= 1.01 * h.max_deviation);
  CHECK(mine >= 0.5 * h.max_deviation);
  CHECK_THROWS_AS(make_helix_cubic(R, pitch, angle, 3), GeometryError);
  CHECK_THROWS_AS(make_helix_cubic(-1.0, pitch, angle, 10), GeometryError);
}

TEST_CASE("make_helix_cubic: deviation decreases like h^4 (observed order >= 3.5)",
          "[geometry][constructions][helix]") {
  for (const double pitch : {0.0, 1.0, 2.0}) {
    double prev = 0.0;
    for (int n_el = 8; n_el <= 128; n_el *= 2) {  // n_points - 1 doubles: h halves
      const double dev = make_helix_cubic(1.0, pitch, kPi, n_el + 1).max_deviation;
      if (prev > 0.0) {
        const double order = std::log2(prev / dev);
        INFO("pitch " << pitch << ", " << n_el << " intervals: deviation " << dev
                      << ", observed order " << order);
        CHECK(order >= 3.5);
      }
      prev = dev;
    }
  }
}

TEST_CASE("fit_curve: reproduces a spline exactly and approximates a circle arc with O(h^4)",
          "[geometry][fitting]") {
  // a cubic B-spline sampled densely is recovered exactly (it lies in the space)
  const std::vector<double> U = {0, 0, 0, 0, 0.3, 0.5, 0.8, 1, 1, 1, 1};
  const std::vector<Vector3d> P = {{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 0, 2},
                                   {4, 1, 0}, {5, 3, 1}, {6, 0, 0}};
  const NurbsCurve c(3, U, P);
  std::vector<Vector3d> Q;
  std::vector<double> t;
  for (int k = 0; k <= 200; ++k) {
    t.push_back(k / 200.0);
    Q.push_back(c.point(k / 200.0));
  }
  const CurveFit f = fit_curve(Q, t, 3, U);
  CHECK(f.max_deviation <= 1e-12);
  for (int i = 0; i < 7; ++i) CHECK((f.curve.control_point(i) - P[i]).norm() <= 1e-10);
  // a quarter circle: the error falls ~ h^4 for cubics under uniform refinement
  double prev = 0.0;
  for (int ne : {4, 8, 16}) {
    std::vector<double> K(4, 0.0);
    for (int e = 1; e < ne; ++e) K.push_back(static_cast<double>(e) / ne);
    K.insert(K.end(), 4, 1.0);
    std::vector<Vector3d> arc;
    std::vector<double> s;
    for (int k = 0; k <= 40 * ne; ++k) {
      const double a = 0.5 * std::numbers::pi * k / (40.0 * ne);
      arc.emplace_back(std::cos(a), std::sin(a), 0.0);
      s.push_back(static_cast<double>(k) / (40 * ne));
    }
    const double dev = fit_curve(arc, s, 3, K).max_deviation;
    if (prev > 0) CHECK(prev / dev >= 10.0);  // 2^4 = 16 in the limit
    prev = dev;
  }
  CHECK(prev <= 1e-6);
}

TEST_CASE("make_wrap_path: spans tangent to a helix of the given radius and pitch, C1 fit",
          "[geometry][constructions]") {
  WrapPathSpec w;
  w.center = Vector3d(0.3, -0.2, 0.5);
  w.axis = Vector3d(0.0, 0.0, 2.0);  // normalized inside
  w.mid_dir = Vector3d(0.1, 1.0, 0.3);
  w.radius = 1.5;
  w.angle = 0.8 * kPi;
  w.pitch = 2.0;
  w.span_length = 0.7;
  w.arc_elements = 24;
  w.span_elements = 2;
  const WrapPath r = make_wrap_path(w);
  const double c = w.pitch / (2.0 * kPi), speed = std::sqrt(w.radius * w.radius + c * c);
  CHECK(r.arc_length == Approx(w.angle * speed).epsilon(1e-14));
  CHECK(r.max_deviation < 1e-6);
  const NurbsCurve& C = r.curve;
  const Interval D = C.domain();
  // Arc-length parameter: the domain is the path length, the speed is 1 to the fit accuracy.
  CHECK(D.hi - D.lo == Approx(2.0 * w.span_length + r.arc_length).epsilon(1e-14));
  // End tangents, the travel directions reported, and the spans straight.
  CHECK((C.derivs(D.lo, 1).d[1].normalized() - r.tangent_start).norm() < 1e-6);
  CHECK((C.derivs(D.hi, 1).d[1].normalized() - r.tangent_end).norm() < 1e-6);
  CHECK((C.point(D.hi) - C.point(D.hi - w.span_length) - w.span_length * r.tangent_end).norm() <
        1e-6);
  // Arc points: distance radius from the axis, rise c per radian of polar angle, mid-point on
  // the side of mid_dir, half-way up.
  const Vector3d ez = Vector3d::UnitZ();
  for (int k = 0; k <= 10; ++k) {
    const double s = D.lo + w.span_length + r.arc_length * k / 10.0;
    const Vector3d d = C.point(s) - w.center;
    CHECK((d - d.dot(ez) * ez).norm() == Approx(w.radius).epsilon(1e-6));
    CHECK(d.dot(ez) == Approx(c * w.angle * (k / 10.0 - 0.5)).margin(1e-6));
  }
  const Vector3d mid = C.point(0.5 * (D.lo + D.hi)) - w.center;
  const Vector3d ey = (w.mid_dir - w.mid_dir.dot(ez) * ez).normalized();
  CHECK((mid - mid.dot(ez) * ez).normalized().dot(ey) == Approx(1.0).epsilon(1e-9));
  // C1 at the double knots (tangent points): the derivative is continuous.
  const double s1 = D.lo + w.span_length;
  CHECK((C.derivs(s1 - 1e-9, 1).d[1] - C.derivs(s1 + 1e-9, 1).d[1]).norm() < 1e-6);

  WrapPathSpec bad = w;
  bad.mid_dir = w.axis;
  CHECK_THROWS_AS(make_wrap_path(bad), GeometryError);
  bad = w;
  bad.arc_elements = 0;
  CHECK_THROWS_AS(make_wrap_path(bad), GeometryError);
}

TEST_CASE("make_wrap_path: degree 4 and 5 are the cubic fit elevated (same curve, C2 inside)",
          "[geometry][constructions]") {
  WrapPathSpec w;
  w.radius = 1.02;
  w.angle = kPi;
  w.arc_elements = 10;
  w.span_elements = 3;
  const WrapPath cubic = make_wrap_path(w);
  for (int p : {4, 5}) {
    w.degree = p;
    const WrapPath r = make_wrap_path(w);
    const NurbsCurve& C = r.curve;
    CHECK(C.degree() == p);
    // Same elements; C2 at the inner knots (multiplicity p - 2), C1 at the tangent points
    // (p - 1): 16 elements add p - 2 control points each beyond the first p + 1, plus one at
    // each tangent point.
    CHECK(C.knots().breaks() == cubic.curve.knots().breaks());
    CHECK(C.num_control_points() == p + 1 + 15 * (p - 2) + 2);
    double dev = 0.0;
    const Interval D = C.domain();
    for (int k = 0; k <= 1000; ++k) {
      const double s = D.lo + (D.hi - D.lo) * k / 1000.0;
      dev = std::max(dev, (C.point(s) - cubic.curve.point(s)).norm());
    }
    CHECK(dev < 1e-12);
  }
  w.degree = 6;
  CHECK_THROWS_WITH(make_wrap_path(w), Catch::Contains("degree must be 3, 4 or 5, got 6"));
}

namespace {

/// The fit as it was computed before the banded solve: the dense m x n collocation matrix and
/// a dense LDL^T of the normal equations, [PT97] (9.66). The reference for the sparse solve.
std::vector<Vector3d> dense_fit(const std::vector<Vector3d>& Q, const std::vector<double>& t, int p,
                                const std::vector<double>& knots) {
  const KnotVector K(p, knots);
  const int n = K.num_basis(), m = static_cast<int>(Q.size());
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(m, n);
  BasisValues b;
  for (int k = 0; k < m; ++k) {
    const int span = K.find_span(t[static_cast<std::size_t>(k)]);
    basis_funs(span, t[static_cast<std::size_t>(k)], p, K.span(), b);
    for (int j = 0; j <= p; ++j) N(k, span - p + j) = b[static_cast<std::size_t>(j)];
  }
  Eigen::MatrixXd rhs(m, 3);
  for (int k = 0; k < m; ++k)
    rhs.row(k) =
        (Q[static_cast<std::size_t>(k)] - N(k, 0) * Q.front() - N(k, n - 1) * Q.back()).transpose();
  const Eigen::MatrixXd Ni = N.block(0, 1, m, n - 2);
  const Eigen::MatrixXd P =
      Eigen::LDLT<Eigen::MatrixXd>(Ni.transpose() * Ni).solve(Ni.transpose() * rhs);
  std::vector<Vector3d> cp(static_cast<std::size_t>(n));
  cp.front() = Q.front();
  cp.back() = Q.back();
  for (int i = 1; i < n - 1; ++i) cp[static_cast<std::size_t>(i)] = P.row(i - 1).transpose();
  return cp;
}

std::string rope(const std::string& radius, const std::string& arc, const std::string& span = "3",
                 const std::string& span_length = "1.0") {
  return R"({"rope": {"type": "construction", "shape": "wrap_path", "radius": )" + radius +
         R"(, "angle_deg": 180, "pitch": 0, "span_length": )" + span_length +
         R"(, "arc_elements": )" + arc + R"(, "span_elements": )" + span + "}}";
}

}  // namespace

TEST_CASE("fit_curve: the banded solve gives the dense normal-equation fit to round-off",
          "[geometry][fitting]") {
  // A wrap path's data (line + helix + line, double knots) and a wiggly curve with uneven
  // knots and degrees 2..5: control points agree with the dense solve within 1e-12 of the
  // curve's size (both are backward stable on the same well-conditioned normal equations).
  WrapPathSpec w;
  w.radius = 0.8;
  w.angle = 1.3 * kPi;
  w.pitch = 0.4;
  w.span_length = 1.1;
  w.arc_elements = 17;
  w.span_elements = 3;
  const WrapPath r = make_wrap_path(w);
  std::vector<double> t;
  std::vector<Vector3d> Q;
  const std::vector<double>& U = r.curve.knots().knots();
  for (std::size_t k = 3; k + 4 < U.size(); ++k)
    if (U[k + 1] > U[k])
      for (int j = 0; j < 16; ++j) t.push_back(U[k] + (U[k + 1] - U[k]) * j / 16.0);
  t.push_back(U.back());
  // Sample the fitted curve plus a wiggle, so that the least-squares residual is not zero.
  for (double s : t)
    Q.push_back(r.curve.point(s) +
                1e-3 * Vector3d(std::sin(7 * s), std::cos(5 * s), std::sin(3 * s)));
  const CurveFit f = fit_curve(Q, t, 3, U);
  const std::vector<Vector3d> ref = dense_fit(Q, t, 3, U);
  for (int i = 0; i < f.curve.num_control_points(); ++i)
    CHECK((f.curve.control_point(i) - ref[static_cast<std::size_t>(i)]).norm() <= 1e-12 * 5.0);

  std::mt19937 g(11);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  for (int p = 2; p <= 5; ++p) {
    std::vector<double> K(static_cast<std::size_t>(p + 1), 0.0);
    double x = 0.0;
    for (int e = 0; e < 12; ++e) K.push_back(x += 0.5 + unif(g));
    K.pop_back();
    K.insert(K.end(), static_cast<std::size_t>(p + 1), x);
    std::vector<double> s;
    std::vector<Vector3d> pts;
    for (int k = 0; k <= 300; ++k) {
      const double sk = x * k / 300.0;
      s.push_back(sk);
      pts.emplace_back(std::cos(sk), std::sin(2 * sk), sk * sk / 10);
    }
    const CurveFit fp = fit_curve(pts, s, p, K);
    const std::vector<Vector3d> rp = dense_fit(pts, s, p, K);
    for (int i = 0; i < fp.curve.num_control_points(); ++i)
      CHECK((fp.curve.control_point(i) - rp[static_cast<std::size_t>(i)]).norm() <= 1e-11);
  }
}

TEST_CASE("make_wrap_path: 50000 arc elements build (banded fit, no dense matrix)",
          "[geometry][constructions]") {
  // The dense collocation matrix of 800,000 samples x 50,000 control points would need 320 GB.
  // The time, about 1 s on one core, is measured by bench/bench_model_setup.cpp.
  WrapPathSpec w;
  w.radius = 1.02;
  w.angle = kPi;
  w.span_length = 1.0;
  w.arc_elements = 50000;
  w.span_elements = 3;
  const WrapPath r = make_wrap_path(w);
  CHECK(r.curve.num_control_points() == 50000 + 2 * 3 + 3 + 2);
  CHECK(r.max_deviation < 1e-12);
}

TEST_CASE("make_helix_cubic: 20000 points solve as a banded system", "[geometry][constructions]") {
  // Dense: a 20000^2 matrix (3.2 GB) and an O(n^3) LU.
  const HelixApproximation h = make_helix_cubic(1.0, 0.5, 8 * kPi, 20000);
  CHECK(h.curve.num_control_points() == 20000);
  CHECK(h.max_deviation < 1e-9);
  CHECK_THROWS_AS(make_helix_cubic(1.0, 0.5, kPi, kMaxCurveElements + 4), GeometryError);
}

TEST_CASE("make_wrap_path: bad inputs are named by their key before any fitting",
          "[geometry][constructions][errors]") {
  WrapPathSpec w;
  auto key_of = [](const WrapPathSpec& spec) -> std::string {
    try {
      make_wrap_path(spec);
    } catch (const ConstructionError& e) {
      return e.key();
    }
    return "(none)";
  };
  WrapPathSpec b = w;
  b.radius = 1e-12;  // the arc's knots would coincide ("interior knot 1 has multiplicity 13")
  CHECK(key_of(b) == "radius");
  b = w;
  b.radius = -1.0;
  CHECK(key_of(b) == "radius");
  b = w;
  b.span_length = 1e-12;
  CHECK(key_of(b) == "span_length");
  b = w;
  b.mid_dir = w.axis;
  CHECK(key_of(b) == "mid_dir");
  b = w;
  b.arc_elements = kMaxCurveElements;
  CHECK(key_of(b) == "arc_elements");
  b = w;
  b.span_elements = 0;
  CHECK(key_of(b) == "span_elements");
  b = w;
  b.pitch = std::numeric_limits<double>::infinity();
  CHECK(key_of(b) == "pitch");
  CHECK(key_of(w) == "(none)");
}

TEST_CASE("geometry_io: construction errors name the key at fault and state the limits",
          "[geometry][constructions][errors]") {
  // Tiny radius: the key, not an internal knot.
  ModelError e = iga::test::geometry_error(rope("1e-12", "10"));
  CHECK(e.pointer() == "/geometry/rope/radius");
  CHECK_THAT(e.message(), Catch::Contains("too small"));
  CHECK_THAT(e.message(), !Catch::Contains("knot"));
  // Too many elements: the limit is stated at the key.
  e = iga::test::geometry_error(rope("1.0", "100000"));
  CHECK(e.pointer() == "/geometry/rope/arc_elements");
  CHECK_THAT(e.message(), Catch::Contains("100000"));
  e = iga::test::geometry_error(rope("1.0", "1e5"));
  CHECK(e.pointer() == "/geometry/rope/arc_elements");
  e = iga::test::geometry_error(rope("1.0", "10", "3", "1e-13"));
  CHECK(e.pointer() == "/geometry/rope/span_length");
  e = iga::test::geometry_error(rope("1e300", "10"));
  CHECK(e.pointer() == "/geometry/rope/radius");
  // A refined surface above the control point limit: at "refine", with the count and limit.
  e = iga::test::geometry_error(
      R"({"shell": {"type": "construction", "shape": "sphere", "center": [0, 0, 0],
      "radius": 1, "refine": {"subdivide": 1024}}})");
  CHECK(e.pointer() == "/geometry/shell/refine");
  CHECK_THAT(e.message(), Catch::Contains(std::to_string(kMaxSurfaceNetPoints)));
  e = iga::test::geometry_error(
      R"({"t": {"type": "construction", "shape": "torus", "center": [0, 0, 0],
      "axis": [0, 0, 1], "major_radius": 1, "minor_radius": 2}})");
  CHECK(e.pointer() == "/geometry/t/minor_radius");
  e = iga::test::geometry_error(
      R"({"c": {"type": "construction", "shape": "cylinder", "center": [0, 0, 0],
      "axis": [0, 0, 1], "radius": 1, "height": 1, "start_deg": 90, "end_deg": 45}})");
  CHECK(e.pointer() == "/geometry/c/end_deg");
  e = iga::test::geometry_error(
      R"({"c": {"type": "construction", "shape": "cylinder", "center": [0, 0, 0],
      "axis": [0, 0, 1], "radius": 1, "height": 1, "start_deg": 0, "end_deg": 400}})");
  CHECK(e.pointer() == "/geometry/c/end_deg");
  e = iga::test::geometry_error(
      R"({"p": {"type": "construction", "shape": "plane", "origin": [0, 0, 0],
      "du": [1, 0, 0], "dv": [2, 0, 0]}})");
  CHECK(e.pointer() == "/geometry/p/dv");
  e = iga::test::geometry_error(
      R"({"l": {"type": "construction", "shape": "line", "start": [0, 0, 0],
      "end": [1, 0, 0], "elements": 200000}})");
  CHECK(e.pointer() == "/geometry/l/elements");
  // The largest allowed surface builds.
  const GeometryModel m = parse_geometry(
      parse_json_text(
          R"({"shell": {"type": "construction", "shape": "cylinder", "center": [0, 0, 0],
      "axis": [0, 0, 1], "radius": 1, "height": 1, "refine": {"subdivide": [235, 1000]}}})",
          "g.json"),
      "g.json", JsonPointer("/geometry"));
  const auto& shell = std::get<NurbsSurface>(m.entities.at(0).second);
  CHECK(static_cast<long>(shell.num_u()) * shell.num_v() <= kMaxSurfaceNetPoints);
  CHECK(static_cast<long>(shell.num_u()) * shell.num_v() > kMaxSurfaceNetPoints * 9 / 10);
}

TEST_CASE("construction arc: exact circle in its plane, elevated and split, errors located",
          "[geometry][constructions][io]") {
  const GeometryModel m =
      parse_geometry(parse_json_text(
                         R"({"a": {"type": "construction", "shape": "arc", "center": [1, 2, 3],
      "x_axis": [0, 1, 0], "normal": [1, 0, 0], "radius": 2, "start_deg": 30, "end_deg": 150,
      "degree": 3, "elements": 5}})",
                         "g.json"),
                     "g.json", JsonPointer("/geometry"));
  const auto& c = std::get<NurbsCurve>(m.entities.at(0).second);
  CHECK(c.degree() == 3);
  const Vector3d center(1, 2, 3), x(0, 1, 0), y(0, 0, 1);  // y = normal x x_axis
  double worst = 0.0;
  for (int k = 0; k <= 100; ++k) {
    const Vector3d p = c.point(k / 100.0) - center;
    worst = std::max({worst, std::abs(p.norm() - 2.0), std::abs(p.x())});
  }
  CHECK(worst < 1e-12);  // on the circle, in the plane x = 1
  const double deg = std::numbers::pi / 180.0;
  CHECK((c.point(0.0) - center - 2.0 * (std::cos(30 * deg) * x + std::sin(30 * deg) * y)).norm() <
        1e-12);
  CHECK((c.point(1.0) - center - 2.0 * (std::cos(150 * deg) * x + std::sin(150 * deg) * y)).norm() <
        1e-12);
  auto e = iga::test::geometry_error(
      R"({"a": {"type": "construction", "shape": "arc", "radius": 1, "start_deg": 10,
      "end_deg": 5}})");
  CHECK(e.pointer() == "/geometry/a/end_deg");
  e = iga::test::geometry_error(
      R"({"a": {"type": "construction", "shape": "arc", "radius": 1, "end_deg": 90,
      "normal": [1, 0, 0]}})");
  CHECK(e.pointer() == "/geometry/a/normal");
}

TEST_CASE("construction sphere zone: exact, its corners at the given latitudes and longitudes",
          "[geometry][constructions][io]") {
  const GeometryModel m =
      parse_geometry(parse_json_text(
                         R"({"s": {"type": "construction", "shape": "sphere", "center": [1, 0, 0],
      "radius": 10, "lat_deg": [0, 72], "lon_deg": [30, 120]}})",
                         "g.json"),
                     "g.json", JsonPointer("/geometry"));
  const auto& s = std::get<NurbsSurface>(m.entities.at(0).second);
  const Vector3d c(1, 0, 0);
  const double deg = std::numbers::pi / 180.0;
  const auto on = [&](double lat, double lon) -> Vector3d {
    return c + 10.0 * Vector3d(std::cos(lat * deg) * std::cos(lon * deg),
                               std::cos(lat * deg) * std::sin(lon * deg), std::sin(lat * deg));
  };
  const Domain2 d = s.domain();
  CHECK((s.point(d.u.lo, d.v.lo) - on(0, 30)).norm() < 1e-12);
  CHECK((s.point(d.u.hi, d.v.lo) - on(0, 120)).norm() < 1e-12);
  CHECK((s.point(d.u.lo, d.v.hi) - on(72, 30)).norm() < 1e-12);
  CHECK((s.point(d.u.hi, d.v.hi) - on(72, 120)).norm() < 1e-12);
  double worst = 0.0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const double u = d.u.lo + (d.u.hi - d.u.lo) * i / 20.0,
                   v = d.v.lo + (d.v.hi - d.v.lo) * j / 20.0;
      const SurfaceDerivs sd = s.derivs(u, v, 1);
      worst = std::max(worst, std::abs((sd.S - c).norm() - 10.0));
      if (i > 0 && j > 0 && j < 20)  // outward normal
        CHECK(sd.Su.cross(sd.Sv).dot(sd.S - c) > 0.0);
    }
  CHECK(worst < 1e-12);
  auto e = iga::test::geometry_error(
      R"({"s": {"type": "construction", "shape": "sphere", "center": [0, 0, 0], "radius": 1,
      "lat_deg": [10, 95]}})");
  CHECK(e.pointer() == "/geometry/s/lat_deg");
  e = iga::test::geometry_error(
      R"({"s": {"type": "construction", "shape": "sphere", "center": [0, 0, 0], "radius": 1,
      "axis": [0, 0, 1], "ref_dir": [0, 0, 2]}})");
  CHECK(e.pointer() == "/geometry/s/ref_dir");
}

}  // namespace test_constructions
