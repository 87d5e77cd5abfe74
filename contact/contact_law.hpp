// Penalty contact with Coulomb friction at one point of a deformable curve (a rope's centre
// line) against a rigid surface that is master: the curves-to-rigid-surface (CTRS) point law
// of [KS15] (see ../shared/paper/EQUATIONS.md §3-4), with its consistent linearization.
//
// Notation ([KS15] -> code): r_s -> r (the deformable point), xi^1, xi^2 -> xi (foot
// parameters on the rigid surface), rho, rho_i, rho_ij -> the surface point and derivatives at
// the foot, n -> n, a_ij -> a, h_ij -> h, xi^3 -> gap, R -> radius, eps_N, eps_T -> eps_n,
// eps_t, mu -> mu, N -> N, T^i (contravariant) -> T.
//
//   gap  xi^3 = (r - rho).n - R                                   (52)
//   N    = eps_N xi^3 if xi^3 <= 0, else 0 (N <= 0: compression)   (34)
//   augmented Lagrangian (exact enforcement, lambda_N <= 0 the multiplier of the point, kept
//   by the caller and updated between Newton solves, Uzawa: lambda_N <- N of the converged
//   state):  N = min(0, lambda_N + eps_N xi^3)   ((34) augmented; lambda_N = 0: (34))
//   The friction history is kept in space, not in the parameters xi, so that it does not
//   depend on the parametrization of the rigid surface: the anchor rho_(n) (the foot at the
//   last converged step, a point of the tool; tools do not move yet, so the tool's frame is the
//   global one) and the committed tangential force T_(n) = T^i_(n) rho_i as a 3-D vector. With
//   P = I - n n^T the projector onto the current tangent plane:
//   g_T  = P (rho - rho_(n))   the slip since the anchor; (54) reads Delta xi^i rho_i, equal to
//                              first order and exact on a plane
//   T_c  = |T_(n)| P T_(n) / |P T_(n)|   T_(n) carried into the current tangent plane, its
//                              length kept (a rotation to first order, like (28))
//   T_tr = T_c - eps_T g_T                                          (66)
//   (augmented stick: T_c carries the multiplier lambda_T instead of T_(n), see
//   ContactEnforcement)
//   Phi  = |T_tr| - mu |N|  (|T_tr| = sqrt(T^i a_ij T^j) of a tangent vector)  (35)
//   T    = T_tr (stick, Phi <= 0),  mu |N| T_tr / |T_tr| (slip)    (36)
//   The parameter form (54), (66) breaks where the parametrization is singular or jumps: at a
//   pole a short chord is a jump of pi in the angle, at the seam of a closed surface and at a
//   border between patches xi restarts; the spatial form sees only the chord and the normal.
//   force on the deformable point  f = -N n + T                      (67: R_S = -R_C, with the
//       sign of T chosen so that f opposes the sliding increment); T^i = a^ij rho_j.T (output)
// and its derivative K = df/dr (3x3, not symmetric with friction; the augmented N has the same
// derivative eps_N n^T as (34), so K keeps its form with N = lambda_N + eps_N xi^3), from
//   dxi/dr = A^{-1} [rho_1 rho_2]^T, A_ij = a_ij - rho_ij.(r - rho)   ((17), implicit function)
//   dgap/dr = n,  dn/dxi^k = -h_kj a^jl rho_l (Weingarten),  drho/dr = rho_i dxi^i/dr,
//   d(P w)/dr = -(n.w) dn/dr - n (w^T dn/dr) for a fixed w.
// The history (rho_(n), T_(n)) is committed only at converged load steps, for every point with
// a foot, in contact or not (T_(n) = 0 for a point that was apart). So friction acts from the
// step in which a point first touches (stick allowed by the return mapping (36)): its anchor is
// the foot of its last converged position. Before the first commit the contact integrals anchor
// each point at its foot in the start state (a rope laid on an inclined surface is held from the
// first step). A point that approaches obliquely within one step counts the tangential part of
// its approach as slip; the return mapping bounds the force that gives by mu |N|. Only a point
// with no foot at the last commit (farther than the search distance) has no anchor: T = 0 in
// that step.
#pragma once

#include <string>

#include "contact/projection.hpp"
#include "geometry/surface.hpp"

