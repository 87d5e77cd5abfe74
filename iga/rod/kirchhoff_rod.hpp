// Geometrically nonlinear, rotation-free Kirchhoff rod on a C1 NURBS curve: the control point
// positions are the unknowns. Element energy, internal forces and consistent tangent, global
// assembly, and a RodProblem (boundary conditions, loads, load curves) for the nonlinear solver.
// References: [PT97] Piegl & Tiller, The NURBS Book, 2nd ed. (A2.1, A2.3; eq. 4.8 for the
//   derivatives of the rational basis);
// [GC13] Greco & Cuomo, "B-spline interpolation of Kirchhoff-Love space rods", CMAME 256 (2013)
//   251-269 (rotation-free C1 spline rods: centre line alone, axial strain and curvature);
// [MPW14] Meier, Popp & Wall, "An objective 3D large deformation finite element formulation for
//   geometrically exact curved Kirchhoff rods", CMAME 278 (2014) 445-478 (the smallest-rotation
//   (SR) mapping of a triad onto a new tangent; objectivity of rod strain measures);
// [MPW15] Meier, Popp & Wall, "A locking-free finite element formulation and reduced models for
//   geometrically exact Kirchhoff rods", CMAME 290 (2015) 314-341 (the torsion-free reduced
//   model: for isotropic, initially straight rods the bending energy is 1/2 EI |kappa|^2);
// [BBP16] Bauer, Breitenberger, Philipp, Wuechner & Bletzinger, "Nonlinear isogeometric spatial
//   Bernoulli beam", CMAME 303 (2016) 101-127 (isogeometric rods, Green-Lagrange axial strain).
// The formulas below are written out and differentiated by us; kirchhoff_rod.cpp cites them.
//
// Notation (symbol -> code):
//   xi                      curve parameter                              xi
//   X_i, x_i                reference / current control points           X, x
//   R_i(xi), R_i', R_i''    rational basis functions and derivatives     N, dN, ddN
//   R' = dX/dxi             reference tangent (not unit), A = |R'|^2     A
//   r' = a, r'' = b         current derivatives of the centre line       a, b
//   S, dS = |R'| dxi        reference arc length                         wJ (weight * |R'| * jac)
//   eps = (|r'|^2 - A)/(2A) Green-Lagrange axial strain                  eps
//   kappa = r' x r'' / (|R'| |r'|^2)   bending curvature vector          kappa
//   K = R' x R''/|R'|^3     reference curvature vector                   K, Kmag = |K|
//   T = R'/|R'|, t = r'/|r'| reference / current unit tangent            T, t
//   D_1, D_2 ; d_1, d_2     reference / current section axes (normal to T, t)  D1, D2
//   kappa_a = kappa.d_a, K_a = K.D_a   bending strains, a = 1, 2         kappa_a, K1, K2
//   EA, EI_1, EI_2          axial stiffness, bending stiffnesses         EA, EI1, EI2
//   lambda(t)               load curve of pseudo-time t                  LoadCurve
//
// kappa = t x dt/dS is the rotation rate of the tangent per unit REFERENCE length (the
// curvature of Simo-Reissner and of [MPW14, MPW15]; the geometric curvature times the stretch
// |r'|/|R'|). It is work-conjugate to the bending moment, so a pure moment M gives
// kappa = M/EI with eps = 0 exactly; a curvature per current length would couple bending to
// stretching (eps ~ M^2/(EA EI) under a pure moment).
//
// Strain energy per unit reference length (St. Venant-Kirchhoff):
//   W = 1/2 EA eps^2 + 1/2 EI_1 (kappa_1 - K_1)^2 + 1/2 EI_2 (kappa_2 - K_2)^2,
// EI_a multiplying the curvature component along d_a, i.e. bending about the axis d_a.
//
// The bending measure. A rotation-free rod has no twist unknown, so the section axes d_a must be
// derived from the centre line; two choices are offered (BendingMeasure):
//  - kTransportedFrame (default): d_a is the image of D_a under the smallest rotation that takes
//    T onto t ([MPW14]): d_a = D_a - (D_a.t)/(1 + T.t) (T + t). For isotropic sections with a
//    straight reference (K = 0) the energy is 1/2 EI |kappa|^2, exact and objective (the
//    torsion-free rod of [MPW15]); it is evaluated that way, so it also holds when t reverses.
//    Otherwise (curved reference or EI_1 != EI_2) the measure is smooth and stiff in every bending
//    direction but NOT objective: a rigid rotation about an axis with a component along T twists
//    the carried frame and costs energy; it is objective for planar problems (rotations about the
//    plane normal). Undefined where t = -T (a tangent reversed against the reference).
//  - kCurvatureMagnitude (isotropic only): W_b = 1/2 EI (|kappa| - |K|)^2. Objective for any
//    reference; it is the minimum of the transported measure over a free twist of the section,
//    i.e. a rod without torsional stiffness. Consequence: a curved reference has no first-order
//    stiffness against rotating its curvature plane about the tangent (e.g. out-of-plane bending
//    of an arch), and |kappa| -> 0 with |K| > 0 is a kink of W (regularized by
//    |kappa| ~ sqrt(|kappa|^2 + (1e-6 |K|)^2)).
//
// Discretization. The basis must be C1 (degree >= 2, interior knot multiplicity <= p - 1); the
// 9-point circle and multi-segment arcs of constructions.hpp have double knots and are rejected
// (use one segment of <= 90 degrees, refined, or an interpolated cubic). Gauss-Legendre with
// p + 1 points per element by default. Like every displacement-based rotation-free rod, the
// element shows membrane locking when a curved shape must be represented with a nearly
// inextensible centre line and EA L^2 / EI is large: measured in the tests (tip-force elastica,
// EA L^2/EI = 1e5) p = 3 converges from 16 elements, p = 2 only from ~32. Integrating the axial
// term alone with p Gauss points (RodOptions::axial_quadrature_points, selective reduced
// integration as in Adam, Bouabdallah, Zarroug & Maitournam, CMAME 279 (2014) 1-28) relieves it
// for p = 2 (roll-up, 16 elements: error 0.2 -> 4e-4); for a straight reference it adds no
// zero-energy mode (the axial strain of a C^{p-1} degree-p spline vanishing at p points per
// element forces a rigid translation).
//
// Cost: the energy density's gradient and Hessian in (r', r'') are written out (no automatic
// differentiation); ~0.2-0.6 us per quadrature point for the element tangent; no heap
// allocation in the element and quadrature loops (fixed-capacity element arrays).
#pragma once

