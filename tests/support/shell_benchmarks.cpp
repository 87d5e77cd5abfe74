// Builders of the Kirchhoff-Love shell benchmarks; see shell_benchmarks.hpp.
#include "tests/support/shell_benchmarks.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "geometry/constructions.hpp"
#include "geometry/fitting.hpp"
#include "geometry/refinement.hpp"
#include "iga/solvers/linear_solver.hpp"

namespace iga {

namespace {

constexpr double kPi = std::numbers::pi;

void check_mesh(const char* what, int elements, int degree) {
  if (elements < 1 || degree < 2 || degree > kMaxShellDegree)
    throw ShellError(std::string(what) + ": need elements >= 1 and degree in [2, " +
                     std::to_string(kMaxShellDegree) + "], got " + std::to_string(elements) + ", " +
                     std::to_string(degree));
}

/// A cylindrical patch (u: one rational quadratic arc <= 90 degrees, v: along the axis),
/// elevated to `degree` in both directions and split into n x n elements.
NurbsSurface cylinder_patch(const Vector3d& axis, const Vector3d& ref_dir, double R, double L,
                            double start, double end, int n, int degree) {
  NurbsSurface s = make_cylinder(Vector3d::Zero(), axis, ref_dir, R, L, start, end);
  s = elevate_degree(s, degree - 2, degree - 1);
  return subdivide(s, n, n);
}

}  // namespace

ShellBenchmark make_scordelis_lo(int elements, int degree) {
  check_mesh("make_scordelis_lo", elements, degree);
  // Axis y, angle measured from the crown e_z: points R (cos t e_z + sin t e_x), t in +-40 deg.
  const double R = 25.0, L = 50.0, phi = 40.0 * kPi / 180.0;
  ShellProblem P(KirchhoffLoveShell(
      cylinder_patch(Vector3d::UnitY(), Vector3d::UnitZ(), R, L, -phi, phi, elements, degree),
      {4.32e8, 0.0, 0.25}));
  P.simply_support(SurfaceEdge::kVMin, {0, 2});  // rigid diaphragms: u_x = u_z = 0
  P.simply_support(SurfaceEdge::kVMax, {0, 2});
  P.fix(P.point_index(0, 0), 1);  // axial rigid translation
  P.add_surface_load(Vector3d(0.0, 0.0, -90.0), ramp());
  return ShellBenchmark{std::move(P), 1.0, 0.5, -Vector3d::UnitZ(), 0.3006};
}

ShellBenchmark make_pinched_cylinder(int elements, int degree) {
  check_mesh("make_pinched_cylinder", elements, degree);
  const double R = 300.0, L = 600.0;
  // t = 0 at the top (x = 0, z = R), t = 90 deg at z = 0; v = 0 at the diaphragm y = 0.
  ShellProblem P(KirchhoffLoveShell(cylinder_patch(Vector3d::UnitY(), Vector3d::UnitZ(), R, 0.5 * L,
                                                   0.0, 0.5 * kPi, elements, degree),
                                    {3e6, 0.3, 3.0}));
  P.symmetry(SurfaceEdge::kVMax, Vector3d::UnitY());              // mid-section
  P.symmetry(SurfaceEdge::kUMin, Vector3d::UnitX());              // top generator
  P.symmetry(SurfaceEdge::kUMax, Vector3d::UnitZ());              // side generator
  P.simply_support(SurfaceEdge::kVMin, {0, 2});                   // diaphragm
  P.add_point_load(0.0, 1.0, Vector3d(0.0, 0.0, -0.25), ramp());  // P/4 on one eighth
  return ShellBenchmark{std::move(P), 0.0, 1.0, -Vector3d::UnitZ(), 1.8248e-5};
}

SlitAnnularPlate make_slit_annular_plate(int elements_radial, int elements_around, int degree) {
  check_mesh("make_slit_annular_plate", std::min(elements_radial, elements_around), degree);
  const double Ri = 6.0, Ro = 10.0;
  // Unit circle, C^{p-1}: least-squares fit of samples at uniform angles, uniform knots.
  const int m = 16 * elements_around + 1;
  std::vector<Vector3d> Q(static_cast<std::size_t>(m));
  std::vector<double> t(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    const double s = static_cast<double>(k) / (m - 1);
    t[static_cast<std::size_t>(k)] = s;
    Q[static_cast<std::size_t>(k)] = Vector3d(std::cos(2 * kPi * s), std::sin(2 * kPi * s), 0.0);
  }
  const KnotVector U = KnotVector::uniform(degree, elements_around);
  const CurveFit fit = fit_curve(Q, t, degree, U.knots());
  double err = 0.0;
  for (int k = 0; k <= 4000; ++k)
    err = std::max(err, std::abs(fit.curve.point(k / 4000.0).norm() - 1.0));
  // Ruled annulus: rows v = 0 (Ri) and v = 1 (Ro), elevated to `degree` and split radially.
  const std::vector<Vector3d> C = fit.curve.control_points();
  std::vector<Vector3d> P;
  for (double r : {Ri, Ro})
    for (const Vector3d& c : C) P.push_back(r * c);
  NurbsSurface s(degree, U.knots(), 1, {0.0, 0.0, 1.0, 1.0}, P);
  s = elevate_degree(s, 0, degree - 1);
  s = subdivide(s, 1, elements_radial);
  ShellProblem prob(KirchhoffLoveShell(s, {21e6, 0.0, 0.03}));
  prob.clamp(SurfaceEdge::kUMin);
  prob.add_edge_load(SurfaceEdge::kUMax, Vector3d(0.0, 0.0, SlitAnnularPlate::kMaxLoad), ramp());
  return SlitAnnularPlate{std::move(prob), err * Ro};
}

VectorXd solve_linear(ShellProblem& problem, double t) {
  const VectorXd u0 = VectorXd::Zero(problem.num_dofs());
  VectorXd R;
  SparseMatrix K;
  problem.assemble(u0, t, R, &K);
  LinearSolver solver(problem.symmetric());
  VectorXd du;
  if (solver.solve(K, -R, du) != LinearSolveStatus::success)
    throw std::runtime_error("solve_linear: " + solver.message());
  return du;
}

}  // namespace iga
