// Tests of the analytic surfaces: exact derivatives against finite differences, normal
// orientation against the paper's closed-form penetrations ([KS15] B.4, B.10, B.16, B.23, (22)),
// placement frames, closedness, equality and parameter validation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include <Eigen/Geometry>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/differential_geometry.hpp"
#include "geometry/knot_vector.hpp"
#include "tests/support/geometry_checks.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_analytic_surfaces {

using namespace iga;
using namespace iga::test;

namespace {

constexpr double kPi = std::numbers::pi;
/// A random placement with a non-unit axis (the constructor normalizes it).
Placement random_placement(std::mt19937& g) {
  std::uniform_real_distribution<double> c(-3.0, 3.0), len(0.5, 2.0);
  Placement p;
  p.center = Vector3d(c(g), c(g), c(g));
  p.axis = len(g) * random_unit(g);
  p.ref_dir = random_unit(g);
  return p;
}
/// Unit normal as the contact code sees it: surface_frame with the surface's normal_sign.
Vector3d unit_normal(const Surface& s, double u, double v) {
  return surface_frame(s.derivs(u, v, 1), s.normal_sign()).n;
}

/// Local coordinates of x in the placement frame.
Vector3d local(const Placement& pl, const Vector3d& x) {
  return pl.frame().transpose() * (x - pl.center);
}

struct Sampler {
  double u0, u1, v0, v1;
  std::pair<double, double> operator()(std::mt19937& g) const {
    std::uniform_real_distribution<double> a(u0, u1), b(v0, v1);
    const double u = a(g);
    return {u, b(g)};
  }
};

}  // namespace

TEST_CASE("Placement::frame: orthonormal, right-handed, e_z along the axis, e_x toward ref_dir",
          "[geometry][analytic]") {
  std::mt19937 g(11);
  for (int k = 0; k < 200; ++k) {
    const Placement p = random_placement(g);
    const Matrix3d E = p.frame();
    CHECK((E.transpose() * E - Matrix3d::Identity()).norm() <= 1e-14);
    CHECK(E.determinant() == Approx(1.0).epsilon(1e-14));
    CHECK((E.col(2) - p.axis.normalized()).norm() <= 1e-15);
    // e_x lies in the plane of (axis, ref_dir), on the side of ref_dir.
    CHECK(std::abs(E.col(0).dot(p.axis.cross(p.ref_dir).normalized())) <= 1e-14);
    CHECK(E.col(0).dot(p.ref_dir) > 0.0);
  }
}

TEST_CASE("Placement::frame: zero or non-finite axis throws, a parallel ref_dir falls back",
          "[geometry][analytic][errors]") {
  Placement p;
  p.axis = Vector3d::Zero();
  REQUIRE_THROWS_AS(p.frame(), GeometryError);
  p.axis = Vector3d(0.0, std::numeric_limits<double>::quiet_NaN(), 1.0);
  REQUIRE_THROWS_AS(p.frame(), GeometryError);

  // ref_dir parallel (or antiparallel, or zero): any perpendicular e_x, still a valid frame.
  for (const Vector3d& axis : {Vector3d(1, 0, 0), Vector3d(0, -2, 0), Vector3d(1, 1, 1)}) {
    for (const Vector3d& ref : {axis, Vector3d(-3 * axis), Vector3d(Vector3d::Zero())}) {
      Placement q;
      q.axis = axis;
      q.ref_dir = ref;
      Matrix3d E;
      REQUIRE_NOTHROW(E = q.frame());
      CHECK((E.transpose() * E - Matrix3d::Identity()).norm() <= 1e-14);
      CHECK(E.determinant() == Approx(1.0).epsilon(1e-14));
      CHECK((E.col(2) - axis.normalized()).norm() <= 1e-15);
    }
  }
  // The default ref_dir (e_x) with the axis e_x works.
  Placement r;
  r.axis = Vector3d::UnitX();
  REQUIRE_NOTHROW(Cylinder(r, 1.0));
}

