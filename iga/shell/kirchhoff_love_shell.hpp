// Geometrically nonlinear, rotation-free Kirchhoff-Love shell on a C1 NURBS surface patch: the
// control point positions are the unknowns. Element energy, internal forces and consistent
// tangent, global assembly, stresses for output; ShellProblem (boundary conditions, loads,
// springs, load curves) for the nonlinear solver.
// References: [KBLW09] J. Kiendl, K.-U. Bletzinger, J. Linhard, R. Wuechner, "Isogeometric shell
//   analysis with Kirchhoff-Love elements", CMAME 198 (2009) 3902-3914: Sect. 3 (kinematics
//   a_alpha, a_3, metric a_ab, curvature b_ab = a_a,b . a_3, membrane strain E_ab = 1/2 (a_ab -
//   A_ab), bending strain K_ab = B_ab - b_ab, thickness-integrated St. Venant-Kirchhoff
//   constitutive law n = h C:E, m = h^3/12 C:K, C from the contravariant reference metric),
//   Sect. 4 (first and second variations of the strains, incl. those of the unit normal);
// [PT97] Piegl & Tiller, The NURBS Book (A2.3 and eq. 4.20 for the rational surface basis);
// [KHB+15] J. Kiendl, M.-C. Hsu, M.C.H. Wu, A. Reali, "Isogeometric Kirchhoff-Love shell
//   formulations for general hyperelastic materials", CMAME 291 (2015) 280-303: Sect. 3 (strain
//   E(z) = eps + z kap through the thickness on the mid-surface metric, plane stress by the
//   condition S^33 = 0 solved for C_33, the condensed tangent C^abcd - C^ab33 C^33cd / C^3333,
//   numerical integration through the thickness), Sect. 3.2 (compressible neo-Hookean).
// The variations below are written out and differentiated by us in the 15 kinematic variables
// y = (a_1, a_2, a_11, a_22, a_12) and then mapped to control points (kirchhoff_love_shell.cpp);
// the equation-level correspondence to [KBLW09] is given in comments there by section.
//
// Notation (symbol -> code):
//   theta^1, theta^2 = (u, v)    surface parameters                      u, v
//   X_I, x_I                     reference / current control points     X, x
//   R_I, R_I,a, R_I,ab           rational basis and derivatives          SurfaceBasis::R, d1, d2,
//                                                                        d11, d22, d12
//   A_a, a_a                     covariant base vectors (ref./current)   A1, A2 / a1, a2
//   A_ab, a_ab                   metric coefficients                     Aab / a (2x2)
//   A^ab                         contravariant reference metric          Ainv
//   a_3 = a_1 x a_2 / |a_1 x a_2|  unit normal (current)                 n
//   B_ab, b_ab = a_a,b . a_3     curvature coefficients                  Bab / b
//   E_ab = 1/2 (a_ab - A_ab)     membrane (Green-Lagrange) strain        eps (Voigt E11, E22, 2E12)
//   K_ab = B_ab - b_ab           bending strain (change of curvature)    kap (Voigt K11, K22, 2K12)
//   C^abcd                       material tensor (Voigt 3x3)             D
//   n^ab = h C:E, m^ab = h^3/12 C:K  membrane forces, moments (contra.)  nf, mf (Voigt)
//   dA = |A_1 x A_2| du dv       reference area element                  wJ (Gauss weight incl.)
//   lambda(t)                    load curve of pseudo-time t             LoadCurve
//   z in [-h/2, h/2]             thickness coordinate along a_3          z (Gauss points)
//   C_ab = A_ab + 2 E_ab(z)      in-plane right Cauchy-Green (covariant) C (2x2)
//   C_33, J = sqrt(det C_ab / det A_ab C_33)  thickness stretch^2, volume ratio  C33, lnJ
//   mu, Lambda                   Lame constants from E, nu               mu, lam
//   n = int S dz, m = int z S dz, D_nn, D_nm, D_mm = int (1, z, z^2) dS/dE dz
//                                resultants and their tangents (neo-Hookean)  Resultants
//
// Energy per unit reference area: W = 1/2 h E:C:E + 1/2 h^3/12 K:C:K with
//   C^abcd = E/(1-nu^2) [nu A^ab A^cd + 1/2 (1-nu)(A^ac A^bd + A^ad A^bc)]   ([KBLW09] Sect. 3).
// Signs: with K = B - b, a plate bent so that its normal side becomes concave has b > 0 there.
//
// Discretization. The basis must be C1 inside the patch (degree >= 2 in u and v, interior knot
// multiplicity <= p - 1): the 9-point circle constructions have double knots and are rejected;
// use a single rational arc of <= 90 degrees (refined by knot insertion) or a fitted cubic.
// Degree <= kMaxShellDegree (fixed-capacity element arrays, no heap allocation in the element
// loops). Gauss-Legendre with p + 1 points per direction by default.
#pragma once