#include <array>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/nurbs_curve.hpp"
#include "geometry/rational_basis.hpp"
#include "iga/core/control_point_problem.hpp"

namespace iga {

/// Bad rod input (section, curve continuity, boundary condition indices).
class RodError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Section and material of the rod (St. Venant-Kirchhoff).
struct RodSection {
  double EA = 0.0;   ///< axial stiffness, > 0
  double EI1 = 0.0;  ///< stiffness of the curvature component along d_1 (bending about d_1), >= 0
  double EI2 = 0.0;  ///< stiffness of the curvature component along d_2 (bending about d_2), >= 0
  /// General section (EI1 != EI2): D_1 = the part of this vector normal to T, normalized;
  /// D_2 = T x D_1. Unused for isotropic sections.
  Vector3d ref_direction = Vector3d::Zero();
  double GJ = 0.0;  ///< torsional stiffness (the twisting rod, twisting_rod.hpp; unused here)

  bool isotropic() const { return EI1 == EI2; }
  /// Solid circle of radius r: EA = E pi r^2, EI1 = EI2 = E pi r^4 / 4.
  static RodSection circular(double E, double r);
  /// Rectangle of width w along `width_direction` (= D_1) and height h along D_2 = T x D_1:
  /// EA = E w h, EI1 = E w h^3 / 12 (bending about D_1), EI2 = E h w^3 / 12.
  static RodSection rectangular(double E, double w, double h, const Vector3d& width_direction);
};

enum class BendingMeasure {
  kTransportedFrame,    ///< section axes carried by the smallest rotation T -> t (see above)
  kCurvatureMagnitude,  ///< 1/2 EI (|kappa| - |K|)^2, isotropic sections only (see above)
};

struct RodOptions {
  int quadrature_points = 0;  ///< Gauss-Legendre points per element; 0 means p + 1
  BendingMeasure bending = BendingMeasure::kTransportedFrame;
  /// Gauss points per element for the axial term alone; 0 means the same points as bending.
  /// Fewer points (p) relieve membrane locking of curved configurations (see the header).
  int axial_quadrature_points = 0;
  /// true: the rod is straight when unloaded (a rope laid along a curved path): the stress-free
  /// curvature is K = 0 whatever the reference curve's shape, W_b = 1/2 EI |kappa|^2 (isotropic;
  /// K_a = 0 otherwise); axial strain and arc length still come from the reference curve.
  /// false: the reference curve is stress-free (K from its shape).
  bool straight_stress_free = false;
};

/// Rods with at least this many elements are assembled on all OpenMP threads (KirchhoffRod::
/// assemble: an element takes about 1 us, so fewer do not pay for the threads' start).
inline constexpr int kParallelRodElements = 128;

/// Element vectors and matrices of fixed capacity 3 (kMaxDegree + 1): no heap allocation.
inline constexpr int kMaxRodElementDofs = 3 * (kMaxDegree + 1);
using RodElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRodElementDofs, 1>;
using RodElementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                       kMaxRodElementDofs, kMaxRodElementDofs>;

/// Strains and section forces at one point of the rod (output, tests).
struct RodStrains {
  double eps = 0.0;                            ///< Green-Lagrange axial strain
  double axial_force = 0.0;                    ///< EA eps
  double curvature = 0.0;                      ///< |kappa| (per unit reference length)
  Vector2d bending_strain = Vector2d::Zero();  ///< (kappa_1 - K_1, kappa_2 - K_2); for the
                                               ///< magnitude measure (|kappa| - |K|, 0)
  Vector2d bending_moment = Vector2d::Zero();  ///< EI_a times bending_strain_a
  double energy_density = 0.0;                 ///< W per unit reference length
};

/// The discretized rod: reference curve, section, quadrature; energy, forces and tangent for a
/// given array of current control points x (one per control point of the reference curve).
/// Global DOF numbering for assembly: 3 i + c for component c of control point i.
class KirchhoffRod {
 public:
  /// Throws RodError: degree < 2, an interior knot of multiplicity > p - 1 (not C1), EA <= 0,
  /// EI < 0, a general section without a usable ref_direction (parallel to T somewhere), the
  /// magnitude measure with EI1 != EI2, quadrature_points outside [0, 20].
  KirchhoffRod(NurbsCurve reference, RodSection section, RodOptions options = {});