TEST_CASE("analytic surfaces: first and second derivatives agree with finite differences",
          "[geometry][analytic]") {
  std::mt19937 g(2024);
  const double tp = 2 * kPi;
  struct Case {
    std::string name;
    std::function<std::unique_ptr<Surface>(const Placement&)> make;
    double L;
    Sampler at;
  };
  const std::vector<Case> cases = {
      {"plane", [](const Placement& p) { return std::make_unique<Plane>(p); }, 1.0, {-3, 3, -3, 3}},
      {"sphere",
       [](const Placement& p) { return std::make_unique<Sphere>(p, 1.7); },
       1.7,
       {0, tp, -1.4, 1.4}},
      {"cylinder",
       [](const Placement& p) { return std::make_unique<Cylinder>(p, 0.8); },
       0.8,
       {0, tp, -2, 2}},
      {"torus",
       [](const Placement& p) { return std::make_unique<Torus>(p, 2.0, 0.7); },
       2.0,
       {0, tp, 0, tp}},
      {"cone",
       [](const Placement& p) { return std::make_unique<Cone>(p, 0.6); },
       1.0,
       {0, tp, 0.2, 3}},
      {"hyperboloid",
       [](const Placement& p) { return std::make_unique<Hyperboloid>(p, 0.35); },
       1.0,
       {-3, 3, -3, 3}},
      {"revolution",
       [](const Placement& p) {
         return std::make_unique<Revolution>(p, std::vector<double>{0.3, -0.2, 0.5, 0.1});
       },
       1.0,
       {0.1, 2, 0, tp}},
  };
  for (const Case& c : cases) {
    double worst = 0.0;
    for (int k = 0; k < 200; ++k) {
      const std::unique_ptr<Surface> s = c.make(random_placement(g));
      const auto [u, v] = c.at(g);
      worst = std::max(worst, surface_fd_error(*s, u, v, c.L));
    }
    INFO(c.name << ": worst relative finite-difference error " << worst);
    CHECK(worst <= 1e-6);
  }
}

TEST_CASE("analytic surfaces: derivs(order) fills exactly the requested orders",
          "[geometry][analytic]") {
  const Torus t(Placement{}, 2.0, 0.5);
  const SurfaceDerivs d0 = t.derivs(0.3, 0.4, 0);
  CHECK(d0.order == 0);
  CHECK(d0.Su.isZero(0.0));
  CHECK(d0.Sv.isZero(0.0));
  const SurfaceDerivs d1 = t.derivs(0.3, 0.4, 1);
  CHECK(d1.order == 1);
  CHECK(d1.Su.norm() > 0.0);
  CHECK(d1.Suu.isZero(0.0));
  CHECK(d1.Svv.isZero(0.0));
  const SurfaceDerivs d2 = t.derivs(0.3, 0.4, 2);
  CHECK(d2.order == 2);
  // The same point whatever the order asked for, to round-off (the compiler may fuse the
  // multiply-adds of the two code paths differently: never bit for bit).
  CHECK((d2.S - d0.S).norm() <= 1e-15 * std::max(1.0, d0.S.norm()));
  CHECK(d2.Suu.norm() > 0.0);
}