#include <array>
#include <span>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/nurbs_surface.hpp"
#include "geometry/rational_basis.hpp"
#include "iga/core/dof_map.hpp"
#include "iga/core/partition.hpp"
#include "iga/core/quadrature.hpp"

namespace iga {

/// Bad shell input (material, continuity, degree, boundary condition indices).
class ShellError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Constitutive law of a shell material (both isotropic, both with Young's modulus E and
/// Poisson's ratio nu at small strain).
enum class ShellLaw {
  /// S = C:E in the Green-Lagrange strain, integrated through the thickness in closed form
  /// (n = h C:eps, m = h^3/12 C:kap; [KBLW09] Sect. 3). Adequate while strains stay small.
  kSaintVenantKirchhoff,
  /// Compressible neo-Hookean (psi = mu/2 (tr C - 3) - mu ln J + lambda/2 ln^2 J; [KHB+15]
  /// Sect. 3.2), plane stress by condensing C_33, integrated through the thickness with
  /// ShellMaterial::thickness_points Gauss points. For large strains (folds, creases, rubber).
  kNeoHookean,
};

/// Isotropic shell material and thickness.
struct ShellMaterial {
  double E = 0.0;          ///< Young's modulus, > 0
  double nu = 0.0;         ///< Poisson's ratio, in (-1, 0.5)
  double thickness = 0.0;  ///< h, > 0
  ShellLaw law = ShellLaw::kSaintVenantKirchhoff;
  int thickness_points = 5;  ///< Gauss points through the thickness (kNeoHookean), in [2, 20]
};

/// Gauss points z and weights w through the thickness, z in [-h/2, h/2] (neo-Hookean).
struct ShellThicknessRule {
  int n = 0;
  std::array<double, kMaxGaussPoints> z{}, w{};
};

/// One material point of the neo-Hookean law in plane stress (S^33 = 0): energy per unit
/// reference volume psi, 2nd Piola-Kirchhoff stress S^ab (Voigt 11, 22, 12), its consistent
/// tangent D = dS/dE condensed over C_33 (Voigt, against E_11, E_22, 2 E_12) and C_33 itself, at
/// the in-plane Green-Lagrange strain E (Voigt E_11, E_22, 2 E_12) on the reference metric A_ab
/// (covariant components, unit thickness direction). psi is +inf and S, D are NaN where
/// det C_ab <= 0 (the material point is inverted).
struct PlaneStressPoint {
  double psi = 0.0;
  Vector3d S = Vector3d::Zero();
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  double C33 = 1.0;
};
PlaneStressPoint neo_hookean_plane_stress(double E, double nu, const Matrix2d& Aab,
                                          const Vector3d& strain);

struct ShellOptions {
  int quadrature_points = 0;  ///< Gauss-Legendre points per direction and element; 0: p + 1
  /// The elements this shell builds and assembles (a process's part of a patch spread over
  /// several, iga/core/partition.hpp); by default all.
  ElementBlock block;
};

/// Largest degree per direction of a shell patch (fixed-capacity element arrays).
inline constexpr int kMaxShellDegree = kMaxSurfaceBasisDegree;
/// Meshes with at least this many elements are assembled in parallel (KirchhoffLoveShell::
/// assemble).
inline constexpr int kParallelElements = 64;
inline constexpr int kMaxShellElementPoints = (kMaxShellDegree + 1) * (kMaxShellDegree + 1);
inline constexpr int kMaxShellElementDofs = 3 * kMaxShellElementPoints;
using ShellElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxShellElementDofs, 1>;
using ShellElementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                         kMaxShellElementDofs, kMaxShellElementDofs>;

/// Strains and stress resultants at one point (output; VTK later).
struct ShellStresses {
  Eigen::Vector3d membrane_strain = Eigen::Vector3d::Zero();  ///< E_11, E_22, 2 E_12 (covariant)
  Eigen::Vector3d bending_strain = Eigen::Vector3d::Zero();   ///< K_11, K_22, 2 K_12 (covariant)
  Eigen::Vector3d membrane_force = Eigen::Vector3d::Zero();   ///< n^11, n^22, n^12 (contravar.)
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();           ///< m^11, m^22, m^12 (contravar.)
  /// The same resultants in the reference local orthonormal frame e_1 = A_1/|A_1|,
  /// e_2 = A_3 x e_1 (per unit reference length; 2nd Piola-Kirchhoff type): (N_11, N_22, N_12),
  /// (M_11, M_22, M_12).
  Eigen::Vector3d membrane_force_local = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_local = Eigen::Vector3d::Zero();
  /// Largest von Mises stress of the top and bottom fibres, sigma = N/h +- 6 M/h^2 (plane stress;
  /// with the neo-Hookean law the same formula on its resultants, an estimate).
  double von_mises = 0.0;
  double energy_density = 0.0;  ///< W per unit reference area
};

/// The discretized shell patch: reference surface, material, quadrature; energy, forces and
/// tangent for the current control points x (one per control point, index i + n_u j).
/// Global DOF numbering for assembly: 3 I + c for component c of control point I.
class KirchhoffLoveShell {
 public:
  /// Throws ShellError: E <= 0, thickness <= 0, nu outside (-1, 0.5), thickness_points
  /// outside [2, 20], degree < 2 or >
  /// kMaxShellDegree in a direction, an interior knot of multiplicity > p - 1 (not C1),
  /// quadrature_points outside [0, 20], a singular reference point (A_1 x A_2 = 0).
  KirchhoffLoveShell(NurbsSurface reference, ShellMaterial material, ShellOptions options = {});

  const NurbsSurface& reference() const { return reference_; }
  const ShellMaterial& material() const { return material_; }
  const ShellOptions& options() const { return options_; }
  int num_control_points() const { return reference_.num_u() * reference_.num_v(); }
  int num_dofs() const { return 3 * num_control_points(); }
  /// The elements built here (those of options.block).
  int num_elements() const { return static_cast<int>(elements_.size()); }
  /// The elements of the whole patch (its non-empty knot spans).
  int num_patch_elements() const { return patch_elements_; }
  int num_quadrature_points(int e) const;
  /// Parameter rectangle of element e.
  Domain2 element_range(int e) const;
  /// Reference control points (u fastest).
  const std::vector<Vector3d>& reference_points() const { return X_; }
  /// Reference area (sum of the quadratures of dA).
  double reference_area() const;

  /// Strain energy of element e / of the patch at the current control points x.
  double element_energy(int e, std::span<const Vector3d> x) const;
  double energy(std::span<const Vector3d> x) const;
  /// Internal forces f_e = d Pi_e / d x_e (3 (p+1)(q+1) entries, local point k = i + (p+1) j).
  void element_forces(int e, std::span<const Vector3d> x, ShellElementVector& f) const;
  /// Internal forces and consistent tangent K_e = d f_e / d x_e (symmetric).
  void element_tangent(int e, std::span<const Vector3d> x, ShellElementVector& f,
                       ShellElementMatrix& K) const;
  /// Global control point of local function k of element e.
  int element_point(int e, int k) const;
  /// Global internal forces (resized to num_dofs()) and, if K != nullptr, the tangent as
  /// triplets appended to *K (duplicates are to be summed), element by element in element
  /// order. Meshes of kParallelElements elements or more are assembled on all OpenMP threads
  /// (OMP_NUM_THREADS, omp_set_num_threads); the result is the same bit for bit for any number
  /// of threads.
  void assemble(std::span<const Vector3d> x, Eigen::VectorXd& f_int, std::vector<Triplet>* K) const;

  /// Current point, unit normal a_3 and stresses at (u, v).
  Vector3d point(double u, double v, std::span<const Vector3d> x) const;
  Vector3d normal(double u, double v, std::span<const Vector3d> x) const;
  ShellStresses stresses(double u, double v, std::span<const Vector3d> x) const;

  /// Precomputed reference data of one quadrature point (public for loads and contact).
  struct QuadraturePoint {
    double u = 0.0, v = 0.0;
    double wJ = 0.0;                  ///< Gauss weight * parametric Jacobian * |A_1 x A_2|
    double w_param = 0.0;             ///< Gauss weight * parametric Jacobian (integrates du dv)
    Matrix2d Aab = Matrix2d::Zero();  ///< A_ab
    Vector3d Bv = Vector3d::Zero();   ///< B_11, B_22, B_12
    Eigen::Matrix3d D = Eigen::Matrix3d::Zero();  ///< C in Voigt form (without h)
  };
  const QuadraturePoint& quadrature_point(int e, int q) const;
  /// The rational basis at quadrature point q of element e (formed from the rule's per-span
  /// tables, SpanBasisTable: the points keep no basis of their own).
  void basis(int e, int q, SurfaceBasis& B) const;

 private:
  QuadraturePoint make_point(double u, double v, double w_param, const SurfaceBasis& B) const;
  /// The elements of options_.block with their quadrature points (the constructor's).
  void build_elements();
  template <int Order>
  void element_kernel(int e, std::span<const Vector3d> x, double* energy, ShellElementVector* f,
                      ShellElementMatrix* K) const;

  struct Element {
    int qp_begin = 0, qp_count = 0;
    int span_u = 0, span_v = 0;
    int row_u = 0, row_v = 0;  ///< the element's first rows of table_u_, table_v_
    Domain2 range;
  };
  NurbsSurface reference_;
  ShellMaterial material_;
  ShellOptions options_;
  std::vector<Vector3d> X_;
  std::vector<Element> elements_;
  int patch_elements_ = 0;
  std::vector<QuadraturePoint> qps_;
  /// The B-spline basis in u at the Gauss points of every non-empty span (u-span after
  /// u-span), and in v: quadrature point (a, b) of an element is row row_u + a and row_v + b.
  SpanBasisTable table_u_, table_v_;
  int ngu_ = 0;  ///< Gauss points per element in u
  ShellThicknessRule thickness_rule_;
};

}  // namespace iga
