// Tests of the projections onto analytic rigid surfaces (contact/analytic_projection.hpp):
// orthogonality and global optimality of the closest point against the paper's closed-form
// penetrations ([KS15] B.4, B.10, B.16, B.23) and a dense parameter grid, the paper's Newton for
// the hyperboloid (16)-(22), normal orientation, bounded domains (edges, vertices, the cone's
// apex), and ray projections (8)-(9), (A.2): hits on the surface, the nearest hit, misses and
// tangent rays.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact/analytic_projection.hpp"
#include "contact/closest_point.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/differential_geometry.hpp"
#include "tests/support/geometry_checks.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_analytic_projection {

using namespace iga;
using namespace iga::test;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Type { plane, sphere, cylinder, torus, cone, hyperboloid, revolution };
constexpr Type kAllTypes[] = {Type::plane, Type::sphere,      Type::cylinder,  Type::torus,
                              Type::cone,  Type::hyperboloid, Type::revolution};

const char* name(Type t) {
  switch (t) {
    case Type::plane:
      return "plane";
    case Type::sphere:
      return "sphere";
    case Type::cylinder:
      return "cylinder";
    case Type::torus:
      return "torus";
    case Type::cone:
      return "cone";
    case Type::hyperboloid:
      return "hyperboloid";
    case Type::revolution:
      return "revolution";
  }
  return "?";
}

/// A random placement with a non-trivial centre and axis (non-unit: the constructor normalizes).
Placement random_placement(std::mt19937& g) {
  Placement p;
  p.center = random_vector(g, 3.0);
  p.axis = uniform(g, 0.5, 2.0) * random_unit(g);
  p.ref_dir = random_unit(g);
  return p;
}

Vector3d local(const AnalyticSurface& s, const Vector3d& x) {
  return s.placement().frame().transpose() * (x - s.placement().center);
}

/// A random surface of the type with the default (full) domain.
std::unique_ptr<AnalyticSurface> random_surface(Type t, std::mt19937& g) {
  const Placement pl = random_placement(g);
  switch (t) {
    case Type::plane:
      return std::make_unique<Plane>(pl);
    case Type::sphere:
      return std::make_unique<Sphere>(pl, uniform(g, 0.5, 3.0));
    case Type::cylinder:
      return std::make_unique<Cylinder>(pl, uniform(g, 0.5, 3.0));
    case Type::torus: {
      const double R = uniform(g, 2.0, 4.0);
      return std::make_unique<Torus>(pl, R, uniform(g, 0.15, 0.45) * R);
    }
    case Type::cone:
      return std::make_unique<Cone>(pl, uniform(g, 0.2, 1.3));
    case Type::hyperboloid: {
      const double a = uniform(g, 0.05, 0.5);
      return std::make_unique<Hyperboloid>(pl, uniform(g, 0.0, 1.0) < 0.5 ? -a : a);
    }
    case Type::revolution: {
      // A cup (paraboloid) or a cup with an inflection at r = 2 (f'' = 0.6 - 0.3 r).
      if (uniform(g, 0.0, 1.0) < 0.5)
        return std::make_unique<Revolution>(
            pl, std::vector<double>{uniform(g, -1.0, 1.0), 0.0, uniform(g, 0.1, 0.3)});
      return std::make_unique<Revolution>(
          pl, std::vector<double>{uniform(g, -1.0, 1.0), 0.0, 0.3, -0.05});
    }
  }
  return nullptr;
}

/// Region of the parameters from which feet are drawn (inside the domain).
Vector2d random_uv(Type t, std::mt19937& g) {
  switch (t) {
    case Type::plane:
      return Vector2d(uniform(g, -5, 5), uniform(g, -5, 5));
    case Type::sphere:
      return Vector2d(uniform(g, 0, 2 * kPi), uniform(g, -1.45, 1.45));
    case Type::cylinder:
      return Vector2d(uniform(g, 0, 2 * kPi), uniform(g, -5, 5));
    case Type::torus:
      return Vector2d(uniform(g, 0, 2 * kPi), uniform(g, 0, 2 * kPi));
    case Type::cone:
      return Vector2d(uniform(g, 0, 2 * kPi), uniform(g, 0.2, 5));
    case Type::hyperboloid:
      return Vector2d(uniform(g, -3, 3), uniform(g, -3, 3));
    case Type::revolution:
      return Vector2d(uniform(g, 0.1, 2.8), uniform(g, 0, 2 * kPi));
  }
  return Vector2d::Zero();
}

/// Radius of the neighbourhood in which x = rho + p n has the foot rho: the smallest principal
/// curvature radius, capped by the global reach where that is smaller (torus: r <= R - r).
double proximity_radius(Type t, const AnalyticSurface& s, const Vector2d& uv) {
  const SurfaceFrame f = surface_frame(s.derivs(uv[0], uv[1], 2), s.normal_sign());
  const double k = std::max({std::abs(f.k1), std::abs(f.k2), 1e-12});
  const double local_radius = 1.0 / k;
  switch (t) {
    case Type::hyperboloid:
      return std::min(0.5 * local_radius, 5.0);
    // The inflected profile turns down beyond r = 4: keep x near the sampled part (r <= 2.8).
    case Type::revolution:
      return std::min(0.5 * local_radius, 1.0);
    default:
      return std::min(local_radius, 5.0);
  }
}

