// The CTRS contact integral along a curve ([KS15] Sects. 4-5): its tangent against central
// finite differences of its residual, frictionless and with friction (stick and slip), on an
// exact NURBS cylinder and an analytic torus; and the resultant of a rope wrapped on a
// cylinder.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <omp.h>
#include <Eigen/SparseCore>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/contact_integrals/curve_contact.hpp"
#include "tests/iga/contact_integrals/pass_through_case.hpp"
#include "tests/iga/fd_tangent.hpp"
#include "tests/iga/same_bits.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_curve_contact {

using namespace iga;
using iga::test::residual;
using iga::test::tangent_error;

namespace {

constexpr double kPi = std::numbers::pi;

// A rope: an arc of radius rho around the z axis from angle a0 to a1 at height z, as a
// cubic NURBS with a few elements.
NurbsCurve rope(double rho, double a0, double a1, double z) {
  NurbsCurve c =
      make_circular_arc(Vector3d(0, 0, z), Vector3d::UnitX(), Vector3d::UnitY(), rho, a0, a1);
  c = elevate_degree(c, 1);
  return subdivide(c, 3);
}

}  // namespace

TEST_CASE("CurveContact: tangent = d(residual)/dx, frictionless and frictional",
          "[iga][contact][ctrs][tangent]") {
  RigidSurface cyl;
  cyl.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  RigidSurface tor;
  tor.add(Torus(Placement{}, 3.0, 1.0));
  std::mt19937 g(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int variant = 0; variant < 4; ++variant) {
    const bool on_torus = variant >= 2;
    const bool friction = variant % 2 == 1;
    const RigidSurface& body = on_torus ? tor : cyl;
    // rope centre line pressed into the surface: radius 0.05, centre line 0.04 from the surface
    const NurbsCurve ref = on_torus ? rope(4.04, 0.2, 1.4, 0.0) : rope(1.04, 0.3, 2.5, 0.1);
    CurveContact cc(ref, body, CurveContactParameters{{2e3, friction ? 1e3 : 0.0, 0.3}, 0.05, 3});
    std::vector<Vector3d> x = ref.control_points();
    // commit a history at a shifted state so that the increments are not zero
    std::vector<Vector3d> x0 = x;
    for (Vector3d& q : x0) q += Vector3d(0, 0, 0.004);
    Eigen::VectorXd R0 = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
    cc.assemble(x0, R0, nullptr);
    cc.commit();
    for (Vector3d& q : x) q += 0.003 * Vector3d(U(g), U(g), U(g));
    const double err = tangent_error(cc, x, 1e-7);
    const CurveContactCounts n = cc.counts();
    INFO("variant " << variant << " active " << n.active << " stick " << n.stick << " slip "
                    << n.slip);
    CHECK(n.active > 0);
    CHECK(err <= 1e-6);
  }
}

TEST_CASE("CurveContact: a uniformly penetrating half wrap has the resultant of its pressure",
          "[iga][contact][ctrs]") {
  // A half circle of rope centre line at uniform gap xi^3 < 0 (52) on a cylinder: the penalty
  // pressure eps_N |xi^3| (34) along the outward normal integrates to eps_N |xi^3| 2 r along
  // the bisector (+y), r the radius of the centre line.
  RigidSurface cyl;
  cyl.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  const double gap = -0.01, rope_radius = 0.05;
  const NurbsCurve ref = rope(1.0 + rope_radius + gap, 0.0, kPi, 0.0);
  CurveContact cc(ref, cyl, CurveContactParameters{{1e3, 0.0, 0.0}, rope_radius, 4});
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * ref.num_control_points());
  cc.assemble(ref.control_points(), R, nullptr);
  Vector3d resultant = Vector3d::Zero();
  for (int a = 0; a < ref.num_control_points(); ++a) resultant -= R.segment<3>(3 * a);
  // int over the half circle of |N| n ds, n = (cos a, sin a, 0), ds = (1 + R + gap) da
  const double r = 1.0 + rope_radius + gap;
  CHECK(resultant.y() == Approx(1e3 * -gap * 2.0 * r).epsilon(1e-6));
  CHECK(resultant.x() == Approx(0.0).margin(1e-6));
  CHECK(cc.counts().active == static_cast<int>(cc.points().size()));
}

