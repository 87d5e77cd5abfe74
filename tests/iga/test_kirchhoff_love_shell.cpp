// Tests of the rotation-free Kirchhoff-Love shell (iga/kirchhoff_love_shell.hpp): forces and
// tangent against central finite differences, rigid body motions, a membrane patch test and
// plate bending against series solutions.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/kirchhoff_love_shell.hpp"

using namespace iga;

namespace {

constexpr double kPi = std::numbers::pi;

/// A curved, rational, non-uniformly weighted patch of degree (p, p): a 70-degree cylindrical
/// arc elevated and refined, control points and weights randomly perturbed (C^{p-1} inside).
NurbsSurface curved_patch(std::mt19937& rng, int p, int nel) {
  NurbsSurface s = make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 1.2,
                                 0.0, 70.0 * kPi / 180.0);
  s = elevate_degree(s, p - 2, p - 1);
  s = subdivide(s, nel, nel);
  std::uniform_real_distribution<double> d(-0.05, 0.05), w(0.8, 1.25);
  std::vector<Vector3d> P = s.control_points();
  std::vector<double> W = s.weights();
  for (Vector3d& X : P) X += Vector3d(d(rng), d(rng), d(rng));
  for (double& x : W) x *= w(rng);
  return NurbsSurface(p, s.knots_u().knots(), p, s.knots_v().knots(), P, W);
}

std::vector<Vector3d> perturbed(const std::vector<Vector3d>& X, std::mt19937& rng, double amp) {
  std::uniform_real_distribution<double> d(-amp, amp);
  std::vector<Vector3d> x = X;
  for (Vector3d& xi : x) xi += Vector3d(d(rng), d(rng), d(rng));
  return x;
}

double max_abs(const Eigen::VectorXd& v) {
  return v.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("KirchhoffLoveShell: element tangent = central FD of the forces, forces = FD of the "
          "energy, degree 2 and 3, curved rational patch",
          "[iga][shell]") {
  std::mt19937 rng(7);
  for (int p : {2, 3}) {
    const KirchhoffLoveShell shell(curved_patch(rng, p, 2), {1000.0, 0.3, 0.05});
    const std::vector<Vector3d> x = perturbed(shell.reference_points(), rng, 0.1);
    const int np = (p + 1) * (p + 1);
    for (int e : {0, shell.num_elements() - 1}) {
      ShellElementVector f, fp, fm;
      ShellElementMatrix K;
      shell.element_tangent(e, x, f, K);
      ShellElementVector f1;
      shell.element_forces(e, x, f1);
      CHECK((f1 - f).norm() <= 1e-12 * f.norm());
      CHECK((K - K.transpose()).norm() <= 1e-12 * K.norm());
      Eigen::MatrixXd Kfd(3 * np, 3 * np);
      Eigen::VectorXd ffd(3 * np);
      const double eps = 1e-6;
      for (int k = 0; k < np; ++k)
        for (int c = 0; c < 3; ++c) {
          std::vector<Vector3d> xp = x, xm = x;
          const std::size_t I = static_cast<std::size_t>(shell.element_point(e, k));
          xp[I][c] += eps;
          xm[I][c] -= eps;
          shell.element_forces(e, xp, fp);
          shell.element_forces(e, xm, fm);
          Kfd.col(3 * k + c) = (fp - fm) / (2 * eps);
          ffd[3 * k + c] = (shell.element_energy(e, xp) - shell.element_energy(e, xm)) / (2 * eps);
        }
      const double errK = (Kfd - Eigen::MatrixXd(K)).norm() / K.norm();
      const double errf = (ffd - Eigen::VectorXd(f)).norm() / f.norm();
      std::printf("shell FD p = %d, element %d: |K - K_fd|/|K| = %.2e, |f - f_fd|/|f| = %.2e\n",
                  p, e, errK, errf);
      CHECK(errK <= 1e-6);
      CHECK(errf <= 1e-6);
    }
  }
}

TEST_CASE("KirchhoffLoveShell: rigid translation and finite rotation give zero energy and "
          "forces",
          "[iga][shell]") {
  std::mt19937 rng(11);
  const KirchhoffLoveShell shell(curved_patch(rng, 3, 3), {1e5, 0.25, 0.02});
  const std::vector<Vector3d>& X = shell.reference_points();
  const Matrix3d Q = Eigen::AngleAxisd(2.1, Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  std::vector<Vector3d> x(X.size());
  for (std::size_t i = 0; i < X.size(); ++i) x[i] = Q * X[i] + Vector3d(0.3, -1.0, 2.0);
  Eigen::VectorXd f;
  std::vector<Triplet> T;
  shell.assemble(x, f, &T);
  // Scale: the forces of a 1 % random perturbation.
  Eigen::VectorXd f_ref;
  shell.assemble(perturbed(X, rng, 0.01), f_ref, nullptr);
  CHECK(shell.energy(x) <= 1e-20 * shell.energy(perturbed(X, rng, 0.01)) + 1e-18);
  CHECK(max_abs(f) <= 1e-10 * max_abs(f_ref));
  CHECK(shell.energy(X) == Approx(0.0).margin(1e-20));
}
