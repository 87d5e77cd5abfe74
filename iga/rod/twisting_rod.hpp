// Geometrically exact Kirchhoff rod with torsion on a C1 NURBS centre line: the control point
// positions and one twist angle at each knot (element border) are the unknowns; axial, two
// bending and one torsional stiffness (EA, EI_1, EI_2, GJ), St. Venant-Kirchhoff. The
// torsion-free rod (kirchhoff_rod.hpp) stays beside it.
// References:
// [MPW14] Meier, Popp & Wall, "An objective 3D large deformation finite element formulation for
//   geometrically exact curved Kirchhoff rods", CMAME 278 (2014) 445-478: the section frame of
//   a Kirchhoff rod carried between nodal triads by the smallest rotation (SR) of the tangent
//   and a relative twist angle, which makes the strain measures objective and
//   path-independent (unlike an SR map from the reference tangent, their Sect. 4);
// [SVQ86] Simo & Vu-Quoc, "A three-dimensional finite-strain rod model. Part II", CMAME 58
//   (1986) 79-116 (the 45-degree bend); [KS15] the reference paper (GI of the rope, (52)).
// The formulas below are written out by us; the element derivatives come from small
// second-order jets (iga/core/jet.hpp) per stage, joined by the chain rule written out (see
// "Derivatives").
//
// Notation (symbol -> code):
//   xi, xi_k               curve parameter; knot k (element borders, k = 0 .. n_el)  xi, knot
//   x_i, X_i               current / reference control points                   x, X
//   a = r', b = r''        derivatives of the centre line in xi                  a, b
//   J = |R'|, A = J^2      reference stretch of the parametrization               J, A
//   t = a/|a|, t'          unit tangent and its xi-derivative                     t, dt
//   (t_k, d1_k, d2_k)      nodal triad at knot k (d2 = t x d1)                     t_k, d1_k
//   alpha_k                twist unknown at knot k (accumulated rotation about t)  alpha
//   SR(a -> t) v           smallest rotation taking the unit vector a onto t:
//                          v - (t.v)/(1 + a.t) (a + t) for v normal to a           sr()
//   Delta_e                relative twist of element e's end triads               Delta
//   phi(xi)                twist angle inside element e: Delta_e (xi - xi_k)/h     phi
//   (t, d1, d2)(xi)        section frame; d1 = cos phi g + sin phi t x g,
//                          g = SR(t_k -> t) d1_k
//   kappa_1,2,3            rotation rate of the frame per reference length, along d1, d2, t:
//                          kappa_1 = -d2.t'/J, kappa_2 = d1.t'/J, kappa_3 = (phi' + g'.(t x g))/J
//   K_1,2,3                the same in the stress-free state                      K1, K2, K3
//   eps = (a.a - A)/(2A)   Green-Lagrange axial strain                            eps
//
// The section frame. A Kirchhoff rod's frame has its first vector along the tangent, so it is
// fixed by one angle about t. At each knot k a nodal triad (t_k, d1_k) with t_k the current
// tangent there: d1_k = R(alpha_k - alpha_k^c, t_k) SR(t_k^c -> t_k) d1_k^c, where (t_k^c,
// d1_k^c, alpha_k^c) are the triad and twist committed at the last converged step (the chart is
// re-centred at each commit, so alpha_k accumulates the rotation about the tangent and stays
// finite through any motion: the SR map is only singular for a tangent reversed within one
// step). Inside element e, between knots k and k + 1, the frame is the SR image of the left
// triad, turned by phi(xi) = Delta_e (xi - xi_k)/h, with Delta_e the angle about t_{k+1} from
// SR(t_k -> t_{k+1}) d1_k to d1_{k+1} (atan2, continued from its committed value, so |Delta_e|
// may exceed pi). At knot k + 1 the element's frame is the nodal triad, so the frame is
// continuous along the rod. Objective: a rigid rotation Q of the centre line and the nodal
// triads maps every SR(t_k -> t) to Q SR Q^T and leaves Delta_e unchanged, so the frame field
// turns by Q and the strains do not change ([MPW14]); path-independent: the strains are
// functions of the positions and nodal triads, not of the way they were reached.
//
// Strain energy per unit reference length:
//   W = 1/2 EA eps^2 + 1/2 EI_1 (kappa_1 - K_1)^2 + 1/2 EI_2 (kappa_2 - K_2)^2
//       + 1/2 GJ (kappa_3 - K_3)^2,
// the K from the same formulas in the reference configuration with its own triads (D_1 normal
// to the tangent from RodSection::ref_direction, or, without one, carried along the reference
// curve by SR from the first knot); with RodOptions::straight_stress_free, K_1 = K_2 = 0 and K_3
// from the reference (a rope laid along a curve without being twisted).
//
// Unknowns. Element e has 3 (p + 1) position DOFs and the twists of its two knots. Global
// numbering for assembly: 3 i + c for component c of control point i (n points), 3 n + k for
// the twist at knot k (TwistingRodProblem keeps the twists as the scalar unknowns of its DofMap,
// so that they are fixed and prescribed along load curves, and their reactions are torques).
//
// Derivatives. One jet over all N = 3 (p + 1) + 2 element DOFs costs O(N^2) per operation
// (~67 / 97 us per element of degree 2 / 3); element_tangent_by_jets keeps that as the
// reference. element_tangent and assemble use the structure instead:
//   - the knot frames F_k = (d1_k, d2_k, t_k) depend on y_k = (a_k, beta_k) only: jets over 4
//     variables, once per knot (neighbouring elements share them);
//   - Delta_e = atan2(y, x), x = d1_0.d1_1 - (t_1.d1_0)(t_0.d1_1)/(1 + t_0.t_1), y = -(d1_0.d2_1
//     - (t_1.d1_0)(t_0.d2_1)/(1 + t_0.t_1)) (t_1 is normal to d1_1, d2_1): products of a jet
//     over y_0 and one over y_1, a jet over 8 variables;
//   - at a quadrature point, in the components of the left frame (a^ = F_0^T a, b^ = F_0^T b,
//     tau = a^/|a^|, w_i = tau_i/(1 + tau_3), del = (b^ - (tau.b^) tau)/|a^| = t'^), since SR
//     maps d1_0, d2_0 to g, t x g: c_1 = g.t' = del_1 - w_1 del_3, c_2 = (t x g).t' = del_2 -
//     w_2 del_3, c_3 = g'.(t x g) = w_2 del_1 - w_1 del_2, so c = M(a^) b^ with M a jet over a^
//     (3 variables), and kappa_1 = (sin phi c_1 - cos phi c_2)/J, kappa_2 = (cos phi c_1 + sin
//     phi c_2)/J, kappa_3 = (Delta/h + c_3)/J, whose derivatives in (c, Delta) are written out;
//   - the chain rule from (a^, b^, Delta) to (a, b, y_0, y_1), with F_0's second derivatives
//     weighted once per element, and to the element DOFs (a, b, a_k linear in the points).
// spin_since uses the knot frames too, with one jet over (a, y_0, y_1) (11 variables) at xi,
// and skips the jets when no derivatives are asked (contact points that are not active).
// Forces and tangent then take ~5.5 / 7.3 us per element of degree 2 / 3 on one core, about 5
// and 4.5 times the torsion-free rod (bench/bench_rod.cpp); the tests compare both paths to
// round-off and the forces and tangent against finite differences of the energy.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "iga/core/section_frames.hpp"
#include "iga/rod/kirchhoff_rod.hpp"

