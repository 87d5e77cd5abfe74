// The CTRS point law ([KS15] (34)-(36), (52), (66)-(67)): physics of the penalty and the
// return mapping, and the consistent tangent df/dr against central finite differences of the
// force recomputed with a fresh closest point projection.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "contact/closest_point.hpp"
#include "contact/contact_law.hpp"
#include "contact/rigid_surface.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_contact_law {

using namespace iga;

namespace {

/// The law's constants and the rope's radius R in the gap (52).
struct Law {
  ContactParameters p;
  double radius = 0.0;
};

ContactPoint at(const Surface& s, const Vector3d& r, const Vector2d& guess, const Law& p,
                const ContactHistory& h, double lambda_n = 0.0,
                const Vector3d* lambda_t = nullptr) {
  ProjectionResult f = closest_point_local(s, r, guess);
  f.patch = 0;
  return evaluate_contact(s, f, r, p.p, h, lambda_n, lambda_t, nullptr, p.radius);
}

// max |K - K_fd| / max(|K|, eps_n) over the columns.
double tangent_error(const Surface& s, const Vector3d& r, const Vector2d& guess, const Law& p,
                     const ContactHistory& h, bool& slip, double lambda_n = 0.0,
                     const Vector3d* lambda_t = nullptr) {
  const ContactPoint c = at(s, r, guess, p, h, lambda_n, lambda_t);
  slip = c.slip;
  const double step = 1e-6;
  Matrix3d fd;
  for (int k = 0; k < 3; ++k) {
    const Vector3d e = Vector3d::Unit(k) * step;
    fd.col(k) = (at(s, r + e, c.xi, p, h, lambda_n, lambda_t).force -
                 at(s, r - e, c.xi, p, h, lambda_n, lambda_t).force) /
                (2 * step);
  }
  return (fd - c.stiffness).cwiseAbs().maxCoeff() /
         std::max(c.stiffness.cwiseAbs().maxCoeff(), p.p.eps_n);
}

}  // namespace

TEST_CASE("contact law: frictionless penalty force along the normal (34), (52)", "[contact][law]") {
  const Cylinder cyl(Placement{}, 2.0);
  const Law p{{1000.0, 0.0, 0.0}, 0.1};
  ContactHistory h;
  // a rope of radius 0.1 whose centre is 2.05 from the axis penetrates by 0.05
  const ContactPoint c = at(cyl, Vector3d(2.05, 0.0, 0.3), Vector2d(0.1, 0.3), p, h);
  REQUIRE(c.active);
  CHECK(c.gap == Approx(-0.05).epsilon(1e-12));
  CHECK(c.N == Approx(-50.0).epsilon(1e-12));
  CHECK((c.force - Vector3d(50.0, 0, 0)).norm() <= 1e-9);  // pushes the rope outward
  const ContactPoint free = at(cyl, Vector3d(2.2, 0.0, 0.3), Vector2d(0.1, 0.3), p, h);
  CHECK(!free.active);
  CHECK(free.force.norm() == 0.0);
}

TEST_CASE(
    "contact law: stick below and slip on the Coulomb cone (35)-(36), friction opposes "
    "sliding",
    "[contact][law]") {
  const Cylinder cyl(Placement{}, 2.0);
  const Law p{{1000.0, 1000.0, 0.3}, 0.0};
  ContactHistory h;
  h.active = true;
  h.patch = 0;
  h.xi = Vector2d(0.5, 0.0);
  h.foot = cyl.point(0.5, 0.0);
  for (double slide : {1e-4, 1e-3, 1e-1}) {
    // the point moved along the axis by `slide` since the last converged step, pressing 0.01
    const Vector3d r =
        (2.0 - 0.01) * Vector3d(std::cos(0.5), std::sin(0.5), 0.0) + Vector3d(0, 0, slide);
    const ContactPoint c = at(cyl, r, h.xi, p, h);
    REQUIRE(c.active);
    const double absN = -c.N, Tn = c.T_vector.norm();
    CHECK(absN == Approx(10.0).epsilon(1e-9));
    if (1000.0 * slide <= 0.3 * absN) {
      CHECK(!c.slip);
      CHECK(Tn == Approx(1000.0 * slide).epsilon(1e-9));  // eps_T times the slide (metric 1)
    } else {
      CHECK(c.slip);
      CHECK(Tn == Approx(0.3 * absN).epsilon(1e-12));  // on the cone
    }
    CHECK(c.T_vector.z() < 0.0);  // opposes the motion along +z
  }
}

