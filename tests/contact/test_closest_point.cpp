// Closest point projection onto NURBS patches and curves ([KS15] eqs. 10-18, Sect. 2.2):
// orthogonality, global minimum against brute force, edges and corners, seams, warm starts,
// and agreement with closed forms for the exact NURBS quadrics.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "contact/analytic_projection.hpp"
#include "contact/closest_point.hpp"
#include "contact/patch_bounds.hpp"
#include "contact/ray_projection.hpp"
#include "geometry/constructions.hpp"
#include "geometry/differential_geometry.hpp"
#include "geometry/refinement.hpp"
#include "tests/support/projection_reference.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_closest_point {

using namespace iga;

namespace {
constexpr double kPi = std::numbers::pi;

Vector3d random_in_box(std::mt19937& g, const Box3& b, double grow) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vector3d c = 0.5 * (b.lo + b.hi), h = 0.5 * (b.hi - b.lo) * (1.0 + grow);
  return c + Vector3d((2 * u(g) - 1) * h.x(), (2 * u(g) - 1) * h.y(), (2 * u(g) - 1) * h.z());
}
}  // namespace

TEST_CASE("PatchProjector: orthogonality residual at convergence on the free-form patch",
          "[contact][closest]") {
  const PatchProjector P(test::data_surface("freeform_bicubic.json"));
  std::mt19937 g(1);
  std::uniform_real_distribution<double> u(0.02, 0.98), off(-0.5, 0.5);
  const double size = (P.box().hi - P.box().lo).norm();
  for (int k = 0; k < 2000; ++k) {
    // points near the surface (|p| <= 5 % of the size 10), feet inside
    const Vector2d uv(u(g), u(g));
    const SurfaceDerivs d = P.surface().derivs(uv[0], uv[1], 1);
    const Vector3d n = d.Su.cross(d.Sv).normalized();
    const Vector3d x = d.S + off(g) * n;
    const ProjectionResult r = P.project(x);
    REQUIRE(found(r.status));
    const SurfaceDerivs f = P.surface().derivs(r.uv[0], r.uv[1], 1);
    const Vector3d diff = x - f.S;
    if (r.status == ProjectionStatus::interior) {
      // (16) = 0: the tangential error of the foot point, relative to max(|x - rho|, size)
      // (the bare cosine of the angle is ill-conditioned as |x - rho| -> 0).
      const double scale = std::max(diff.norm(), size);
      CHECK(std::abs(diff.dot(f.Su)) / (f.Su.norm() * scale) <= 1e-12);
      CHECK(std::abs(diff.dot(f.Sv)) / (f.Sv.norm() * scale) <= 1e-12);
      CHECK(r.residual <= 1e-12);
    }
    CHECK(std::abs(r.distance) <= std::abs((x - d.S).norm()) + 1e-12);
  }
}

TEST_CASE("PatchProjector: cold start finds the global minimum (brute-force reference)",
          "[contact][closest]") {
  const PatchProjector P(test::data_surface("freeform_bicubic.json"));
  std::mt19937 g(2);
  int checked = 0;
  for (double grow : {0.1, 0.3, 3.0}) {  // near, around (edges/corners), far
    for (int k = 0; k < 120; ++k) {
      const Vector3d x = random_in_box(g, P.box(), grow);
      const ProjectionResult r = P.project(x);
      const ProjectionResult ref = test::brute_force_closest(P.surface(), x);
      INFO("x = " << x.transpose() << " status " << to_string(r.status));
      REQUIRE(found(r.status));
      INFO("ours " << (r.point - x).norm() << " ref " << (ref.point - x).norm() << " uv "
                   << r.uv.transpose() << " ref uv " << ref.uv.transpose());
      CHECK((r.point - x).norm() <= (ref.point - x).norm() + 1e-10);
      ++checked;
    }
  }
  CHECK(checked == 360);
}

TEST_CASE(
    "PatchProjector: a minimum at a kink where four elements meet (a tent's apex) is found and "
    "certified",
    "[contact][closest]") {
  // A degree-1 tent over [-1, 1]^2 with its apex (0, 0, 1) at the corner of its four elements:
  // C0 across both inner knots. For x above the apex the closest point is the apex: every
  // other point y has z_y < 1 and |x - y| >= x_z - z_y, which beats the apex's distance
  // sqrt((x_z - 1)^2 + r^2) for r small. F decreases towards the apex on all four elements, so
  // each element's minimum is on borders it shares with the others, and no element may leave
  // it to another (PatchProjector's kinks; on OCC17026-1.igs, issue 34, all four did and the
  // search returned a pole 4.4 times farther, marked certified; here the seeds find the apex).
  std::vector<Vector3d> cps;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) cps.emplace_back(i - 1.0, j - 1.0, i == 1 && j == 1 ? 1.0 : 0.0);
  const NurbsSurface tent(1, {0, 0, 0.5, 1, 1}, 1, {0, 0, 0.5, 1, 1}, cps);
  const PatchProjector P(tent);
  const Vector3d apex(0, 0, 1);
  for (const Vector3d& x : {Vector3d(0.01, 0.02, 3.0), Vector3d(-0.03, 0.01, 2.0),
                            Vector3d(0.0, 0.0, 1.5), Vector3d(0.02, -0.02, 1.2)}) {
    INFO("x = " << x.transpose());
    const ProjectionResult r = P.project(x);
    REQUIRE(found(r.status));
    CHECK((r.point - apex).norm() < 1e-12);
    CHECK(r.uv.isApprox(Vector2d(0.5, 0.5), 1e-12));
    CHECK(r.certified);
    const ProjectionResult ref = test::brute_force_closest(tent, x);
    CHECK((r.point - x).norm() <= (ref.point - x).norm() + 1e-12);
  }
}