/// Signed level function whose zero set is the surface (a distance to first order).
class Level {
 public:
  explicit Level(const AnalyticSurface& s)
      : s_(s), Et_(s.placement().frame().transpose()), c_(s.placement().center) {}
  double operator()(const Vector3d& x) const {
    const Vector3d w = Et_ * (x - c_);
    const double rho = std::hypot(w.x(), w.y());
    if (dynamic_cast<const Plane*>(&s_)) return w.z();
    if (const auto* p = dynamic_cast<const Sphere*>(&s_)) return w.norm() - p->radius();
    if (const auto* p = dynamic_cast<const Cylinder*>(&s_)) return rho - p->radius();
    if (const auto* p = dynamic_cast<const Torus*>(&s_))
      return std::hypot(rho - p->major_radius(), w.z()) - p->minor_radius();
    if (const auto* p = dynamic_cast<const Cone*>(&s_))
      return rho * std::sin(p->alpha()) - w.z() * std::cos(p->alpha());  // (B.23)
    if (const auto* p = dynamic_cast<const Hyperboloid*>(&s_)) {
      const double a = p->a();
      return (w.z() - a * w.x() * w.y()) / std::sqrt(1 + a * a * (w.x() * w.x() + w.y() * w.y()));
    }
    if (const auto* p = dynamic_cast<const Revolution*>(&s_)) {
      double f, df, ddf;
      p->profile(rho, f, df, ddf);
      return (w.z() - f) / std::sqrt(1 + df * df);
    }
    return kInf;
  }

 private:
  const AnalyticSurface& s_;
  Matrix3d Et_;
  Vector3d c_;
};

double level(const AnalyticSurface& s, const Vector3d& x) {
  return Level(s)(x);
}

/// Oriented unit normal at a regular point.
Vector3d unit_normal(const Surface& s, const Vector2d& uv) {
  return surface_frame(s.derivs(uv[0], uv[1], 1), s.normal_sign()).n;
}

/// Smallest |x - rho| over an n x n grid of the parameter window (domain clipped to +-w).
double grid_min_distance(const Surface& s, const Vector3d& x, double w, int n,
                         Vector2d* best_uv = nullptr) {
  const Domain2 d = s.domain();
  const double u0 = std::max(d.u.lo, -w), u1 = std::min(d.u.hi, w);
  const double v0 = std::max(d.v.lo, -w), v1 = std::min(d.v.hi, w);
  double best = kInf;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = u0 + (u1 - u0) * i / n, v = v0 + (v1 - v0) * j / n;
      const double dist = (s.point(u, v) - x).norm();
      if (dist < best) {
        best = dist;
        if (best_uv) *best_uv = Vector2d(u, v);
      }
    }
  return best;
}

}  // namespace

TEST_CASE(
    "closest_point_analytic: foot orthogonal, on the surface, distance = closed-form p, "
    "for 10,000 points per type in the proximity domain",
    "[contact][analytic]") {
  std::mt19937 g(2024);
  for (const Type t : kAllTypes) {
    INFO("type " << name(t));
    int checked = 0;
    double worst_orth = 0.0, worst_level = 0.0, worst_p = 0.0, worst_foot = 0.0;
    double worst_res = 0.0;
    for (int surf = 0; surf < 10; ++surf) {
      const std::unique_ptr<AnalyticSurface> s = random_surface(t, g);
      if (uniform(g, 0, 1) < 0.5) s->set_normal_sign(-1);
      for (int k = 0; k < 1000; ++k) {
        const Vector2d uv = random_uv(t, g);
        const Vector3d rho = s->point(uv[0], uv[1]);
        const Vector3d n = unit_normal(*s, uv);
        const double p = uniform(g, -0.9, 0.9) * proximity_radius(t, *s, uv);
        const Vector3d x = rho + p * n;
        const ProjectionResult r = closest_point_analytic(*s, x);
        REQUIRE(r.status == ProjectionStatus::interior);
        const double scale = 1.0 + (x - s->placement().center).norm();
        // (a) x - rho parallel to n, rho on the surface, |n| = 1.
        worst_orth = std::max(worst_orth, (x - r.point).cross(r.normal).norm() / scale);
        worst_level = std::max(worst_level, std::abs(level(*s, r.point)) / scale);
        CHECK(r.normal.norm() == Approx(1.0).epsilon(1e-14));
        // (b) the global minimum: the distance is the paper's p, the foot the generating point.
        worst_p = std::max(worst_p, std::abs(r.distance - p));
        worst_foot = std::max(worst_foot, (r.point - rho).norm() / scale);
        CHECK((r.normal - n).norm() <= 1e-9);
        if (std::abs(p) > 1e-2) worst_res = std::max(worst_res, r.residual);
        ++checked;
      }
    }
    CHECK(checked == 10000);
    CHECK(worst_orth <= 1e-12);
    CHECK(worst_level <= 1e-12);
    CHECK(worst_p <= 1e-10);
    CHECK(worst_foot <= 1e-10);
    CHECK(worst_res <= 1e-12);
  }
}

