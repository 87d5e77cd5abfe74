// CTRS with a rod with torsion (CurveContact::set_rolling): the contact point on the
// rope's surface turns with the section, so friction acts on the twist unknowns. Tests: the
// tangent against central differences in stick and slip, and a rope rolling on a plane
// (turned about its axis at both ends: with friction its centre line travels R theta, without
// it only twists in place), and the same contact on a moving tool.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include "contact/rigid_motion.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/contact_integrals/curve_contact.hpp"
#include "iga/contact_integrals/curve_contact_pair.hpp"
#include "iga/rod/twisting_rod.hpp"
#include "iga/solvers/nonlinear_solver.hpp"
#include "tests/iga/contact_integrals/moving_pair.hpp"
#include "tests/iga/fd_tangent.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_curve_contact_twist {

using namespace iga;

namespace {

NurbsCurve straight(double L, double z, int n_el) {
  NurbsCurve c = make_line(Vector3d(0, 0, z), Vector3d(L, 0, z));
  c = elevate_degree(c, 2);
  return subdivide(c, n_el);
}

RodSection rope_section() {
  RodSection s;
  s.EA = 1e3;
  s.EI1 = s.EI2 = 1e-2;
  s.GJ = 1e-2;
  return s;
}

/// A rolling rope's contact (integral or pair) as test::tangent_error's Contact: the body's
/// state packed as points, twist k the first coordinate of entry n + k (residual entry
/// 3 (n + k), the entry's other two coordinates unused), handed to the contact as a BodyState
/// with the rod's section frames (twist k at Cartesian DOF 3 n + k).
struct Packed {
  std::function<void(const BodyState&, Eigen::VectorXd&, std::vector<Triplet>*)> add;
  const SectionFrames& frames;
  int n = 0, m = 0;
  void assemble(const std::vector<Vector3d>& packed, Eigen::VectorXd& R, std::vector<Triplet>* K) {
    std::vector<double> s(static_cast<std::size_t>(m));
    for (int k = 0; k < m; ++k)
      s[static_cast<std::size_t>(k)] = packed[static_cast<std::size_t>(n + k)][0];
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * n + m);
    std::vector<Triplet> t;
    add(BodyState{std::span<const Vector3d>(packed.data(), static_cast<std::size_t>(n)), s,
                  &frames},
        g, K ? &t : nullptr);
    const auto packed_index = [&](Eigen::Index i) { return i < 3 * n ? i : 3 * (n + (i - 3 * n)); };
    for (Eigen::Index i = 0; i < g.size(); ++i) R[packed_index(i)] += g[i];
    if (K)
      for (const Triplet& tr : t)
        K->emplace_back(static_cast<int>(packed_index(tr.row())),
                        static_cast<int>(packed_index(tr.col())), tr.value());
  }
};

Packed packed(CurveContact& cc, const TwistingRod& rod) {
  return {[&cc](const BodyState& st, Eigen::VectorXd& g, std::vector<Triplet>* K) {
            cc.assemble(st, g, K);
          },
          rod, rod.num_control_points(), rod.num_knots()};
}

Packed packed(ContactPair& pair, const TwistingRod& rod) {
  return {[&pair](const BodyState& st, Eigen::VectorXd& g, std::vector<Triplet>* K) {
            pair.add(st, 1.0, g, K);
          },
          rod, rod.num_control_points(), rod.num_knots()};
}

}  // namespace

