// The capstan (Euler-Eytelwein) problem of [KS15] Sect. 6.3: a rope (a Kirchhoff rod of small
// bending stiffness) wrapped over a rigid circular cylinder by the angle phi, one end under a
// dead load T0, the other end held, then pulled until the whole contact arc slides; the
// reaction T at the pulled end then obeys T / T0 = exp(mu phi)  (82).
// References: [KS15] see ../shared/paper/EQUATIONS.md §3-5 (CTRS contact, (52), (66)-(70),
//   (82)); ../shared/BENCHMARKS.md "Belt friction" (closed forms, the bending correction);
//   [PT97] Sect. 9.4.1 (least-squares fit of the reference centre line).
//
// Set-up (planar, in the plane z = 0 normal to the cylinder axis e_z through the origin):
//   centre line radius rho = R + r (cylinder radius plus rope radius, gap (52) zero);
//   the arc is symmetric about +e_y, from theta_A = pi/2 + phi/2 to theta_B = pi/2 - phi/2
//   (clockwise), unit travel direction tau(theta) = (sin theta, -cos theta, 0);
//   span A: the tangent line of length L ending at the arc start, end A = P_A - L tau_A;
//   span B: the tangent line of length L from the arc end, end B = P_B + L tau_B.
// The reference centre line is that line + arc + line, least-squares fitted by a cubic B-spline
// with arc-length parameter, simple knots inside each piece and double knots (C1) at the
// tangent points, where the curvature jumps (geometry/constructions.hpp, make_wrap_path). All z
// components are fixed (planar problem).
// The helix of [KS15] Sect. 6.4 is the same model with pitch H != 0: the arc becomes a helix
// of rise H per turn (a geodesic of the cylinder), the spans its tangent lines, the problem is
// 3-D (no component fixed) and the reference is (83).
// Loads: F_A = lambda_A(t) T0 (-tau_A) at end A, lambda_A = min(t, 1) (dead load along the
// outgoing direction); end B pinned, displaced by min(max(t - 1, 0), 1) * pull * tau_B.
// T = |reaction at end B| = |g_B| (RodContactProblem::reactions, i.e. RodProblem::nodal_residual):
// the end is a pin and span B is straight and free, so the reaction is the tension.
//
// Notation (symbol -> code): R -> radius, r -> rope_radius, phi -> phi, mu -> mu, T0 -> T0,
// EA, EI -> EA, EI, eps_N, eps_T -> eps_N, eps_T, L -> span_length, rho -> centre line radius.
//
// Default parameters (justification). The paper gives EA = eps_N = eps_T = 2.1e4 and 10 C1
// elements on the arc; R, T0 and the rope radius are free (EQUATIONS.md §5). R = 1, T0 = 10,
// r = 0.02. A Kirchhoff rod acts as a rope only for small EI / (T0 R^2) (BENCHMARKS.md):
// EI = 1e-2 gives 1e-3, the limit allowed there. The reference arc is stress-free, so bending
// enters only where material slides across a tangent point (its curvature changes by
// 1/rho over a lift-off zone sqrt(EI / T) ~ 0.03): the power balance of steady sliding puts
// that effect below EI / (rho^2 T0) = 1e-3 of T (measured: EI = 1e-2 -> 1e-4 changes T / T0 by
// less than 3e-4 even after a slide of 0.05). Axial strain T / EA <= 10 e^{mu pi} / 2.1e4,
// e.g. 1.2e-3 for mu = 0.3 and 2.3e-3 for mu = 0.5 (Green-Lagrange strain; the rope is
// practically inextensible). The penalty penetration |xi3| = T / (eps_N rho) <= 2.3e-3 lowers
// the contact radius, which turns span B about end B by ~|xi3| / L; the measured wrap angle
// (CapstanResult::wrap_angle) shows by how much. pull = 0.05 (0.005 per step of 0.1) reaches
// full slip for mu up to 1: measured at a pull of 0.005 (mu <= 0.3), 0.01 (0.5), 0.035 (1.0).
#pragma once

#include <iosfwd>
#include <memory>
#include <numbers>
#include <vector>

#include "iga/contact_integrals/rod_contact_problem.hpp"
#include "iga/solvers/nonlinear_solver.hpp"

namespace iga {

/// Parameters of the capstan model; validate() throws std::invalid_argument naming the field.
struct CapstanParameters {
  double radius = 1.0;            ///< cylinder radius R
  double rope_radius = 0.02;      ///< rope radius r in the gap (52)
  double phi = std::numbers::pi;  ///< wrap angle, in (0, 2 pi]
  double pitch = 0.0;             ///< helix pitch H ([KS15] Sect. 6.4); 0: planar capstan
  double mu = 0.3;                ///< Coulomb friction coefficient
  double T0 = 10.0;               ///< dead load at end A
  double EA = 2.1e4;              ///< axial stiffness ([KS15] Sect. 6.3)
  double EI = 1e-2;               ///< bending stiffness: EI / (T0 R^2) = 1e-3
  double eps_N = 2.1e4;           ///< normal penalty (34)
  double eps_T = 2.1e4;           ///< tangential penalty (66)
  double span_length = 1.0;       ///< length L of each straight free span
  int arc_elements = 10;          ///< C1 cubic elements on the arc ([KS15]: 10)
  int span_elements = 3;          ///< elements on each straight span
  int contact_points = 3;         ///< contact (Gauss) points per element
  double pull = 0.05;             ///< displacement of end B over t in [1, 2]
  bool nurbs_cylinder = true;     ///< exact NURBS patch (make_cylinder), else analytic
  bool planar = true;             ///< fix every z for pitch 0 (false: a free 3-D rope)
  int plateau_steps = 1;          ///< steps of steady sliding before kFullSlip stops
  /// If set, this rigid surface replaces the cylinder (tests: the same circle of radius
  /// `radius` in the plane z = 0 on other surfaces and parametrizations: a sphere's equator or
  /// a meridian over its pole, a cylinder with its seam or patch borders under the arc).
  std::shared_ptr<const RigidSurface> rigid;