TEST_CASE(
    "PatchProjector: a minimum next to a crease whose far side starts with a zero derivative "
    "(repeated control points) is found",
    "[contact][closest]") {
  // In u (degree 2, double knot 0.5: C0 there) a parabola arch P0 P1 P2 and, past the crease, a
  // segment that starts with zero speed (P3 = P2): S = P2 + t^2 (P4 - P2); swept along z in v
  // (degree 1). x lies 0.3 off the arch along its outer normal at local t = 0.998 (u = 0.499),
  // on the convex side, so that foot is the arch's only minimum, and x_y > 0, so the segment's
  // nearest point is P2, farther: |x - P2|^2 = 0.09 + |f - P2|^2. On the segment's side of the
  // crease F_u = 0 at u = 0.5 (S_u = 0): a Newton evaluated there took P2 for stationary and
  // the search stopped on it (OCC17026-1.igs, issue 34: 3861.90 for 3861.53).
  const Vector2d P0(0, 0), P1(0.5, 0.5), P2(1, 0), P4(1, -1);
  std::vector<Vector3d> cps;
  for (const double z : {0.0, 1.0})
    for (const Vector2d& p : {P0, P1, P2, P2, P4}) cps.emplace_back(p.x(), p.y(), z);
  const NurbsSurface s(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}, 1, {0, 0, 1, 1}, cps);
  const PatchProjector P(s);
  for (const double t : {0.998, 0.99, 0.9999}) {
    const Vector2d f = (1 - t) * (1 - t) * P0 + 2 * t * (1 - t) * P1 + t * t * P2;
    const Vector2d d = 2 * (1 - t) * (P1 - P0) + 2 * t * (P2 - P1);
    const Vector2d n = Vector2d(-d.y(), d.x()).normalized();
    REQUIRE(n.y() > 0);  // the outer side of the arch
    const Vector2d xy = f + 0.3 * n;
    const Vector3d x(xy.x(), xy.y(), 0.4);
    INFO("t = " << t << ", x = " << x.transpose());
    for (const ProjectionResult& r : {P.project(x), P.project(x, Vector2d(0.5, 0.4))}) {
      REQUIRE(found(r.status));
      CHECK((r.point - Vector3d(f.x(), f.y(), 0.4)).norm() < 1e-12);
      CHECK(r.uv[0] == Approx(0.5 * t).margin(1e-12));
      CHECK((r.point - x).norm() == Approx(0.3).epsilon(1e-13));
      CHECK(r.certified);
    }
  }
}

TEST_CASE("PatchProjector: a minimum on a crease is converged along it", "[contact][closest]") {
  // A roof whose ridge (v = 0.5, degree 1 across: C0) is the parabola arch R(u) with control
  // points (-1, 0, 1), (0, 1, 1), (1, 0, 1); the roof falls to z = 0 at y -/+ 0.5 on both
  // sides. For x well above the ridge the foot is on the ridge (as for a tent's apex), at the
  // minimum of |x - R(u)| over u, found here by the 1-D Newton on the ridge's curve. A Newton
  // on the patch zigzags across the crease and stops short along it (OCC17026-1.igs, issue 34:
  // 0.026 off along a crease, 1.3e-7 farther, and certified: the certificate bounds the
  // distance, not the foot).
  std::vector<Vector3d> cps;
  const Vector2d Q[3] = {{-1, 0}, {0, 1}, {1, 0}};
  for (int j = 0; j < 3; ++j)
    for (const Vector2d& q : Q) cps.emplace_back(q.x(), q.y() + (j - 1) * 0.5, j == 1 ? 1.0 : 0.0);
  const NurbsSurface s(2, {0, 0, 0, 1, 1, 1}, 1, {0, 0, 0.5, 1, 1}, cps);
  const NurbsCurve ridge(2, {0, 0, 0, 1, 1, 1},
                         {Vector3d(-1, 0, 1), Vector3d(0, 1, 1), Vector3d(1, 0, 1)});
  const PatchProjector P(s);
  int checked = 0;
  for (const double ux : {0.13, 0.31, 0.52, 0.77}) {
    const Vector3d on = ridge.point(ux);
    const Vector3d x = on + Vector3d(0.05, 0.02, 2.0);
    const ProjectionResult ref = closest_point_local(ridge, x, ux);
    REQUIRE(found(ref.status));
    INFO("x = " << x.transpose() << ", the ridge's foot at u = " << ref.uv[0]);
    for (const ProjectionResult& r : {P.project(x), P.project(x, Vector2d(ux, 0.3))}) {
      REQUIRE(found(r.status));
      CHECK(r.uv[1] == 0.5);
      CHECK((r.point - ref.point).norm() < 1e-12);
      CHECK(r.certified);
      ++checked;
    }
  }
  CHECK(checked == 8);
}