TEST_CASE("contact law: the tangent df/dr matches finite differences (normal, stick, slip)",
          "[contact][law][tangent]") {
  std::mt19937 g(21);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double pi = std::numbers::pi;
  const Torus torus(Placement{}, 3.0, 1.0);
  const NurbsSurface nurbs =
      make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 2.0, 4.0);
  const Surface* surfaces[2] = {&torus, &nurbs};
  int n_slip = 0, n_stick = 0;
  for (const Surface* s : surfaces) {
    for (int k = 0; k < 200; ++k) {
      const Domain2 dom = s->domain();
      const Vector2d uv(dom.u.lo + (0.1 + 0.8 * U(g)) * (dom.u.hi - dom.u.lo),
                        s == &torus ? 2 * pi * U(g) : 0.2 + 0.6 * U(g));
      const SurfaceDerivs d = s->derivs(uv[0], uv[1], 1);
      const Vector3d n = s->normal_sign() * d.Su.cross(d.Sv).normalized();
      const Law p{{500.0, 300.0, 0.4}, 0.05};
      const Vector3d r = d.S + (0.05 - 0.02 * U(g)) * n;  // penetrating by up to 0.02
      ContactHistory h;
      h.active = U(g) < 0.7;
      h.patch = 0;
      h.xi = uv + 0.02 * Vector2d(U(g) - 0.5, U(g) - 0.5);
      h.foot = s->point(h.xi[0], h.xi[1]);
      h.T = Vector2d(U(g) - 0.5, U(g) - 0.5);
      h.T_vector = Vector3d(d.Su * h.T[0] + d.Sv * h.T[1]);
      bool slip = false;
      const double err = tangent_error(*s, r, uv, p, h, slip);
      const ContactPoint c = at(*s, r, uv, p, h);
      INFO("slip " << slip << " err " << err << " gap " << c.gap << " phi " << c.phi);
      // The law has kinks at gap = 0 and where the trial force meets the Coulomb cone
      // (phi = 0); central differences that straddle one are meaningless: skip those points.
      if (std::abs(c.gap) < 1e-4 || std::abs(c.phi) < 1e-3 * p.p.mu * std::abs(c.N)) continue;
      (slip ? n_slip : n_stick)++;
      CHECK(err <= 1e-6);
    }
  }
  CHECK(n_slip > 20);  // both branches of the return mapping are exercised
  CHECK(n_stick > 20);
}

TEST_CASE("contact law: augmented normal force N = min(0, lambda_N + eps_N gap) ((34) augmented)",
          "[contact][law][augmented]") {
  const Cylinder cyl(Placement{}, 2.0);
  const Law p{{1000.0, 0.0, 0.0}, 0.1};
  ContactHistory h;
  // lambda_N = 0 is the penalty law, bit for bit (the option off changes nothing)
  const Vector3d r_in(2.05, 0.0, 0.3);
  const ContactPoint c0 = at(cyl, r_in, Vector2d(0.1, 0.3), p, h);
  const ContactPoint c00 = at(cyl, r_in, Vector2d(0.1, 0.3), p, h, 0.0);
  CHECK(c0.N == c00.N);
  CHECK(c0.force == c00.force);
  CHECK(c0.stiffness == c00.stiffness);
  // penetrating by 0.05 with lambda_N = -30: N = -30 - 50
  const ContactPoint c = at(cyl, r_in, Vector2d(0.1, 0.3), p, h, -30.0);
  REQUIRE(c.active);
  CHECK(c.N == Approx(-80.0).epsilon(1e-12));
  CHECK((c.force - Vector3d(80.0, 0, 0)).norm() <= 1e-9);
  // 0.02 apart: still pressed by the multiplier, N = -30 + 1000 * 0.02 = -10
  const ContactPoint apart = at(cyl, Vector3d(2.12, 0.0, 0.3), Vector2d(0.1, 0.3), p, h, -30.0);
  REQUIRE(apart.active);
  CHECK(apart.gap == Approx(0.02).epsilon(1e-12));
  CHECK(apart.N == Approx(-10.0).epsilon(1e-12));
  // 0.04 apart: lambda_N + eps_N gap = +10 > 0, no force
  const ContactPoint free = at(cyl, Vector3d(2.14, 0.0, 0.3), Vector2d(0.1, 0.3), p, h, -30.0);
  CHECK(!free.active);
  CHECK(free.force.norm() == 0.0);
}