  const NurbsCurve& reference() const { return reference_; }
  const RodSection& section() const { return section_; }
  const RodOptions& options() const { return options_; }
  int degree() const { return reference_.degree(); }
  int num_control_points() const { return reference_.num_control_points(); }
  int num_dofs() const { return 3 * num_control_points(); }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  int num_quadrature_points(int e) const;
  /// Parameter range and first control point of element e (its p + 1 points are consecutive).
  Interval element_range(int e) const;
  int element_first_point(int e) const;
  /// Reference length of the rod (sum of the element quadratures of |R'|).
  double reference_length() const;

  /// Strain energy of element e / of the whole rod at the current control points x.
  double element_energy(int e, std::span<const Vector3d> x) const;
  double energy(std::span<const Vector3d> x) const;
  /// Internal forces f_e = dPi_e/dx_e (3(p+1) entries, point-major) of element e.
  void element_forces(int e, std::span<const Vector3d> x, RodElementVector& f) const;
  /// Internal forces and consistent tangent K_e = d f_e / d x_e (symmetric).
  void element_tangent(int e, std::span<const Vector3d> x, RodElementVector& f,
                       RodElementMatrix& K) const;
  /// Global internal forces (resized to num_dofs()) and, if K != nullptr, the tangent as
  /// triplets appended to *K (duplicates are to be summed), in element order. Rods of
  /// kParallelRodElements elements or more are assembled on all OpenMP threads; the result is
  /// the same bit for bit for any number of threads.
  void assemble(std::span<const Vector3d> x, Eigen::VectorXd& f_int, std::vector<Triplet>* K) const;