namespace iga {

/// Rods with torsion of at least this many elements are assembled on all OpenMP threads
/// (TwistingRod::assemble; an element takes 5-8 us).
inline constexpr int kParallelTwistingRodElements = 16;

/// Strains, section forces and frame at one point of the twisting rod (output, tests).
struct TwistStrains {
  double eps = 0.0;                    ///< Green-Lagrange axial strain
  double axial_force = 0.0;            ///< EA eps
  Vector3d kappa = Vector3d::Zero();   ///< (kappa_1, kappa_2, kappa_3), per reference length
  Vector3d moment = Vector3d::Zero();  ///< (EI_1 (kappa_1 - K_1), EI_2 (..), GJ (kappa_3 - K_3))
  double twist = 0.0;                  ///< phi + the left knot's alpha (for plots)
  Vector3d t = Vector3d::Zero(), d1 = Vector3d::Zero(), d2 = Vector3d::Zero();  ///< frame
  double energy_density = 0.0;
};

/// The discretized rod with torsion: reference curve, section (RodSection with GJ), quadrature,
/// the committed nodal triads; energy, forces and tangent for control points x and knot
/// twists alpha. Its section frames are what a rope's contact rolls by (SectionFrames).
class TwistingRod final : public SectionFrames {
 public:
  /// Throws RodError: degree outside [2, 5], an interior knot of multiplicity > p - 1, EA <= 0,
  /// EI < 0, GJ <= 0, a ref_direction parallel to the tangent at a knot, a general section
  /// (EI1 != EI2) without ref_direction, bad quadrature counts.
  TwistingRod(NurbsCurve reference, RodSection section, RodOptions options = {});