TEST_CASE(
    "closest_point_analytic: never farther than a dense parameter grid, and a local "
    "minimum (closest_point_local does not improve it), for arbitrary points",
    "[contact][analytic]") {
  std::mt19937 g(77);
  for (const Type t : kAllTypes) {
    INFO("type " << name(t));
    for (int surf = 0; surf < 4; ++surf) {
      const std::unique_ptr<AnalyticSurface> s = random_surface(t, g);
      for (int k = 0; k < 10; ++k) {
        const Vector2d uv = random_uv(t, g);
        const Vector3d x = s->point(uv[0], uv[1]) + random_vector(g, 2.0);
        const ProjectionResult r = closest_point_analytic(*s, x);
        REQUIRE(found(r.status));
        CHECK(std::abs(r.distance) == Approx((x - r.point).norm()).epsilon(1e-12).margin(1e-14));
        const double grid = grid_min_distance(*s, x, 10.0, 300);
        CHECK(std::abs(r.distance) <= grid + 1e-12);
        const ProjectionResult polish = closest_point_local(*s, x, r.uv);
        CHECK(std::abs(polish.distance) >= std::abs(r.distance) - 1e-12);
      }
    }
  }
}

TEST_CASE(
    "closest_point_analytic: hyperboloid points far on the concave side (beyond the reach "
    "1/|a|, several critical points) still get the global minimum",
    "[contact][analytic]") {
  std::mt19937 g(55);
  int ks_failed_or_local = 0;
  for (int k = 0; k < 200; ++k) {
    Placement pl = random_placement(g);
    const double a = uniform(g, 0.5, 2.0) * (k % 2 ? 1.0 : -1.0);
    const Hyperboloid s(pl, a);
    const Vector3d x = pl.center + random_vector(g, 4.0);
    const ProjectionResult r = closest_point_analytic(s, x);
    REQUIRE(r.status == ProjectionStatus::interior);
    Vector2d uv_best;
    const double grid = grid_min_distance(s, x, 6.0, 200, &uv_best);
    const ProjectionResult polish = closest_point_local(s, x, uv_best);
    CHECK(std::abs(r.distance) <= std::min(grid, std::abs(polish.distance)) + 1e-12);
    CHECK(r.residual <= 1e-10);
    const ProjectionResult ks = hyperboloid_closest_point_ks(a, local(s, x));
    if (ks.status != ProjectionStatus::interior ||
        std::abs(ks.distance) > std::abs(r.distance) + 1e-9)
      ++ks_failed_or_local;
  }
  CHECK(ks_failed_or_local > 0);  // the set does exercise the fallback
}

TEST_CASE(
    "hyperboloid_closest_point_ks: the paper's Newton (16)-(22) from (20) agrees with "
    "closest_point_analytic, with a round-off orthogonality residual",
    "[contact][analytic]") {
  std::mt19937 g(5);
  double worst_uv = 0.0, worst_d = 0.0, worst_res = 0.0;
  int max_iter = 0;
  for (int surf = 0; surf < 10; ++surf) {
    const std::unique_ptr<AnalyticSurface> s = random_surface(Type::hyperboloid, g);
    const double a = dynamic_cast<const Hyperboloid&>(*s).a();
    for (int k = 0; k < 1000; ++k) {
      const Vector2d uv = random_uv(Type::hyperboloid, g);
      // The paper's plain Newton from (20) is meant for points near the surface (it may wander
      // off for |p| ~ 1/|k|; closest_point_analytic then falls back to the safeguarded Newton).
      const double p = uniform(g, -0.2, 0.2) * proximity_radius(Type::hyperboloid, *s, uv);
      const Vector3d x = s->point(uv[0], uv[1]) + p * unit_normal(*s, uv);
      const ProjectionResult ks = hyperboloid_closest_point_ks(a, local(*s, x));
      REQUIRE(ks.status == ProjectionStatus::interior);
      const ProjectionResult r = closest_point_analytic(*s, x);
      worst_uv = std::max(worst_uv, (ks.uv - r.uv).norm());
      worst_d = std::max({worst_d, std::abs(ks.distance - r.distance), std::abs(ks.distance - p)});
      // (21) is (x - rho).n; in the local frame the foot satisfies z = a x y (11).
      CHECK(std::abs(ks.point.z() - a * ks.point.x() * ks.point.y()) <= 1e-12);
      if (std::abs(p) > 1e-2) worst_res = std::max(worst_res, ks.residual);
      max_iter = std::max(max_iter, ks.iterations);
    }
  }
  CHECK(worst_uv <= 1e-10);
  CHECK(worst_d <= 1e-10);
  CHECK(worst_res <= 1e-12);
  CHECK(max_iter <= 10);  // quadratic convergence from (20)
}