  /// Current position and strains at parameter xi.
  Vector3d point(double xi, std::span<const Vector3d> x) const;
  RodStrains strains(double xi, std::span<const Vector3d> x) const;

  /// Precomputed data of one quadrature point (public for tests and contact integrals).
  struct QuadraturePoint {
    double xi = 0.0;
    double wJ = 0.0;    ///< Gauss weight * d xi / d(ref. coordinate) * |R'|: integrates dS
    double A = 0.0;     ///< |R'|^2
    double Kmag = 0.0;  ///< |K|
    double K1 = 0.0, K2 = 0.0;
    Vector3d T = Vector3d::Zero(), D1 = Vector3d::Zero(), D2 = Vector3d::Zero();
    bool frame = false;   ///< true: transported-frame formula; false: |kappa|^2 formula
    bool axial = true;    ///< the axial term is integrated at this point
    bool bending = true;  ///< the bending term is integrated at this point
    RationalBasis basis;
  };
  const QuadraturePoint& quadrature_point(int e, int q) const;

 private:
  QuadraturePoint make_point(double xi, double weight, double element_length) const;
  /// The one element kernel: forces f (Tangent = false) or forces and tangent K (true).
  template <bool Tangent>
  void element_kernel(int e, std::span<const Vector3d> x, RodElementVector& f,
                      RodElementMatrix* K) const;

  struct Element {
    int first = 0;     ///< first control point
    int qp_begin = 0;  ///< index into qps_
    int qp_count = 0;
    Interval range;
  };
  NurbsCurve reference_;
  RodSection section_;
  RodOptions options_;
  std::vector<Element> elements_;
  std::vector<QuadraturePoint> qps_;
};

enum class RodEnd { kStart, kEnd };

/// The generalized forces f_i = int R_i q dS of a dead load q per unit reference length over
/// the parameter range of a rod's reference curve (one per control point).
std::vector<Vector3d> rod_line_load(const NurbsCurve& reference, const Vector3d& q, Interval range);

/// A rod with boundary conditions and loads as a NonlinearProblem. The unknowns u are the
/// displacements of the free control point components; constrained components are fixed or
/// prescribed along load curves. Each control point has an orthonormal local basis Q_i (default
/// identity): component c of point i means the displacement along the column Q_i(:, c).
/// Residual R = f_int(x) - f_ext(x, t) on the free components; K = dR/du.
///
/// Clamped ends: at an open-knot end r'(end) is parallel to x_1 - x_0 (second and last but one
/// control points), so clamp() fixes the end point and the two components of its neighbour
/// normal to the reference end tangent (a local basis with axis 0 along the tangent): the
/// tangent direction is held exactly, no penalty; the neighbour may still slide along it.
///
/// Moments at a parameter xi (end moments): the virtual work of a moment M on the rotation of
/// the tangent, delta W = M.(t x delta t) = (M x r').delta r' / |r'|^2, gives the generalized
/// forces f_i = lambda R_i'(xi) (M x r') / |r'|^2 and the load stiffness -d f / d x. The
/// component of M along t (torsion) does no work: a rotation-free rod has no twist unknown.
/// In a plane normal to M this is the conservative moment of potential -lambda M theta (theta
/// the tangent angle, unwrapped), so an end moment can roll a rod up into a full circle. Out of
/// that plane the load stiffness is not symmetric, so symmetric() is false when moments exist.
class RodProblem : public ControlPointProblem {
 public:
  explicit RodProblem(KirchhoffRod rod);