TEST_CASE(
    "contact law: the augmented tangent df/dr matches finite differences (normal, stick, "
    "slip, gaps of both signs)",
    "[contact][law][tangent][augmented]") {
  std::mt19937 g(22);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double pi = std::numbers::pi;
  const Torus torus(Placement{}, 3.0, 1.0);
  const NurbsSurface nurbs =
      make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 2.0, 4.0);
  const Surface* surfaces[2] = {&torus, &nurbs};
  int n_slip = 0, n_stick = 0, n_apart = 0;
  for (const Surface* s : surfaces) {
    for (int k = 0; k < 200; ++k) {
      const Domain2 dom = s->domain();
      const Vector2d uv(dom.u.lo + (0.1 + 0.8 * U(g)) * (dom.u.hi - dom.u.lo),
                        s == &torus ? 2 * pi * U(g) : 0.2 + 0.6 * U(g));
      const SurfaceDerivs d = s->derivs(uv[0], uv[1], 1);
      const Vector3d n = s->normal_sign() * d.Su.cross(d.Sv).normalized();
      const Law p{{500.0, 300.0, 0.4}, 0.05};
      const double lambda = -10.0 * U(g);                        // up to 0.02 eps_N
      const Vector3d r = d.S + (0.05 - 0.02 + 0.04 * U(g)) * n;  // gap in (-0.02, 0.02)
      ContactHistory h;
      h.active = U(g) < 0.7;
      h.patch = 0;
      h.xi = uv + 0.02 * Vector2d(U(g) - 0.5, U(g) - 0.5);
      h.foot = s->point(h.xi[0], h.xi[1]);
      h.T = Vector2d(U(g) - 0.5, U(g) - 0.5);
      h.T_vector = Vector3d(d.Su * h.T[0] + d.Sv * h.T[1]);
      bool slip = false;
      const ContactPoint c = at(*s, r, uv, p, h, lambda);
      // kinks at lambda_N + eps_N gap = 0 and phi = 0: skip points next to them
      if (!c.active || std::abs(lambda + p.p.eps_n * c.gap) < 1e-4 * p.p.eps_n ||
          std::abs(c.phi) < 1e-3 * p.p.mu * std::abs(c.N))
        continue;
      const double err = tangent_error(*s, r, uv, p, h, slip, lambda);
      INFO("slip " << slip << " err " << err << " gap " << c.gap << " lambda " << lambda);
      CHECK(c.N == Approx(lambda + p.p.eps_n * c.gap).epsilon(1e-12));
      if (c.gap > 0.0) ++n_apart;
      (slip ? n_slip : n_stick)++;
      CHECK(err <= 1e-6);
    }
  }
  CHECK(n_slip > 20);  // both branches of the return mapping are exercised
  CHECK(n_stick > 20);
  CHECK(n_apart > 10);  // active points held by their multiplier above the surface
}

namespace {

// The committed state of a point anchored at the foot of `anchor` on `rigid`, with the
// committed tangential force T_(n) = length * (the tangential part of dir, normalized); the
// parameter form xi_(n), T^i_(n) is filled in as well (what the parameter law (54), (66) used).
ContactHistory anchored(const RigidSurface& rigid, const Vector3d& anchor, const Vector3d& dir,
                        double length) {
  const ProjectionResult f = rigid.closest_point(anchor);
  const SurfaceDerivs d = rigid.patch(f.patch).derivs(f.uv[0], f.uv[1], 1);
  Eigen::Matrix<double, 3, 2> J;
  J << d.Su, d.Sv;
  const Vector3d n = d.Su.cross(d.Sv).normalized();
  const Vector3d t = (dir - dir.dot(n) * n).normalized() * length;
  ContactHistory h;
  h.active = true;
  h.patch = f.patch;
  h.xi = f.uv;
  h.foot = d.S;
  h.T_vector = t;
  h.T = (J.transpose() * J).inverse() * (J.transpose() * t);
  return h;
}

ContactPoint evaluate_on(const RigidSurface& rigid, const Vector3d& r, const ContactParameters& p,
                         const ContactHistory& h) {
  const ProjectionResult f = rigid.closest_point(r);
  return evaluate_contact(rigid.patch(f.patch), f, r, p, h);
}

// The force and its tangent of one physical state evaluated on two parametrizations of one
// surface: the largest difference relative to the force's size and to eps_N.
void check_same_law(const RigidSurface& a, const RigidSurface& b, const Vector3d& anchor,
                    const Vector3d& r, const Vector3d& dir, const ContactParameters& p,
                    bool expect_slip) {
  const ContactPoint ca = evaluate_on(a, r, p, anchored(a, anchor, dir, 2.0));
  const ContactPoint cb = evaluate_on(b, r, p, anchored(b, anchor, dir, 2.0));
  REQUIRE(ca.active);
  REQUIRE(cb.active);
  CHECK(ca.slip == expect_slip);
  CHECK(cb.slip == expect_slip);
  INFO("force a " << ca.force.transpose() << ", b " << cb.force.transpose());
  // Both are the same function of the geometry; what differs is round-off of the
  // projections and of two parametrizations' derivatives.
  CHECK((ca.force - cb.force).norm() <= 1e-9 * ca.force.norm());
  CHECK((ca.T_vector - cb.T_vector).norm() <= 1e-9 * ca.force.norm());
  CHECK((ca.stiffness - cb.stiffness).cwiseAbs().maxCoeff() <= 1e-7 * p.eps_n);
}

}  // namespace