TEST_CASE(
    "closest_point_local: a small step that clamps a parameter onto a bound goes on (a start "
    "1e-16 inside a bound, next to a corner that is no minimum)",
    "[contact][closest]") {
  // Face 187 of OpenCASCADE's data/iges/bearing.iges (degree 1 x 3, one element). The minimum
  // lies on the edge u = u_hi at v = 0.99622; at the corner (u_hi, 1) F_v > 0. Started at
  // u_hi - 1e-16 (a sample of the search, 0.89474579999999992 for 0.8947458), the coupled
  // Newton step clamped both parameters, the step was below the tolerance, and the corner was
  // returned as converged: 1.03e-7 farther (of 1.72e-3), and then certified by the chord test,
  // which assumes the optimality conditions hold.
  const std::vector<Vector3d> cps = {
      {-0.024809227412131075, 0.029382935342713443, 0.012134056738883228},
      {-0.0108519205846876, 0.014695367453856, 0.028199602560149802},
      {-0.023266806837404005, 0.03084867534271344, 0.01213405160097383},
      {-0.009309497005704399, 0.016161107453856, 0.028199601928624602},
      {-0.021994337412131075, 0.03205787534271344, 0.01046826160097383},
      {-0.0080370305846876, 0.017370307453856, 0.0265338119286246},
      {-0.02191361626267694, 0.032134585342713434, 0.008343393313610295},
      {-0.0079563034267212, 0.017447017453855997, 0.024408942139133}};
  const NurbsSurface s(1, {0.143681767, 0.143681767, 0.8947458, 0.8947458}, 3,
                       {0, 0, 0, 0, 1, 1, 1, 1}, cps);
  const Vector3d x(-0.0081180015097562144, 0.015734135967744256, 0.024357429434519313);
  const double u_hi = s.domain().u.hi;
  // The edge's minimum: F_v = 0 along u = u_hi, by bisection on the sign of F_v.
  double a = 0.5, b = 1.0;
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (a + b);
    const SurfaceDerivs d = s.derivs(u_hi, m, 1);
    ((d.S - x).dot(d.Sv) < 0.0 ? a : b) = m;
  }
  const Vector3d foot = s.point(u_hi, a);
  REQUIRE((s.point(u_hi, 1.0) - x).norm() > (foot - x).norm() + 1e-8);
  const ProjectionResult r = closest_point_local(s, x, Vector2d(std::nextafter(u_hi, 0.0), 1.0));
  REQUIRE(found(r.status));
  CHECK(r.status == ProjectionStatus::edge);
  CHECK(r.uv[1] == Approx(a).margin(1e-10));
  CHECK((r.point - foot).norm() < 1e-14);
  const PatchProjector P(s);
  const ProjectionResult c = P.project(x);
  REQUIRE(found(c.status));
  CHECK((c.point - foot).norm() < 1e-14);
  CHECK(c.certified);
}

TEST_CASE("PatchProjector: warm and cold starts agree near the surface", "[contact][closest]") {
  const PatchProjector P(test::data_surface("freeform_bicubic.json"));
  std::mt19937 g(3);
  std::uniform_real_distribution<double> u(0.05, 0.95), off(-0.3, 0.3), jit(-0.02, 0.02);
  for (int k = 0; k < 1000; ++k) {
    const Vector2d uv(u(g), u(g));
    const SurfaceDerivs d = P.surface().derivs(uv[0], uv[1], 1);
    const Vector3d x = d.S + off(g) * d.Su.cross(d.Sv).normalized();
    const ProjectionResult cold = P.project(x);
    const ProjectionResult warm = P.project(x, uv + Vector2d(jit(g), jit(g)));
    CHECK((cold.point - warm.point).norm() <= 1e-10);
    CHECK(cold.distance == Approx(warm.distance).margin(1e-10));
  }
}

TEST_CASE("PatchProjector: points beyond an edge or a corner land on it", "[contact][closest]") {
  // Unit square in z = 0, normal +z (bilinear patch).
  const PatchProjector P(make_plane_patch(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()));
  const ProjectionResult e = P.project(Vector3d(1.5, 0.25, 0.3));
  CHECK(e.status == ProjectionStatus::edge);
  CHECK((e.point - Vector3d(1, 0.25, 0)).norm() <= 1e-14);
  CHECK(e.distance == Approx(std::sqrt(0.25 + 0.09)).epsilon(1e-14));
  const ProjectionResult below = P.project(Vector3d(0.4, -0.7, -0.2));
  CHECK(below.status == ProjectionStatus::edge);
  CHECK(below.distance == Approx(-std::sqrt(0.49 + 0.04)).epsilon(1e-14));  // under: negative
  const ProjectionResult v = P.project(Vector3d(-0.5, 1.5, 0.1));
  CHECK(v.status == ProjectionStatus::vertex);
  CHECK((v.point - Vector3d(0, 1, 0)).norm() <= 1e-14);
  const ProjectionResult in = P.project(Vector3d(0.3, 0.6, -0.4));
  CHECK(in.status == ProjectionStatus::interior);
  CHECK(in.distance == Approx(-0.4).epsilon(1e-14));

  // A curved patch: a quarter cylinder, points beyond its straight edge and its arc edge.
  const NurbsSurface q =
      make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 2.0, 1.0, 0.0, kPi / 2);
  const PatchProjector Q(q);
  const ProjectionResult top = Q.project(Vector3d(1.0, 1.0, 1.7));  // above the top arc
  CHECK(top.status == ProjectionStatus::edge);
  CHECK(top.point.z() == Approx(1.0).epsilon(1e-14));
  CHECK(top.point.head<2>().norm() == Approx(2.0).epsilon(1e-13));
  const ProjectionResult side = Q.project(Vector3d(-1.0, 3.0, 0.5));  // beyond the x = 0 line
  CHECK(side.status == ProjectionStatus::edge);
  CHECK((side.point - Vector3d(0, 2, 0.5)).norm() <= 1e-12);
  const ProjectionResult corner = Q.project(Vector3d(3.0, -1.0, -1.0));
  CHECK(corner.status == ProjectionStatus::vertex);
  CHECK((corner.point - Vector3d(2, 0, 0)).norm() <= 1e-12);
}

