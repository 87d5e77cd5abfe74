// The STAS contact integral of a deformable NURBS surface against a rigid surface ([KS15]
// Sects. 2-3): its tangent against central finite differences of its residual for both
// strategies, frictionless / stick / slip, the three faces, on a plane, a hyperboloid (bilinear
// NURBS patch and analytic) and a sphere; a multi-patch rigid surface against the single patch;
// resultants of a uniformly pressed and of a sheared plate; master against slave; the pair of a
// moving, rotating tool (residual turned with the motion, tangent against differences).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <utility>

#include <omp.h>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/contact_integrals/surface_contact.hpp"
#include "iga/contact_integrals/surface_contact_pair.hpp"
#include "tests/iga/contact_integrals/moving_pair.hpp"
#include "tests/iga/contact_integrals/pass_through_case.hpp"
#include "tests/iga/fd_tangent.hpp"
#include "tests/iga/same_bits.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_surface_contact {

using namespace iga;
using iga::test::residual;
using iga::test::tangent_error;

namespace {

using Strategy = SurfaceContactStrategy;

// A bicubic plate over [x0, x1] x [y0, y1] with n_el x n_el elements at height z(x, y), z a
// bilinear function (represented exactly: its control points are its values at the Greville
// points). flip: u runs along y, so that the normal a1 x a2 is -e_z instead of +e_z.
NurbsSurface plate(double x0, double x1, double y0, double y1, int n_el, bool flip,
                   const std::function<double(double, double)>& z) {
  std::vector<Vector3d> P;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      P.emplace_back(flip ? (j ? x1 : x0) : (i ? x1 : x0), flip ? (i ? y1 : y0) : (j ? y1 : y0),
                     0.0);
  NurbsSurface s(1, {0, 0, 1, 1}, 1, {0, 0, 1, 1}, P);
  s = subdivide(elevate_degree(s, 2, 2), n_el, n_el);
  std::vector<Vector3d> X = s.control_points();
  for (Vector3d& q : X) q.z() = z(q.x(), q.y());
  return NurbsSurface(3, s.knots_u().knots(), 3, s.knots_v().knots(), X);
}

Vector3d resultant(const Eigen::VectorXd& R) {
  Vector3d s = Vector3d::Zero();
  for (Eigen::Index a = 0; a < R.size() / 3; ++a) s += R.segment<3>(3 * a);
  return s;
}

/// The plate's control points perturbed randomly (x), and the same shifted tangentially by
/// `shift` (x0: where the friction history is committed).
std::pair<std::vector<Vector3d>, std::vector<Vector3d>> perturbed_states(const NurbsSurface& ref,
                                                                         double shift) {
  std::mt19937 g(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<Vector3d> x = ref.control_points();
  for (Vector3d& q : x) q += 0.003 * Vector3d(U(g), U(g), U(g));
  std::vector<Vector3d> x0 = x;
  for (Vector3d& q : x0) q += shift * Vector3d(1.0, 0.5, 0.0);
  return {x, x0};
}

const char* name(Strategy s) {
  return s == Strategy::kRigidMaster ? "master" : "slave";
}
const char* name(ShellFace f) {
  return f == ShellFace::kLower ? "lower" : f == ShellFace::kUpper ? "upper" : "mid";
}

}  // namespace

TEST_CASE("SurfaceContact: tangent = d(residual)/dx for both strategies, friction, faces, surfaces",
          "[iga][contact][surface_contact][tangent]") {
  // Rigid bodies below their surfaces (outward normals ~ +e_z). The plate's contact face
  // penetrates by about delta; its control points are perturbed randomly.
  const double a = 0.2, R_sphere = 2.0;
  struct Body {
    std::string name;
    RigidSurface rigid;
    double x0, x1;                            // plate over [x0, x1]^2
    std::function<double(double, double)> z;  // the surface height the plate follows
  };
  std::vector<Body> bodies(4);
  bodies[0] = {"plane", {}, -0.5, 0.5, [](double, double) { return 0.0; }};
  bodies[0].rigid.add(Plane());
  bodies[1] = {"nurbs hyperboloid", {}, 0.2, 1.2, [a](double x, double y) { return a * x * y; }};
  bodies[1].rigid.add(make_bilinear_hyperboloid(a, -2.0, 2.0, -2.0, 2.0));
  bodies[2] = {"analytic hyperboloid", {}, 0.2, 1.2, [a](double x, double y) { return a * x * y; }};
  bodies[2].rigid.add(Hyperboloid(Placement{}, a));
  bodies[3] = {"sphere", {}, -0.3, 0.3, [](double, double) { return -0.03; }};
  bodies[3].rigid.add(Sphere(Placement{Vector3d(0, 0, -R_sphere)}, R_sphere));

  const double h_shell = 0.1, delta = 0.02, step = 1e-7;  // step: absolute, the plate is ~1 wide
  const bool print = std::getenv("IGA_PRINT_FD") != nullptr;
  double worst = 0.0;
  for (const Body& body : bodies)
    for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave})
      for (const ShellFace face : {ShellFace::kLower, ShellFace::kUpper, ShellFace::kMid})
        for (int friction = 0; friction < 3; ++friction) {
          // lower face: n = +e_z, face below the mid-surface; upper face: flipped plate (n = -e_z),
          // the face again below; mid: the mid-surface itself.
          const double lift = face == ShellFace::kMid ? 0.0 : 0.5 * h_shell;
          const NurbsSurface ref =
              plate(body.x0, body.x1, body.x0, body.x1, 2, face == ShellFace::kUpper,
                    [&](double x, double y) { return body.z(x, y) - delta + lift; });
          SurfaceContactParameters prm;
          prm.law.eps_n = 1e3;
          prm.law.eps_t = friction ? 1e3 : 0.0;
          prm.law.mu =
              friction == 1 ? 0.5 : 0.1;  // stick: |T| ~ 2 < 0.5 |N| ~ 10; slip: 10 > 0.1 |N|
          prm.strategy = strategy;
          prm.face = face;
          prm.thickness = h_shell;
          prm.points_per_direction = 3;
          prm.search_distance = 0.5;
          SurfaceContact sc(ref, body.rigid, prm);
          // history: committed at a tangentially shifted state x0
          const auto [x, x0] = perturbed_states(ref, friction == 1 ? 0.002 : 0.01);
          residual(sc, x0);
          sc.commit();
          const double err = tangent_error(sc, x, step);
          const SurfaceContactCounts n = sc.counts();
          worst = std::max(worst, err);
          if (print)
            std::printf(
                "FD %-20s %-6s %-5s %-12s active %3d stick %3d slip %3d failed %d  err %.2e\n",
                body.name.c_str(), name(strategy), name(face),
                friction == 0   ? "frictionless"
                : friction == 1 ? "stick"
                                : "slip",
                n.active, n.stick, n.slip, n.failed, err);
          INFO(body.name << " " << name(strategy) << " " << name(face) << " friction " << friction
                         << ": active " << n.active << " stick " << n.stick << " slip " << n.slip
                         << " failed " << n.failed << " error " << err);
          CHECK(n.active == static_cast<int>(sc.points().size()));
          CHECK(n.failed == 0);
          if (friction == 0) CHECK(n.slip == n.active);  // frictionless points slide freely
          if (friction == 1) CHECK(n.stick == n.active);
          if (friction == 2) CHECK(n.slip == n.active);
          CHECK(err <= 1e-6);
        }
  if (print)
    std::printf("FD worst relative error %.2e (central differences, step %.0e)\n", worst, step);
}

