// Contact of a deformable NURBS surface (a shell's mid-surface, one of its faces) with a rigid
// surface: the surface-to-rigid-surface (STAS) contact integral of [KS15] Sects. 2-3 (see
// ../shared/paper/EQUATIONS.md §1, §3), with both strategies for the penetration and Coulomb
// friction, and its consistent tangent (checked against finite differences of the residual in
// tests/iga/test_surface_contact.cpp).
//
// Notation ([KS15] -> code):
//   xi^1, xi^2            shell parameters of a contact point           uv (SurfaceContactPoint)
//   rho(xi), rho_i        current shell mid-surface point, basis        rho, a1, a2 (G = (rho, a1,
//   a2)) n = rho_1 x rho_2/|.| current shell normal (of the parametrization) n a_ij, a^ij, rho^i
//   shell metric, its inverse, contravariant basis  a, a_inv h, s                  shell thickness,
//   face (-1 lower, +1 upper, 0 mid)  thickness, face x_c = rho + s h/2 n   the contact point on
//   the face                 x alpha^1, alpha^2      rigid surface parameters of the foot foot.uv
//   r(alpha), r_j         rigid surface point and basis at the foot     foot.point, Su, Sv
//   xi^3                  penetration (gap), <= 0 in contact            gap
//   eps_N, eps_T, mu      penalties, Coulomb coefficient                eps_n, eps_t, mu
//   N                     normal force (34), <= 0                       N
//   T_i, T^i              tangential force components (35)-(36)         T (history)
//   X_a                   control points, dof 3 a + k                   x[a]
//
// Strategies (SurfaceContactStrategy):
//  - kRigidMaster ((10)-(18), Sect. 2.4): x_c is projected onto the rigid surface (closest
//    point, warm-started); the point law of contact/contact_law.hpp (radius 0) gives the gap
//    xi^3 = (x_c - r).n_r along the rigid normal n_r, N = eps_N xi^3 (34), the friction trial
//    (35)/(66) with the slip of the foot (27) taken in space (the tangential part of the chord
//    from the anchor, independent of the rigid parametrization: contact_law.hpp), the
//    return mapping (36), the force f on x_c and df/dx_c.
//  - kRigidSlave ((2)-(5), Sect. 2.1): the ray x_c + xi3 n along the CURRENT shell normal is
//    intersected with the rigid surface, unknowns (alpha^1, alpha^2, xi3) of
//    F = r(alpha) - x_c - xi3 n = 0 (3). The gap is measured along the shell normal:
//    with sigma = sign(n . n_r) and nu = sigma n (the shell normal turned to point out of the
//    rigid body), gap = (x_c - r).nu = -sigma xi3; this is the paper's xi^3 for a shell normal
//    n_xi = -nu facing the rigid body (r = x_c + xi^3 n_xi). Normal force (34) along nu.
//    Friction in the shell's convected coordinates: Delta xi^i = -Delta alpha^j (r_j . rho^i)
//    (28), evaluated with the chord d = r(alpha_(k+1)) - r(alpha_(k)) in place of
//    Delta alpha^j r_j (equal to first order, exact on a plane, independent of the rigid
//    parametrization and of patch changes), so that with (35)
//        T_tr_i = T_i^(k) - eps_T Delta xi^j a_ij = T_i^(k) + eps_T d . rho_i,
//    |T_tr| = sqrt(T_tr_i a^ij T_tr_j), return mapping (36) with |N| = eps_N |gap|.
//    Master and slave agree where the face is parallel to the rigid surface. Where it is
//    inclined by theta (a flat face over a plane, depth p along the plane normal): master
//    gap -p, force eps_N p n_r; slave gap -p/cos(theta) (along the shell normal), force
//    eps_N p/cos(theta) nu, i.e. the same component along n_r and an extra tangential one,
//    tan(theta) times it (tested). They differ at first order in the angle between the normals,
//    which the penalty drives to zero in contact (Sect. 2.4).
//    The linearization (37)-(39) is derived with the implicit function theorem on F = 0:
//    d(alpha, xi3)/dG = [r_1 r_2 -n]^{-1} (dx_c/dG + xi3 dn/dG) (the ray direction n depends on
//    the control points), then all quantities are differentiated exactly (Newton is quadratic).
//
// Sign conventions (both strategies). R = f_int - f_ext (iga/core/nonlinear_problem.hpp); the
// contact force f on the shell point x_c is external:
//    R_a -= int (dx_c/dX_a)^T f dA,   K_ab -= int d/dX_b [(dx_c/dX_a)^T f] dA,
// dA the reference mid-surface area element times the Gauss weight. N <= 0 and the normal
// force is f_N = -N n_out, n_out the normal pointing out of the rigid body (n_r for the
// master strategy, nu for the slave strategy): a penetrating point is pushed out. The
// tangential force on the shell opposes its slip relative to the rigid surface: in stick
// f_T = -eps_T (tangential slip since the last commit) (+ the committed force). For the slave
// strategy, (35) read literally makes T_i grow along the slip (T_i is the traction the shell
// exerts on the rigid body, (32) with the tangential sign of Ts dss = -Tm dsm); the force on the
// shell is f_T = -T_i rho^i. For the master strategy f_T = T^i r_i of contact_law.hpp.
// Output: SurfaceContactPoint::T_vector is always the tangential force on the shell, f_T.
//
// Remark 2 (weak form in the deformable body's coordinates). The virtual work is
// delta W_c = int f . delta x_c dA (33 with (31): delta xi^3 n_xi + delta xi^i rho_i =
// -delta x_c for a rigid master point), integrated over the shell's reference surface with
// the shell's Gauss points and differentiated with respect to the shell's control points only.
// f is a spatial vector; its split N n + T^i r_i in the rigid basis (master strategy) equals
// the split in the shell's basis rho_i, n_xi ((28): the bases span the same tangent plane at
// first-order contact), so computing the friction in the rigid coordinates (27) and mapping it
// by (28) gives the same weak form. The slave strategy computes it in the shell basis directly.
//
// Offset faces: x_c = rho + c n, c = s h/2. dx_c/dG = [I, c dn/da1, c dn/da2] and the tangent
// contains c d^2(f.n)/d(a1,a2)^2, the dependence of the normal on the control points.
//
// Contact search. Every contact point keeps its last foot (warm start). Per assemble, points
// with a foot are projected locally on the foot's patch (closest point Newton (18) or ray Newton
// (5)); those without a foot, or whose local result leaves the patch interior (edge, vertex,
// miss, not converged), are collected and searched together: one broad phase
// (RigidSurface::element_index: the uniform grid of contact/contact_search.hpp over the Bezier
// element boxes of all rigid NURBS patches enlarged by the search distance, built once for the
// tool) of these points, then the narrow phase among each point's candidates only
// (RigidSurface::closest_points for the master strategy;
// ray projection on the candidate patches for the slave strategy). Analytic pieces are always
// candidates. Points with no foot within the search distance (far), a missing ray (miss,
// tangent) or a failed projection are inactive and counted as failed. A foot in the interior
// of a NURBS patch gets one more Newton step before the point law (the projections stop at a
// scaled residual of 1e-13; the friction force eps_T Delta alpha would see that noise).
//
// Performance: basis functions at the Gauss points are computed once (the reference knots and
// weights are those of the current configuration); the per-point kernel works on the 9
// quantities G = (rho, a1, a2) with fixed-size Eigen types and no heap allocation; tangents are
// collected per element and multiplied out in one matrix product per element (workspace
// allocated once), then emitted as triplets per element.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "contact/contact_law.hpp"
#include "contact/rigid_surface.hpp"
#include "geometry/nurbs_surface.hpp"
#include "geometry/rational_basis.hpp"
#include "iga/contact_integrals/contact_augmentation.hpp"
#include "iga/core/contact_pair.hpp"
#include "iga/core/partition.hpp"
#include "iga/core/state_archive.hpp"