TEST_CASE("PatchProjector: exact NURBS quadrics agree with the closed forms",
          "[contact][closest][closed-form]") {
  // (B.10) cylinder, (B.4) sphere, (B.16) torus, (B.23) cone: |p| from the formulas, 10,000
  // random points per surface on both sides within the proximity domain.
  std::mt19937 g(4);
  std::uniform_real_distribution<double> ang(0.0, 2 * kPi), unit(0.0, 1.0);
  const double R = 1.5, r = 0.6, H = 3.0, alpha = 0.5;
  const PatchProjector cyl(
      make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), R, H));
  const PatchProjector sph(make_sphere(Vector3d::Zero(), R));
  const PatchProjector tor(make_torus(Vector3d::Zero(), Vector3d::UnitZ(), 3.0, r));
  const PatchProjector con(
      make_cone(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), alpha, 1.0, 3.0));
  int n = 0;
  for (int k = 0; k < 10000; ++k) {
    const double phi = ang(g), t = unit(g);
    {  // cylinder: p = |d| - R (B.10), outward normal, foot height unchanged
      const double rho = R * (0.2 + 1.6 * t), z = 0.05 * H + 0.9 * H * unit(g);
      const Vector3d x(rho * std::cos(phi), rho * std::sin(phi), z);
      const ProjectionResult c = cyl.project(x);
      CHECK(c.status == ProjectionStatus::interior);
      CHECK(c.distance == Approx(rho - R).margin(1e-10));
      CHECK((c.point - Vector3d(R * std::cos(phi), R * std::sin(phi), z)).norm() <= 1e-10);
    }
    {  // sphere: p = |x| - R (B.4)
      const double rho = R * (0.2 + 1.6 * t), th = std::acos(1.8 * unit(g) - 0.9);
      const Vector3d x =
          rho * Vector3d(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th));
      const ProjectionResult c = sph.project(x);
      CHECK(found(c.status));
      CHECK(c.distance == Approx(rho - R).margin(1e-10));
      CHECK((c.point - R * x.normalized()).norm() <= 1e-10);
    }
    {  // torus: p = sqrt(x^2 + y^2 + z^2 + R^2 - 2 R s) - r (B.16)
      const double a = 0.1 * r + 1.8 * r * t, th = ang(g);
      const Vector3d x((3.0 + a * std::cos(th)) * std::cos(phi),
                       (3.0 + a * std::cos(th)) * std::sin(phi), a * std::sin(th));
      const double s = x.head<2>().norm();
      const double p = std::sqrt(x.squaredNorm() + 9.0 - 6.0 * s) - r;
      const ProjectionResult c = tor.project(x);
      CHECK(c.status == ProjectionStatus::interior);
      CHECK(c.distance == Approx(p).margin(1e-10));
    }
    {  // cone: p = s sin(alpha) - z cos(alpha) (B.23), within the frustum's normal band
      const double sg = 1.3 + 1.4 * t, pp = 0.8 * unit(g) - 0.4;  // foot radial distance, offset
      const Vector3d foot(sg * std::cos(phi), sg * std::sin(phi), sg * std::tan(alpha));
      const Vector3d nrm(std::sin(alpha) * std::cos(phi), std::sin(alpha) * std::sin(phi),
                         -std::cos(alpha));
      const Vector3d x = foot + pp * nrm;
      const double p = x.head<2>().norm() * std::sin(alpha) - x.z() * std::cos(alpha);
      const ProjectionResult c = con.project(x);
      CHECK(c.status == ProjectionStatus::interior);
      CHECK(c.distance == Approx(p).margin(1e-10));
      CHECK((c.point - foot).norm() <= 1e-10);
    }
    ++n;
  }
  CHECK(n == 10000);
}

TEST_CASE("PatchProjector: a full cylinder is seamless, warm starts continue across the seam",
          "[contact][closest][seam]") {
  const NurbsSurface s =
      make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0);
  REQUIRE(s.closed_u());
  const PatchProjector P(s);
  for (double phi : {-1e-3, -1e-9, 0.0, 1e-9, 1e-3}) {
    const Vector3d x(1.3 * std::cos(phi), 1.3 * std::sin(phi), 1.0);
    const ProjectionResult r = P.project(x);
    CHECK(r.status == ProjectionStatus::interior);
    CHECK(r.distance == Approx(0.3).epsilon(1e-12));
    // warm start from the other side of the seam
    const ProjectionResult w = P.project(x, Vector2d(phi < 0 ? 0.01 : 0.99, 0.5));
    CHECK(w.status == ProjectionStatus::interior);
    CHECK((w.point - r.point).norm() <= 1e-12);
  }
}

