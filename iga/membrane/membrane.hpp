// A membrane: a Kirchhoff-Love surface without bending (fabrics, airbags, rubber sheets) on a
// NURBS patch, its control point positions the unknowns: membrane strain energy, internal forces
// and consistent tangent, St. Venant-Kirchhoff and incompressible neo-Hookean laws, an optional
// isotropic prestress, edge conditions, dead surface loads and follower pressure. Contact with
// rigid tools is the shells' STAS pair on its surface (iga/contact_integrals).
// References: [KBLW09] (kirchhoff_love_shell.hpp) Sect. 3 for the membrane kinematics and the
//   St. Venant-Kirchhoff plane-stress tensor; the incompressible neo-Hookean membrane (thickness
//   stretch lambda_3^2 = det A / det a from J = 1): G.A. Holzapfel, Nonlinear Solid Mechanics
//   (2000), Sect. 6.5 (incompressible neo-Hookean), written on the surface metric by us:
//     W = mu t / 2 (A^ab a_ab + r - 3),  r = det A_ab / det a_ab,
//     S^ab = 2 dW/da_ab = mu t (A^ab - r a^ab),
//     C^abcd = dS^ab/dE_cd = mu t r (2 a^ab a^cd + a^ac a^bd + a^ad a^bc).
//
// Notation (symbol -> code):
//   theta^a = (u, v)               surface parameters                  u, v
//   X_I, x_I                       reference / current control points  X, x
//   R_I, R_I,a                     rational basis and first derivatives  basis.R, d1, d2
//   A_a, a_a = sum R_I,a x_I       covariant base vectors              A1, A2 / a1, a2
//   A_ab, a_ab; A^ab, a^ab         metrics and their inverses          A, a; Ainv, ainv
//   E_ab = 1/2 (a_ab - A_ab)       Green-Lagrange membrane strain       E (Voigt E11, E22, 2E12)
//   S^ab                           2nd Piola-Kirchhoff membrane force   S (Voigt 11, 22, 12)
//                                  per unit reference length (t included)
//   C^abcd                         tangent dS/dE (t included)           D (Voigt 3x3)
//   n_0                            isotropic prestress, S^ab += n_0 A^ab  prestress
//   t, E, nu, mu                   thickness, Young's modulus, Poisson's ratio, shear modulus
//   dA = |A_1 x A_2| du dv         reference area element               wJ (Gauss weight incl.)
//   B_I                            dE/dx_I (Voigt rows): [R_I,1 a_1; R_I,2 a_2; R_I,1 a_2 + R_I,2
//   a_1]
//
// Weak form: f_I = int B_I^T S dA, K_IJ = int (B_I^T D B_J + (S^ab R_I,a R_J,b) 1) dA
// (symmetric). St. Venant-Kirchhoff: S = D E with C^abcd = t E/(1 - nu^2) [nu A^ab A^cd +
// (1 - nu)/2 (A^ac A^bd + A^ad A^bc)], W = 1/2 E:D:E. A flat membrane without prestress has no
// stiffness normal to itself: load it with a prestress, or in its plane first.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/nurbs_surface.hpp"
#include "geometry/rational_basis.hpp"
#include "iga/core/control_point_problem.hpp"
#include "iga/core/partition.hpp"

namespace iga {

/// Bad membrane input (material, degree, singular reference, conditions).
class MembraneError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

enum class MembraneLaw {
  kSaintVenantKirchhoff,  ///< S = C:E (E, nu); small strains
  kNeoHookean,            ///< incompressible neo-Hookean (mu); rubber, large stretches
};

struct MembraneMaterial {
  MembraneLaw law = MembraneLaw::kSaintVenantKirchhoff;
  double E = 0.0;          ///< Young's modulus (St. Venant-Kirchhoff), > 0
  double nu = 0.0;         ///< Poisson's ratio (St. Venant-Kirchhoff), in (-1, 0.5]
  double mu = 0.0;         ///< shear modulus (neo-Hookean), > 0
  double thickness = 0.0;  ///< t, > 0
  double prestress = 0.0;  ///< n_0 >= 0, a force per unit reference length, in every direction
};

/// The law at one point: energy per reference area W, S and D (Voigt, t included), from the
/// reference and current metrics. W = +inf and S, D NaN where det a <= 0 (a degenerate point).
struct MembraneResponse {
  double W = 0.0;
  Eigen::Vector3d S = Eigen::Vector3d::Zero();
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
};
MembraneResponse membrane_response(const MembraneMaterial& m, const Matrix2d& A, const Matrix2d& a);

class MembraneProblem : public ControlPointProblem {
 public:
  /// Throws MembraneError: a bad material, degree < 1 or > kMaxSurfaceBasisDegree in a
  /// direction, quadrature_points outside [0, 20] (0: p + 1), a singular reference point.
  /// Only the elements of `block` are built (a process's part of a membrane cut over several,
  /// iga/core/partition.hpp): its energy, forces, tangent, surface loads, pressure and samples
  /// are that part's; by default the whole patch.
  MembraneProblem(NurbsSurface reference, MembraneMaterial material, int quadrature_points = 0,
                  const ElementBlock& block = {});