TEST_CASE("CurveContact: parameters out of their ranges are rejected, the law's by the law",
          "[iga][contact][ctrs]") {
  // The rope's parameters are built on the law's (ContactParameters): the law checks its
  // constants for every integral, the rope its radius and points.
  RigidSurface cyl;
  cyl.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  const NurbsCurve ref = rope(1.05, 0.0, kPi, 0.0);
  const CurveContactParameters good{{1e3, 1e2, 0.3}, 0.05, 3};
  CHECK(good.law.friction());
  CHECK_FALSE(ContactParameters{1e3, 0.0, 0.3}.friction());
  CHECK_FALSE(ContactParameters{1e3, 1e2, 0.0}.friction());
  struct Bad {
    CurveContactParameters p;
    const char* message;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Bad& b : {Bad{{{0.0, 0.0, 0.0}, 0.05, 3}, "eps_n must be > 0 and finite, got 0"},
                       Bad{{{nan, 0.0, 0.0}, 0.05, 3}, "eps_n must be > 0"},
                       Bad{{{1e3, -1.0, 0.0}, 0.05, 3}, "eps_t must be >= 0"},
                       Bad{{{1e3, 0.0, -0.1}, 0.05, 3}, "mu must be >= 0"},
                       Bad{{{1e3, 0.0, 0.0}, -0.05, 3}, "radius must be >= 0"},
                       Bad{{{1e3, 0.0, 0.0}, 0.05, 0}, "points per element must be in 1..16"}}) {
    INFO(b.message);
    CHECK_THROWS_WITH(CurveContact(ref, cyl, b.p), Catch::Contains(b.message));
  }
  CurveContact cc(ref, cyl, good);
  CurveContactParameters more = good;
  more.law.mu = 0.5;
  more.radius = 0.06;
  cc.set_parameters(more);
  CHECK(cc.parameters().law.mu == 0.5);
  CHECK(cc.parameters().radius == 0.06);
  more.points_per_element = 4;
  CHECK_THROWS_WITH(cc.set_parameters(more), Catch::Contains("points_per_element cannot change"));
  more.points_per_element = 3;
  more.law.eps_n = -1.0;
  CHECK_THROWS_WITH(cc.set_parameters(more), Catch::Contains("eps_n must be > 0"));
  CHECK(cc.parameters().law.eps_n == 1e3);
}

TEST_CASE("CurveContact: broad phase on a 4-patch cylinder = single patch, far points inactive",
          "[iga][contact][ctrs]") {
  // The same penetrating half wrap on one exact cylinder patch and on four 90-degree patches
  // (a multi-patch rigid body): the first assembly projects every point through the CGAL broad
  // phase, the second warm-starts all of them; residuals agree to round-off.
  RigidSurface one, four;
  one.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  for (int k = 0; k < 4; ++k)
    four.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0,
                           0.5 * kPi * k, 0.5 * kPi * (k + 1)));
  const NurbsCurve ref = rope(1.04, 0.1, kPi - 0.1, 0.2);
  const CurveContactParameters cp{{1e3, 0.0, 0.0}, 0.05, 4};
  CurveContact c1(ref, one, cp), c4(ref, four, cp);
  const Eigen::VectorXd R1 = residual(c1, ref.control_points());
  const Eigen::VectorXd R4 = residual(c4, ref.control_points());
  CHECK(c4.broad_phase_points() == static_cast<int>(c4.points().size()));
  CHECK((R1 - R4).norm() <= 1e-10 * R1.norm());
  CHECK(c4.counts().active == static_cast<int>(c4.points().size()));
  // Every point has a foot: the second assembly warm-starts all of them.
  const Eigen::VectorXd R4b = residual(c4, ref.control_points());
  CHECK(c4.broad_phase_points() == 0);
  CHECK((R4b - R4).norm() <= 1e-12 * R4.norm());
  // Moved far above the cylinder's top: the warm start ends on the top edge with the points off
  // its normal (beyond the edge): inactive, no force, although the radial offset alone would
  // give a negative gap (52). A cold start finds no surface within the search distance.
  std::vector<Vector3d> away = ref.control_points();
  for (Vector3d& p : away) p.z() += 10.0;
  const Eigen::VectorXd R_away = residual(c4, away);
  CHECK(c4.counts().active == 0);
  CHECK(R_away.norm() == 0.0);
  CurveContact cold(ref, four, cp);
  CHECK(residual(cold, away).norm() == 0.0);
  for (const CurveContactPoint& p : cold.points()) CHECK(p.foot.status == ProjectionStatus::far);
}