TEST_CASE("ray_project: agrees with the closest point where the normals are parallel",
          "[contact][ray]") {
  const PatchProjector P(test::data_surface("freeform_bicubic.json"));
  std::mt19937 g(5);
  std::uniform_real_distribution<double> u(0.05, 0.95), off(-0.5, 0.5);
  for (int k = 0; k < 500; ++k) {
    const Vector2d uv(u(g), u(g));
    const SurfaceDerivs d = P.surface().derivs(uv[0], uv[1], 1);
    const Vector3d n = d.Su.cross(d.Sv).normalized();
    const double p = off(g);
    const Vector3d x = d.S + p * n;
    // the ray from x along the surface normal at its foot hits the foot at xi3 = -p (2)-(3)
    const ProjectionResult cp = P.project(x);
    const ProjectionResult ray = ray_project(P, x, cp.normal);
    REQUIRE(found(ray.status));
    INFO("ray res " << ray.residual << " it " << ray.iterations << " cp res " << cp.residual
                    << " p " << p);
    CHECK((ray.point - cp.point).norm() <= 1e-10);
    CHECK(ray.distance == Approx(-cp.distance).margin(1e-10));
  }
  // A ray beside the patch misses; a ray inside the plane of a flat patch is tangent or misses.
  const PatchProjector Q(make_plane_patch(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()));
  CHECK(ray_project(Q, Vector3d(2, 2, 1), Vector3d::UnitZ()).status == ProjectionStatus::miss);
  const ProjectionResult t = ray_project(Q, Vector3d(-1, 0.5, 0), Vector3d::UnitX());
  CHECK((t.status == ProjectionStatus::tangent || t.status == ProjectionStatus::miss));
  const ProjectionResult hit = ray_project(Q, Vector3d(0.2, 0.7, 2), Vector3d(0, 0, -2));
  CHECK(hit.status == ProjectionStatus::interior);
  CHECK(hit.distance == Approx(2.0).epsilon(1e-14));  // N normalized: x + 2 (-e_z) = foot
}

TEST_CASE("closest_point on curves: circle, helix, and the ends as vertices",
          "[contact][closest][curve]") {
  const NurbsCurve circle = make_circle(Vector3d::Zero(), Vector3d::UnitZ(), 2.0);
  std::mt19937 g(6);
  std::uniform_real_distribution<double> ang(0, 2 * kPi), rad(0.3, 5.0), z(-1, 1);
  for (int k = 0; k < 1000; ++k) {
    const double a = ang(g), rr = rad(g), zz = z(g);
    const Vector3d x(rr * std::cos(a), rr * std::sin(a), zz);
    const ProjectionResult r = closest_point(circle, x);
    CHECK(r.distance == Approx(std::hypot(rr - 2.0, zz)).epsilon(1e-12));
  }
  const NurbsCurve line = make_line(Vector3d::Zero(), Vector3d(1, 0, 0));
  const ProjectionResult end = closest_point(line, Vector3d(1.5, 1, 0));
  CHECK(end.status == ProjectionStatus::vertex);
  CHECK((end.point - Vector3d(1, 0, 0)).norm() <= 1e-15);
  const HelixApproximation h = make_helix_cubic(1.0, 1.0, kPi, 33);
  const ProjectionResult hr = closest_point(h.curve, Vector3d(0.0, 1.5, 0.25));
  CHECK(hr.status == ProjectionStatus::interior);
  const CurveDerivs d = h.curve.derivs(hr.uv[0], 1);
  CHECK(std::abs((Vector3d(0.0, 1.5, 0.25) - hr.point).dot(d.d[1].normalized())) <= 1e-12);
}

TEST_CASE("PatchProjector: the bilinear NURBS hyperboloid agrees with the paper's Newton (16)-(22)",
          "[contact][closest][closed-form]") {
  // z = a x y over [-10, 10]^2 is exactly a bilinear patch with (u, v) = (x, y) (eq. 11).
  const double a = 0.025;
  const PatchProjector P(make_bilinear_hyperboloid(a, -10.0, 10.0, -10.0, 10.0));
  std::mt19937 g(10);
  std::uniform_real_distribution<double> c(-8.0, 8.0), off(-2.0, 2.0);
  for (int k = 0; k < 10000; ++k) {
    const double x = c(g), y = c(g);
    const Vector3d n = Vector3d(-a * y, -a * x, 1.0).normalized();  // (22)
    const Vector3d pt = Vector3d(x, y, a * x * y) + off(g) * n;
    const ProjectionResult ks = hyperboloid_closest_point_ks(a, pt);
    const ProjectionResult r = P.project(pt);
    REQUIRE(found(ks.status));
    REQUIRE(r.status == ProjectionStatus::interior);
    CHECK((r.uv - ks.uv).norm() <= 1e-10);  // the same parametrization (alpha^1, alpha^2)
    CHECK(r.distance == Approx(ks.distance).margin(1e-10));  // (21)
  }
}