TEST_CASE(
    "contact law: friction across a sphere's pole equals friction on a sphere whose pole "
    "is elsewhere (spatial history)",
    "[contact][law][friction]") {
  // Anchor 0.01 rad from the pole +z on the +x side, the point now 0.005 rad past the pole on
  // the -x side, 1e-3 inside: in the parameters of sphere a the foot jumped by pi in the angle
  // about the axis; sphere b (axis e_x) has no singular point near. Stick and slip.
  constexpr double kPi = std::numbers::pi;
  RigidSurface a, b;
  a.add(Sphere(Placement{Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX()}, 1.0));
  b.add(Sphere(Placement{Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()}, 1.0));
  const Vector3d anchor(std::sin(0.01), 0.0, std::cos(0.01));
  const Vector3d r = 0.999 * Vector3d(-std::sin(0.005), 0.0, std::cos(0.005));
  const Vector3d dir(0.3, 1.0, 0.0);  // committed force, partly along the slide
  check_same_law(a, b, anchor, r, dir, ContactParameters{1e4, 100.0, 1.0}, false);
  check_same_law(a, b, anchor, r, dir, ContactParameters{1e4, 1e4, 1.0}, true);
  // The same on the NURBS sphere (poles on its axis e_z) against the analytic sphere b.
  RigidSurface c;
  c.add(make_sphere(Vector3d::Zero(), 1.0));
  check_same_law(c, b, anchor, r, dir, ContactParameters{1e4, 100.0, 1.0}, false);
  check_same_law(c, b, anchor, r, dir, ContactParameters{1e4, 1e4, 1.0}, true);
  (void)kPi;
}

TEST_CASE(
    "contact law: friction across a patch border and a seam equals friction on one patch "
    "(spatial history)",
    "[contact][law][friction]") {
  // A cylinder of radius 1 about e_z as one full NURBS patch (seam at +x) and as four patches
  // with borders at 45, 135, 225 and 315 degrees; the anchor 0.01 rad before a border, the point
  // 0.005 rad past it (another patch), 1e-3 inside; then the same across the seam of the one
  // patch against the four patches.
  constexpr double kPi = std::numbers::pi;
  RigidSurface one, four;
  one.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  for (int k = 0; k < 4; ++k)
    four.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0,
                           kPi / 4 + k * kPi / 2, kPi / 4 + (k + 1) * kPi / 2));
  auto at_angle = [](double t, double s) {
    return Vector3d(s * std::cos(t), s * std::sin(t), 0.1);
  };
  const Vector3d dir(0.0, 1.0, 0.5);
  for (double border : {kPi / 4, 3 * kPi / 4, 0.0}) {
    INFO("border at " << border);
    const Vector3d anchor = at_angle(border - 0.01, 1.0), r = at_angle(border + 0.005, 0.999);
    const bool other_patch = four.closest_point(anchor).patch != four.closest_point(r).patch;
    REQUIRE((other_patch || border == 0.0));
    check_same_law(four, one, anchor, r, dir, ContactParameters{1e4, 100.0, 1.0}, false);
    check_same_law(four, one, anchor, r, dir, ContactParameters{1e4, 1e4, 1.0}, true);
  }
}