TEST_CASE(
    "SurfaceContactPair: a moving, rotating tool gives the still contact turned, and its tangent "
    "equals central differences (master and slave, stick and slip)",
    "[iga][contact][surface_contact][tangent][moving_tools]") {
  // The plate of the test above on the NURBS hyperboloid, its history committed at a shifted
  // state; the same with tool and plate carried by a rigid motion G (a turn by 0.9 about a
  // skew axis through (1, -1, 2), then a shift): the tool's pose is G, the plate's points G x.
  const double a = 0.2, h_shell = 0.1, delta = 0.02;
  auto rigid = std::make_shared<RigidSurface>();
  rigid->add(make_bilinear_hyperboloid(a, -2.0, 2.0, -2.0, 2.0));
  const std::shared_ptr<RigidMotion> motion = test::skew_motion();
  const RigidPose G = motion->pose(1.0);
  using AtTime = test::PairAtTime;
  for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave})
    for (int friction = 1; friction < 3; ++friction) {
      const NurbsSurface ref = plate(0.2, 1.2, 0.2, 1.2, 2, false, [&](double x, double y) {
        return a * x * y - delta + 0.5 * h_shell;
      });
      SurfaceContactParameters prm;
      prm.law.eps_n = 1e3;
      prm.law.eps_t = 1e3;
      prm.law.mu = friction == 1 ? 0.5 : 0.1;
      prm.strategy = strategy;
      prm.face = ShellFace::kLower;
      prm.thickness = h_shell;
      prm.points_per_direction = 3;
      prm.search_distance = 0.5;
      SurfaceContactPair still(ref, rigid, prm), moved(ref, rigid, prm);
      moved.set_motion(motion);
      const auto [x, x0] = perturbed_states(ref, friction == 1 ? 0.002 : 0.01);
      std::vector<Vector3d> xm = x, x0m = x0;
      for (Vector3d& q : xm) q = G.to_world(q);
      for (Vector3d& q : x0m) q = G.to_world(q);
      AtTime ps{still}, pm{moved};
      residual(ps, x0);
      still.commit();
      residual(pm, x0m);
      moved.commit();
      const Eigen::VectorXd r = residual(ps, x), rm = residual(pm, xm);
      Eigen::VectorXd turned = r;
      for (Eigen::Index i = 0; i < r.size(); i += 3) turned.segment<3>(i) = G.Q * r.segment<3>(i);
      INFO(name(strategy) << (friction == 1 ? " stick: " : " slip: ") << still.status()
                          << " / moved: " << moved.status());
      REQUIRE(r.norm() > 0.0);
      CHECK((rm - turned).norm() <= 1e-9 * r.norm());
      const ContactCounts n = still.counts(), nm = moved.counts();
      CHECK(n.active == static_cast<int>(still.contact().points().size()));
      CHECK(nm.active == n.active);
      CHECK(nm.stick == n.stick);
      CHECK((friction == 1 ? n.stick : n.slip) == n.active);
      // Output in the world frame: the moved pair's contact points are the still ones carried.
      const SampledMesh a_pts = still.points(), b_pts = moved.points();
      REQUIRE(a_pts.points.size() == b_pts.points.size());
      for (std::size_t k = 0; k < a_pts.points.size(); ++k)
        CHECK((b_pts.points[k] - G.to_world(a_pts.points[k])).norm() < 1e-9);
      CHECK(tangent_error(pm, xm, 1e-7) <= 1e-6);
    }
}