TEST_CASE("CurveContact with torsion: tangent = d(residual)/d(points, twists), stick and slip",
          "[iga][contact][ctrs][twist][tangent]") {
  // A straight rope (radius 0.05) pressed 0.004 into a plane, committed at one state, then
  // moved and twisted: the contact residual's derivative by central differences against the
  // tangent, with the rolling displacement, the twist rows and the coupling blocks.
  RigidSurface plane;
  plane.add(make_plane_patch(Vector3d(-2, -2, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)));
  const double R = 0.05;
  std::mt19937 g(9);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int stick = 0, slip = 0;
  for (const double mu : {0.05, 0.3, 5.0}) {
    const NurbsCurve ref = straight(1.0, R - 0.004, 4);
    const TwistingRod rod(ref, rope_section());
    CurveContact cc(ref, plane, CurveContactParameters{{2e3, 1e3, mu}, R, 3});
    cc.set_rolling(true);
    Packed pc = packed(cc, rod);
    const int n = rod.num_control_points(), m = rod.num_knots();
    std::vector<Vector3d> x0 = ref.control_points();
    x0.resize(static_cast<std::size_t>(n + m), Vector3d::Zero());
    Eigen::VectorXd R0 = Eigen::VectorXd::Zero(3 * (n + m));
    pc.assemble(x0, R0, nullptr);
    cc.commit();
    std::vector<Vector3d> x = x0;
    for (int i = 0; i < n; ++i)
      x[static_cast<std::size_t>(i)] += 0.002 * Vector3d(U(g), U(g), U(g));
    for (int k = 0; k < m; ++k) x[static_cast<std::size_t>(n + k)][0] = 0.05 * U(g);
    const double err = test::tangent_error(pc, x, 1e-7);
    const CurveContactCounts c = cc.counts();
    stick += c.stick;
    slip += c.slip;
    INFO("mu " << mu << " active " << c.active << " stick " << c.stick << " slip " << c.slip);
    CHECK(c.active > 0);
    CHECK(err <= 1e-6);
    // The twist rows carry the friction torque: not all zero.
    Eigen::VectorXd Rx = Eigen::VectorXd::Zero(3 * (n + m));
    pc.assemble(x, Rx, nullptr);
    double torque = 0.0;
    for (int k = 0; k < m; ++k) torque += std::abs(Rx[3 * (n + k)]);
    CHECK(torque > 0.0);
  }
  CHECK(stick > 0);
  CHECK(slip > 0);
}

