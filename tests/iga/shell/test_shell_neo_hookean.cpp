// Tests of the neo-Hookean shell law (iga/shell/kirchhoff_love_shell.hpp, ShellLaw::kNeoHookean):
// the plane-stress material point (small-strain limit, stress and tangent against finite
// differences, S^33 = 0) and a tube inflated by a follower pressure to twice its radius against
// the closed form. The element's forces and tangent are checked against finite differences in
// test_kirchhoff_love_shell.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/shell/kirchhoff_love_shell.hpp"
#include "iga/shell/shell_problem.hpp"
#include "iga/solvers/nonlinear_solver.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_shell_neo_hookean {

using namespace iga;

namespace {

/// Plane-stress isotropic tensor of the St. Venant-Kirchhoff shell on the metric A (Voigt).
Matrix3d linear_tensor(double E, double nu, const Matrix2d& A) {
  const Matrix2d G = A.inverse();
  const double g11 = G(0, 0), g22 = G(1, 1), g12 = G(0, 1);
  Matrix3d D;
  D << g11 * g11, nu * g11 * g22 + (1 - nu) * g12 * g12, g11 * g12,  //
      nu * g11 * g22 + (1 - nu) * g12 * g12, g22 * g22, g22 * g12,   //
      g11 * g12, g22 * g12, 0.5 * (1 - nu) * g11 * g22 + 0.5 * (1 + nu) * g12 * g12;
  return E / (1 - nu * nu) * D;
}

}  // namespace

TEST_CASE(
    "neo-Hookean plane stress: the small-strain tangent is the linear one, S and D are the "
    "derivatives of psi, and S^33 = 0",
    "[iga][shell][neo_hookean]") {
  const double E = 200.0, nu = 0.35;
  Matrix2d A;  // an oblique, stretched reference metric
  A << 2.0, 0.6, 0.6, 0.7;
  const PlaneStressPoint p0 = neo_hookean_plane_stress(E, nu, A, Vector3d::Zero());
  CHECK(p0.psi == Approx(0.0).margin(1e-14));
  CHECK(p0.S.norm() <= 1e-12 * E);
  CHECK(p0.C33 == Approx(1.0).epsilon(1e-15));
  const Matrix3d Dlin = linear_tensor(E, nu, A);
  CHECK((p0.D - Dlin).norm() <= 1e-12 * Dlin.norm());

  // A large strain (stretches up to ~1.6): S = d psi / dE, D = dS / dE (Voigt with the
  // engineering shear 2 E_12, so d/d(2 E_12) on the third entry).
  const Vector3d Eps(0.8, -0.15, 0.5);
  const PlaneStressPoint p = neo_hookean_plane_stress(E, nu, A, Eps);
  Vector3d S_fd;
  Matrix3d D_fd;
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    Vector3d ep = Eps, em = Eps;
    ep[j] += h;
    em[j] -= h;
    const PlaneStressPoint pp = neo_hookean_plane_stress(E, nu, A, ep);
    const PlaneStressPoint pm = neo_hookean_plane_stress(E, nu, A, em);
    S_fd[j] = (pp.psi - pm.psi) / (2 * h);
    D_fd.col(j) = (pp.S - pm.S) / (2 * h);
  }
  std::printf("neo-Hookean point: |S - S_fd|/|S| = %.2e, |D - D_fd|/|D| = %.2e, C33 = %.6f\n",
              (S_fd - p.S).norm() / p.S.norm(), (D_fd - p.D).norm() / p.D.norm(), p.C33);
  CHECK((S_fd - p.S).norm() <= 1e-7 * p.S.norm());
  CHECK((D_fd - p.D).norm() <= 1e-7 * p.D.norm());
  CHECK((p.D - p.D.transpose()).norm() <= 1e-13 * p.D.norm());
  // The 3D stress normal to the shell vanishes: S^33 = mu (1 - 1/C33) + lambda ln J / C33.
  const double mu = E / (2 * (1 + nu)), lam = E * nu / ((1 + nu) * (1 - 2 * nu));
  Matrix2d C = A;
  C(0, 0) += 2 * Eps[0];
  C(1, 1) += 2 * Eps[1];
  C(0, 1) += Eps[2];
  C(1, 0) += Eps[2];
  const double lnJ = 0.5 * std::log(C.determinant() / A.determinant() * p.C33);
  CHECK(std::abs(mu * (1 - 1 / p.C33) + lam * lnJ / p.C33) <= 1e-12 * mu);
  // An inverted point has infinite energy.
  CHECK(std::isinf(neo_hookean_plane_stress(E, nu, A, Vector3d(-1.2, 0.0, 0.0)).psi));
}

