// Contact of a deformable curve (a rope's or rod's centre line) with a rigid surface: the
// CTRS contact integral of [KS15] Sects. 4-5 (see ../shared/paper/EQUATIONS.md §4).
// Contact points are Gauss points along the curve (a number per element); each is projected
// onto the rigid surface (closest point, warm-started from its last foot; points without one go
// through a CGAL broad phase against the rigid patches' elements first), the point law of
// contact/contact_law.hpp gives the force f and df/dr, and with r_s = sum_a R_a(eta) x_a (77)
//   residual    R_a  -= int R_a f ds,      tangent  K_ab -= int R_a R_b (df/dr) ds,
// ds the reference arc length (the residual convention of iga/core/nonlinear_problem.hpp:
// R = f_int - f_ext, contact forces are external). The forces are kept for output in the
// curve's Serret-Frenet frame: N (68), pulling T (69), dragging B (70).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "contact/contact_law.hpp"
#include "contact/rigid_surface.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/rational_basis.hpp"
#include "iga/contact_integrals/contact_augmentation.hpp"
#include "iga/core/contact_pair.hpp"
#include "iga/core/state_archive.hpp"

namespace iga {

/// One contact point's state for output.
struct CurveContactPoint : ContactMultipliers {
  double eta = 0.0;                         ///< curve parameter
  double weight = 0.0;                      ///< quadrature weight times reference ds/deta
  Vector3d x = Vector3d::Zero();            ///< current position r_s
  ProjectionResult foot;                    ///< its projection (warm start of the next evaluation)
  ContactPoint law;                         ///< the point law's state
  ContactHistory history;                   ///< committed state of the last converged step
  Vector3d x_committed = Vector3d::Zero();  ///< x at the last commit (passed_through)
  double N = 0.0, T = 0.0, B = 0.0;         ///< normal (68), pulling (69) and dragging (70) forces
  // A rope that rolls (CurveContact::set_rolling):
  Vector3d frame_t = Vector3d::Zero(), frame_d1 = Vector3d::Zero();      ///< section frame now
  Vector3d frame_t_c = Vector3d::Zero(), frame_d1_c = Vector3d::Zero();  ///< and at the commit
  Vector3d normal_c = Vector3d::Zero();   ///< the tool's normal at the commit (n_c)
  Vector3d tangent_c = Vector3d::Zero();  ///< frame_t_c in the tool's frame (t_c)
  double spin = 0.0;    ///< the section's rotation about t since the commit (dphi)
  double torque = 0.0;  ///< friction torque about the centre line per length: T.ds/dphi
};

struct CurveContactCounts {
  int active = 0, stick = 0, slip = 0;
  /// Weighted sums over the active points of |T| (69) and |B| (70): friction along the rope
  /// and across it.
  double along = 0.0, across = 0.0;
  int slip_positive = 0, slip_negative = 0;  ///< slipping points by the sign of T (69)
  /// across / along: the share of the friction that drags across the rope (0 when it slides
  /// along itself)
  double drag_ratio() const { return along > 0.0 ? across / along : 0.0; }
};

/// The rule of the sliding plateau (issue 12, item 3): the rope slides steadily along itself
/// when every active point slips, all with the pulling force T (69) of one sign (no point
/// still sliding back), and at most `max_drag` of the friction drags across the rope (70).
/// While the rope still sinks into a groove or slips sideways, part of the friction goes
/// across it: that part takes mu |N| from T and, in a groove, props the rope up (its radial
/// component adds to the normal force's), so T / T0 is still short of its limit. A rope pulled
/// into a V-groove (half-angle 30 deg, mu 0.3) has every point slipping from the first step
/// of the pull, with 63 % of the friction across and T / T0 49 % low; the share then falls by
/// about half per step (0.26, 0.11, 0.046, 0.018, 0.0075, 0.0043) and levels off near 0.004
/// while T / T0 reaches its limit. max_drag = 0.005: its effect on the radial balance,
/// max_drag mu cot(alpha), is below 0.3 % there. mu = 0: always (nothing sticks).
inline bool steady_sliding(int active, int slip, int slip_back, double drag_ratio, double mu,
                           double max_drag = 0.005) {
  if (mu == 0.0) return true;
  return active > 0 && slip == active && slip_back == 0 && drag_ratio <= max_drag;
}

/// The rope's contact: the point law's constants, the rope's radius and the contact points.
struct CurveContactParameters {
  ContactParameters law;       ///< eps_N > 0 (34), eps_T >= 0 (35), mu >= 0 (36)
  double radius = 0.0;         ///< the rope's radius R >= 0 in the gap (52)
  int points_per_element = 3;  ///< contact (Gauss) points per element, 1..16
};

/// Contact integrals of at least this many points evaluate them on all OpenMP threads.
inline constexpr std::ptrdiff_t kParallelCurvePoints = 256;

class CurveContact {
 public:
  /// `reference`: the curve in its reference configuration (knots, degree, weights are those
  /// of the current configuration too). Throws std::invalid_argument for parameters out of
  /// their ranges.
  CurveContact(const NurbsCurve& reference, const RigidSurface& rigid,
               const CurveContactParameters& params);