TEST_CASE("SurfaceContact: a 2 x 2 split hyperboloid gives the residual of the single patch",
          "[iga][contact][surface_contact]") {
  const double a = 0.2;
  RigidSurface one, four;
  one.add(make_bilinear_hyperboloid(a, -2.0, 2.0, -2.0, 2.0));
  four.add(make_bilinear_hyperboloid(a, -2.0, 0.0, -2.0, 0.0));
  four.add(make_bilinear_hyperboloid(a, 0.0, 2.0, -2.0, 0.0));
  four.add(make_bilinear_hyperboloid(a, -2.0, 0.0, 0.0, 2.0));
  four.add(make_bilinear_hyperboloid(a, 0.0, 2.0, 0.0, 2.0));
  // a plate over the split lines x = 0 and y = 0
  const NurbsSurface ref = plate(-0.6, 0.6, -0.5, 0.7, 3, false,
                                 [a](double x, double y) { return a * x * y - 0.02 + 0.05; });
  std::mt19937 g(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<Vector3d> x = ref.control_points();
  for (Vector3d& q : x) q += 0.003 * Vector3d(U(g), U(g), U(g));
  for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave}) {
    SurfaceContactParameters prm{{1e3, strategy == Strategy::kRigidSlave ? 1e3 : 0.0, 0.3},
                                 strategy,
                                 ShellFace::kLower,
                                 0.1,
                                 5,
                                 0.5};
    SurfaceContact s1(ref, one, prm), s4(ref, four, prm);
    // slave with friction: a history committed at a shifted state (the chord (28) does not
    // depend on the patches)
    std::vector<Vector3d> x0 = x;
    for (Vector3d& q : x0) q += Vector3d(0.004, -0.003, 0.0);
    residual(s1, x0);
    residual(s4, x0);
    s1.commit();
    s4.commit();
    const Eigen::VectorXd R1 = residual(s1, x), R4 = residual(s4, x);
    INFO(name(strategy) << ": active " << s1.counts().active << " / " << s4.counts().active);
    CHECK(s1.counts().active == static_cast<int>(s1.points().size()));
    CHECK(s4.counts().active == s1.counts().active);
    CHECK((R1 - R4).cwiseAbs().maxCoeff() <= 1e-12 * R1.cwiseAbs().maxCoeff());
    int other_patches = 0;
    for (const SurfaceContactPoint& cp : s4.points()) other_patches += cp.foot.patch != 0;
    CHECK(other_patches > 0);
  }
}