TEST_CASE(
    "analytic surfaces: points satisfy the implicit equations and outward normals give "
    "the paper's closed-form penetrations",
    "[geometry][analytic]") {
  std::mt19937 g(7);
  std::uniform_real_distribution<double> ang(0.0, 2 * kPi), t_off(-0.3, 0.3);
  for (int k = 0; k < 500; ++k) {
    const Placement pl = random_placement(g);
    const Vector3d ez = pl.axis.normalized();
    const double u = ang(g), t = t_off(g);
    {  // (B.4) sphere: p = |r - c| - R
      const Sphere s(pl, 1.3);
      const double v = 0.95 * (ang(g) / kPi - 1.0) * 0.5 * kPi;
      const Vector3d x = s.point(u, v);
      CHECK(std::abs((x - pl.center).norm() - 1.3) <= 1e-14 * 4);
      const Vector3d r = x + t * unit_normal(s, u, v);
      CHECK((r - pl.center).norm() - 1.3 == Approx(t).margin(1e-13));
    }
    {  // (B.10) cylinder: p = |d| - R, d the part of r - c normal to the axis
      const Cylinder s(pl, 0.8);
      const double v = t_off(g) * 10;
      const Vector3d r = s.point(u, v) + t * unit_normal(s, u, v);
      const Vector3d rc = r - pl.center;
      const Vector3d dvec = rc - rc.dot(ez) * ez;
      CHECK(dvec.norm() - 0.8 == Approx(t).margin(1e-13));
      CHECK(rc.dot(ez) == Approx(v).margin(1e-13));
    }
    {  // (B.16) torus: p = sqrt(x^2 + y^2 + z^2 + R^2 - 2 R s) - r in local coordinates
      const double R = 2.0, rt = 0.7;
      const Torus s(pl, R, rt);
      const double v = ang(g);
      const Vector3d x = local(pl, s.point(u, v) + t * unit_normal(s, u, v));
      const double sx = std::hypot(x.x(), x.y());
      const double p = std::sqrt(x.squaredNorm() + R * R - 2 * R * sx) - rt;
      CHECK(p == Approx(t).margin(1e-13));
    }
    {  // (B.23) cone: p = s sin(alpha) - z cos(alpha) in local coordinates
      const double alpha = 0.6;
      const Cone s(pl, alpha);
      const double v = 0.5 + 3 * ang(g) / (2 * kPi);
      const Vector3d x0 = local(pl, s.point(u, v));
      CHECK(std::hypot(x0.x(), x0.y()) == Approx(v).epsilon(1e-14));
      const Vector3d x = local(pl, s.point(u, v) + t * unit_normal(s, u, v));
      const double p = std::hypot(x.x(), x.y()) * std::sin(alpha) - x.z() * std::cos(alpha);
      CHECK(p == Approx(t).margin(1e-13));
    }
    {  // (11), (22) hyperboloid: z = a x y, n = (-a y, -a x, 1)/norm in local coordinates
      const double a = 0.35, xu = 3 * t_off(g), yv = 3 * t_off(g);
      const Hyperboloid s(pl, a);
      const Vector3d x = local(pl, s.point(xu, yv));
      CHECK(x.x() == Approx(xu).margin(1e-14));
      CHECK(x.y() == Approx(yv).margin(1e-14));
      CHECK(x.z() == Approx(a * xu * yv).margin(1e-14));
      const Vector3d n_paper = Vector3d(-a * yv, -a * xu, 1.0).normalized();
      CHECK((pl.frame().transpose() * unit_normal(s, xu, yv) - n_paper).norm() <= 1e-14);
    }
    {  // (A.1) revolution: local point (r cos phi, r sin phi, f(r)), normal (e_z - f' e_r)/norm
      const Revolution s(pl, {0.3, -0.2, 0.5});
      const double rr = 0.1 + 2 * ang(g) / (2 * kPi);
      const Vector3d x = local(pl, s.point(rr, u));
      CHECK((x - Vector3d(rr * std::cos(u), rr * std::sin(u), 0.3 - 0.2 * rr + 0.5 * rr * rr))
                .norm() <= 1e-13);
      const double df = -0.2 + rr;
      const Vector3d er(std::cos(u), std::sin(u), 0.0);
      const Vector3d n_expected = (Vector3d::UnitZ() - df * er).normalized();
      CHECK((pl.frame().transpose() * unit_normal(s, rr, u) - n_expected).norm() <= 1e-14);
    }
    {  // plane: n = e_z
      const Plane s(pl);
      CHECK((unit_normal(s, u, t) - ez).norm() <= 2e-15);
      CHECK(local(pl, s.point(u, t)).z() == Approx(0.0).margin(1e-14));
    }
  }
}

TEST_CASE(
    "analytic surfaces: normal_sign -1 (\"inward\") flips the normal, (B.4) and (B.16) "
    "inward penetrations",
    "[geometry][analytic]") {
  std::mt19937 g(8);
  std::uniform_real_distribution<double> ang(0.0, 2 * kPi), t_off(-0.3, 0.3);
  for (int k = 0; k < 200; ++k) {
    const Placement pl = random_placement(g);
    const double u = ang(g), t = t_off(g);
    Sphere s(pl, 1.3);
    const double v = 0.4 * (ang(g) - kPi) / kPi * kPi;
    const Vector3d n_out = unit_normal(s, u, v);
    s.set_normal_sign(-1);
    REQUIRE(s.normal_sign() == -1);
    const Vector3d n_in = unit_normal(s, u, v);
    CHECK((n_in + n_out).norm() <= 1e-15);
    const Vector3d r = s.point(u, v) + t * n_in;
    CHECK(1.3 - (r - pl.center).norm() == Approx(t).margin(1e-13));  // (B.4) inward

    Torus tor(pl, 2.0, 0.5);
    tor.set_normal_sign(-1);
    const Vector3d x = local(pl, tor.point(u, v) + t * unit_normal(tor, u, v));
    const double sx = std::hypot(x.x(), x.y());
    CHECK(0.5 - std::sqrt(x.squaredNorm() + 4.0 - 4.0 * sx) == Approx(t).margin(1e-13));
  }
}