  const NurbsCurve& reference() const { return reference_; }
  const RodSection& section() const { return section_; }
  int degree() const { return reference_.degree(); }
  int num_control_points() const { return reference_.num_control_points(); }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  /// Knots carrying a twist unknown: num_elements() + 1.
  int num_knots() const { return num_elements() + 1; }
  double knot(int k) const { return knots_.at(static_cast<std::size_t>(k)); }
  /// Unknowns: 3 per control point and 1 per knot (see the header).
  int num_dofs() const { return 3 * num_control_points() + num_knots(); }
  Interval element_range(int e) const;
  int element_first_point(int e) const;
  double reference_length() const;
  /// The reference nodal triad at knot k: tangent and D_1.
  Vector3d reference_tangent(int k) const { return ref_.at(static_cast<std::size_t>(k)).t; }
  Vector3d reference_d1(int k) const { return ref_.at(static_cast<std::size_t>(k)).d1; }

  /// Energy of element e / of the rod; f and K: element forces dPi_e/dq_e and tangent
  /// d2Pi_e/dq_e^2 (element DOFs: positions point-major, then alpha_k, alpha_k+1).
  double element_energy(int e, std::span<const Vector3d> x, std::span<const double> alpha) const;
  double energy(std::span<const Vector3d> x, std::span<const double> alpha) const;
  void element_tangent(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                       Eigen::VectorXd& f, Eigen::MatrixXd* K) const;
  /// The same forces and tangent by second-order jets over all element DOFs (the slow
  /// reference the written-out chain of element_tangent is tested against).
  void element_tangent_by_jets(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                               Eigen::VectorXd& f, Eigen::MatrixXd& K) const;
  /// Global internal forces (num_dofs(), numbering of the header) and tangent triplets, in
  /// element order. Rods of kParallelTwistingRodElements elements or more are assembled on all
  /// OpenMP threads; the result is the same bit for bit for any number of threads.
  void assemble(std::span<const Vector3d> x, std::span<const double> alpha, Eigen::VectorXd& f,
                std::vector<Triplet>* K) const;

  /// The generalized forces of a couple M fixed in space and a torque Mt about the current
  /// tangent at parameter xi, by their virtual work M.(t x dt) + (M.t + Mt) dd1.d2 on the spin
  /// of the section's frame there (at a knot: the nodal triad), and their derivative
  /// K = df/dq (not symmetric): the element's DOFs (e: the element holding xi; f, K in its
  /// local numbering). Throws RodError for xi outside the domain.
  void moment_at(double xi, const Vector3d& M, double Mt, std::span<const Vector3d> x,
                 std::span<const double> alpha, int& e, Eigen::VectorXd& f,
                 Eigen::MatrixXd& K) const;
  /// Global DOF of local DOF l of element e (the header's numbering).
  int global_dof(int e, int l) const;