TEST_CASE("SurfaceContact: beyond an open edge of the rigid surface there is no contact",
          "[iga][contact][surface_contact]") {
  // A rigid unit square (a bounded patch, open edges) and a plate twice as wide, delta below
  // the square's plane: over the square the points penetrate by delta; beside it their feet
  // are on the square's edge x = 0, off its normal (outside its normal prism, [KS15] Sect.
  // 2.2): not in contact, whatever the distance to the edge (before the rule, as -|x - edge|).
  RigidSurface square;
  square.add(make_plane_patch(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY()));
  const double delta = 0.01, eps_n = 1e4;
  const NurbsSurface ref =
      plate(-1.0, 1.0, 0.0, 1.0, 4, false, [&](double, double) { return -delta; });
  SurfaceContact sc(ref, square,
                    {eps_n, 0.0, 0.0, Strategy::kRigidMaster, ShellFace::kMid, 0.1, 4, 1.0});
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * ref.num_u() * ref.num_v());
  sc.assemble(ref.control_points(), R, nullptr);
  int beside = 0;
  for (const SurfaceContactPoint& cp : sc.points()) {
    if (cp.x.x() > 0.0) {
      CHECK(cp.active);
      CHECK(cp.gap == Approx(-delta).epsilon(1e-12));
    } else {
      ++beside;
      CHECK(found(cp.foot.status));  // the edge is within the search distance
      CHECK_FALSE(cp.active);
    }
  }
  CHECK(beside == 4 * 4 * 16 / 2);
  CHECK(resultant(R).z() == Approx(-delta * eps_n * 1.0).epsilon(1e-12));  // the square's area
}

TEST_CASE("SurfaceContact: a step that carries points through the rigid body is reported",
          "[iga][contact][surface_contact]") {
  // The slab 0.5 thick and a plate 0.01 above it, committed there. Moved to 0.2 below the slab
  // (farther than the search distance 0.3 from where it was, and apart from the slab again),
  // it went through: passed_through() fails, augment() with it. Moved up, or down into
  // contact, it did not.
  const RigidSurface slab = test::slab();
  const NurbsSurface ref =
      plate(-1.0, 1.0, -1.0, 1.0, 2, false, [](double, double) { return 0.01; });
  SurfaceContact sc(ref, slab,
                    {1e4, 0.0, 0.0, Strategy::kRigidMaster, ShellFace::kMid, 0.1, 3, 0.3});
  CHECK(test::moved_by(sc, ref, 0.0).status == AugmentStatus::satisfied);
  sc.commit();
  const AugmentResult through = test::moved_by(sc, ref, -0.71);  // to z = -0.7
  CHECK(through.status == AugmentStatus::passed_through);
  CHECK(through.message.find("36 contact point(s) went through") != std::string::npos);
  CHECK(sc.augment().status == AugmentStatus::passed_through);
  CHECK(test::moved_by(sc, ref, 0.5).status == AugmentStatus::satisfied);    // lifted off
  CHECK(test::moved_by(sc, ref, -0.02).status == AugmentStatus::satisfied);  // 0.01 deep
  CHECK(sc.counts().active == 36);
  CHECK(test::moved_by(sc, ref, -0.2).status == AugmentStatus::satisfied);  // in contact, -0.19
}

TEST_CASE("SurfaceContact: a flat plate pressed uniformly into a plane carries eps_N delta area",
          "[iga][contact][surface_contact]") {
  RigidSurface plane;
  plane.add(Plane());
  const double delta = 0.013, h = 0.2, eps_n = 2.5e5, L = 2.0, area = L * L;
  for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave})
    for (const ShellFace face : {ShellFace::kLower, ShellFace::kUpper, ShellFace::kMid}) {
      const double lift = face == ShellFace::kMid ? 0.0 : 0.5 * h;
      const NurbsSurface ref = plate(0.0, L, -1.0, L - 1.0, 4, face == ShellFace::kUpper,
                                     [&](double, double) { return -delta + lift; });
      SurfaceContact sc(ref, plane, {eps_n, 0.0, 0.0, strategy, face, h, 7, 1.0});
      Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * ref.num_u() * ref.num_v());
      std::vector<Eigen::Triplet<double>> K;
      sc.assemble(ref.control_points(), R, &K);
      const Vector3d F = resultant(R);  // = -int f dA
      INFO(name(strategy) << " " << name(face));
      CHECK(F.z() == Approx(-delta * eps_n * area).epsilon(1e-12));
      CHECK(F.head<2>().norm() == Approx(0.0).margin(1e-9 * eps_n * delta * area));
      CHECK(sc.counts().active == 16 * 49);
      for (const SurfaceContactPoint& cp : sc.points())
        CHECK(cp.gap == Approx(-delta).epsilon(1e-12));
    }
}

