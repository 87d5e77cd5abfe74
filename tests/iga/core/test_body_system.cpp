// Several bodies as one problem (iga/core/body_system.hpp) and several contact pairs on one body
// (ControlPointProblem::attach): the stacked residual and block tangent, the solution of each
// body as if alone (a cantilever's tip deflection P L^3 / (3 EI), an end moment's roll-up angle
// M L / EI), and pairs whose forces add up.
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include <Eigen/SVD>
#include <catch2/catch.hpp>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/contact_integrals/curve_contact_pair.hpp"
#include "iga/core/body_system.hpp"
#include "iga/rod/kirchhoff_rod.hpp"
#include "iga/solvers/nonlinear_solver.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_body_system {

using namespace iga;

namespace {

constexpr double kL = 2.0, kEI = 3.0, kEA = 1e5;

/// A straight cubic rod of 4 elements from a along x, length kL.
KirchhoffRod rod_at(const Vector3d& a) {
  NurbsCurve c = make_line(a, a + Vector3d(kL, 0, 0));
  c = subdivide(elevate_degree(c, 2), 4);
  return KirchhoffRod(c, {kEA, kEI, kEI, Vector3d::Zero()});
}

/// Rod A: clamped at the start, an end moment about y (the rod rolls up in the x-z plane).
RodProblem rolling(double M) {
  RodProblem P(rod_at(Vector3d::Zero()));
  P.clamp(RodEnd::kStart);
  P.add_moment(1.0, Vector3d(0, M, 0));
  return P;
}

/// Rod B: clamped at the start, a small tip force along z.
RodProblem cantilever(double Pz) {
  RodProblem P(rod_at(Vector3d(0, 1, 0)));
  P.clamp(RodEnd::kStart);
  P.add_point_load(1.0, Vector3d(0, 0, Pz));
  return P;
}

NonlinearSolverResult solve(NonlinearProblem& P, VectorXd& u) {
  NonlinearSolverSettings s;
  s.tol_residual_abs = 1e-15 * kEA;
  s.initial_step = s.max_step = 0.25;
  s.max_iterations = 30;
  NonlinearSolver solver(s);
  return solver.solve(P, u);
}

double rel(const VectorXd& a, const VectorXd& b) {
  return (a - b).norm() / std::max(a.norm(), 1e-300);
}

}  // namespace

