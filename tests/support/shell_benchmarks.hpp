// Reusable builders of the Kirchhoff-Love shell benchmarks of ../shared/BENCHMARKS.md
// (Scordelis-Lo roof, pinched cylinder, slit annular plate) for tests, apps and JSON models.
// References: [MH85] R. H. MacNeal, R. L. Harder, A proposed standard set of problems to test
//   finite element accuracy, Finite Elem. Anal. Des. 1 (1985) 3-20 (Scordelis-Lo 0.3024,
//   pinched cylinder 1.8248e-5); [KBLW09] Sect. 6 (IGA KL: Scordelis-Lo converges to 0.3006);
// [SLL04] K. Y. Sze, X. H. Liu, S. H. Lo, Popular benchmark problems for geometric nonlinear
//   analysis of shells, Finite Elem. Anal. Des. 40 (2004) 1551-1569 (slit annular plate).
#pragma once

#include <string>

#include "iga/shell/shell_problem.hpp"

namespace iga {

/// A linear benchmark: the problem (loads at t = 1) and where / what to measure.
struct ShellBenchmark {
  ShellProblem problem;
  double u = 0.0, v = 0.0;                ///< measuring point (parameters)
  Vector3d direction = Vector3d::Zero();  ///< measured displacement component d . direction
  double reference = 0.0;                 ///< reference value of that component
};

/// Scordelis-Lo roof ([MH85]): R = 25, L = 50, arc +-40 degrees about the crown (z up, axis y),
/// h = 0.25, E = 4.32e8, nu = 0, self weight 90 per area (-z), rigid diaphragms at y = 0, L
/// (u_x = u_z = 0), free straight edges; u_y fixed at one diaphragm corner (no reaction: the
/// load has no y resultant). Full roof, one rational quadratic segment of 80 degrees elevated to
/// `degree` and split into `elements` x `elements`. Measure: vertical displacement (-u_z) at
/// the mid-point of a free edge; reference 0.3006 (converged KL value, [KBLW09]).
ShellBenchmark make_scordelis_lo(int elements, int degree);

/// Pinched cylinder with rigid diaphragms ([MH85]): R = 300, L = 600, h = 3, E = 3e6, nu = 0.3,
/// two opposite loads P = 1. One eighth (axis y, y in [0, 300], arc from the top (x = 0) to
/// z = 0), symmetry at y = 300, x = 0, z = 0; diaphragm at y = 0 (u_x = u_z = 0); load P/4 at
/// the top of the mid-section (-z). Measure: -u_z under the load; reference 1.8248e-5.
ShellBenchmark make_pinched_cylinder(int elements, int degree);

/// Slit annular plate ([SLL04]): Ri = 6, Ro = 10, h = 0.03, E = 21e6, nu = 0; u runs around
/// (u = 0: clamped side of the slit, u = 1: loaded side), v radially (0: inner, 1: outer). The
/// circle is a least-squares cubic (or `degree`) B-spline fit of `elements_around` elements (C^
/// {p-1}, one patch); geometric_error is max ||C(s)| - 1| * Ro over a dense sample. Line force
/// 0.8 t per reference length in +z on the edge u = 1. W_A = u_z at (1, 0), W_B at (1, 1).
struct SlitAnnularPlate {
  ShellProblem problem;
  double geometric_error = 0.0;
  static constexpr double kMaxLoad = 0.8;  ///< line force at t = 1
};
SlitAnnularPlate make_slit_annular_plate(int elements_radial, int elements_around, int degree);

/// The linear solution of a problem at pseudo-time t: one Newton step from u = 0,
/// u = -K(0)^-1 R(0, t) (exact for the linearized problem: f_int is linear in u to first
/// order). Throws std::runtime_error if the factorization fails.
VectorXd solve_linear(ShellProblem& problem, double t = 1.0);

}  // namespace iga