  /// A rope that rolls: a rod whose sections turn about its centre line (a rod with torsion,
  /// iga/rod/twisting_rod.hpp) on the same reference curve, which hands its section frames
  /// (SectionFrames) with its state at every assembly. The contact point sits on the rope's
  /// surface, at -R n from the centre line ((52)), and the section turns under it: since the
  /// commit the rope's surface there has moved by
  ///   s = -R dphi (t_c x n_c)
  /// relative to the centre line (dphi the section's spin about t since the commit,
  /// SectionFrames::spin_since; t_c, n_c the tangent and the tool's normal then: the contact
  /// stays on the line of the normal, as in rolling, rather than following one material
  /// point, which would lift off by R (1 - cos dphi)), which enters the slip
  /// (evaluate_contact's roll): a rope that rolls without slipping sticks. The
  /// friction force T then does the work T.ds = (T.s_phi) d(dphi) on the DOFs of the spin (the
  /// rod's twists, the body's scalar unknowns): the moment ((-R n) x T).t of the friction about
  /// the centre line (the friction's moment normal to t, on the bending, is not taken). With a
  /// moving tool (set_turn) the rod's frames are world frames, computed from the points turned
  /// back by Q (translations do not change them), and the slip and its moment in the tool's
  /// frame. False (default): a rod without torsion; its frames, if given, are not used.
  void set_rolling(bool rolling) { rolling_ = rolling; }
  bool rolling() const { return rolling_; }
  /// Control points of the body.
  int num_body_points() const { return ref_.num_control_points(); }

  /// Adds the contact contributions in the body's state (3 unknowns per control point, dof
  /// 3 a + k, then the scalars) to R and, if K is not null, to the triplets of the tangent. A
  /// rope that rolls needs the state's section frames (throws std::invalid_argument without).
  void assemble(const BodyState& state, Eigen::VectorXd& R, std::vector<Eigen::Triplet<double>>* K);
  /// The same at the control points x of a rod without torsion.
  void assemble(std::span<const Vector3d> x, Eigen::VectorXd& R,
                std::vector<Eigen::Triplet<double>>* K) {
    assemble(BodyState{x, {}, nullptr}, R, K);
  }
  /// Stores the current state of every point as history (after a converged step), with the
  /// multipliers.
  void commit();
  /// Augmented Lagrange (parameters().enforcement): the Uzawa update of the multipliers from
  /// the state of the last assembly (iga/contact_integrals/contact_augmentation.hpp); penalty:
  /// satisfied.
  AugmentResult augment();
  /// Failed when a point apart from the body at the last commit and now went through it on
  /// its way (pass_through.hpp); augment() reports it first, so the solver cuts the step.
  AugmentResult passed_through() const;
  /// Augmented Lagrange: multipliers for the first solve of a step at time t, extrapolated
  /// from the last two commits (NormalAugmentation::predict); no effect after an update.
  void predict(double t);
  /// Multipliers back to the last commit (a step cut back).
  void restore();
  /// The points' state (history, multipliers, last feet, law and frames) and the multipliers'
  /// bookkeeping, written to or read from a restart archive (iga/core/state_archive.hpp); a
  /// reader checks the number of points.
  void archive(StateArchive& a);
  /// Multiplier updates and the last largest penetration (augmented Lagrange).
  const NormalAugmentation& augmentation() const { return augmentation_; }
  /// This integral is one part of a pair spread over several processes: the augmentation's
  /// decisions take the whole pair's maxima through `max` (NormalAugmentation::parts_max).
  void set_parts_maximum(std::function<void(std::span<double>)> max) {
    augmentation_.parts_max = std::move(max);
  }