namespace {

/// Inflation of a long tube in plane strain (axial stretch 1) to the hoop stretch s: the
/// pressure per current area p = h S / R with the hoop 2nd Piola-Kirchhoff stress S (the hoop
/// force lambda S h of the current thickness, over the current radius s R; C_33 = c from
/// S^33 = 0, found here by bisection). Thin-shell closed form: bending adds O((h/R)^2).
double tube_pressure_neo_hookean(double E, double nu, double h, double R, double s) {
  const double mu = E / (2 * (1 + nu)), lam = E * nu / ((1 + nu) * (1 - 2 * nu));
  auto g = [&](double c) { return mu * (c - 1) + lam * (std::log(s) + 0.5 * std::log(c)); };
  double lo = 1e-6, hi = 1.0;  // g(lo) < 0 <= g(1) for s >= 1
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0 ? lo : hi) = mid;
  }
  const double c = 0.5 * (lo + hi);
  const double lnJ = std::log(s) + 0.5 * std::log(c);
  return h / R * (mu * (1 - 1 / (s * s)) + lam * lnJ / (s * s));
}

/// The same for St. Venant-Kirchhoff: S = E/(1 - nu^2) (s^2 - 1)/2 (no axial strain).
double tube_pressure_svk(double E, double nu, double h, double R, double s) {
  return h / R * E / (1 - nu * nu) * 0.5 * (s * s - 1);
}

/// Hoop stretch of a quarter tube (R = 1, length 0.5, symmetry on all four edges: plane strain)
/// under the follower pressure p (ramped over t in [0, 1]).
double inflate(ShellLaw law, double E, double nu, double h, double p) {
  NurbsSurface s = make_cylinder(Vector3d::Zero(), Vector3d::UnitY(), Vector3d::UnitZ(), 1.0, 0.5,
                                 0.0, std::numbers::pi / 2);
  s = subdivide(elevate_degree(s, 1, 2), 4, 2);
  ShellProblem P(KirchhoffLoveShell(s, {E, nu, h, law, 5}));
  P.symmetry(SurfaceEdge::kUMin, Vector3d::UnitX());
  P.symmetry(SurfaceEdge::kUMax, Vector3d::UnitZ());
  P.symmetry(SurfaceEdge::kVMin, Vector3d::UnitY());
  P.symmetry(SurfaceEdge::kVMax, Vector3d::UnitY());
  // The follower pressure acts along a_3: its sign makes it push outwards.
  const Vector3d n = P.shell().normal(0.3, 0.4, P.shell().reference_points());
  const Vector3d X = s.point(0.3, 0.4);
  const double sign = n.dot(Vector3d(X.x(), 0.0, X.z())) > 0 ? 1.0 : -1.0;
  P.add_pressure(sign * p);
  NonlinearSolverSettings st;
  st.initial_step = 0.05;
  st.max_step = 0.1;
  NonlinearSolver solver(st);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(P.num_dofs());
  const NonlinearSolverResult r = solver.solve(P, u);
  INFO(r.message);
  REQUIRE(r.converged());
  const std::vector<Vector3d> x = P.current_points(u, 1.0);
  double smin = 1e300, smax = 0.0;
  for (double uu : {0.0, 0.17, 0.5, 0.83, 1.0}) {
    const Vector3d y = P.shell().point(uu, 0.3, x);
    const double si = std::hypot(y.x(), y.z());
    smin = std::min(smin, si);
    smax = std::max(smax, si);
  }
  CHECK(smax - smin <= 1e-6 * smax);  // stays a circle
  return smax;
}

}  // namespace

TEST_CASE(
    "neo-Hookean shell: a tube inflated to 1.2, 1.5 and 2 times its radius follows the closed "
    "form, and St. Venant-Kirchhoff at the same pressure does not",
    "[iga][shell][neo_hookean]") {
  const double E = 1.0, nu = 0.3, h = 1e-3, R = 1.0;
  for (double s : {1.2, 1.5, 2.0}) {
    const double p = tube_pressure_neo_hookean(E, nu, h, R, s);
    const double s_nh = inflate(ShellLaw::kNeoHookean, E, nu, h, p);
    const double s_svk = inflate(ShellLaw::kSaintVenantKirchhoff, E, nu, h, p);
    // St. Venant-Kirchhoff's own closed form at the pressure it carries, as a check of the
    // test's set-up (the same tube, the same load).
    const double p_svk = tube_pressure_svk(E, nu, h, R, s_svk);
    std::printf(
        "tube, hoop stretch %.1f: p = %.6e; neo-Hookean %.8f (%+.1e), St. Venant-Kirchhoff %.6f "
        "(its closed form at that stretch: p %+.1e)\n",
        s, p, s_nh, s_nh / s - 1, s_svk, p_svk / p - 1);
    // Thin-shell closed form: bending and the membrane-bending coupling add O((h/R)^2) = 1e-6.
    CHECK(s_nh == Approx(s).epsilon(1e-6));
    CHECK(p_svk == Approx(p).epsilon(1e-6));
    CHECK(std::abs(s_svk - s) > 0.02 * (s - 1));  // the laws differ at these strains
  }
}

}  // namespace test_shell_neo_hookean