TEST_CASE("closest_point_analytic: the inward normal flips the signs of distance and normal",
          "[contact][analytic]") {
  std::mt19937 g(8);
  for (const Type t : kAllTypes) {
    INFO("type " << name(t));
    for (int surf = 0; surf < 5; ++surf) {
      std::unique_ptr<AnalyticSurface> s = random_surface(t, g);
      for (int k = 0; k < 200; ++k) {
        const Vector2d uv = random_uv(t, g);
        const Vector3d x = s->point(uv[0], uv[1]) + random_vector(g, 0.3);
        s->set_normal_sign(1);
        const ProjectionResult out = closest_point_analytic(*s, x);
        s->set_normal_sign(-1);
        const ProjectionResult in = closest_point_analytic(*s, x);
        CHECK(in.distance == Approx(-out.distance).margin(1e-15));
        CHECK((in.normal + out.normal).norm() <= 1e-15);
        CHECK((in.point - out.point).norm() <= 1e-15);
      }
    }
  }
}

TEST_CASE(
    "closest_point_analytic: sphere, cylinder, torus and cone signs follow (B.4), (B.10), "
    "(B.16), (B.23): positive outside with the outward normal",
    "[contact][analytic]") {
  Placement pl;
  pl.center = Vector3d(1, 2, 3);
  pl.axis = Vector3d(0, 0, 2);
  const Sphere sphere(pl, 2.0);
  CHECK(closest_point_analytic(sphere, Vector3d(1, 2, 6)).distance == Approx(1.0));
  CHECK(closest_point_analytic(sphere, Vector3d(1, 2, 4)).distance == Approx(-1.0));
  const Cylinder cyl(pl, 2.0);
  CHECK(closest_point_analytic(cyl, Vector3d(4, 2, 9)).distance == Approx(1.0));
  const Torus torus(pl, 3.0, 1.0);
  CHECK(closest_point_analytic(torus, Vector3d(4, 2, 3)).distance == Approx(-1.0));  // centre
  CHECK(closest_point_analytic(torus, Vector3d(1, 2, 3)).distance == Approx(2.0));   // axis
  CHECK(closest_point_analytic(torus, Vector3d(1, 2, 4)).distance == Approx(std::sqrt(10.0) - 1));
  const Cone cone(pl, kPi / 4);
  // (B.23): p = s sin a - z cos a, below the generator = outside.
  const ProjectionResult c = closest_point_analytic(cone, Vector3d(3, 2, 3));
  CHECK(c.distance == Approx(2 * std::sin(kPi / 4)));
  CHECK(c.status == ProjectionStatus::interior);
}

TEST_CASE(
    "closest_point_analytic: undefined angles are chosen deterministically (0, or the "
    "domain's lower bound)",
    "[contact][analytic]") {
  Placement pl;
  pl.center = Vector3d(0.5, -1, 2);
  pl.axis = Vector3d(1, 1, 0);
  const Matrix3d E = pl.frame();
  const Vector3d on_axis = pl.center + 0.7 * E.col(2);

  const Cylinder cyl(pl, 1.5);
  ProjectionResult r = closest_point_analytic(cyl, on_axis);
  CHECK(r.uv[0] == 0.0);
  CHECK(r.uv[1] == Approx(0.7));
  CHECK(r.distance == Approx(-1.5));
  CHECK(r.status == ProjectionStatus::interior);
  const Cylinder sector(pl, 1.5, {{1.0, 2.0}, {-5.0, 5.0}});
  r = closest_point_analytic(sector, on_axis);
  CHECK(r.uv[0] == 1.0);
  CHECK(r.status == ProjectionStatus::interior);  // every angle is as near: no active bound

  const Sphere sphere(pl, 2.0);
  r = closest_point_analytic(sphere, pl.center);
  CHECK(r.uv == Vector2d(0.0, 0.0));
  CHECK(r.distance == Approx(-2.0));
  r = closest_point_analytic(sphere, on_axis);  // the north pole
  CHECK(r.uv[1] == Approx(kPi / 2));
  CHECK((r.point - (pl.center + 2.0 * E.col(2))).norm() <= 1e-14);
  CHECK(r.distance == Approx(-1.3));
  CHECK(r.status == ProjectionStatus::interior);

  const Torus torus(pl, 3.0, 1.0);
  r = closest_point_analytic(torus, pl.center + 3.0 * E.col(1));  // on the tube's centre circle
  CHECK(r.uv[1] == 0.0);
  CHECK(r.distance == Approx(-1.0));
  r = closest_point_analytic(torus, pl.center + E.col(2));  // on the axis
  CHECK(r.uv[0] == 0.0);
  CHECK(r.distance == Approx(std::sqrt(10.0) - 1.0));

  const Revolution cup(pl, {0.0, 0.0, 0.25});
  r = closest_point_analytic(cup, pl.center + 0.5 * E.col(2));  // above the smooth pole
  CHECK(r.uv == Vector2d(0.0, 0.0));
  CHECK(r.status == ProjectionStatus::interior);
  CHECK(r.distance == Approx(0.5));
}