// Issue 12, item 5: points where the sampled search of earlier versions (certify = false)
// returns a local minimum that is not the global one, found by a scan of far points around the
// free-form patch (two local minima closer together than the element's 8 x 8 samples, or a
// warm start from a nearby point whose foot lies elsewhere). The certified search must find
// the global minimum, and say that it proved it.
TEST_CASE("PatchProjector: the certified search finds the global minimum where sampling missed it",
          "[contact][closest][certified]") {
  const NurbsSurface s = test::data_surface("freeform_bicubic.json");
  const PatchProjector P(s);
  const double diag = (P.box().hi - P.box().lo).norm();
  ProjectionOptions sampled;
  sampled.certify = false;
  const Vector3d cold_cases[] = {{-13.946460824523554, -3.9300924040770231, 12.18975641085156},
                                 {-16.82950428695699, 14.659592801944799, -29.793319582974039},
                                 {-12.606001627472773, 6.5081733292075974, -12.506303800945481}};
  for (const Vector3d& x : cold_cases) {
    const double ref = (test::brute_force_closest(s, x, 300, 6).point - x).norm();
    const ProjectionResult r = P.project(x);
    INFO("x = " << x.transpose() << ", sampled search excess "
                << (P.project(x, sampled).point - x).norm() - ref);
    CHECK(r.certified);
    CHECK(found(r.status));
    CHECK((r.point - x).norm() <= ref + 1e-10 * diag);
  }
  struct Warm {
    Vector3d x;
    Vector2d guess;
  };
  const Warm warm_cases[] = {
      {{-25.895779475036864, -0.88747374430823356, 10.243173582345728}, {0, 0.56039396430332022}},
      {{5.3688128882628305, -18.31125535331519, 39.378415438263225}, {0.14169616357413739, 0}},
      {{2.3750700230763724, 41.746017865569435, -8.8208009938278895}, {0.2428250970051781, 1}}};
  for (const Warm& w : warm_cases) {
    const double ref = (test::brute_force_closest(s, w.x, 300, 6).point - w.x).norm();
    const ProjectionResult r = P.project(w.x, w.guess);
    INFO("x = " << w.x.transpose() << ", sampled warm start excess "
                << (P.project(w.x, w.guess, sampled).point - w.x).norm() - ref);
    CHECK(r.certified);
    CHECK((r.point - w.x).norm() <= ref + 1e-10 * diag);
  }
}

TEST_CASE("PatchProjector: certified cold and warm projections on random points are global",
          "[contact][closest][certified][heavy]") {
  // The three point sets of bench_projection (near band, around the box, far), on the
  // polynomial free-form patch and the rational torus, and on both raised to degrees 7 and 8
  // (the nets of degrees above 5: HighNet; CAD files have such faces), against a dense
  // reference.
  const NurbsSurface freeform = test::data_surface("freeform_bicubic.json");
  const NurbsSurface torus = test::data_surface("torus_patch.json");
  const std::pair<const char*, NurbsSurface> patches[] = {
      {"freeform_bicubic.json", freeform},
      {"torus_patch.json", torus},
      {"freeform_bicubic.json raised to degree 7 x 8", elevate_degree(freeform, 4, 5)},
      {"torus_patch.json raised to degree 8 x 7", elevate_degree(torus, 6, 5)}};
  for (const auto& [file, s] : patches) {
    const PatchProjector P(s);
    REQUIRE(P.tree_nodes() > 0);
    const Box3 box = P.box();
    const Vector3d c = 0.5 * (box.lo + box.hi);
    const double diag = (box.hi - box.lo).norm(), size = (box.hi - box.lo).maxCoeff();
    const Domain2 dom = s.domain();
    std::mt19937 g(2026);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int misses = 0, unproven = 0, n = 0;
    for (int set = 0; set < 3; ++set)
      for (int i = 0; i < 150; ++i, ++n) {
        Vector3d x;
        if (set == 0) {
          const SurfaceDerivs d = s.derivs(dom.u.lo + U(g) * (dom.u.hi - dom.u.lo),
                                           dom.v.lo + U(g) * (dom.v.hi - dom.v.lo), 1);
          x = d.S + (2 * U(g) - 1) * 0.05 * size * d.Su.cross(d.Sv).normalized();
        } else if (set == 1) {
          x = random_in_box(g, box, 0.3);
        } else {
          const Vector3d dir(U(g) - 0.5, U(g) - 0.5, U(g) - 0.5);
          x = c + (1.0 + 2.0 * U(g)) * diag * dir.normalized();
        }
        const Vector3d near =
            x + 0.01 * size * Vector3d(U(g) - 0.5, U(g) - 0.5, U(g) - 0.5).normalized();
        const double ref = (test::brute_force_closest(s, x, 150, 4).point - x).norm();
        const ProjectionResult cold = P.project(x);
        const ProjectionResult warm = P.project(x, P.project(near).uv);
        misses += (cold.point - x).norm() > ref + 1e-10 * diag;
        misses += (warm.point - x).norm() > ref + 1e-10 * diag;
        unproven += !cold.certified + !warm.certified;
      }
    INFO(file << ": " << n << " points");
    CHECK(misses == 0);
    CHECK(unproven == 0);
  }
}