  const KirchhoffRod& rod() const { return rod_; }

  // Constraints (set_local_basis, fix, prescribe, constrained, dof), current_points,
  // nodal_residual, dead_load and assemble: see ControlPointProblem.

  /// Fixes the end control point and the neighbour's components normal to the reference end
  /// tangent (sets the neighbour's local basis: axis 0 along the tangent). Throws RodError if the
  /// neighbour already has a local basis or constraints.
  void clamp(RodEnd end);
  /// A symmetry plane through the end, normal n, that the rod crosses at right angles (its
  /// reference end tangent along n, else RodError): the end control point stays in the plane
  /// and the neighbour moves with it in the plane's directions, so the end tangent stays along
  /// n (open knots: r'(end) is along x_1 - x_0). For n along a coordinate axis k: x_0's
  /// component k fixed, x_1's other two tied to x_0's (other constraints of the points stay);
  /// else both points get the local basis (e1, e2, n) (RodError if they have constraints).
  /// A quarter of a ring between two plates, a half of a symmetric rope.
  void symmetry(RodEnd end, const Vector3d& n);

  // ---- loads (all scaled by their load curve) ----------------------------------------------
  /// Dead force F at parameter xi, distributed by the basis functions: f_i = R_i(xi) F.
  void add_point_load(double xi, const Vector3d& F, LoadCurve curve = ramp());
  /// Dead distributed force q per unit reference length over the parameter range (default: all).
  void add_line_load(const Vector3d& q, LoadCurve curve = ramp());
  void add_line_load(const Vector3d& q, Interval range, LoadCurve curve = ramp());
  /// Moment M at parameter xi (use the domain ends for end moments); see the class comment.
  void add_moment(double xi, const Vector3d& M, LoadCurve curve = ramp());

  /// The current centre line (reference knots and weights, current control points).
  NurbsCurve current_curve(const VectorXd& u, double t) const;

  // ---- Body ------------------------------------------------------------------------------------
  std::string type() const override { return "rod"; }
  /// "rod of 8 elements (degree 3, 11 control points)".
  std::string describe() const override;
  int default_samples() const override { return 16; }
  /// Displacement of the centre line point at parameter pu (pv unused).
  Vector3d displacement(double pu, double pv, const VectorXd& u, double t) const override;

 protected:
  bool model_symmetric() const override { return moments_.empty(); }
  /// The centre line sampled per element (kPolyline) with the axial force and the curvature. A
  /// sample where the strains cannot be evaluated (a zero tangent, e.g. at an end whose first
  /// two control points coincide) gets zero force and curvature and the flag singular = 1.
  SampledMesh sample_model(const VectorXd& u, double t, int samples) const override;

  /// g = f_int - (moment loads), tangent triplets.
  void assemble_model(std::span<const Vector3d> x, std::span<const double> s, double t, VectorXd& g,
                      std::vector<Triplet>* K) override;
  /// The moment loads' terms.
  bool add_load_terms(std::span<const Vector3d> x, std::span<const double> s, double t,
                      VectorXd& g) const override {
    (void)s;
    add_moment_terms(x, t, g, nullptr);
    return true;
  }

 private:
  struct Moment {
    RationalBasis basis;
    Vector3d M = Vector3d::Zero();
    LoadCurve curve;
  };

  void add_moment_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                        std::vector<Triplet>* K) const;

  KirchhoffRod rod_;
  std::vector<Moment> moments_;
};

}  // namespace iga
