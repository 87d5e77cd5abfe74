// Reactions that carry the whole constraint (issue 17, item 2): on the pinched cylinder's octant
// (symmetry planes tie the second row of control points to the first), the load point driven by
// the displacement the load P/4 produced reports the reaction -P/4 in full, the tied neighbours'
// share included (before: about three quarters), and the reactions of all points sum to minus
// the applied load (the internal forces are self-equilibrated).
#include <catch2/catch.hpp>

#include <vector>

#include "iga/shell/shell_problem.hpp"
#include "iga/solvers/nonlinear_solver.hpp"
#include "tests/support/shell_benchmarks.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_shell_reactions {

using namespace iga;

namespace {

constexpr double kLoad = 2500.0;  // P/4 on the octant: w ~ 0.05 h, round-off of |R| ~ 5e-6

/// The octant of make_pinched_cylinder (8 x 8 cubic elements), without its load.
ShellProblem octant() {
  ShellProblem q(
      KirchhoffLoveShell(make_pinched_cylinder(8, 3).problem.shell().reference(), {3e6, 0.3, 3.0}));
  q.symmetry(SurfaceEdge::kVMax, Vector3d::UnitY());  // mid-section
  q.symmetry(SurfaceEdge::kUMin, Vector3d::UnitX());  // top generator
  q.symmetry(SurfaceEdge::kUMax, Vector3d::UnitZ());  // side generator
  q.simply_support(SurfaceEdge::kVMin, {0, 2});       // diaphragm
  return q;
}

VectorXd solve(ShellProblem& p) {
  NonlinearSolverSettings s;
  s.initial_step = 0.5;
  s.tol_residual_abs = 1e-5;  // the round-off floor of |f_int| (E h = 9e6, |x| ~ 300)
  VectorXd u = VectorXd::Zero(p.num_dofs());
  const NonlinearSolverResult r = NonlinearSolver(s).solve(p, u);
  REQUIRE(r.converged());
  return u;
}

Vector3d sum(const std::vector<Vector3d>& r) {
  Vector3d s = Vector3d::Zero();
  for (const Vector3d& x : r) s += x;
  return s;
}

}  // namespace

TEST_CASE("ShellProblem: a prescribed point with tied neighbours reports its whole reaction",
          "[iga][shell][reactions]") {
  ShellProblem p = octant();
  p.add_point_load(0.0, 1.0, Vector3d(0.0, 0.0, -kLoad), ramp());
  const VectorXd u = solve(p);
  const int n_v = p.shell().reference().num_v();
  const int load_point = p.point_index(0, n_v - 1);  // (u, v) = (0, 1): the top of the mid-section
  const Vector3d d = p.current_points(u, 1.0)[static_cast<std::size_t>(load_point)] -
                     p.reference_point(load_point);
  // Load control: the reactions of all points sum to minus the applied load (0, 0, -P/4).
  const std::vector<Vector3d> r_loaded = p.reactions(u, 1.0);
  CHECK((sum(r_loaded) - Vector3d(0.0, 0.0, kLoad)).norm() < 1e-6 * kLoad);
  // z is free at the load point (x and y lie on symmetry planes: membrane reactions there).
  CHECK(std::abs(r_loaded[static_cast<std::size_t>(load_point)].z()) < 1e-6 * kLoad);

  // Displacement control: the load point's z prescribed to what the load produced.
  ShellProblem q = octant();
  double sign = 1.0;
  const int c = q.dof_map().axis_along(load_point, Vector3d::UnitZ(), &sign);
  REQUIRE(c >= 0);
  q.prescribe(load_point, c, sign * d.z());
  const VectorXd v = solve(q);
  const std::vector<Vector3d> r = q.reactions(v, 1.0);
  // The whole load comes back at the point, the tied rows' share included.
  CHECK(r[static_cast<std::size_t>(load_point)].z() == Approx(-kLoad).epsilon(1e-6));
  // The symmetry planes' reactions there are the same as under the load.
  CHECK((r[static_cast<std::size_t>(load_point)] - r_loaded[static_cast<std::size_t>(load_point)])
            .head<2>()
            .norm() < 1e-6 * kLoad);
  // Without applied loads the reactions balance.
  CHECK(sum(r).norm() < 1e-6 * kLoad);
  // The neighbour tied to the load point along z reports nothing along z: its force is the
  // load point's.
  const int neighbour = q.point_index(1, n_v - 1);
  CHECK(std::abs(r[static_cast<std::size_t>(neighbour)].z()) < 1e-12 * kLoad);
}

}  // namespace test_shell_reactions
