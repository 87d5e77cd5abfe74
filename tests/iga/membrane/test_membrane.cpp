// The membrane (iga/membrane/membrane.hpp): its internal forces are the derivative of its
// energy, its tangent the derivative of its residual (central differences, both laws, with
// prestress and follower pressure, at a stretched and sheared state of a curved patch), and its
// laws give the uniaxial and equibiaxial closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/SparseCore>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/membrane/membrane.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_membrane {

using namespace iga;

namespace {

/// A quarter cylinder (R = 1, height 0.6), degree 2 x 2, 3 x 2 elements.
NurbsSurface patch() {
  const NurbsSurface c = make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0,
                                       0.6, 0.0, 0.5 * std::numbers::pi);
  return subdivide(elevate_degree(c, 0, 1), 3, 2);
}

/// A smooth, non-uniform state: stretch, shear and a bulge (u: all control points, 3 each).
Eigen::VectorXd state(const MembraneProblem& p) {
  Eigen::VectorXd u(p.num_dofs());
  for (int i = 0; i < p.num_control_points(); ++i) {
    const Vector3d X = p.reference_point(i);
    u.segment<3>(3 * i) = Vector3d(0.08 * X.x() + 0.03 * X.z(), 0.05 * X.y() * X.y(),
                                   0.04 * std::sin(3.0 * X.x()) + 0.02 * X.y());
  }
  return u;
}

Eigen::VectorXd residual(MembraneProblem& p, const Eigen::VectorXd& u) {
  Eigen::VectorXd R;
  p.assemble(u, 1.0, R, nullptr);
  return R;
}

/// max |K - dR/du| / max |K| by central differences of step h.
double tangent_error(MembraneProblem& p, const Eigen::VectorXd& u, double h) {
  Eigen::VectorXd R;
  Eigen::SparseMatrix<double> K;
  p.assemble(u, 1.0, R, &K);
  const Eigen::MatrixXd Kd(K);
  double err = 0.0;
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    Eigen::VectorXd up = u, um = u;
    up[j] += h;
    um[j] -= h;
    err = std::max(
        err, ((residual(p, up) - residual(p, um)) / (2.0 * h) - Kd.col(j)).cwiseAbs().maxCoeff());
  }
  return err / Kd.cwiseAbs().maxCoeff();
}

MembraneMaterial svk() {
  MembraneMaterial m;
  m.E = 200.0;
  m.nu = 0.3;
  m.thickness = 0.01;
  return m;
}

MembraneMaterial neo_hookean() {
  MembraneMaterial m;
  m.law = MembraneLaw::kNeoHookean;
  m.mu = 1.5;
  m.thickness = 0.02;
  return m;
}

}  // namespace

TEST_CASE("membrane: the internal forces are the derivative of the energy (both laws)",
          "[iga][membrane]") {
  for (const MembraneMaterial& m : {svk(), neo_hookean()}) {
    INFO("law " << static_cast<int>(m.law));
    MembraneProblem p(patch(), m);
    const Eigen::VectorXd u = state(p);
    const Eigen::VectorXd f = residual(p, u);  // no loads: f_int
    const std::vector<Vector3d> x = p.current_points(u, 1.0);
    double err = 0.0;
    const double h = 1e-6;
    for (int i = 0; i < p.num_control_points(); ++i)
      for (int c = 0; c < 3; ++c) {
        std::vector<Vector3d> xp = x, xm = x;
        xp[static_cast<std::size_t>(i)][c] += h;
        xm[static_cast<std::size_t>(i)][c] -= h;
        const double d = (p.energy(xp) - p.energy(xm)) / (2.0 * h);
        err = std::max(err, std::abs(d - f[3 * i + c]));
      }
    CHECK(err < 1e-7 * f.cwiseAbs().maxCoeff());
    CHECK(f.cwiseAbs().maxCoeff() > 1e-3);  // the state is loaded
  }
}

TEST_CASE(
    "membrane: the tangent is the derivative of the residual (both laws, prestress, "
    "follower pressure)",
    "[iga][membrane]") {
  for (MembraneMaterial m : {svk(), neo_hookean()}) {
    INFO("law " << static_cast<int>(m.law));
    m.prestress = 0.05;
    MembraneProblem p(patch(), m);
    p.add_pressure(0.7);
    const Eigen::VectorXd u = state(p);
    const double err = tangent_error(p, u, 1e-6);
    INFO("relative error " << err);
    CHECK(err < 1e-6);
    CHECK_FALSE(p.symmetric());  // the follower pressure's stiffness
  }
}

TEST_CASE("membrane: the laws at a point give the uniaxial and equibiaxial closed forms",
          "[iga][membrane]") {
  // Unit reference metric; stretches l1, l2: a = diag(l1^2, l2^2).
  const double l1 = 1.3, l2 = 0.9;
  Matrix2d A = Matrix2d::Identity(), a;
  a << l1 * l1, 0.0, 0.0, l2 * l2;
  // St. Venant-Kirchhoff: S^11 = t E/(1 - nu^2) (E_11 + nu E_22).
  const MembraneMaterial s = svk();
  const double E11 = 0.5 * (l1 * l1 - 1.0), E22 = 0.5 * (l2 * l2 - 1.0);
  const MembraneResponse rs = membrane_response(s, A, a);
  CHECK(rs.S[0] == Approx(s.thickness * s.E / (1.0 - s.nu * s.nu) * (E11 + s.nu * E22)));
  CHECK(rs.S[2] == Approx(0.0).margin(1e-15));
  // Incompressible neo-Hookean: S^11 = mu t (1 - 1/(l1^2 l2^2) / l1^2), i.e. the Cauchy stress
  // sigma_1 = mu (l1^2 - l3^2) with l3 = 1/(l1 l2).
  const MembraneMaterial n = neo_hookean();
  const MembraneResponse rn = membrane_response(n, A, a);
  const double l3 = 1.0 / (l1 * l2);
  CHECK(rn.S[0] * l1 * l1 / (l1 * l2) == Approx(n.mu * n.thickness * l3 * (l1 * l1 - l3 * l3)));
  CHECK(rn.W == Approx(0.5 * n.mu * n.thickness * (l1 * l1 + l2 * l2 + l3 * l3 - 3.0)));
  // A degenerate point: no finite response.
  const MembraneResponse bad = membrane_response(n, A, Matrix2d::Zero());
  CHECK(std::isinf(bad.W));
  CHECK(std::isnan(bad.S[0]));
}

TEST_CASE("membrane: bad input is refused", "[iga][membrane]") {
  MembraneMaterial m = svk();
  m.nu = 0.6;
  CHECK_THROWS_AS(MembraneProblem(patch(), m), MembraneError);
  m = neo_hookean();
  m.mu = 0.0;
  CHECK_THROWS_WITH(MembraneProblem(patch(), m), Catch::Contains("mu must be > 0"));
  MembraneProblem p(patch(), svk());
  CHECK_THROWS_AS(p.support(SurfaceEdge::kUMin, {3}), MembraneError);
  CHECK_THROWS_AS(p.symmetry(SurfaceEdge::kUMin, Vector3d::Zero()), MembraneError);
}

}  // namespace test_membrane