TEST_CASE("patch_bounds: a rational patch's derivative boxes are tight enough for the chord test",
          "[contact][closest][certified]") {
  // The derivatives of a rational patch bounded as rational Bezier functions (numerators over
  // w^2 and w^3): on every quarter of a quarter of the torus's elements (22.5 degrees of arc),
  // the boxes of S_u and S_v prove the Gram matrix positive definite, so the chord test holds
  // on the surface (r* = 0) and 1 % of the tube radius off it. The interval quotient rule
  // alone gave S_u in [11, 24] x [-4.3, 4.9] for |S_u| = 17 there and failed.
  const NurbsSurface s = test::data_surface("torus_patch.json");
  int pieces = 0;
  for (const BezierPatch& b : bezier_extract(s)) {
    detail::Net net, half[2], quarter[4], sixteenth[16];
    REQUIRE(detail::to_net(b, net));
    detail::split_half(net, 0, half[0], half[1]);
    for (int i = 0; i < 2; ++i) detail::split_half(half[i], 1, quarter[2 * i], quarter[2 * i + 1]);
    int k = 0;
    for (const detail::Net& q : quarter) {
      detail::Net lo, hi;
      detail::split_half(q, 0, lo, hi);
      detail::split_half(lo, 1, sixteenth[k], sixteenth[k + 1]);
      detail::split_half(hi, 1, sixteenth[k + 2], sixteenth[k + 3]);
      k += 4;
    }
    for (const detail::Net& n : sixteenth) {
      const SurfaceDerivs dc =
          s.derivs(0.5 * (n.range.u.lo + n.range.u.hi), 0.5 * (n.range.v.lo + n.range.v.hi), 1);
      const detail::PatchBounds pb = detail::patch_bounds(n, detail::tangent_frame(dc));
      const Vector3d normal = dc.Su.cross(dc.Sv).normalized();
      CHECK(detail::chord_test(pb, Vector3d::Zero()));
      CHECK(detail::chord_test(pb, 0.01 * normal));
      CHECK(detail::chord_test(pb, -0.01 * normal));
      ++pieces;
    }
  }
  CHECK(pieces == 256);
}

namespace {
// A hairpin: two flat sheets z = 0 and z = 1, x in [0, 4], y in [0, 1], joined by a bend at
// x < 0 (quadratic in u, extruded in y).
NurbsSurface hairpin() {
  const std::vector<Vector3d> polygon = {{4, 0, 0},  {2, 0, 0}, {0, 0, 0}, {-1, 0, 0},
                                         {-1, 0, 1}, {0, 0, 1}, {2, 0, 1}, {4, 0, 1}};
  std::vector<Vector3d> pts;
  for (double y : {0.0, 1.0})
    for (const Vector3d& q : polygon) pts.push_back(q + Vector3d(0, y, 0));
  return {2, {0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6}, 1, {0, 0, 1, 1}, pts};
}
}  // namespace

TEST_CASE("PatchProjector: a warm start on the farther of two sheets is not certified as it is",
          "[contact][closest][certified]") {
  // A hairpin: two flat sheets z = 0 and z = 1 joined by a bend (quadratic in u, extruded in
  // y). From x between them, 0.7 above the lower sheet and 0.3 below the upper one, a warm
  // start on the lower sheet converges to its foot, a local minimum that passes the chord
  // test on its region; the certificate without a search must refuse it (the upper sheet,
  // outside the region, is closer than half the region's gap allows), and the search must
  // return the upper foot, certified.
  const NurbsSurface s = hairpin();
  const PatchProjector P(s);
  const Vector3d x(2.5, 0.5, 0.7);
  const ProjectionResult local = closest_point_local(s, x, Vector2d(0.5, 0.5));
  REQUIRE(found(local.status));
  REQUIRE(std::abs(local.point.z()) < 1e-12);  // the lower sheet's foot: a local minimum
  const ProjectionResult warm = P.project(x, Vector2d(0.5, 0.5));
  CHECK(warm.certified);
  CHECK(warm.point.z() == Approx(1.0).margin(1e-12));
  CHECK((warm.point - x).norm() == Approx(0.3).epsilon(1e-12));
  // From the upper sheet's own foot the certificate holds at once.
  const ProjectionResult upper = P.project(x, warm.uv);
  CHECK(upper.certified);
  CHECK((upper.point - warm.point).norm() < 1e-12);
}

TEST_CASE("PatchProjector: warm starts on the farther sheet, completed among the pieces left",
          "[contact][closest][certified]") {
  // The hairpin above, from many points between the sheets nearer the upper one, each warm
  // started on the lower sheet's foot below it: the local Newton returns that foot, the ball
  // test fails on the upper sheet's pieces (closer than the foot), and the search among them
  // (or the whole search where they are too many) must return the upper foot, certified, as
  // the cold search does. Points nearer the lower sheet keep the lower foot.
  const NurbsSurface s = hairpin();
  const PatchProjector P(s);
  std::mt19937 g(17);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int wrong = 0, unproven = 0, differ = 0;
  for (int i = 0; i < 400; ++i) {
    const double z = 0.05 + 0.9 * U(g);
    const Vector3d x(0.8 + 3.0 * U(g), 0.05 + 0.9 * U(g), z);
    const ProjectionResult below = P.project(Vector3d(x.x(), x.y(), -0.1));
    REQUIRE(std::abs(below.point.z()) < 1e-9);
    const ProjectionResult warm = P.project(x, below.uv);
    const ProjectionResult cold = P.project(x);
    wrong += std::abs((warm.point - x).norm() - std::min(z, 1.0 - z)) > 1e-10;
    unproven += !warm.certified;
    differ += (warm.point - cold.point).norm() > 1e-9;
  }
  CHECK(wrong == 0);
  CHECK(unproven == 0);
  CHECK(differ == 0);
}