TEST_CASE(
    "closest_point_analytic: the cone's apex is the foot of the points behind it "
    "(vertex), a cone tip of a surface of revolution too",
    "[contact][analytic]") {
  std::mt19937 g(9);
  for (int k = 0; k < 500; ++k) {
    const Placement pl = random_placement(g);
    const double alpha = uniform(g, 0.2, 1.3);
    const Cone cone(pl, alpha);
    const Matrix3d E = pl.frame();
    // A point with along = s cos a + z sin a < 0: behind the apex.
    const double s = uniform(g, 0.0, 2.0), phi = uniform(g, 0, 2 * kPi);
    const double z = -s / std::tan(alpha) - uniform(g, 0.01, 2.0);
    const Vector3d x =
        pl.center + s * (std::cos(phi) * E.col(0) + std::sin(phi) * E.col(1)) + z * E.col(2);
    const ProjectionResult r = closest_point_analytic(cone, x);
    CHECK(r.status == ProjectionStatus::vertex);
    CHECK((r.point - pl.center).norm() <= 1e-15 * (1 + pl.center.norm()));
    CHECK(r.distance == Approx((x - pl.center).norm()).epsilon(1e-13));  // outside: positive
    CHECK(r.distance <= grid_min_distance(cone, x, 6.0, 60) + 1e-12);
  }
  // f(r) = r: a 45 degree cone tip at the pole, points below it project onto the tip.
  Placement pl;
  const Revolution tip(pl, {0.0, 1.0});
  const ProjectionResult r = closest_point_analytic(tip, Vector3d(0.2, 0.1, -2.0));
  CHECK(r.status == ProjectionStatus::vertex);
  CHECK(r.point.norm() <= 1e-15);
}

TEST_CASE(
    "closest_point_analytic: points beyond a bounded cylinder's end land on the edge "
    "circle with status edge and distance |(s - R, z - h)|",
    "[contact][analytic]") {
  std::mt19937 g(10);
  for (int k = 0; k < 2000; ++k) {
    const Placement pl = random_placement(g);
    const double R = uniform(g, 0.5, 2.0);
    Cylinder cyl(pl, R, {{0.0, 2 * kPi}, {-2.0, 2.0}});
    if (k % 2) cyl.set_normal_sign(-1);
    const Matrix3d E = pl.frame();
    double s = uniform(g, 0.01, 3.0 * R);
    if (std::abs(s - R) < 1e-3) s += 0.01;
    const double phi = uniform(g, -kPi, kPi);
    const double end = k % 4 < 2 ? 2.0 : -2.0;
    const double z = end + (end > 0 ? 1.0 : -1.0) * uniform(g, 0.01, 2.0);
    const Vector3d er = std::cos(phi) * E.col(0) + std::sin(phi) * E.col(1);
    const Vector3d x = pl.center + s * er + z * E.col(2);
    const ProjectionResult r = closest_point_analytic(cyl, x);
    CHECK(r.status == ProjectionStatus::edge);
    CHECK(r.uv[1] == end);
    CHECK((r.point - (pl.center + R * er + end * E.col(2))).norm() <= 1e-13);
    const double expect = cyl.normal_sign() * (s > R ? 1.0 : -1.0) * std::hypot(s - R, z - end);
    CHECK(r.distance == Approx(expect).epsilon(1e-13));
    CHECK(r.residual <= 1e-12);  // free direction (around) still orthogonal
  }
}

TEST_CASE(
    "closest_point_analytic: bounded sectors (sphere, torus, cone, revolution, plane, "
    "hyperboloid) give the global constrained minimum, edge/vertex when on the bound",
    "[contact][analytic]") {
  std::mt19937 g(11);
  std::vector<std::unique_ptr<AnalyticSurface>> surfaces;
  for (int k = 0; k < 3; ++k) {
    const Placement pl = random_placement(g);
    surfaces.push_back(std::make_unique<Sphere>(pl, 1.5, Domain2{{0.5, 2.0}, {-0.5, 1.2}}));
    surfaces.push_back(
        std::make_unique<Torus>(pl, 3.0, 1.0, Domain2{{kPi / 4, 1.5 * kPi}, {-1.0, 2.0}}));
    surfaces.push_back(std::make_unique<Cone>(pl, 0.6, Domain2{{-1.0, 2.5}, {0.5, 2.0}}));
    surfaces.push_back(std::make_unique<Cylinder>(pl, 1.0, Domain2{{-2.0, 1.0}, {-1.0, 1.0}}));
    surfaces.push_back(std::make_unique<Revolution>(pl, std::vector<double>{0.3, 0.0, 0.3, -0.05},
                                                    Domain2{{0.5, 2.5}, {0.0, 3.0}}));
    surfaces.push_back(std::make_unique<Plane>(pl, Domain2{{-1.0, 2.0}, {0.0, 1.0}}));
    surfaces.push_back(std::make_unique<Hyperboloid>(pl, 0.3, Domain2{{-1.0, 2.0}, {-2.0, 1.0}}));
  }
  for (const auto& s : surfaces) {
    INFO(s->type_name());
    const Domain2 d = s->domain();
    for (int k = 0; k < 40; ++k) {
      const Vector3d x = s->placement().center + random_vector(g, 4.0);
      const ProjectionResult r = closest_point_analytic(*s, x);
      REQUIRE(found(r.status));
      // Within the domain, and the status tells the active bounds.
      CHECK(r.uv[0] >= d.u.lo);
      CHECK(r.uv[0] <= d.u.hi);
      CHECK(r.uv[1] >= d.v.lo);
      CHECK(r.uv[1] <= d.v.hi);
      const int on_bound = (r.uv[0] == d.u.lo || r.uv[0] == d.u.hi ? 1 : 0) +
                           (r.uv[1] == d.v.lo || r.uv[1] == d.v.hi ? 1 : 0);
      const ProjectionStatus expect = on_bound == 0   ? ProjectionStatus::interior
                                      : on_bound == 1 ? ProjectionStatus::edge
                                                      : ProjectionStatus::vertex;
      CHECK(r.status == expect);
      // Global: not farther than the grid; equal to the local polish from the grid's best.
      Vector2d uv_best;
      const double grid = grid_min_distance(*s, x, 10.0, 200, &uv_best);
      CHECK(std::abs(r.distance) <= grid + 1e-12);
      const ProjectionResult polish = closest_point_local(*s, x, uv_best);
      CHECK(std::abs(r.distance) <= std::abs(polish.distance) + 1e-10);
      CHECK(std::abs(r.distance) == Approx((x - r.point).norm()).epsilon(1e-12).margin(1e-14));
    }
  }
}