  const NurbsSurface& reference() const { return reference_; }
  const MembraneMaterial& material() const { return material_; }
  int num_elements() const { return elements_; }
  /// Strain energy at the current control points x (prestress and loads not included).
  double energy(std::span<const Vector3d> x) const;

  // ---- edge conditions -------------------------------------------------------------------------
  /// The given Cartesian displacement components (0, 1, 2) of the edge's control points fixed.
  void support(SurfaceEdge edge, const std::vector<int>& components);
  /// The edge stays in a symmetry plane of normal N: its control points have u.N = 0 (a
  /// membrane has no rotation to hold).
  void symmetry(SurfaceEdge edge, const Vector3d& plane_normal);

  // ---- loads -----------------------------------------------------------------------------------
  /// Dead force q per reference area: f_I = int R_I q dA lambda(t).
  void add_surface_load(const Vector3d& q, LoadCurve curve = ramp());
  /// Follower pressure p per current area along a_1 x a_2: f_I = int p R_I (a_1 x a_2) du dv,
  /// load stiffness d f_I / d x_J = int p R_I (R_J,2 [a_1]x - R_J,1 [a_2]x) du dv.
  void add_pressure(double p, LoadCurve curve = ramp());

  /// The current surface (reference knots and weights, current control points).
  NurbsSurface current_surface(const VectorXd& u, double t) const;

  // ---- Body ------------------------------------------------------------------------------------
  std::string type() const override { return "membrane"; }
  /// "membrane of 64 elements (degree 2 x 2, 100 control points, neo-Hookean)".
  std::string describe() const override;
  int default_samples() const override { return 4; }
  Vector3d displacement(double u, double v, const VectorXd& state, double t) const override;

 protected:
  bool model_symmetric() const override { return pressures_.empty(); }
  /// The patch's points cut as its elements are (patch_point_partition).
  void point_partition(int rank, int processes, std::vector<int>& owner,
                       std::vector<char>& reads) const override;
  /// The surface on a grid, `samples` intervals per element span and direction (kGrid), with
  /// the displacement, the normal, the principal stretches and the membrane forces S in the
  /// reference local frame e_1 = A_1/|A_1|, e_2 = A_3 x e_1 (N_11, N_22, N_12).
  SampledMesh sample_model(const VectorXd& u, double t, int samples) const override;
  void assemble_model(std::span<const Vector3d> x, std::span<const double> s, double t, VectorXd& g,
                      std::vector<Triplet>* K) override;
  /// The pressure's terms (follower pressure along its curves).
  bool add_load_terms(std::span<const Vector3d> x, std::span<const double> s, double t,
                      VectorXd& g) const override {
    (void)s;
    add_pressure_terms(x, t, g, nullptr);
    return true;
  }

 private:
  struct Point {
    int row_u = 0, row_v = 0;  ///< its rows of table_u_, table_v_ (basis)
    double w_param = 0.0;      ///< Gauss weight * parametric Jacobian (integrates du dv)
    double wJ = 0.0;           ///< w_param |A_1 x A_2|
    Matrix2d A = Matrix2d::Zero();
  };
  struct Pressure {
    double p = 0.0;
    LoadCurve curve;
  };
  /// The base vectors a_1, a_2 at a point for control points x.
  std::pair<Vector3d, Vector3d> base(const SurfaceBasis& B, std::span<const Vector3d> x) const;
  void add_pressure_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                          std::vector<Triplet>* K) const;

  NurbsSurface reference_;
  MembraneMaterial material_;
  int elements_ = 0;
  ElementBlock block_;         ///< the elements built here
  std::vector<Point> points_;  ///< quadrature points, element by element
  /// The B-spline basis in u at the Gauss points of every span (span after span), and in v.
  SpanBasisTable table_u_, table_v_;
  /// The rational basis at a quadrature point (the points keep none of their own).
  void basis(const Point& pt, SurfaceBasis& B) const {
    rational_basis(reference_, table_u_[static_cast<std::size_t>(pt.row_u)],
                   table_v_[static_cast<std::size_t>(pt.row_v)], B);
  }
  int points_per_element_ = 0;
  std::vector<Pressure> pressures_;
};

}  // namespace iga