TEST_CASE(
    "SurfaceContact: master and slave agree on a parallel face, differ by the tilt on an "
    "inclined one",
    "[iga][contact][surface_contact]") {
  RigidSurface plane;
  plane.add(Plane());
  const double eps_n = 1e3;
  for (const double slope : {0.0, 0.3}) {
    // z = -0.05 + slope x on [0, 1]^2: every point below the plane z = 0
    const NurbsSurface ref = plate(0.0, 1.0, 0.0, 1.0, 3, false, [slope](double x, double) {
      return -0.05 - slope * 0.5 + slope * x * 0.5;
    });
    SurfaceContact m(ref, plane,
                     {eps_n, 0.0, 0.0, Strategy::kRigidMaster, ShellFace::kMid, 0.0, 5, 1.0});
    SurfaceContact s(ref, plane,
                     {eps_n, 0.0, 0.0, Strategy::kRigidSlave, ShellFace::kMid, 0.0, 5, 1.0});
    const Eigen::VectorXd Rm = residual(m, ref.control_points()),
                          Rs = residual(s, ref.control_points());
    const Vector3d Fm = -resultant(Rm), Fs = -resultant(Rs);  // total contact force on the plate
    INFO("slope " << slope);
    if (slope == 0.0) {
      CHECK((Rm - Rs).cwiseAbs().maxCoeff() <= 1e-12 * Rm.cwiseAbs().maxCoeff());
    } else {
      // Master: gap along the plane normal, f = eps_N p e_z. Slave: gap along the shell
      // normal n = (-sin t, 0, cos t), p / cos t, f = eps_N p / cos t n: the same vertical
      // resultant and a horizontal one -tan t F_z; the normal force is larger by 1/cos t.
      const double t = std::atan(0.5 * slope);
      CHECK(Fs.z() == Approx(Fm.z()).epsilon(1e-12));
      CHECK(Fm.x() == Approx(0.0).margin(1e-12 * Fm.z()));
      CHECK(Fs.x() == Approx(-std::tan(t) * Fs.z()).epsilon(1e-12));
      const SurfaceContactPoint &pm = m.points()[7], &ps = s.points()[7];
      CHECK(ps.N == Approx(pm.N / std::cos(t)).epsilon(1e-12));
      CHECK((Rm - Rs).cwiseAbs().maxCoeff() > 1e-3 * Rm.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("SurfaceContact: a uniformly sheared plate has T = eps_T slip in stick, mu |N| in slip",
          "[iga][contact][surface_contact][friction]") {
  RigidSurface plane;
  plane.add(Plane());
  const double delta = 0.01, eps_n = 1e3, eps_t = 2e3, slip = 0.002, L = 1.0;
  const NurbsSurface ref =
      plate(0.0, L, 0.0, L, 2, false, [&](double, double) { return -delta + 0.05; });
  for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave})
    for (const double mu : {0.5, 0.1}) {
      // |T_tr| = eps_T slip = 4; mu |N| = 5 (stick) or 1 (slip)
      SurfaceContact sc(ref, plane, {eps_n, eps_t, mu, strategy, ShellFace::kLower, 0.1, 4, 1.0});
      residual(sc, ref.control_points());
      sc.commit();
      std::vector<Vector3d> x = ref.control_points();
      for (Vector3d& q : x) q += Vector3d(slip, 0.0, 0.0);
      const Eigen::VectorXd R = residual(sc, x);
      const bool sticks = mu == 0.5;
      const double T = sticks ? eps_t * slip : mu * eps_n * delta;
      INFO(name(strategy) << " mu " << mu);
      const SurfaceContactCounts n = sc.counts();
      CHECK(n.active == static_cast<int>(sc.points().size()));
      CHECK((sticks ? n.stick : n.slip) == n.active);
      for (const SurfaceContactPoint& cp : sc.points()) {
        CHECK(cp.T_vector.x() == Approx(-T).epsilon(1e-10));  // opposes the slip (+x)
        CHECK(cp.T_vector.tail<2>().norm() == Approx(0.0).margin(1e-10 * T));
        CHECK(cp.N == Approx(-eps_n * delta).epsilon(1e-10));
      }
      CHECK(resultant(R).x() == Approx(T * L * L).epsilon(1e-10));  // R -= int f dA
    }
}

TEST_CASE(
    "SurfaceContact: points beyond the search distance are failed and inactive, bad "
    "parameters throw",
    "[iga][contact][surface_contact]") {
  RigidSurface body;
  body.add(make_bilinear_hyperboloid(0.2, -2.0, 2.0, -2.0, 2.0));
  // 0.3 above the surface, search distance 0.2: nothing found; then pressed in: all active
  const NurbsSurface ref =
      plate(0.0, 1.0, 0.0, 1.0, 2, false, [](double x, double y) { return 0.2 * x * y + 0.3; });
  for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave}) {
    SurfaceContact sc(ref, body, {1e3, 0.0, 0.0, strategy, ShellFace::kMid, 0.0, 3, 0.2});
    const Eigen::VectorXd R = residual(sc, ref.control_points());
    CHECK(R.cwiseAbs().maxCoeff() == 0.0);
    CHECK(sc.counts().failed == static_cast<int>(sc.points().size()));
    CHECK(sc.counts().active == 0);
    std::vector<Vector3d> x = ref.control_points();
    for (Vector3d& q : x) q.z() -= 0.31;
    residual(sc, x);
    CHECK(sc.counts().failed == 0);
    CHECK(sc.counts().active == static_cast<int>(sc.points().size()));
  }
  SurfaceContactParameters bad;
  bad.law.eps_n = -1.0;
  CHECK_THROWS_WITH(SurfaceContact(ref, body, bad), Catch::Contains("eps_n must be > 0"));
  SurfaceContact sc(ref, body,
                    {{1e3, 0.0, 0.0}, Strategy::kRigidMaster, ShellFace::kMid, 0.0, 3, 0.2});
  SurfaceContactParameters p = sc.parameters();
  p.points_per_direction = 4;
  CHECK_THROWS_AS(sc.set_parameters(p), std::invalid_argument);
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3);
  CHECK_THROWS_AS(sc.assemble(ref.control_points(), R, nullptr), std::invalid_argument);
}