TEST_CASE(
    "ray_project_analytic: hits lie on the surface, x + xi3 N = rho, and no hit is nearer "
    "along the line",
    "[contact][analytic][ray]") {
  std::mt19937 g(12);
  for (const Type t : kAllTypes) {
    INFO("type " << name(t));
    int hits = 0;
    double worst_level = 0.0, worst_line = 0.0, worst_res = 0.0;
    for (int surf = 0; surf < 10; ++surf) {
      const std::unique_ptr<AnalyticSurface> s = random_surface(t, g);
      if (surf % 2) s->set_normal_sign(-1);
      for (int k = 0; k < 200; ++k) {
        const Vector2d uv = random_uv(t, g);
        const Vector3d x = s->point(uv[0], uv[1]) + random_vector(g, 1.0);
        const Vector3d N = uniform(g, 0.5, 2.0) * random_unit(g);  // normalized inside
        const ProjectionResult r = ray_project_analytic(*s, x, N);
        const Vector3d Nu = N.normalized();
        if (r.status == ProjectionStatus::interior) {
          ++hits;
          const double scale = 1.0 + (x - s->placement().center).norm() + std::abs(r.distance);
          worst_level = std::max(worst_level, std::abs(level(*s, r.point)) / scale);
          worst_line = std::max(worst_line, (x + r.distance * Nu - r.point).norm() / scale);
          worst_res = std::max(worst_res, r.residual);
          CHECK((r.normal - unit_normal(*s, r.uv)).norm() <= 1e-9);
        }
        // The smallest |xi3|: the level function keeps its sign on |t| < |xi3| (or everywhere
        // on a long stretch of the line when it misses).
        const double reach = found(r.status) || r.status == ProjectionStatus::tangent
                                 ? std::abs(r.distance) * (1 - 1e-7) - 1e-9
                                 : (t == Type::revolution ? 0.0 : 20.0);
        if (reach > 0.0) {
          const int n = 1000;
          const Level lev(*s);
          double prev = lev(x - reach * Nu);
          bool crossed = false;
          for (int i = 1; i <= n; ++i) {
            const double cur = lev(x + (-reach + 2 * reach * i / n) * Nu);
            crossed = crossed || (cur < 0) != (prev < 0);
            prev = cur;
          }
          CHECK_FALSE(crossed);
        }
      }
    }
    CHECK(hits > 300);
    CHECK(worst_level <= 1e-12);
    CHECK(worst_line <= 1e-12);
    CHECK(worst_res <= 1e-13);
  }
}

TEST_CASE(
    "ray_project_analytic: along the normal the ray meets the surface at the closest "
    "point (xi3 = -p)",
    "[contact][analytic][ray]") {
  std::mt19937 g(13);
  for (const Type t : kAllTypes) {
    INFO("type " << name(t));
    for (int surf = 0; surf < 5; ++surf) {
      const std::unique_ptr<AnalyticSurface> s = random_surface(t, g);
      for (int k = 0; k < 200; ++k) {
        const Vector2d uv = random_uv(t, g);
        const Vector3d n = unit_normal(*s, uv);
        const double p = uniform(g, -0.9, 0.9) * proximity_radius(t, *s, uv);
        const Vector3d x = s->point(uv[0], uv[1]) + p * n;
        const ProjectionResult cp = closest_point_analytic(*s, x);
        const Vector3d N = (k % 2 ? 1.0 : -1.0) * cp.normal;
        const ProjectionResult r = ray_project_analytic(*s, x, N);
        REQUIRE(r.status == ProjectionStatus::interior);
        CHECK(r.distance == Approx(-cp.distance * N.dot(cp.normal)).margin(1e-10));
        CHECK((r.point - cp.point).norm() <= 1e-10);
      }
    }
  }
}