TEST_CASE("CurveContact: a step that carries the rope through the rigid body is reported",
          "[iga][contact][curve_contact]") {
  // The slab 0.5 thick and a rope of radius 0.05 lying 0.1 above it, committed there (search
  // distance 0.5). Moved to 0.2 below the slab it went through; moved up, or down into
  // contact, it did not.
  const RigidSurface slab = test::slab();
  const NurbsCurve ref = subdivide(elevate_degree(make_line({-1, 0, 0.15}, {1, 0, 0.15}), 2), 4);
  CurveContact cc(ref, slab, CurveContactParameters{{1e3, 0.0, 0.0}, 0.05, 3});
  cc.set_search_distance(0.5);
  CHECK(test::moved_by(cc, ref, 0.0).status == AugmentStatus::satisfied);
  cc.commit();
  const AugmentResult through = test::moved_by(cc, ref, -0.85);  // centre line at z = -0.7
  CHECK(through.status == AugmentStatus::passed_through);
  CHECK(through.message.find("12 contact point(s) went through") != std::string::npos);
  CHECK(cc.augment().status == AugmentStatus::passed_through);
  CHECK(test::moved_by(cc, ref, 0.5).status == AugmentStatus::satisfied);    // lifted off
  CHECK(test::moved_by(cc, ref, -0.11).status == AugmentStatus::satisfied);  // 0.01 deep
  CHECK(cc.counts().active == 12);
}

TEST_CASE("CurveContact: assembly on 1 and 2 threads is the same bit for bit",
          "[iga][contact][ctrs][threads]") {
  // Issue 17, item 4: the points' projections and laws run on all threads, the residual and
  // tangent are summed in point order by one thread. A rope of 120 cubic elements, 3 points
  // each (360, above the parallel threshold), pressed into a cylinder, with friction from a
  // history committed at a shifted state.
  RigidSurface cyl;
  cyl.add(make_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  NurbsCurve ref =
      make_circular_arc(Vector3d(0, 0, 0.1), Vector3d::UnitX(), Vector3d::UnitY(), 1.04, 0.3, 2.5);
  ref = subdivide(elevate_degree(ref, 1), 60);
  std::vector<Vector3d> x = ref.control_points(), x0 = x;
  for (Vector3d& q : x0) q += Vector3d(0, 0, 0.004);
  std::mt19937 g(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (Vector3d& q : x) q += 0.003 * Vector3d(U(g), U(g), U(g));
  const int saved = omp_get_max_threads();
  Eigen::VectorXd R[2];
  std::vector<Eigen::Triplet<double>> K[2];
  for (int t = 0; t < 2; ++t) {
    omp_set_num_threads(t + 1);
    CurveContact cc(ref, cyl, CurveContactParameters{{2e3, 1e3, 0.3}, 0.05, 3});
    REQUIRE(static_cast<std::ptrdiff_t>(cc.points().size()) >= kParallelCurvePoints);
    Eigen::VectorXd R0 = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
    cc.assemble(x0, R0, nullptr);
    cc.commit();
    R[t] = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
    cc.assemble(x, R[t], &K[t]);
    CHECK(cc.counts().active > 300);
  }
  omp_set_num_threads(saved);
  CHECK(R[0].norm() > 0.0);
  REQUIRE(K[0].size() == K[1].size());
  CHECK(test::count_differences(R[0], R[1], K[0], K[1]) == 0);
}

}  // namespace test_curve_contact