namespace iga {

enum class SurfaceContactStrategy {
  kRigidMaster,  ///< closest point projection of the shell point onto the rigid surface (10)-(18)
  kRigidSlave,   ///< ray along the shell normal onto the rigid surface (2)-(5)
};

enum class ShellFace {
  kLower,  ///< s = -1: x_c = rho - h/2 n
  kUpper,  ///< s = +1: x_c = rho + h/2 n
  kMid,    ///< s = 0: x_c = rho
};

/// The shell's contact: the point law's constants and where and how the shell touches.
struct SurfaceContactParameters {
  ContactParameters law;  ///< eps_N > 0 (34), eps_T >= 0 (35), mu >= 0 (36)
  SurfaceContactStrategy strategy = SurfaceContactStrategy::kRigidMaster;
  ShellFace face = ShellFace::kMid;
  double thickness = 0.0;        ///< shell thickness h >= 0
  int points_per_direction = 7;  ///< n x n Gauss points per element (1..20), 7 as in [KS15]
  /// Contact search distance (broad phase and narrow phase): points farther from the rigid
  /// surface (master) or with a ray hit farther than this (slave) are "far". Must be finite
  /// and > 0.
  double search_distance = 1.0;
};

/// One contact point's state for output.
struct SurfaceContactPoint : ContactMultipliers {
  int element = 0;                       ///< element index (u fastest over the non-empty spans)
  Vector2d uv = Vector2d::Zero();        ///< shell parameters (xi^1, xi^2)
  double weight = 0.0;                   ///< Gauss weight times the reference area element
  Vector3d x = Vector3d::Zero();         ///< contact point x_c on the face (current)
  Vector3d normal = Vector3d::Zero();    ///< current shell normal n at uv
  ProjectionResult foot;                 ///< closest point / ray hit on the rigid surface
  double gap = 0.0;                      ///< xi^3 (<= 0 in contact)
  double N = 0.0;                        ///< normal force (34), <= 0
  Vector2d T = Vector2d::Zero();         ///< master: T^i (rigid basis); slave: T_i (shell, (36))
  Vector3d T_vector = Vector3d::Zero();  ///< tangential force on the shell f_T
  double phi = 0.0;                      ///< slip function of the trial force (35)
  bool active = false;                   ///< penetrating, contributes to R and K
  bool slip = false;                     ///< return mapping on the slip surface (36)
  bool first_contact = false;            ///< active, but not in contact at the last converged step
  ContactHistory history;                ///< committed state of the last converged step
  Vector3d x_committed = Vector3d::Zero();  ///< x at the last commit (passed_through)
  double slip_distance = 0.0;               ///< |g_T| (master) or the chord of the feet |d| (slave)
};

/// Active points split into sticking and sliding ones (SurfaceContact::sticks).
struct SurfaceContactCounts {
  int active = 0, stick = 0, slip = 0;
  int failed = 0;  ///< no foot point: far, miss, tangent or not converged
};

/// Contact integrals with at least this many points are assembled on all OpenMP threads.
inline constexpr int kParallelContactPoints = 256;

class SurfaceContact {
 public:
  /// `reference`: the shell mid-surface in its reference configuration (its knots and
  /// weights are those of the current configuration too). Throws std::invalid_argument on
  /// invalid parameters. `rigid` must outlive this object. Contact points are made in the
  /// elements of `block` only (a process's part of a patch spread over several,
  /// iga/core/partition.hpp); SurfaceContactPoint::element numbers elements over the whole
  /// patch (e_u + n_u e_v).
  SurfaceContact(const NurbsSurface& reference, const RigidSurface& rigid,
                 const SurfaceContactParameters& params, const ElementBlock& block = {});
  /// Control points of the body.
  int num_body_points() const { return ref_.num_u() * ref_.num_v(); }