  /// The rotation of the section at xi about its tangent since it had the frame (t_c, d1_c)
  /// (e.g. at the last commit): the angle from SR(t_c -> t) d1_c to d1 about t (in (-pi, pi]),
  /// with its gradient and Hessian with respect to the DOFs of the element holding xi (their
  /// global numbers in SectionSpin::dofs); and the current frame there. A rope's contact point
  /// rolls by it (iga/contact_integrals/curve_contact.hpp).
  SectionSpin spin_since(double xi, const Vector3d& t_c, const Vector3d& d1_c,
                         std::span<const Vector3d> x, std::span<const double> alpha,
                         bool derivatives) const override;
  /// The same by second-order jets over all element DOFs (the reference spin_since is tested
  /// against).
  SectionSpin spin_since_by_jets(double xi, const Vector3d& t_c, const Vector3d& d1_c,
                                 std::span<const Vector3d> x, std::span<const double> alpha) const;
  /// The section frame (t, d1) at xi (as strains()).
  void frame(double xi, std::span<const Vector3d> x, std::span<const double> alpha, Vector3d& t,
             Vector3d& d1) const override;

  /// Position, frame and strains at parameter xi.
  TwistStrains strains(double xi, std::span<const Vector3d> x, std::span<const double> alpha) const;
  Vector3d point(double xi, std::span<const Vector3d> x) const;
  /// The current nodal triad at knot k: tangent and d1.
  void knot_triad(int k, std::span<const Vector3d> x, std::span<const double> alpha, Vector3d& t,
                  Vector3d& d1) const;

  /// Re-centres the triads' chart at the converged state (x, alpha): see the header.
  void commit(std::span<const Vector3d> x, std::span<const double> alpha);

  /// The committed history: per knot the triad (t, d1) and twist alpha, per element the
  /// relative twist Delta (a restart, or a test that turns the whole state).
  struct History {
    std::vector<Vector3d> t, d1;
    std::vector<double> alpha, Delta;
  };
  History history() const;
  /// Throws RodError on wrong sizes or a triad that is not orthonormal (1e-10).
  void set_history(const History& h);