TEST_CASE("CurveContact with torsion: a rope turned at both ends rolls by R theta",
          "[iga][contact][ctrs][twist]") {
  // A straight rope (L = 1, R = 0.05) lying on a plane under its weight q, both end sections
  // turned by theta = 1 about the axis. With mu = 1 the surface sticks, so the rope rolls: its
  // centre line travels -R theta along y (a right-hand turn about +x rolls it towards -y), its
  // twist is uniform (no torsion strain) and the contact carries no net torque. With mu = 0
  // the contact carries no torque and the rope twists in place (y of one end held: nothing else
  // would fix it sideways).
  RigidSurface plane;
  plane.add(make_plane_patch(Vector3d(-2, -2, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)));
  const auto tool = std::make_shared<const RigidSurface>(plane);
  const double R = 0.05, theta = 1.0, q = 1.0;
  for (const double mu : {1.0, 0.0}) {
    // Laid at its sinking under q (gap q / eps_N), so that friction holds it from the start.
    TwistingRodProblem P(TwistingRod(straight(1.0, R - q / 1e4, 8), rope_section()));
    auto pair = std::make_unique<CurveContactPair>(P.rod().reference(), tool,
                                                   CurveContactParameters{{1e4, 1e4, mu}, R, 3});
    pair->contact().set_rolling(true);
    P.attach(std::move(pair));
    P.add_line_load(Vector3d(0, 0, -q), constant_curve());  // on from the start
    P.prescribe_twist(P.end_knot(RodEnd::kStart), theta);
    P.prescribe_twist(P.end_knot(RodEnd::kEnd), theta);
    P.fix(0, 0);  // the axial rigid mode
    if (mu == 0.0) P.fix(0, 1);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(P.num_dofs());
    // Small first steps, then the secant predictor: a step whose start has the rope still
    // where it was and its ends turned lets the ends slip at the first iterate, and Newton on
    // the slip tangent wanders off; started from the extrapolated (rolled) state it sticks.
    NonlinearSolverSettings settings;
    settings.initial_step = 1e-3;
    settings.max_step = 0.05;
    settings.secant_predictor = true;
    settings.max_iterations = 30;
    // Rolling is nearly free (its only stiffness the torsion and bending of the rope, 1e-2,
    // against contact penalties of 1e4): the residual's round-off floor is ~3e-10 of forces of
    // order 1, above the default absolute test, and the corrections at that floor do not
    // shrink (the energy test is off).
    settings.tol_residual_abs = 1e-8;
    settings.tol_energy_rel = 0.0;
    NonlinearSolver solver(settings);
    const NonlinearSolverResult r = solver.solve(P, u);
    INFO("mu " << mu << ": " << r.message);
    REQUIRE(r.status == NonlinearSolverStatus::converged);
    std::vector<Vector3d> x;
    std::vector<double> alpha;
    P.split(u, 1.0, x, alpha);
    double y_min = 1e9, y_max = -1e9, torque = 0.0, kappa3 = 0.0;
    for (int k = 0; k <= 10; ++k) {
      const double xi = k / 10.0;
      const double y = P.rod().point(xi, x).y();
      y_min = std::min(y_min, y), y_max = std::max(y_max, y);
      kappa3 = std::max(kappa3, std::abs(P.rod().strains(xi, x, alpha).kappa[2]));
    }
    for (const CurveContactPoint& cp :
         dynamic_cast<const CurveContactPair&>(P.pair(0)).contact().points())
      torque += cp.weight * cp.torque;
    std::printf(
        "rolling rope, mu = %.0f: centre line y in [%.5f, %.5f] (rolling: %.5f), "
        "max twist rate %.2e, friction torque %.2e\n",
        mu, y_min, y_max, -R * theta, kappa3, torque);
    if (mu > 0.0) {
      CHECK(y_min == Approx(-R * theta).epsilon(2e-3));
      CHECK(y_max == Approx(-R * theta).epsilon(2e-3));
    } else {
      CHECK(std::abs(y_min) < 1e-9);
      CHECK(std::abs(y_max) < 1e-9);
    }
    // Measured (mu = 1): y -0.05000 inside, -0.04995 at the ends; twist rate 1.3e-3 and torque
    // -5e-7 (of mu q R L = 0.05), the penalty's creep near the turned ends.
    CHECK(kappa3 < 5e-3 * theta);
    CHECK(std::abs(torque) < 1e-5);
  }
}