  void validate() const;
  /// exp(mu phi rho / sqrt(rho^2 + (H / 2 pi)^2)) (83), rho = radius + rope_radius the centre
  /// line's radius; exp(mu phi) (82) for H = 0.
  double exact_ratio() const;
};

/// The built model: the problem (rod + contact + BCs + loads) and what the run needs to know.
struct CapstanModel {
  CapstanParameters parameters;
  RodContactProblem problem;
  double fit_deviation = 0.0;  ///< largest distance of the fitted centre line from line+arc+line
  int end_a = 0;               ///< control point of end A (dead load)
  int end_b = 0;               ///< control point of end B (held, pulled)
  Vector3d out_a = Vector3d::Zero();  ///< outgoing unit direction at A (-tau_A): the load's
  Vector3d out_b = Vector3d::Zero();  ///< outgoing unit direction at B (tau_B): the pull's
};

/// Builds the model of the file comment. Throws std::invalid_argument for bad parameters.
CapstanModel make_capstan(const CapstanParameters& p);

/// One converged load step.
struct CapstanStep {
  double t = 0.0;
  double T_ratio = 0.0;  ///< |reaction at B| / T0
  int active = 0, stick = 0, slip = 0;
  int iterations = 0;       ///< Newton iterations of the step
  double drag_ratio = 0.0;  ///< CurveContactCounts::drag_ratio
  int slip_back = 0;        ///< slipping points pulling the other way than the most
};

/// The sliding plateau: the run of consecutive steps (t > 1) of steady sliding
/// (steady_sliding, curve_contact.hpp), and T / T0 over it.
struct CapstanPlateau {
  double t = -1.0;     ///< its first step (-1: none)
  double onset = 0.0;  ///< T / T0 at that step
  double mean = 0.0, min = 0.0, max = 0.0;
  int steps = 0;
  /// Half the range relative to the mean: how much T / T0 swings while sliding.
  double spread() const { return steps > 0 ? 0.5 * (max - min) / mean : 0.0; }
};

struct CapstanResult {
  NonlinearSolverResult solver;
  std::vector<CapstanStep> steps;
  double T_ratio = 0.0;  ///< at the last converged step (the first step of the
                         ///< plateau when kFullSlip stops with plateau_steps = 1)
  CapstanPlateau plateau;
  double exact = 0.0;             ///< exp(mu phi)  (82)
  bool full_slip = false;         ///< the rope slides steadily at the last step (mu = 0:
                                  ///< always, there is nothing to stick)
  double full_slip_t = -1.0;      ///< first converged t in (1, 2] of steady sliding (-1: none)
  double wrap_angle = 0.0;        ///< angle from the load direction at A to the tension at B
  double max_axial_strain = 0.0;  ///< largest |eps| over the rod's quadrature points, all steps
  VectorXd u;                     ///< state at the last converged step (time solver.t)
  Vector3d reaction = Vector3d::Zero();  ///< force of the support on end B, last step
  double rel_error() const { return T_ratio / exact - 1.0; }
};

/// How far to pull.
enum class CapstanStop {
  kFullSlip,  ///< stop once the sliding plateau has CapstanParameters::plateau_steps steps
  kEnd,       ///< pull on to t = 2 (the whole `pull`)
};

/// Default solver settings of the capstan run: t in [0, 2], steps of at most 0.1.
NonlinearSolverSettings capstan_solver_settings();

/// Runs the model from its reference state over t in [0, 2] (settings.t0, t1 are overwritten).
/// Progress lines go to `log` if not null, plus one line "t, T/T0, active, stick, slip" per
/// converged step. Non-convergence is reported in result.solver.status; stopping at full slip
/// gives the status `stopped` with result.full_slip true.
///
/// Why stop at the onset of full slip: T / T0 is the sliding limit from then on in the
/// continuum, but the discrete rope is not invariant under sliding. The knots (material) leave
/// the tangent points, where the curvature jumps from 1/rho to 0, and a cubic element straddling
/// a lift-off point cannot follow that jump: the free spans move off the tangent lines and the
/// lever arms of the end forces about the axis change (T_B d_B = T_A d_A holds to round-off
/// with frictionless contact). Measured: the drift does not depend on EI nor on the contact
/// points per element, and falls with the element size. With 10 arc elements T / T0 drifts by ~0.1
/// % per 0.01 of slide (0.55 % after sliding 0.05, mu = 0); 40 arc elements cut that to 0.09 %.
[[nodiscard]] CapstanResult run_capstan(
    CapstanModel& model, NonlinearSolverSettings settings = capstan_solver_settings(),
    std::ostream* log = nullptr, CapstanStop stop = CapstanStop::kFullSlip);

}  // namespace iga