  /// Adds the contact contributions at the current control points x (3 unknowns per control
  /// point, dof 3 a + k, a = reference.index(i, j)) to R and, if K is not null, appends the
  /// tangent's triplets. R must have size 3 x.size().
  void assemble(std::span<const Vector3d> x, Eigen::VectorXd& R,
                std::vector<Eigen::Triplet<double>>* K);
  /// The same in the body's state (RigidContactPair); a surface body has no scalar unknowns
  /// (R has 3 n entries).
  void assemble(const BodyState& state, Eigen::VectorXd& R,
                std::vector<Eigen::Triplet<double>>* K) {
    assemble(state.x, R, K);
  }
  /// History and multipliers, as CurveContact: commit() after a converged step, augment() the
  /// Uzawa update, predict(t) the step's first multipliers, restore() after a cut-back.
  void commit();
  /// Failed when a point apart from the body at the last commit and now went through it on
  /// its way (pass_through.hpp); augment() reports it first, so the solver cuts the step.
  AugmentResult passed_through() const;
  AugmentResult augment();
  void predict(double t);
  void restore();
  /// The points' state and the multipliers' bookkeeping for a restart, as CurveContact.
  void archive(StateArchive& a);
  const NormalAugmentation& augmentation() const { return augmentation_; }
  /// This integral is one part of a pair spread over several processes: the augmentation's
  /// decisions take the whole pair's maxima through `max` (NormalAugmentation::parts_max).
  void set_parts_maximum(std::function<void(std::span<double>)> max) {
    augmentation_.parts_max = std::move(max);
  }