TEST_CASE("CurveContact with torsion on a moving tool: the still pair's residual, turned",
          "[iga][contact][ctrs][twist][motion]") {
  // A rope with torsion pressed into a plane, committed, moved and twisted; the same with the
  // plane and the rope carried by a rigid motion G (a turn by 0.9 about a skew axis, then a
  // shift): the moving pair's residual is the still one's with its position entries turned by
  // G's rotation (the twist entries as they are), in stick and slip, and its tangent matches
  // central differences.
  auto plane = std::make_shared<RigidSurface>();
  plane->add(make_plane_patch(Vector3d(-2, -2, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)));
  const std::shared_ptr<RigidMotion> motion = test::skew_motion();
  const RigidPose G = motion->pose(1.0);
  const double R = 0.05;
  std::mt19937 g(4);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (const double mu : {0.05, 5.0}) {
    const NurbsCurve ref = straight(1.0, R - 0.004, 4);
    std::vector<Vector3d> Pm = ref.control_points();
    for (Vector3d& q : Pm) q = G.to_world(q);
    const NurbsCurve ref_m(ref.degree(), ref.knots().knots(), Pm, ref.weights());
    RodSection sec = rope_section();
    sec.ref_direction = Vector3d(0.3, 1.0, 0.2);
    RodSection sec_m = sec;
    sec_m.ref_direction = G.Q * sec.ref_direction;
    const TwistingRod rod(ref, sec), rod_m(ref_m, sec_m);
    CurveContactPair still(ref, plane, CurveContactParameters{{2e3, 1e3, mu}, R, 3});
    CurveContactPair moved(ref_m, plane, CurveContactParameters{{2e3, 1e3, mu}, R, 3});
    still.contact().set_rolling(true);
    moved.contact().set_rolling(true);
    moved.set_motion(motion);
    const int n = rod.num_control_points(), m = rod.num_knots();
    std::vector<Vector3d> x0 = ref.control_points();
    x0.resize(static_cast<std::size_t>(n + m), Vector3d::Zero());
    std::vector<Vector3d> x = x0;
    for (int i = 0; i < n; ++i)
      x[static_cast<std::size_t>(i)] += 0.002 * Vector3d(U(g), U(g), U(g));
    for (int k = 0; k < m; ++k) x[static_cast<std::size_t>(n + k)][0] = 0.05 * U(g);
    auto carried = [&](std::vector<Vector3d> y) {
      for (int i = 0; i < n; ++i)
        y[static_cast<std::size_t>(i)] = G.to_world(y[static_cast<std::size_t>(i)]);
      return y;
    };
    Packed ps = packed(still, rod), pm = packed(moved, rod_m);
    test::residual(ps, x0);
    still.commit();
    test::residual(pm, carried(x0));
    moved.commit();
    const Eigen::VectorXd r = test::residual(ps, x), rm = test::residual(pm, carried(x));
    Eigen::VectorXd turned = r;
    for (int i = 0; i < n; ++i) turned.segment<3>(3 * i) = G.Q * r.segment<3>(3 * i);
    double torque = 0.0;
    for (int k = 0; k < m; ++k) torque += std::abs(r[3 * (n + k)]);
    INFO("mu " << mu << ": " << still.status() << " / moved: " << moved.status());
    REQUIRE(torque > 0.0);
    CHECK((rm - turned).norm() <= 1e-9 * r.norm());
    CHECK(test::tangent_error(pm, carried(x), 1e-7) <= 1e-6);
  }
}

TEST_CASE("CurveContact with torsion: a copy of the rod's problem rolls on its own frames",
          "[iga][contact][ctrs][twist]") {
  // The pair takes the rod's section frames with the state at each assembly (no pointer to the
  // rod): a copy of the problem, assembled after the original is gone, gives the original's
  // residual and tangent, and a rope pressed in and twisted carries a friction torque.
  auto plane = std::make_shared<RigidSurface>();
  plane->add(make_plane_patch(Vector3d(-2, -2, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)));
  const double R = 0.05;
  auto original = std::make_unique<TwistingRodProblem>(
      TwistingRod(straight(1.0, R - 0.004, 4), rope_section()));
  auto pair = std::make_unique<CurveContactPair>(original->rod().reference(), plane,
                                                 CurveContactParameters{{2e3, 1e3, 0.3}, R, 3});
  pair->contact().set_rolling(true);
  original->attach(std::move(pair));
  original->fix(0);
  original->fix_twist(0);
  TwistingRodProblem copy(*original);
  std::mt19937 g(2);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd u(original->num_dofs());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = 1e-3 * U(g);
  for (int k = 1; k < original->rod().num_knots(); ++k)
    u[original->dof_map().scalar_dof(k)] = 0.05 * U(g);
  Eigen::VectorXd R1, R2;
  SparseMatrix K1, K2;
  original->assemble(u, 1.0, R1, &K1);
  const ContactCounts c1 = original->pair(0).counts();
  original.reset();
  copy.assemble(u, 1.0, R2, &K2);
  INFO(copy.status());
  REQUIRE(c1.active > 0);
  CHECK(copy.pair(0).counts().active == c1.active);
  CHECK((R2 - R1).norm() <= 1e-12 * R1.norm());
  CHECK((Eigen::MatrixXd(K2) - Eigen::MatrixXd(K1)).norm() <= 1e-12 * Eigen::MatrixXd(K1).norm());
  double torque = 0.0;
  for (const CurveContactPoint& cp :
       dynamic_cast<const CurveContactPair&>(copy.pair(0)).contact().points())
    torque += std::abs(cp.torque);
  CHECK(torque > 0.0);
}

}  // namespace test_curve_contact_twist