TEST_CASE("BodySystem: two rods, stacked residual and block tangent, each solved as if alone",
          "[iga][core][body]") {
  const double M = 0.25 * kEI / kL, Pz = 1e-7;  // tip angle M L / EI = 0.25 rad
  RodProblem A = rolling(M), B = cantilever(Pz);
  BodySystem S;
  S.add(A);
  S.add(B);
  REQUIRE(S.num_dofs() == A.num_dofs() + B.num_dofs());
  REQUIRE(S.offset(1) == A.num_dofs());
  // A's moment makes its tangent non-symmetric, and so the system's.
  CHECK_FALSE(A.symmetric());
  CHECK(B.symmetric());
  CHECK_FALSE(S.symmetric());

  // The residual and tangent at a random state are the bodies' own, stacked.
  std::mt19937 g(5);
  std::uniform_real_distribution<double> U(-0.01, 0.01);
  VectorXd u(S.num_dofs());
  for (Eigen::Index k = 0; k < u.size(); ++k) u[k] = U(g);
  VectorXd R, RA, RB;
  SparseMatrix K, KA, KB;
  S.assemble(u, 0.7, R, &K);
  A.assemble(S.block(u, 0), 0.7, RA, &KA);
  B.assemble(S.block(u, 1), 0.7, RB, &KB);
  CHECK(R.head(A.num_dofs()) == RA);
  CHECK(R.tail(B.num_dofs()) == RB);
  const Eigen::MatrixXd Kd(K), KAd(KA), KBd(KB);
  CHECK(Kd.topLeftCorner(A.num_dofs(), A.num_dofs()) == KAd);
  CHECK(Kd.bottomRightCorner(B.num_dofs(), B.num_dofs()) == KBd);
  CHECK(Kd.topRightCorner(A.num_dofs(), B.num_dofs()).cwiseAbs().maxCoeff() == 0.0);
  CHECK(Kd.bottomLeftCorner(B.num_dofs(), A.num_dofs()).cwiseAbs().maxCoeff() == 0.0);

  // Solved together, each body as solved alone, and as theory says.
  VectorXd us = VectorXd::Zero(S.num_dofs());
  const NonlinearSolverResult rs = solve(S, us);
  INFO(rs.message);
  REQUIRE(rs.converged());
  RodProblem A1 = rolling(M), B1 = cantilever(Pz);
  VectorXd ua = VectorXd::Zero(A1.num_dofs()), ub = VectorXd::Zero(B1.num_dofs());
  REQUIRE(solve(A1, ua).converged());
  REQUIRE(solve(B1, ub).converged());
  CHECK(rel(ua, S.block(us, 0)) < 1e-8);
  CHECK(rel(ub, S.block(us, 1)) < 1e-8);
  // B: the linear cantilever (cubic splines hold the exact cubic deflection).
  CHECK(B.displacement(1.0, 0.0, S.block(us, 1), 1.0).z() ==
        Approx(Pz * kL * kL * kL / (3 * kEI)).epsilon(1e-7));
  // A: a circular arc of radius EI / M, so the tip tangent turns by M L / EI; its tip sits at
  // (R sin phi, 0, R (1 - cos phi)) (sign of z: a moment +y turns x towards -z).
  const double Rc = kEI / M, phi = M * kL / kEI;
  const Vector3d tip = A.displacement(1.0, 0.0, S.block(us, 0), 1.0) + Vector3d(kL, 0, 0);
  CHECK(std::abs(tip.x() - Rc * std::sin(phi)) < 2e-4 * kL);
  CHECK(std::abs(std::abs(tip.z()) - Rc * (1 - std::cos(phi))) < 2e-4 * kL);
}

TEST_CASE("ControlPointProblem: two contact pairs add up (two half-stiffness pairs = one pair)",
          "[iga][core][body][contact]") {
  // A rope of radius 0.6 with its centre line at height 0.5 over the plane z = 0: every contact
  // point penetrates by 0.1. Penalty forces are linear in eps_N, so two pairs with eps_N / 2
  // give the residual and tangent of one pair with eps_N.
  const auto plane = std::make_shared<RigidSurface>();
  plane->add(Plane(Placement{}, Domain2{{-10, 10}, {-10, 10}}));
  const CurveContactParameters full{{1e3, 0.0, 0.0}, 0.6, 3}, half{{5e2, 0.0, 0.0}, 0.6, 3};
  RodProblem one(rod_at(Vector3d(0, 0, 0.5))), two(rod_at(Vector3d(0, 0, 0.5)));
  for (RodProblem* P : {&one, &two}) P->clamp(RodEnd::kStart);
  one.attach(std::make_unique<CurveContactPair>(one.rod().reference(), plane, full));
  two.attach(std::make_unique<CurveContactPair>(two.rod().reference(), plane, half));
  two.attach(std::make_unique<CurveContactPair>(two.rod().reference(), plane, half));
  REQUIRE(two.num_pairs() == 2);
  std::mt19937 g(7);
  std::uniform_real_distribution<double> U(-0.02, 0.02);
  VectorXd u(one.num_dofs());
  for (Eigen::Index k = 0; k < u.size(); ++k) u[k] = U(g);
  VectorXd R1, R2;
  SparseMatrix K1, K2;
  one.assemble(u, 1.0, R1, &K1);
  two.assemble(u, 1.0, R2, &K2);
  REQUIRE(R1.norm() > 1.0);  // the contact acts
  CHECK(rel(R1, R2) < 1e-13);
  CHECK((Eigen::MatrixXd(K1) - Eigen::MatrixXd(K2)).norm() <= 1e-13 * Eigen::MatrixXd(K1).norm());
  // Status: one line per pair; counts per pair.
  const ContactCounts c = two.pair(0).counts();
  CHECK(c.active == 12);  // 4 elements x 3 points, all penetrating
  CHECK(two.status() == one.status() + "; " + one.status());
  // Reactions leave the pairs' state as it was.
  const std::string before = two.status();
  (void)two.reactions(VectorXd::Zero(two.num_dofs()), 1.0);
  CHECK(two.status() == before);
  // A copy of the body has its own pairs.
  RodProblem copy = two;
  REQUIRE(copy.num_pairs() == 2);
  CHECK(&copy.pair(0) != &two.pair(0));
  VectorXd R3;
  copy.assemble(u, 1.0, R3, nullptr);
  CHECK(rel(R2, R3) == 0.0);
}