TEST_CASE("SurfaceContact: assembly on 1 and 2 threads is the same bit for bit",
          "[iga][contact][surface_contact][threads]") {
  // Issue 17, item 4: the points' projections and laws run on all threads; the residual is
  // summed and the triplets joined in element order by one thread. A bicubic plate of 8 x 8
  // elements (1600 points, above the parallel threshold) on the NURBS hyperboloid, master and
  // slave, with friction from a history committed at a shifted state.
  const double a = 0.2;
  RigidSurface rigid;
  rigid.add(make_bilinear_hyperboloid(a, -2.0, 2.0, -2.0, 2.0));
  const NurbsSurface ref =
      plate(0.2, 1.2, 0.2, 1.2, 8, false, [a](double x, double y) { return a * x * y - 0.02; });
  const auto [x, x0] = perturbed_states(ref, 0.01);
  const int saved = omp_get_max_threads();
  for (const Strategy strategy : {Strategy::kRigidMaster, Strategy::kRigidSlave}) {
    SurfaceContactParameters prm;
    prm.law.eps_n = 1e3;
    prm.law.eps_t = 1e3;
    prm.law.mu = 0.1;
    prm.strategy = strategy;
    prm.points_per_direction = 5;
    prm.search_distance = 0.5;
    Eigen::VectorXd R[2];
    std::vector<Eigen::Triplet<double>> K[2];
    for (int t = 0; t < 2; ++t) {
      omp_set_num_threads(t + 1);
      SurfaceContact sc(ref, rigid, prm);
      REQUIRE(static_cast<int>(sc.points().size()) >= kParallelContactPoints);
      residual(sc, x0);
      sc.commit();
      R[t] = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
      sc.assemble(x, R[t], &K[t]);
      CHECK(sc.counts().active == static_cast<int>(sc.points().size()));
    }
    omp_set_num_threads(saved);
    INFO(name(strategy));
    CHECK(R[0].norm() > 0.0);
    REQUIRE(K[0].size() == K[1].size());
    CHECK(test::count_differences(R[0], R[1], K[0], K[1]) == 0);
  }
}

}  // namespace test_surface_contact