  const std::vector<CurveContactPoint>& points() const { return points_; }
  /// Contact points per element: points_ holds them element by element, in order.
  int points_per_element() const { return params_.points_per_element; }
  CurveContactCounts counts() const;
  /// Round-off of the contact forces at the last assembly: 8 machine epsilons times
  /// sum_active w (eps_N + eps_T) (|x| + R) with the law's (possibly raised) penalties, an
  /// estimate of the error of computing each force from a gap of coordinates of size |x|.
  double roundoff() const;
  const CurveContactParameters& parameters() const { return params_; }
  /// New parameters (a continuation); the contact points stay: points_per_element cannot
  /// change (std::invalid_argument), nor may the others leave their ranges.
  void set_parameters(const CurveContactParameters& p);
  /// Penalty (default) or augmented Lagrange for the normal constraint (contact_law.hpp);
  /// throws std::invalid_argument out of its ranges (ContactEnforcement::check).
  const ContactEnforcement& enforcement() const { return enforcement_; }
  void set_enforcement(const ContactEnforcement& e);
  /// Points without a warm start (first assembly, or no foot last time) are projected in one
  /// batch: a broad phase (RigidSurface::closest_points: the tool's grid index, built once)
  /// between the points and the Bezier elements of the rigid patches, inflated by this distance,
  /// then the projection among each point's candidates; farther points are inactive (status far).
  /// Default: rope radius + the longest reference element chord.
  double search_distance() const { return search_distance_; }
  void set_search_distance(double d) { search_distance_ = d; }
  /// A point at most this far above the surface counts as near contact: while no point is in
  /// contact, the near points add their normal penalty stiffness to the tangent (not to the
  /// residual), so that a body held only by the contact has no rigid mode at the start.
  /// 1e-3 of the search distance.
  double near_distance() const { return 1e-3 * search_distance_; }
  /// Points projected through the broad phase in the last assembly (the others warm-started).
  int broad_phase_points() const { return broad_phase_points_; }
  /// The tangent's 3 x 3 blocks are emitted turned, Q K_ab Q^T (a moving tool: the integral
  /// works in the tool's frame, RigidContactPair turns its results forward); identity: as they
  /// are.
  void set_turn(const Matrix3d& Q) { turn_ = Q; }

 private:
  NurbsCurve ref_;
  const RigidSurface* rigid_;
  CurveContactParameters params_;
  ContactEnforcement enforcement_;
  NormalAugmentation augmentation_;
  std::vector<CurveContactPoint> points_;
  /// The rational basis at each point's eta (geometry/rational_basis.hpp), parallel to points_.
  std::vector<RationalBasis> basis_;
  double search_distance_ = 0.0;
  Matrix3d turn_ = Matrix3d::Identity();
  int broad_phase_points_ = 0;
  bool anchored_start_ = false;  ///< the first assembly anchored the points at rest
  bool rolling_ = false;
  std::vector<int> cold_;  ///< work: points without a warm start
  std::vector<Vector3d> cold_x_;
  std::vector<int> near_;  ///< work: points near contact (see near_distance)
  /// assemble's first pass: the points' positions at x, the feet of those without a warm start
  /// (warm[i] = 0) from the broad phase.
  void locate(std::span<const Vector3d> x, bool parallel, std::vector<char>& warm);
};

}  // namespace iga