namespace iga {

/// How the normal contact constraint is enforced (docs/contact.md, "Enforcement").
///  - penalty: N = eps_N xi^3 (34); the penetration is |N| / eps_N.
///  - augmented Lagrange: N = min(0, lambda_N + eps_N xi^3) with a multiplier lambda_N per
///    contact point, updated between Newton solves of a load step (Uzawa: lambda_N <- N of the
///    converged state) until the largest penetration max(-xi^3) of the active points is at
///    most penetration_tol; at most max_augmentations updates per load step, else the step
///    fails (cut back like a Newton failure). lambda_N is committed with the history.
///  - with slip_tol > 0 the stick constraint is augmented too: the tangential multiplier
///    lambda_T (a 3-D tangent vector per point; the slave strategy of STAS: the covariant
///    components T_i) takes the place of the committed force T_(n) in the trial force (66)
///    after the first update of a step, lambda_T <- T of the converged state, until the slip
///    since the anchor |g_T| of every sticking point is at most slip_tol (exact stick: a
///    sticking point does not move on the tool; with the penalty alone it creeps by |T|/eps_T).
struct ContactEnforcement {
  bool augmented = false;        ///< false: penalty (default); true: augmented Lagrange
  double penetration_tol = 0.0;  ///< a length > 0 (augmented only)
  int max_augmentations = 10;    ///< >= 1 (augmented only)
  double slip_tol = 0.0;         ///< a length > 0: augment the stick constraint; 0: do not
  /// Throws std::invalid_argument, prefixed by `who`, for augmented enforcement with a
  /// penetration_tol not > 0 and finite or max_augmentations < 1, or a slip_tol other than 0
  /// that is not > 0 and finite with augmented enforcement.
  void check(const std::string& who) const;
};

/// The point law's constants, shared by every contact integral (a rope's, CurveContact; a
/// shell's, SurfaceContact: each builds its own parameters on these).
struct ContactParameters {
  double eps_n = 0.0;  ///< normal penalty eps_N > 0 (34)
  double eps_t = 0.0;  ///< tangential penalty eps_T >= 0 (0: frictionless) (35)
  double mu = 0.0;     ///< Coulomb friction coefficient >= 0 (36)
  /// Whether the law has friction: mu > 0 and eps_T > 0.
  bool friction() const { return mu > 0.0 && eps_t > 0.0; }
  /// Throws std::invalid_argument, prefixed by `who`, unless eps_N > 0, eps_T >= 0, mu >= 0,
  /// all finite.
  void check(const std::string& who) const;
};

/// Converged state of the previous load step at one contact point.
struct ContactHistory {
  bool active = false;                   ///< in contact at the last converged step
  int patch = -1;                        ///< rigid patch of the stored foot (warm start)
  Vector2d xi = Vector2d::Zero();        ///< foot parameters xi_(n) (warm start only)
  Vector3d foot = Vector3d::Zero();      ///< the anchor rho_(n): the stored foot point
  Vector2d T = Vector2d::Zero();         ///< contravariant T^i_(n) (output only)
  Vector3d T_vector = Vector3d::Zero();  ///< the committed tangential force T_(n), 3-D
};

/// The contact state at one point for the current iterate.
struct ContactPoint {
  bool active = false;  ///< penetrating: lambda_N + eps_N gap <= 0 (gap <= 0 for the penalty)
  bool slip = false;    ///< return mapping on the slip surface (36)
  double gap = 0.0;     ///< xi^3 (52)
  double N = 0.0;       ///< normal force (34) (augmented: lambda_N + eps_N gap), <= 0
  double phi = 0.0;     ///< slip function |T_tr| - mu |N| of the trial force (35)
  double slip_distance = 0.0;     ///< |g_T|, the slip since the anchor (stick: elastic creep)
  Vector2d T = Vector2d::Zero();  ///< contravariant tangential force T^i (36)
  Vector3d T_vector = Vector3d::Zero();  ///< the tangential force T = T^i rho_i (3-D)
  Vector2d xi = Vector2d::Zero();        ///< foot parameters
  Vector3d foot = Vector3d::Zero();
  Vector3d normal = Vector3d::Zero();
  Vector3d force = Vector3d::Zero();           ///< f on the deformable point
  Matrix3d stiffness = Matrix3d::Zero();       ///< df/dr
  Matrix3d stiffness_roll = Matrix3d::Zero();  ///< df/ds, s the rolling displacement (if given)
  Matrix3d stiffness_tangential = Matrix3d::Zero();  ///< dT/dr, the tangential force's part
};

/// Evaluates the law at the deformable point r whose closest point on `s` is `foot` (computed
/// by the caller, e.g. RigidSurface warm-started from the history). The foot must be an
/// interior or seam point of the patch for the linearization to be exact; at edges and
/// vertices the tangent drops the terms of the held parameters. `lambda_n` <= 0: the normal
/// multiplier of the augmented Lagrangian at this point (0: the penalty law (34)). `lambda_t`:
/// the tangential multiplier, used in (66) in place of the committed force T_(n) (null: T_(n)).
/// `roll`: the displacement s of the body's material point at the contact relative to its
/// centre line since the anchor (a rope turning about its axis by dphi carries its surface
/// point by about -R dphi t x n): the slip is then g_T = P (rho - rho_(n) + s), the material
/// point's motion, so that a point that rolls without slipping sticks; stiffness_roll = df/ds
/// (null: s = 0). `radius`: the rope's radius R >= 0 in the gap (52) (the rope's own setting,
/// CurveContactParameters; 0 for a point on a shell's face).
ContactPoint evaluate_contact(const Surface& s, const ProjectionResult& foot, const Vector3d& r,
                              const ContactParameters& p, const ContactHistory& history,
                              double lambda_n = 0.0, const Vector3d* lambda_t = nullptr,
                              const Vector3d* roll = nullptr, double radius = 0.0);

/// The history of a point at rest on its foot: anchored there, no tangential force (the start
/// state, before the first commit).
ContactHistory anchor_at(const ProjectionResult& foot);

/// A foot on an open edge or corner of the rigid body (status edge or vertex) with the point x
/// off the surface normal there: x lies beyond the edge (outside the normal prism of the
/// surface, [KS15] Sect. 2.2), where the gap along the edge normal means nothing, so the point
/// is not in contact. False for an interior foot.
bool beyond_open_edge(const ProjectionResult& foot, const Vector3d& x);

/// The history to store after a converged step.
ContactHistory commit_contact(const ContactPoint& c, int patch);

}  // namespace iga