  const std::vector<SurfaceContactPoint>& points() const { return points_; }
  SurfaceContactCounts counts() const;
  /// Round-off of the contact forces at the last assembly (as CurveContact::roundoff).
  double roundoff() const;
  /// Whether an active point sticks: friction is on (mu, eps_T > 0), the point is on the stick
  /// branch of (36) and was in contact at the last converged step. Without friction every active
  /// point slides freely; in its step of first contact a point carries no tangential force
  /// (contact/contact_law.hpp) and is not counted as sticking either.
  bool sticks(const SurfaceContactPoint& cp) const;
  const SurfaceContactParameters& parameters() const { return params_; }
  /// New penalties, friction, face, thickness or search distance; the Gauss points stay
  /// (points_per_direction cannot change).
  void set_parameters(const SurfaceContactParameters& p);
  /// Penalty (default) or augmented Lagrange for the normal constraint (contact_law.hpp);
  /// throws std::invalid_argument out of its ranges (ContactEnforcement::check).
  const ContactEnforcement& enforcement() const { return enforcement_; }
  void set_enforcement(const ContactEnforcement& e);
  /// The tangent's 3 x 3 blocks are emitted turned, Q K_ab Q^T (a moving tool: the integral
  /// works in the tool's frame, RigidContactPair turns its results forward); identity: as they
  /// are.
  void set_turn(const Matrix3d& Q) { turn_ = Q; }

 private:
  struct Element {
    int first_u = 0, first_v = 0;  ///< index of the first non-zero basis function in u and v
    int row_u = 0, row_v = 0;      ///< the element's first rows of table_u_, table_v_
  };
  /// The element's basis rows: per point (u fastest), nen_ rows (R_a, R_a,1, R_a,2), row-major:
  /// rows[(point * nen_ + a) * 3 + k] (per_element * 3 nen_ values).
  void element_basis(const Element& el, double* rows) const;
  /// Elements with a point that has a foot (a bound of those with an active point).
  std::size_t elements_with_foot() const;
  /// evaluate's tangent on one thread: K's room for it, reserved at once (no doubling).
  void reserve_tangent(std::vector<Eigen::Triplet<double>>& K) const;
  /// evaluate's tangent on several threads: their lists appended to K in thread order.
  void join_tangents(std::vector<Eigen::Triplet<double>>& K) const;
  /// Local (warm) projection from the point's last foot; true if it stays inside its patch.
  bool warm_project(SurfaceContactPoint& cp) const;
  /// One more Newton step on a NURBS foot (to round-off).
  void polish(ProjectionResult& foot, const Vector3d& x, const Vector3d& n) const;
  /// Broad + narrow phase for the points in cold_.
  void cold_project();
  /// What both passes of assemble use: the strategy, points per element, basis rows and their
  /// stride per point, elements, and whether to run on all threads.
  struct Layout {
    bool master;
    int per_element;
    std::size_t stride;
    int n_el;
    bool parallel;
  };
  Layout layout() const;
  /// assemble's two passes: the contact points at x and their feet (warm, else cold_project),
  /// c the face's offset; then the laws, the residual and the element tangents.
  void locate(std::span<const Vector3d> x, double c);
  void evaluate(std::span<const Vector3d> x, double c, Eigen::VectorXd& R,
                std::vector<Eigen::Triplet<double>>* K);
  void check(const SurfaceContactParameters& p) const;

  NurbsSurface ref_;
  const RigidSurface* rigid_;
  SurfaceContactParameters params_;
  ContactEnforcement enforcement_;
  NormalAugmentation augmentation_;
  int nen_ = 0;  ///< control points per element (p+1)(q+1)
  std::vector<Element> elements_;
  std::vector<SurfaceContactPoint> points_;
  /// The B-spline basis at the Gauss points of every span (span after span), in u and in v:
  /// point (a, b) of an element is row row_u + a and row_v + b (element_basis).
  SpanBasisTable table_u_, table_v_;
  // Rigid element boxes of all NURBS pieces, and their (piece, element) tags (broad phase).
  // Workspace (allocated once).
  std::vector<int> cold_;        ///< points needing a search in this assemble
  bool anchored_start_ = false;  ///< the first assembly anchored the points at rest (master)
  std::vector<Vector3d> cold_x_;
  Matrix3d turn_ = Matrix3d::Identity();
  // Scratch of assemble: the elements' residuals and whether they have active points, each
  // thread's triplets, which points the warm start placed.
  std::vector<int> dofs_;
  std::vector<double> element_R_;
  std::vector<char> element_active_;
  std::vector<std::vector<Eigen::Triplet<double>>> thread_K_;
  std::vector<char> warm_;
};

}  // namespace iga