TEST_CASE(
    "BodySystem: the near null space is each body's rigid-body motions, in the tangent's kernel "
    "where the body is free and unstressed",
    "[iga][core][body]") {
  // A free straight rod, oblique to the axes (no supports: all six motions are free), and a rod
  // clamped at its start, side by side. (Straight: the torsion-free reduced model is the one of
  // initially straight rods, [MPW15] in kirchhoff_rod.hpp; its tangent at a curved reference
  // does not annihilate rotations out of the curve's plane.)
  NurbsCurve line = make_line(Vector3d(0.1, -0.2, 0.3), Vector3d(1.3, 0.7, -0.4));
  line = subdivide(elevate_degree(line, 2), 6);
  RodProblem free_rod(KirchhoffRod(line, {kEA, kEI, kEI, Vector3d::Zero()}));
  RodProblem clamped = cantilever(0.0);
  BodySystem S;
  S.add(free_rod);
  S.add(clamped);
  const VectorXd u = VectorXd::Zero(S.num_dofs());
  const Eigen::MatrixXd Z = S.near_null_space(u, 0.0);
  REQUIRE(Z.rows() == S.num_dofs());
  REQUIRE(Z.cols() == 12);
  const int n0 = free_rod.num_dofs();
  // Each body's columns in its own rows only; five independent motions of the centre line (a
  // turn about the rod's own axis moves none of its control points).
  CHECK(Z.block(n0, 0, clamped.num_dofs(), 6).cwiseAbs().maxCoeff() == 0.0);
  CHECK(Z.block(0, 6, n0, 6).cwiseAbs().maxCoeff() == 0.0);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Z.topLeftCorner(n0, 6));
  const VectorXd sv = svd.singularValues();  // descending
  CHECK(sv[4] > 1e-3 * sv[0]);
  CHECK(sv[5] < 1e-12 * sv[0]);
  // A translation along y moves every free component by 1 along y.
  const Eigen::MatrixXd Zf = free_rod.near_null_space(VectorXd::Zero(n0), 0.0);
  for (int i = 0; i < free_rod.num_control_points(); ++i) CHECK(Zf(free_rod.dof(i, 1), 1) == 1.0);
  // The free rod's tangent at rest annihilates its six motions (to round-off); the clamped
  // rod's does not annihilate its translations (its supports hold them).
  VectorXd R;
  SparseMatrix K;
  S.assemble(u, 0.0, R, &K);
  const double scale = Eigen::MatrixXd(K).cwiseAbs().maxCoeff();
  for (int m = 0; m < 6; ++m) {
    CAPTURE(m);
    CHECK((K * Z.col(m)).norm() <= 1e-10 * scale * Z.col(m).norm());
  }
  CHECK((K * Z.col(8)).norm() > 1e-6 * scale * Z.col(8).norm());  // the clamped rod along z
}

}  // namespace test_body_system
