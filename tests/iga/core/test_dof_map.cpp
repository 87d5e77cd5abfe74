// Tests of DofMap (iga/core/dof_map.hpp) with scalar unknowns beside the points: the free
// numbering (points first, then the scalars), prescribed values along load curves, and the
// reductions R = P^T g and K = P^T K_cart P (appended or in place) against the dense map P read
// off current_points / current_scalars, with rotated, fixed, tied and prescribed components and
// rows and columns of scalars; bad indices and sizes fail.
#include <catch2/catch.hpp>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "iga/core/dof_map.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_dof_map {

using namespace iga;

namespace {

void fail(const std::string& message) {
  throw std::runtime_error(message);
}

/// 4 points and 3 scalars: point 0 fixed along z, point 1 in a turned basis with its local
/// axis 1 fixed, point 3's x tied to point 2's (antiparallel through a basis on 3: sign -1),
/// point 2's y prescribed; scalar 1 fixed, scalar 2 prescribed 0.5 t, scalar 0 free.
DofMap example() {
  DofMap d(4, "Test", &fail, 3);
  const Matrix3d Q = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  d.set_local_basis(1, Q);
  Matrix3d F = Matrix3d::Identity();
  F(0, 0) = -1.0;
  F(1, 1) = -1.0;  // a rotation by pi about z: its axis 0 is -x
  d.set_local_basis(3, F);
  d.fix(0, 2);
  d.fix(1, 1);
  d.tie(3, 0, 2, 0);
  d.prescribe(2, 1, 0.25, ramp());
  d.fix_scalar(1);
  d.prescribe_scalar(2, 0.5, ramp());
  return d;
}

/// The Cartesian state (3 n + m: points' displacements, then scalars) at (u, t).
Eigen::VectorXd cartesian(const DofMap& d, const std::vector<Vector3d>& X, const VectorXd& u,
                          double t) {
  std::vector<Vector3d> x;
  std::vector<double> s;
  d.current_points(X, u, t, x);
  d.current_scalars(u, t, s);
  Eigen::VectorXd c(d.num_cartesian());
  for (int i = 0; i < d.num_points(); ++i)
    c.segment<3>(3 * i) = x[static_cast<std::size_t>(i)] - X[static_cast<std::size_t>(i)];
  for (int k = 0; k < d.num_scalars(); ++k)
    c[3 * d.num_points() + k] = s[static_cast<std::size_t>(k)];
  return c;
}

}  // namespace

TEST_CASE("DofMap: scalar unknowns are numbered after the points and follow their load curves",
          "[iga][core][dofs]") {
  const DofMap d = example();
  // Points: 12 components, 3 constrained (0.z, 1.axis 1, 2.y), 1 tied (3.x): 8 free; scalars: 1.
  REQUIRE(d.num_cartesian() == 15);
  REQUIRE(d.num_free() == 9);
  int last_point_dof = -1;
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) last_point_dof = std::max(last_point_dof, d.dof(i, c));
  CHECK(d.scalar_dof(0) == last_point_dof + 1);
  CHECK(d.scalar_dof(1) == -1);
  CHECK(d.scalar_dof(2) == -1);
  CHECK(d.scalar_constrained(1));
  CHECK_FALSE(d.scalar_constrained(0));
  VectorXd u = VectorXd::Zero(d.num_free());
  u[d.scalar_dof(0)] = 1.5;
  std::vector<double> s;
  d.current_scalars(u, 0.4, s);
  REQUIRE(s.size() == 3);
  CHECK(s[0] == 1.5);
  CHECK(s[1] == 0.0);
  CHECK(s[2] == Approx(0.2).epsilon(1e-15));
  // A tied component follows its master with the tie's sign.
  const std::vector<Vector3d> X(4, Vector3d(1, 2, 3));
  u.setZero();
  u[d.dof(2, 0)] = 0.3;
  const Eigen::VectorXd c = cartesian(d, X, u, 0.0);
  CHECK(c[6] == Approx(0.3).epsilon(1e-15));
  CHECK(c[9] == Approx(0.3).epsilon(1e-15));  // point 3's x: its axis 0 is -x, tied with -1
}

TEST_CASE("DofMap: R = P^T g and K = P^T K_cart P with scalar rows and columns",
          "[iga][core][dofs]") {
  const DofMap d = example();
  const std::vector<Vector3d> X(4, Vector3d::Zero());
  const int nf = d.num_free(), nc = d.num_cartesian();
  // P column by column: the state is linear in u at t = 0 (prescribed values 0 there).
  Eigen::MatrixXd P(nc, nf);
  const Eigen::VectorXd c0 = cartesian(d, X, VectorXd::Zero(nf), 0.0);
  CHECK(c0.norm() == 0.0);
  for (int j = 0; j < nf; ++j) P.col(j) = cartesian(d, X, VectorXd::Unit(nf, j), 0.0) - c0;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd g(nc);
  for (int i = 0; i < nc; ++i) g[i] = U(gen);
  VectorXd R;
  d.reduce(g, R);
  CHECK((R - P.transpose() * g).cwiseAbs().maxCoeff() < 1e-14);
  // A dense Cartesian tangent as triplets (scalar rows and columns included).
  Eigen::MatrixXd Kc(nc, nc);
  std::vector<Triplet> cart, free;
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j < nc; ++j) {
      Kc(i, j) = U(gen);
      cart.emplace_back(i, j, Kc(i, j));
    }
  d.reduce(cart, free);
  Eigen::SparseMatrix<double> K(nf, nf);
  K.setFromTriplets(free.begin(), free.end());
  const Eigen::MatrixXd expected = P.transpose() * Kc * P;
  CHECK((Eigen::MatrixXd(K) - expected).cwiseAbs().maxCoeff() < 1e-13);
  // In place: the same triplets, those of plain points in their places, the spread ones after.
  std::vector<Triplet> in_place = cart;
  d.reduce_in_place(in_place);
  CHECK(in_place.size() == free.size());
  Eigen::SparseMatrix<double> Ki(nf, nf);
  Ki.setFromTriplets(in_place.begin(), in_place.end());
  CHECK((Eigen::MatrixXd(Ki) - expected).cwiseAbs().maxCoeff() < 1e-13);
}

TEST_CASE("DofMap: bad scalar indices and residual sizes fail with the owner's message",
          "[iga][core][dofs]") {
  DofMap d(2, "Test", &fail, 1);
  CHECK_THROWS_WITH(d.fix_scalar(1), Catch::Contains("Test::fix_scalar") &&
                                         Catch::Contains("scalar unknown 1 out of range [0, 0]"));
  CHECK_THROWS_WITH(d.prescribe_scalar(-1, 1.0, ramp()), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(d.scalar_dof(3), Catch::Contains("out of range"));
  VectorXd R;
  CHECK_THROWS_WITH(d.reduce(VectorXd::Zero(6), R), Catch::Contains("expected 7"));
  std::vector<double> s;
  CHECK_THROWS_WITH(d.current_scalars(VectorXd::Zero(2), 0.0, s), Catch::Contains("expected 7"));
}

}  // namespace test_dof_map