TEST_CASE("PatchProjector: the tree and its memory", "[contact][closest][certified]") {
  // The torus (16 biquadratic elements) is subdivided four levels deep, 16 (1 + 4 + ... + 256)
  // nodes; the free-form patch (25 bicubic elements) three levels (the node budget).
  const PatchProjector torus(test::data_surface("torus_patch.json"));
  CHECK(torus.tree_nodes() == 16 * 341);
  const PatchProjector freeform(test::data_surface("freeform_bicubic.json"));
  CHECK(freeform.tree_nodes() == 25 * 85);
  CHECK(torus.memory_bytes() > torus.tree_nodes() * sizeof(detail::Net));
  CHECK(torus.memory_bytes() < std::size_t{64} << 20);
  // Raised to degree 8 its nodes hold bigger nets (HighNet): the same budget in bytes gives
  // three levels, 16 (1 + 4 + 16 + 64) nodes.
  const PatchProjector high(elevate_degree(test::data_surface("torus_patch.json"), 6, 6));
  CHECK(high.tree_nodes() == 16 * 85);
  CHECK(high.memory_bytes() > high.tree_nodes() * sizeof(detail::HighNet));
  CHECK(high.memory_bytes() < std::size_t{64} << 20);
}

TEST_CASE("PatchProjector: a smaller tree budget gives shallower trees and the same feet",
          "[contact][closest][certified]") {
  // The budget the fuzz targets set (fuzz/fuzz_caps.hpp): the torus's 16 elements get a tree
  // one level deep with 80 nodes, none below the elements with 16; the default comes back.
  const NurbsSurface s = test::data_surface("torus_patch.json");
  const PatchProjector full(s);
  REQUIRE(PatchProjector::tree_budget() == PatchProjector::kTreeNodes);
  PatchProjector::set_tree_budget(80);
  const PatchProjector shallow(s);
  PatchProjector::set_tree_budget(0);
  const PatchProjector flat(s);
  PatchProjector::set_tree_budget(PatchProjector::kTreeNodes);
  CHECK(shallow.tree_nodes() == 16 * 5);
  CHECK(flat.tree_nodes() == 16);
  CHECK(PatchProjector(s).tree_nodes() == full.tree_nodes());
  const Box3 box = full.box();
  const double diag = (box.hi - box.lo).norm();
  std::mt19937 g(34);
  int n = 0;
  for (const PatchProjector* P : {&shallow, &flat})
    for (int i = 0; i < 100; ++i, ++n) {
      const Vector3d x = random_in_box(g, box, 0.3);
      const ProjectionResult a = full.project(x), b = P->project(x);
      INFO("point " << n);
      CHECK(b.certified);
      CHECK(std::abs((b.point - x).norm() - (a.point - x).norm()) <= 1e-10 * diag);
    }
}

TEST_CASE("patch_bounds: the boxes hold the patch's points and derivatives (sampled check)",
          "[contact][closest][certified]") {
  // The interval bounds of S and its first and second derivatives over a Bezier element must
  // hold every sampled value, on a rational element (torus) and a polynomial one, whole and
  // after de Casteljau halving in u and v; and the bounds of pieces from the whole's
  // (patch_bounds_within, as the certified search takes them below its tree), nested twice.
  for (const char* file : {"freeform_bicubic.json", "torus_patch.json"}) {
    const NurbsSurface s = test::data_surface(file);
    for (const BezierPatch& b : bezier_extract(s)) {
      detail::Net net, lo, hi;
      REQUIRE(detail::to_net(b, net));
      detail::split_half(net, 0, lo, hi);
      detail::Net lo_lo, lo_hi;
      detail::split_half(lo, 1, lo_lo, lo_hi);
      // whole, halves, and the whole in a turned frame (the boxes are taken in that frame)
      const Eigen::Matrix3d turn =
          Eigen::AngleAxisd(0.7, Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
      const detail::PatchBounds turned = detail::patch_bounds(net, turn);
      const detail::PatchBounds lo_within = detail::patch_bounds_within(lo, turned);
      for (int variant = 0; variant < 6; ++variant) {
        const detail::Net* n = variant == 1 || variant == 4 ? &lo
                               : variant == 2               ? &hi
                               : variant == 5               ? &lo_hi
                                                            : &net;
        const Eigen::Matrix3d frame = variant >= 3 ? turn : Eigen::Matrix3d::Identity();
        const detail::PatchBounds pb = variant == 4 ? lo_within
                                       : variant == 5
                                           ? detail::patch_bounds_within(lo_hi, lo_within)
                                           : detail::patch_bounds(*n, frame);
        auto inside = [&](const detail::IVec3& box, const Vector3d& v) {
          bool ok = true;
          for (int k = 0; k < 3; ++k) {
            const double slack = 1e-9 * (1.0 + std::abs(box.c[k].lo) + std::abs(box.c[k].hi));
            ok = ok && v[k] >= box.c[k].lo - slack && v[k] <= box.c[k].hi + slack;
          }
          return ok;
        };
        for (int j = 0; j <= 6; ++j)
          for (int i = 0; i <= 6; ++i) {
            const double u = n->range.u.lo + (n->range.u.hi - n->range.u.lo) * i / 6.0;
            const double v = n->range.v.lo + (n->range.v.hi - n->range.v.lo) * j / 6.0;
            const SurfaceDerivs d = s.derivs(u, v, 2);
            CHECK(inside(pb.S, frame * (d.S - pb.centre)));
            CHECK(inside(pb.Su, frame * d.Su));
            CHECK(inside(pb.Sv, frame * d.Sv));
            CHECK(inside(pb.Suu, frame * d.Suu));
            CHECK(inside(pb.Suv, frame * d.Suv));
            CHECK(inside(pb.Svv, frame * d.Svv));
          }
      }
    }
  }
}

}  // namespace test_closest_point
