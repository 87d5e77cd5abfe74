// Horn and spindle tori (minor radius r >= major radius R, issue 34 item 4): closest points
// against a dense parameter grid refined around its best cell (global minimum over the domain,
// full and partial), the normal against rho_u x rho_v, and ray hits on the surface (the quartic
// of (B.16) and the parameters of its roots on the inner part R + r cos v < 0).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "contact/analytic_projection.hpp"
#include "geometry/analytic_surfaces.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_spindle_torus {

using namespace iga;

namespace {

constexpr double kPi = std::numbers::pi;

double uniform(std::mt19937& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}

/// The smallest |x - rho(u, v)| over the domain: a 241 x 241 grid, then five passes of a
/// 21 x 21 grid over the 2 x 2 cells around the best point so far (each pass shrinks the cell
/// tenfold). The grid's points are surface points: an upper bound of the minimum, converged to
/// about 1e-9 of the parameter box in the best basin.
double grid_min(const Torus& t, const Vector3d& x) {
  const Domain2 d = t.domain();
  auto dist = [&](double u, double v) { return (x - t.derivs(u, v, 0).S).norm(); };
  double best = std::numeric_limits<double>::infinity(), bu = 0, bv = 0;
  int n = 240;
  double hu = (d.u.hi - d.u.lo) / n, hv = (d.v.hi - d.v.lo) / n;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = d.u.lo + i * hu, v = d.v.lo + j * hv, e = dist(u, v);
      if (e < best) best = e, bu = u, bv = v;
    }
  for (int pass = 0; pass < 5; ++pass) {
    const double cu = bu, cv = bv;
    for (int j = -10; j <= 10; ++j)
      for (int i = -10; i <= 10; ++i) {
        const double u = std::clamp(cu + i * hu / 10, d.u.lo, d.u.hi);
        const double v = std::clamp(cv + j * hv / 10, d.v.lo, d.v.hi);
        const double e = dist(u, v);
        if (e < best) best = e, bu = u, bv = v;
      }
    hu /= 10, hv /= 10;
  }
  return best;
}

Placement random_placement(std::mt19937& g) {
  Placement p;
  p.center = Vector3d(uniform(g, -2, 2), uniform(g, -2, 2), uniform(g, -2, 2));
  p.axis = Vector3d(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, 0.2, 1));
  p.ref_dir = Vector3d(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1));
  return p;
}

}  // namespace

TEST_CASE("spindle and horn tori: the closest point is the global minimum over the domain",
          "[contact][analytic][torus]") {
  std::mt19937 g(34);
  int inner = 0, bounded = 0;
  for (int k = 0; k < 24; ++k) {
    const double R = uniform(g, 0.5, 2.0);
    const double r = k % 4 == 0 ? R : uniform(g, 1.05, 4.0) * R;  // horn every fourth
    Domain2 d = Torus::default_domain();
    if (k % 2 == 1) {  // a partial face, as CAD files hold
      const double u0 = uniform(g, -kPi, kPi), v0 = uniform(g, -kPi, kPi);
      d = {{u0, u0 + uniform(g, 0.5, 5.5)}, {v0, v0 + uniform(g, 0.5, 5.5)}};
    }
    const Torus t(random_placement(g), R, r, d);
    const double size = 2 * (R + r);
    for (int m = 0; m < 12; ++m) {
      const Vector3d x =
          t.placement().center +
          (R + r) * Vector3d(uniform(g, -1.3, 1.3), uniform(g, -1.3, 1.3), uniform(g, -1.3, 1.3));
      const ProjectionResult res = closest_point_analytic(t, x);
      REQUIRE(found(res.status));
      INFO("R = " << R << ", r = " << r << ", domain u [" << d.u.lo << ", " << d.u.hi << "], v ["
                  << d.v.lo << ", " << d.v.hi << "], x = " << x.transpose());
      // The foot is the surface point at its parameters, inside the domain.
      CHECK((t.derivs(res.uv[0], res.uv[1], 0).S - res.point).norm() <= 1e-12 * size);
      CHECK(res.uv[0] >= d.u.lo - 1e-12);
      CHECK(res.uv[0] <= d.u.hi + 1e-12);
      CHECK(res.uv[1] >= d.v.lo - 1e-12);
      CHECK(res.uv[1] <= d.v.hi + 1e-12);
      const double ours = (x - res.point).norm(), ref = grid_min(t, x);
      // Not farther than any grid point; the grid's best, refined, within 1e-8 of the size
      // (its last pass steps 1e-5 of the box's cells: the distance is converged far below).
      CHECK(ours <= ref + 1e-12 * size);
      CHECK(ours >= ref - 1e-8 * size);
      CHECK(std::abs(std::abs(res.distance) - ours) <= 1e-12 * size);
      inner += t.major_radius() + t.minor_radius() * std::cos(res.uv[1]) < 0.0;
      bounded += res.status != ProjectionStatus::interior;
      // The normal is rho_u x rho_v's direction (times the surface's sign), off the axis.
      const SurfaceDerivs dd = t.derivs(res.uv[0], res.uv[1], 1);
      const Vector3d n = dd.Su.cross(dd.Sv);
      if (n.norm() > 1e-6 * size * size) CHECK((n.normalized() - res.normal).norm() <= 1e-9);
    }
  }
  // The cases reach the inner part and the domain's bounds (the test exercises both).
  CHECK(inner >= 10);
  CHECK(bounded >= 10);
}

TEST_CASE("spindle tori: rays hit the surface, the inner part too, at the nearest crossing",
          "[contact][analytic][torus]") {
  std::mt19937 g(35);
  int inner = 0;
  for (int k = 0; k < 20; ++k) {
    const double R = uniform(g, 0.5, 2.0), r = uniform(g, 1.1, 3.0) * R;
    const Torus t(random_placement(g), R, r);
    for (int m = 0; m < 10; ++m) {
      const double u = uniform(g, 0, 2 * kPi), v = uniform(g, 0, 2 * kPi);
      const Vector3d P = t.derivs(u, v, 0).S;
      const Vector3d x =
          P + 0.3 * (R + r) * Vector3d(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1));
      const Vector3d N = (P - x).normalized();
      const ProjectionResult res = ray_project_analytic(t, x, N);
      INFO("R = " << R << ", r = " << r << ", target (" << u << ", " << v << ")");
      REQUIRE(found(res.status));
      // A crossing no farther than the target, on the line, and the surface point of its uv.
      CHECK(std::abs(res.distance) <= (P - x).norm() * (1 + 1e-12) + 1e-12);
      CHECK((x + res.distance * N - res.point).norm() <= 1e-10 * (R + r));
      CHECK((t.derivs(res.uv[0], res.uv[1], 0).S - res.point).norm() <= 1e-10 * (R + r));
      inner += R + r * std::cos(res.uv[1]) < 0.0;
    }
  }
  CHECK(inner >= 10);
}

}  // namespace test_spindle_torus