TEST_CASE(
    "analytic surfaces: closed_u/closed_v exactly when the angle spans 2 pi, and then "
    "the surface is periodic",
    "[geometry][analytic]") {
  const Placement pl;
  const double tp = 2 * kPi;
  CHECK(Sphere(pl, 1.0).closed_u());
  CHECK_FALSE(Sphere(pl, 1.0).closed_v());
  CHECK_FALSE(Sphere(pl, 1.0, {{0.0, kPi}, {-1.0, 1.0}}).closed_u());
  CHECK(Sphere(pl, 1.0, {{-kPi, kPi}, {-1.0, 1.0}}).closed_u());
  CHECK(Cylinder(pl, 1.0).closed_u());
  CHECK_FALSE(Cylinder(pl, 1.0).closed_v());
  CHECK_FALSE(Cylinder(pl, 1.0, {{0.0, 1.5 * kPi}, {0.0, 1.0}}).closed_u());
  CHECK(Torus(pl, 2.0, 1.0).closed_u());
  CHECK(Torus(pl, 2.0, 1.0).closed_v());
  CHECK_FALSE(Torus(pl, 2.0, 1.0, {{0.0, tp}, {0.0, kPi}}).closed_v());
  CHECK(Cone(pl, 0.5).closed_u());
  CHECK_FALSE(Cone(pl, 0.5).closed_v());
  CHECK(Revolution(pl, {1.0}).closed_v());
  CHECK_FALSE(Revolution(pl, {1.0}).closed_u());
  CHECK_FALSE(Plane(pl).closed_u());
  CHECK_FALSE(Hyperboloid(pl, 1.0).closed_v());

  // Where a direction is reported closed, rho(lo, .) == rho(hi, .).
  const Torus t(pl, 2.0, 1.0, {{0.3, 0.3 + tp}, {-1.0, -1.0 + tp}});
  REQUIRE(t.closed_u());
  REQUIRE(t.closed_v());
  for (double s = 0.0; s < tp; s += 0.1) {
    CHECK((t.point(0.3, s) - t.point(0.3 + tp, s)).norm() <= 1e-14);
    CHECK((t.point(s, -1.0) - t.point(s, -1.0 + tp)).norm() <= 1e-14);
  }
}

TEST_CASE("analytic surfaces: operator== compares parameters, placement, domain and normal sign",
          "[geometry][analytic]") {
  Placement pl;
  pl.center = Vector3d(1, 2, 3);
  pl.axis = Vector3d(0, 0, 2);  // normalized on construction
  const Torus a(pl, 2.0, 0.5);
  Torus b = a;
  CHECK(a == b);
  CHECK(a.placement().axis == Vector3d::UnitZ());
  // Constructing again from the stored placement reproduces the surface exactly.
  CHECK(Torus(a.placement(), 2.0, 0.5) == a);
  CHECK_FALSE(a == Torus(pl, 2.0, 0.6));
  CHECK_FALSE(a == Torus(pl, 2.5, 0.5));
  CHECK_FALSE(a == Torus(pl, 2.0, 0.5, {{0.0, 1.0}, {0.0, 1.0}}));
  b.set_normal_sign(-1);
  CHECK_FALSE(a == b);
  Placement moved = pl;
  moved.center.x() += 1e-9;
  CHECK_FALSE(a == Torus(moved, 2.0, 0.5));

  CHECK(Revolution(pl, {1.0, 2.0}) == Revolution(pl, {1.0, 2.0}));
  CHECK_FALSE(Revolution(pl, {1.0, 2.0}) == Revolution(pl, {1.0, 2.5}));
  CHECK_FALSE(Cone(pl, 0.5) == Cone(pl, 0.6));
  CHECK_FALSE(Hyperboloid(pl, 0.5) == Hyperboloid(pl, -0.5));
  CHECK_FALSE(Sphere(pl, 1.0) == Sphere(pl, 1.0, {{0.0, kPi}, {-1.0, 1.0}}));
  CHECK_FALSE(Cylinder(pl, 1.0) == Cylinder(Placement{}, 1.0));
  CHECK(Plane(pl) == Plane(pl));
}

TEST_CASE("Revolution::profile: f, f', f'' of the polynomial (A.1)", "[geometry][analytic]") {
  const Revolution s(Placement{}, {0.5, -1.0, 0.25, 0.125});
  for (double r = 0.0; r <= 3.0; r += 0.25) {
    double f = 0, df = 0, ddf = 0;
    s.profile(r, f, df, ddf);
    CHECK(f == Approx(0.5 - r + 0.25 * r * r + 0.125 * r * r * r).margin(1e-14));
    CHECK(df == Approx(-1.0 + 0.5 * r + 0.375 * r * r).margin(1e-14));
    CHECK(ddf == Approx(0.5 + 0.75 * r).margin(1e-14));
  }
  double f = 1, df = 1, ddf = 1;
  Revolution(Placement{}, {}).profile(2.0, f, df, ddf);  // no coefficients: f = 0
  CHECK(f == 0.0);
  CHECK(df == 0.0);
  CHECK(ddf == 0.0);
}