 private:
  struct Triad {
    Vector3d t = Vector3d::UnitX(), d1 = Vector3d::UnitY();
    double alpha = 0.0;
  };
  struct QuadraturePoint {
    double xi = 0.0, s = 0.0;  ///< parameter, (xi - xi_k)/h
    double wJ = 0.0;           ///< Gauss weight * d xi * |R'|
    double J = 0.0, A = 0.0;
    Vector3d K = Vector3d::Zero();  ///< K_1, K_2, K_3
    bool axial = true, bending = true;
    RationalBasis basis;
  };
  struct Element {
    int first = 0;
    Interval range;
    int qp_begin = 0, qp_count = 0;
    /// Derivatives R_j'(xi) of the element's p + 1 functions at its two knots.
    std::array<double, kMaxDegree + 1> dN_lo{}, dN_hi{};
    double Delta = 0.0;  ///< committed relative twist
  };
  /// What one evaluation of an element gives: the energy, optionally its gradient and
  /// Hessian; with `xi` set, the strains there instead of the quadrature; always the element's
  /// end triads and relative twist.
  struct Eval {
    bool derivatives = false;
    const double* xi = nullptr;
    /// With xi: instead, the generalized force f and its derivative K of a couple M (fixed in
    /// space) and a torque Mt about the current tangent at xi.
    bool moment = false;
    Vector3d M = Vector3d::Zero();
    double Mt = 0.0;
    /// With xi: also the spin about t since the frame (t_c, d1_c) as W, f, K.
    const std::pair<Vector3d, Vector3d>* spin_from = nullptr;
    double W = 0.0;
    Eigen::VectorXd f;
    Eigen::MatrixXd K;
    TwistStrains strains;
    Vector3d t0, d10, t1, d11;
    double Delta = 0.0;
  };
  template <int P>
  void kernel(int e, std::span<const Vector3d> x, std::span<const double> alpha,
              const std::vector<Triad>& triads, Eval& out) const;
  void evaluate(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                const std::vector<Triad>& triads, Eval& out) const;
  /// The nodal frame (d1_k, d2_k, t_k) at knot k as jets over (a_k, beta_k) (twisting_rod.cpp).
  struct NodalFrame;
  void nodal_frame(int knot, std::span<const Vector3d> x, std::span<const double> alpha,
                   const std::vector<Triad>& triads, NodalFrame& F) const;
  /// Energy, forces f and tangent K of element e by the chain of the header's "Derivatives"
  /// (small jets per stage, the chain rule between them written out), from the frames of its
  /// two knots.
  template <int P>
  double fast_tangent(int e, std::span<const Vector3d> x, const NodalFrame& F0,
                      const NodalFrame& F1, Eigen::VectorXd& f, Eigen::MatrixXd& K) const;
  /// spin_since by the frames of the element's knots: the spin as a jet over (a, y_0, y_1)
  /// (11 variables) with derivatives, as a number without; B: the basis at xi (inside element e).
  template <typename T>
  T spin_at(int e, double xi, const RationalBasis& B, const Vector3d& t_c, const Vector3d& d1_c,
            std::span<const Vector3d> x, const NodalFrame& F0, const NodalFrame& F1, Vector3d& t,
            Vector3d& d1) const;
  /// fast_tangent for the rod's degree; the knots' frames computed here unless given.
  double tangent(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                 const std::vector<Triad>& triads, Eigen::VectorXd& f, Eigen::MatrixXd& K,
                 const NodalFrame* F0 = nullptr, const NodalFrame* F1 = nullptr) const;
  void check(std::span<const Vector3d> x, std::span<const double> alpha) const;
  /// The element holding parameter xi (the last one for xi at its end).
  int element_at(double xi) const;
  /// The strains and frame at xi as the element gives them (no stress-free part).
  TwistStrains strains_at(double xi, std::span<const Vector3d> x,
                          std::span<const double> alpha) const;
  void set_reference_triads(const std::vector<Vector3d>& X);
  void set_stress_free_strains(const std::vector<Vector3d>& X);

  NurbsCurve reference_;
  RodSection section_;
  RodOptions options_;
  std::vector<double> knots_;
  std::vector<Element> elements_;
  std::vector<QuadraturePoint> qps_;
  std::vector<Triad> ref_;        ///< reference triads
  std::vector<Triad> committed_;  ///< triads of the last commit
};

/// The rod with torsion, its conditions and loads as a Body. Unknowns: the displacements of
/// the control points (as RodProblem) and the twists alpha_k, the DofMap's scalar unknowns (k:
/// the knot), fixed and prescribed along load curves; scalar_reactions() gives the torques
/// about the tangent that fixed twists carry. The rod hands its section frames to its contact
/// pairs (a rope that rolls, CurveContact::set_rolling).
///
/// Couples and torques at knots (end moments): a couple M fixed in space and a torque M_t about
/// the current tangent do the virtual work M.(t x dt) + (M.t + M_t) dd1.d2 on the spin of the
/// nodal triad (TwistingRod::knot_moment), so the section at the knot carries exactly M (+ M_t
/// t) in equilibrium; their load stiffness is not symmetric (symmetric() is false with them).
class TwistingRodProblem : public ControlPointProblem {
 public:
  explicit TwistingRodProblem(TwistingRod rod);

  const TwistingRod& rod() const { return rod_; }