TEST_CASE(
    "contact law: the spatial friction tangent = central differences across a pole and a "
    "patch border",
    "[contact][law][friction]") {
  // Sphere a of the pole test, the anchor on the other side of the pole; then the four-patch
  // cylinder with the anchor on the neighbouring patch. Stick and slip.
  RigidSurface a, four;
  a.add(Sphere(Placement{Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX()}, 1.0));
  constexpr double kPi = std::numbers::pi;
  for (int k = 0; k < 4; ++k)
    four.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0,
                           kPi / 4 + k * kPi / 2, kPi / 4 + (k + 1) * kPi / 2));
  struct Case {
    const RigidSurface* s;
    Vector3d anchor, r;
  };
  const Case cases[] = {
      {&a, Vector3d(std::sin(0.01), 0.0, std::cos(0.01)),
       0.999 * Vector3d(-std::sin(0.005), 0.003, std::cos(0.005))},
      {&four, Vector3d(std::cos(kPi / 4 - 0.01), std::sin(kPi / 4 - 0.01), 0.1),
       Vector3d(0.999 * std::cos(kPi / 4 + 0.005), 0.999 * std::sin(kPi / 4 + 0.005), 0.1)}};
  for (const Case& k : cases)
    for (double eps_t : {100.0, 1e4}) {
      const ContactParameters p{1e4, eps_t, 1.0};
      const ContactHistory h = anchored(*k.s, k.anchor, Vector3d(0.3, 1.0, 0.2), 2.0);
      const ContactPoint c = evaluate_on(*k.s, k.r, p, h);
      REQUIRE(c.active);
      CHECK(c.slip == (eps_t > 1e3));
      const double step = 1e-6;
      Matrix3d fd;
      for (int j = 0; j < 3; ++j) {
        const Vector3d e = Vector3d::Unit(j) * step;
        fd.col(j) =
            (evaluate_on(*k.s, k.r + e, p, h).force - evaluate_on(*k.s, k.r - e, p, h).force) /
            (2 * step);
      }
      INFO("eps_t " << eps_t << "\nK\n" << c.stiffness << "\nFD\n" << fd);
      CHECK((fd - c.stiffness).cwiseAbs().maxCoeff() <= 1e-6 * p.eps_n);
    }
}

TEST_CASE(
    "contact law: the tangential multiplier lambda_T takes the place of T_(n) in (66), the "
    "tangent matches finite differences in stick and slip",
    "[contact][law][tangent][augmented]") {
  const Cylinder cyl(Placement{}, 2.0);
  const Law p{{1000.0, 100.0, 0.4}, 0.1};
  ContactHistory h;
  h.active = true;
  h.patch = 0;
  h.foot = cyl.point(0.0, 0.31);         // the anchor, 0.01 below the foot along the axis
  h.T_vector = Vector3d(0.0, 0.0, 2.0);  // the committed force, along the axis
  const Vector3d r(2.09, 0.0, 0.32);     // penetrating by 0.01: N = -10, mu |N| = 4
  // lambda_T equal to T_(n): the same law bit for bit; the slip since the anchor reported
  const ContactPoint c0 = at(cyl, r, Vector2d(0.0, 0.3), p, h);
  const ContactPoint c1 = at(cyl, r, Vector2d(0.0, 0.3), p, h, 0.0, &h.T_vector);
  CHECK(c0.force == c1.force);
  CHECK(c1.slip_distance == Approx(0.01).epsilon(1e-9));
  REQUIRE(!c0.slip);
  CHECK((c0.T_vector - Vector3d(0.0, 0.0, 1.0)).norm() < 1e-9);  // T_(n) - eps_T g_T (66)
  // another multiplier: T_tr = lambda_T - eps_T g_T (tangent to the cylinder here)
  const Vector3d lt(0.0, 1.0, 1.0);
  const ContactPoint c2 = at(cyl, r, Vector2d(0.0, 0.3), p, h, 0.0, &lt);
  REQUIRE(!c2.slip);
  CHECK((c2.T_vector - Vector3d(0.0, 1.0, 0.0)).norm() < 1e-9);
  for (const Vector3d& l : {Vector3d(0.0, 1.0, 1.0), Vector3d(0.0, 3.0, -6.0)}) {  // stick, slip
    bool slip = false;
    const double err = tangent_error(cyl, r, Vector2d(0.0, 0.3), p, h, slip, -3.0, &l);
    INFO("lambda_T " << l.transpose() << (slip ? " slip" : " stick") << ", error " << err);
    CHECK(err < 1e-6);
    CHECK(slip == (l.y() > 2.0));
  }
}

}  // namespace test_contact_law