TEST_CASE("analytic surfaces: constructors reject invalid parameters, naming the value",
          "[geometry][analytic][errors]") {
  using Catch::Matchers::Contains;
  const Placement pl;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  REQUIRE_THROWS_AS(Sphere(pl, 0.0), GeometryError);
  REQUIRE_THROWS_WITH(Sphere(pl, -2.5), Contains("radius") && Contains("-2.5"));
  REQUIRE_THROWS_AS(Sphere(pl, nan), GeometryError);
  REQUIRE_THROWS_WITH(Cylinder(pl, -1.0), Contains("radius") && Contains("-1"));
  REQUIRE_THROWS_WITH(Torus(pl, 1.0, -1.5), Contains("minor") && Contains("-1.5"));
  REQUIRE_THROWS_AS(Torus(pl, 1.0, 0.0), GeometryError);
  REQUIRE_THROWS_AS(Torus(pl, -1.0, 0.5), GeometryError);
  REQUIRE_THROWS_WITH(Cone(pl, 0.0), Contains("alpha") && Contains("0"));
  REQUIRE_THROWS_AS(Cone(pl, -0.3), GeometryError);
  REQUIRE_THROWS_AS(Cone(pl, 0.5 * kPi), GeometryError);
  REQUIRE_THROWS_WITH(Cone(pl, 2.0), Contains("2"));
  REQUIRE_THROWS_AS(Hyperboloid(pl, nan), GeometryError);
  REQUIRE_THROWS_AS(Revolution(pl, {1.0, nan}), GeometryError);
  // Domains need lo < hi.
  REQUIRE_THROWS_WITH(Sphere(pl, 1.0, {{1.0, 0.5}, {0.0, 1.0}}),
                      Contains("domain u") && Contains("0.5"));
  REQUIRE_THROWS_WITH(Plane(pl, {{0.0, 1.0}, {2.0, 2.0}}), Contains("domain v"));
  REQUIRE_THROWS_AS(Cylinder(pl, 1.0, {{0.0, 1.0}, {nan, 1.0}}), GeometryError);
  // A zero axis is reported at construction.
  Placement zero;
  zero.axis = Vector3d::Zero();
  REQUIRE_THROWS_WITH(Plane(zero), Contains("axis"));
  // Valid borderline values are accepted.
  REQUIRE_NOTHROW(Torus(pl, 1.0, 0.999));
  REQUIRE_NOTHROW(Torus(pl, 1.0, 1.0));  // horn torus (issue 34)
  REQUIRE_NOTHROW(Torus(pl, 1.0, 1.5));  // spindle torus
  REQUIRE_NOTHROW(Cone(pl, 1e-3));
  REQUIRE_NOTHROW(Hyperboloid(pl, 0.0));
}

TEST_CASE("analytic surfaces: clone() keeps the type and the shape, visit_analytic the type",
          "[geometry][analytic]") {
  const Placement pl{Vector3d(0.1, -0.2, 0.3), Vector3d(0.2, 0.1, 1.0), Vector3d(1, 0, 0)};
  std::vector<std::unique_ptr<AnalyticSurface>> all;
  all.push_back(std::make_unique<Plane>(pl));
  all.push_back(std::make_unique<Sphere>(pl, 1.7));
  all.push_back(std::make_unique<Cylinder>(pl, 0.8));
  all.push_back(std::make_unique<Torus>(pl, 2.0, 0.7));
  all.push_back(std::make_unique<Cone>(pl, 0.6));
  all.push_back(std::make_unique<Hyperboloid>(pl, 0.4));
  all.push_back(std::make_unique<Revolution>(pl, std::vector<double>{0.5, 0.0, 0.3}));
  for (const auto& s : all) {
    INFO(s->type_name());
    const std::unique_ptr<AnalyticSurface> c = s->clone();
    CHECK(c->type_name() == s->type_name());
    CHECK(c.get() != s.get());
    const SurfaceDerivs a = s->derivs(0.3, 0.4, 2), b = c->derivs(0.3, 0.4, 2);
    CHECK(a.S == b.S);
    CHECK(a.Suv == b.Suv);
    // The visitor sees the concrete type: its name is the surface's own.
    std::string seen;
    visit_analytic(*c, Overloaded{
                           [&](const Plane&) { seen = "plane"; },
                           [&](const Sphere&) { seen = "sphere"; },
                           [&](const Cylinder&) { seen = "cylinder"; },
                           [&](const Torus&) { seen = "torus"; },
                           [&](const Cone&) { seen = "cone"; },
                           [&](const Hyperboloid&) { seen = "hyperboloid"; },
                           [&](const Revolution&) { seen = "revolution"; },
                       });
    CHECK(seen == s->type_name());
  }
}

}  // namespace test_analytic_surfaces