TEST_CASE(
    "ray_project_analytic: a ray beside a sphere misses, a ray tangent to a cylinder is "
    "tangent, the plane follows (8)-(9), a ray along a cone's axis meets the apex",
    "[contact][analytic][ray]") {
  std::mt19937 g(14);
  for (int k = 0; k < 200; ++k) {
    const Placement pl = random_placement(g);
    const Matrix3d E = pl.frame();
    const double R = uniform(g, 0.5, 2.0);
    const Vector3d e1 = E.col(0), e2 = E.col(1), e3 = E.col(2);

    const Sphere sphere(pl, R);
    const ProjectionResult miss =
        ray_project_analytic(sphere, pl.center + 1.01 * R * e1 - 3.0 * e2, e2);
    CHECK(miss.status == ProjectionStatus::miss);
    CHECK_FALSE(found(miss.status));
    const ProjectionResult hit = ray_project_analytic(sphere, pl.center + 0.99 * R * e1, e2);
    CHECK(hit.status == ProjectionStatus::interior);

    const Cylinder cyl(pl, R);
    const double u0 = uniform(g, 0, 2 * kPi), z0 = uniform(g, -3, 3);
    const Vector3d er = std::cos(u0) * e1 + std::sin(u0) * e2;
    const Vector3d eu = -std::sin(u0) * e1 + std::cos(u0) * e2;
    const Vector3d touch = pl.center + R * er + z0 * e3;
    const Vector3d tilt = uniform(g, -1, 1) * e3;  // any direction in the tangent plane
    const Vector3d N = (eu + tilt).normalized();
    const ProjectionResult tan = ray_project_analytic(cyl, touch - 3.0 * N, N);
    CHECK(tan.status == ProjectionStatus::tangent);
    CHECK(tan.distance == Approx(3.0).epsilon(1e-6));
    CHECK((tan.point - touch).norm() <= 1e-6);

    const Plane plane(pl);
    const Vector3d x = pl.center + random_vector(g, 2.0);
    const Vector3d Np = random_unit(g);
    const ProjectionResult rp = ray_project_analytic(plane, x, Np);
    if (std::abs(Np.dot(e3)) > 1e-3) {
      CHECK(rp.distance == Approx(-(x - pl.center).dot(e3) / Np.dot(e3)).epsilon(1e-12));  // (8)
      CHECK(rp.status == ProjectionStatus::interior);
    }
    const ProjectionResult parallel = ray_project_analytic(plane, x, e1 + 1e-12 * e3);
    CHECK(parallel.status == ProjectionStatus::tangent);  // (9)

    const Cone cone(pl, uniform(g, 0.2, 1.3));
    const ProjectionResult apex = ray_project_analytic(cone, pl.center - 2.0 * e3, e3);
    CHECK(apex.status == ProjectionStatus::vertex);
    CHECK(apex.distance == Approx(2.0).epsilon(1e-12));
    CHECK((apex.point - pl.center).norm() <= 1e-12);
  }
}

TEST_CASE(
    "ray_project_analytic: a ray through a torus meets up to four points and returns the "
    "nearest, hits outside a bounded domain are skipped",
    "[contact][analytic][ray]") {
  Placement pl;
  pl.center = Vector3d(1, 1, 1);
  const Torus torus(pl, 3.0, 1.0);
  // Along e_x through the centre: hits at x - c = -4, -2, 2, 4.
  ProjectionResult r = ray_project_analytic(torus, Vector3d(1.5, 1, 1), Vector3d(1, 0, 0));
  CHECK(r.status == ProjectionStatus::interior);
  CHECK(r.distance == Approx(1.5));
  r = ray_project_analytic(torus, Vector3d(-6, 1, 1), Vector3d(2, 0, 0));
  CHECK(r.distance == Approx(3.0));
  r = ray_project_analytic(torus, Vector3d(-6, 1, 1), Vector3d(-2, 0, 0));
  CHECK(r.distance == Approx(-3.0));  // behind x: xi3 < 0
  // Tangent to the top of the tube.
  r = ray_project_analytic(torus, Vector3d(4, -2, 2), Vector3d(0, 1, 0));
  CHECK(r.status == ProjectionStatus::tangent);
  CHECK(r.distance == Approx(3.0).epsilon(1e-6));

  const Cylinder short_cyl(pl, 1.0, {{0.0, 2 * kPi}, {-1.0, 1.0}});
  r = ray_project_analytic(short_cyl, Vector3d(-3, 1, 3), Vector3d(1, 0, 0));
  CHECK(r.status == ProjectionStatus::miss);                      // passes above the end
  const Sphere half(pl, 1.0, {{0.0, kPi}, {-kPi / 2, kPi / 2}});  // y >= 1 half
  r = ray_project_analytic(half, Vector3d(1, -3, 1), Vector3d(0, 1, 0));
  CHECK(r.status == ProjectionStatus::interior);
  CHECK(r.distance == Approx(5.0));  // the near side (y = 0) is not in the domain
}

TEST_CASE(
    "ray_project_analytic: surface of revolution by Newton (A.2) agrees with the level "
    "function root nearest along the line",
    "[contact][analytic][ray]") {
  Placement pl;
  pl.center = Vector3d(0.2, -0.1, 0.3);
  pl.axis = Vector3d(0.1, 0.2, 1.0);
  const Revolution cup(pl, {0.0, 0.0, 0.25});  // z = r^2 / 4
  const Matrix3d E = pl.frame();
  // A vertical line at radius 1: one hit at z = 0.25.
  ProjectionResult r =
      ray_project_analytic(cup, pl.center + 1.0 * E.col(0) + 2.0 * E.col(2), -E.col(2));
  CHECK(r.status == ProjectionStatus::interior);
  CHECK(r.distance == Approx(1.75).epsilon(1e-12));
  // A horizontal line at height 1 through the axis: hits at radius 2 on both sides.
  r = ray_project_analytic(cup, pl.center + 1.0 * E.col(2) + 0.5 * E.col(1), E.col(1));
  CHECK(r.status == ProjectionStatus::interior);
  CHECK(r.distance == Approx(1.5).epsilon(1e-12));
  CHECK(std::abs(level(cup, r.point)) <= 1e-13);
}