  /// Clamp: the end point, the neighbour's components normal to the end tangent and the twist.
  void clamp(RodEnd end);
  /// A symmetry plane through the end, normal n, crossed at right angles: the positions as
  /// RodProblem::symmetry; the twist stays free, since a mirror-symmetric state carries no
  /// torque through the plane (the section moment m(-s) = M m(s) of the mirror M makes its
  /// component along n vanish there; the bending moments may not).
  void symmetry(RodEnd end, const Vector3d& n);
  /// The end knot's twist (0: start, num_knots() - 1: end).
  int end_knot(RodEnd end) const { return end == RodEnd::kStart ? 0 : rod_.num_knots() - 1; }
  void fix_twist(int knot);
  /// Twist alpha_k = angle * curve(t) (radians).
  void prescribe_twist(int knot, double angle, LoadCurve curve = ramp());
  /// The twist at knot k in the state (u, t).
  double twist(int knot, const VectorXd& u, double t) const;

  /// Dead force F at parameter xi (f_i = R_i(xi) F).
  void add_point_load(double xi, const Vector3d& F, LoadCurve curve = ramp());
  /// Dead distributed force q per unit reference length over the parameter range (default:
  /// all).
  void add_line_load(const Vector3d& q, LoadCurve curve = ramp()) {
    add_line_load(q, rod_.reference().domain(), std::move(curve));
  }
  void add_line_load(const Vector3d& q, Interval range, LoadCurve curve = ramp()) {
    add_nodal_load(rod_line_load(rod_.reference(), q, range), std::move(curve));
  }
  /// Torque M_t about the current tangent at parameter xi / at knot k (see the class comment).
  void add_torque_at(double xi, double Mt, LoadCurve curve = ramp());
  void add_torque(int knot, double Mt, LoadCurve curve = ramp()) {
    add_torque_at(rod_.knot(check_knot(knot)), Mt, std::move(curve));
  }
  /// Couple M, fixed in space, at parameter xi / at knot k (see the class comment).
  void add_moment_at(double xi, const Vector3d& M, LoadCurve curve = ramp());
  void add_moment(int knot, const Vector3d& M, LoadCurve curve = ramp()) {
    add_moment_at(rod_.knot(check_knot(knot)), M, std::move(curve));
  }

  /// Control points and twists of the state.
  void split(const VectorXd& u, double t, std::vector<Vector3d>& x,
             std::vector<double>& alpha) const;

  // ---- Body ------------------------------------------------------------------------------------
  std::string type() const override { return "twisting_rod"; }
  std::string describe() const override;
  int default_samples() const override { return 16; }
  Vector3d displacement(double pu, double pv, const VectorXd& u, double t) const override;
  /// Re-centres the rod's triads (TwistingRod::commit), then the pairs' history.
  void commit(const VectorXd& u, double t) override;
  /// The rod's committed triads and twists (TwistingRod::history), then the pairs'.
  void archive(StateArchive& a) override;

 protected:
  bool model_symmetric() const override { return moments_.empty(); }
  /// The centre line with the axial force, the three moments (two bending, torque), the twist
  /// and the section frame (d1, d2) per sample.
  SampledMesh sample_model(const VectorXd& u, double t, int samples) const override;
  void assemble_model(std::span<const Vector3d> x, std::span<const double> s, double t, VectorXd& g,
                      std::vector<Triplet>* K) override;
  /// The knot moments' terms.
  bool add_load_terms(std::span<const Vector3d> x, std::span<const double> s, double t,
                      VectorXd& g) const override;
  const SectionFrames* section_frames() const override { return &rod_; }

 private:
  /// g -= the knot moments' work-conjugate forces at t, their tangent into K if not null.
  void add_moment_terms(std::span<const Vector3d> x, std::span<const double> s, double t,
                        VectorXd& g, std::vector<Triplet>* K) const;
  void check_parameter(double xi) const;
  int check_knot(int knot) const;
  struct KnotMoment {
    double xi = 0.0;
    Vector3d M = Vector3d::Zero();
    double Mt = 0.0;
    LoadCurve curve;
  };
  TwistingRod rod_;
  std::vector<KnotMoment> moments_;
};

}  // namespace iga