TEST_CASE(
    "closest_point_analytic: NURBS cylinder, sphere, torus and cone projections equal the "
    "closed forms (points and distances)",
    "[contact][analytic][nurbs]") {
  std::mt19937 g(15);
  for (int k = 0; k < 3; ++k) {
    const Placement pl = random_placement(g);
    const Matrix3d E = pl.frame();
    const Vector3d axis = E.col(2), ref = E.col(0);
    struct Pair {
      std::unique_ptr<AnalyticSurface> analytic;
      NurbsSurface nurbs;
      double size;
    };
    std::vector<Pair> pairs;
    pairs.push_back({std::make_unique<Cylinder>(pl, 1.5, Domain2{{0, 2 * kPi}, {0.0, 3.0}}),
                     make_cylinder(pl.center, axis, ref, 1.5, 3.0), 3.0});
    pairs.push_back({std::make_unique<Sphere>(pl, 1.2), make_sphere(pl.center, 1.2), 1.2});
    pairs.push_back(
        {std::make_unique<Torus>(pl, 2.5, 0.7), make_torus(pl.center, axis, 2.5, 0.7), 3.2});
    pairs.push_back({std::make_unique<Cone>(pl, 0.7, Domain2{{0, 2 * kPi}, {0.5, 2.5}}),
                     make_cone(pl.center, axis, ref, 0.7, 0.5, 2.5), 2.5});
    for (const Pair& p : pairs) {
      INFO(p.analytic->type_name());
      const PatchProjector proj(p.nurbs);
      double worst_d = 0.0, worst_x = 0.0;
      for (int i = 0; i < 200; ++i) {
        const Vector2d uv = random_uv(p.analytic->type_name() == "cylinder" ? Type::cylinder
                                      : p.analytic->type_name() == "sphere" ? Type::sphere
                                      : p.analytic->type_name() == "torus"  ? Type::torus
                                                                            : Type::cone,
                                      g);
        Vector2d uvc = uv;
        const Domain2 d = p.analytic->domain();
        uvc[1] = std::clamp(uvc[1], d.v.lo, d.v.hi);
        const Vector3d x = p.analytic->point(uvc[0], uvc[1]) + random_vector(g, 0.3);
        const ProjectionResult a = closest_point_analytic(*p.analytic, x);
        const ProjectionResult b = proj.project(x);
        REQUIRE(found(b.status));
        worst_d = std::max(worst_d, std::abs(a.distance - b.distance));
        worst_x = std::max(worst_x, (a.point - b.point).norm());
      }
      CHECK(worst_d <= 1e-10);
      CHECK(worst_x <= 1e-10);
    }
  }
}

TEST_CASE("analytic projections: far points keep finite distances, a zero ray direction is a miss",
          "[contact][analytic][projection]") {
  const Placement pl{Vector3d(0.0, 0.0, 2.0), Vector3d::UnitZ()};
  const Sphere sphere(pl, 0.5);
  // |x|^2 overflows at 1e154 per coordinate: the distance was +inf with status interior and
  // the foot at u = v = 0 (the angle taken as undefined).
  const Vector3d far(1e154, 1e154, 1e154);
  const ProjectionResult r = closest_point_analytic(sphere, far);
  CHECK(found(r.status));
  CHECK(r.distance == Approx(std::sqrt(3.0) * 1e154).epsilon(1e-12));
  CHECK((r.point - pl.center).normalized().dot(Vector3d(1, 1, 1).normalized()) ==
        Approx(1.0).epsilon(1e-12));
  const Cylinder cyl(pl, 0.5);
  const ProjectionResult rc = closest_point_analytic(cyl, Vector3d(-1e300, 1e300, 5.0));
  CHECK(rc.distance == Approx(std::sqrt(2.0) * 1e300).epsilon(1e-12));
  // A ray without a direction: a miss (it threw and aborted a whole batch), as on NURBS.
  const ProjectionResult z = ray_project_analytic(sphere, Vector3d(0, 0, 3), Vector3d::Zero());
  CHECK(z.status == ProjectionStatus::miss);
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(ray_project_analytic(sphere, Vector3d(0, 0, 3), Vector3d(0, 0, inf)).status ==
        ProjectionStatus::miss);
  // A direction too long for |N|^2 is still a direction.
  const ProjectionResult h =
      ray_project_analytic(sphere, Vector3d(0, 0, 3), Vector3d(0, 0, -1e300));
  CHECK(h.status == ProjectionStatus::interior);
  CHECK(h.distance == Approx(0.5).epsilon(1e-12));
}

}  // namespace test_analytic_projection
