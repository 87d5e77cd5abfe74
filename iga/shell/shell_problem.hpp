// A Kirchhoff-Love shell patch with boundary conditions, springs and loads as a NonlinearProblem
// (the shell counterpart of RodProblem). References: [KBLW09] (see kirchhoff_love_shell.hpp),
// Sect. 5 (boundary conditions of rotation-free shells through the first two rows of control
// points).
//
// Notation (symbol -> code): X_I, x_I reference / current control points; u_I = x_I - X_I;
// row 0 / row 1 the control points on an edge / the next row inward; N_p a symmetry plane's
// unit normal; n_I the reference surface normal at the edge point of column I; lambda(t) load
// curves (LoadCurve); p pressure; q distributed / line force; k(t) spring stiffness.
//
// Edge conditions. At an open-knot edge the surface and its cross-edge derivative depend on
// rows 0 and 1 only: x(edge) = sum_j M_j x_0j and a_cross(edge) = c sum_j M_j (x_1j - x_0j)
// (c = p / first knot span, times weights for NURBS). Hence
//  - simply_support(edge, {components}): the chosen Cartesian components of row 0 are fixed.
//  - clamp(edge): row 0 fixed, and row 1's displacement along n_I (the reference normal at the
//    edge point of column I) fixed. Then (x_1 - x_0).n_I = (X_1 - X_0).n_I = 0 and the edge's
//    tangent plane (hence its normal, the rotation) is held exactly where n is constant along
//    the edge (flat or straight-generator edges: plates, cylinder generators); along a curved
//    edge it is held at the control points' normals (an O(h^2) approximation between them).
//    Row 1 may still move in the tangent plane, so the membrane strains at the edge are not
//    constrained. (Fixing row 1 entirely would also hold a_cross's length and direction, i.e.
//    the edge's membrane strains E_nn, E_nt = 0: an over-constraint.)
//  - symmetry(edge, N_p): row 0 has u.N_p = 0 (it stays in the plane), and row 1 is tied to
//    row 0 in the two in-plane directions t_1, t_2 (one shared unknown per pair): then
//    x_1 - x_0 stays parallel to N_p, i.e. a_cross is normal to the plane: the mirror image is
//    C1 across the plane, the rotation about the edge is zero. Note: fixing u.N_p on rows 0 AND 1
//    (as sometimes suggested) does NOT hold the rotation (a rigid rotation about the edge moves
//    row 1 normal to the surface, which lies in the plane), and over-constrains the membrane
//    stretch normal to the plane (u.N_p is odd in the distance to the plane, not zero at row 1).
//    The tie in t_1 along the edge is the discrete counterpart of the natural condition of zero
//    in-plane shear at the plane (exact for symmetric solutions).
// All edge conditions act along a direction at each point (DofMap::fix_along): a point keeps
// the local basis of its first constraint; a later condition along a direction not parallel to
// one of its axes throws ShellError (e.g. a clamp on a curved edge after a symmetry condition in
// another basis). Corners of two symmetry planes with coordinate normals work in any order.
//
// Loads (all scaled by their load curve lambda(t)):
//  - dead surface force q per reference area: f_I = int R_I q dA;
//  - follower pressure p per current area along the current normal a_3 = a_1 x a_2 / |.|
//    (positive p pushes towards +a_3): f_I = int p R_I (a_1 x a_2) du dv, load stiffness
//    d f_I / d x_J = int p R_I (R_J,2 [a_1]x - R_J,1 [a_2]x) du dv, not symmetric in general
//    (it is only for a closed surface or a boundary held fixed), so symmetric() is false when a
//    pressure is present;
//  - dead line force q per reference length along an edge: f_I = int_edge R_I q dS;
//  - dead point force F at (u, v): f_I = R_I(u, v) F.
// Springs: force -k lambda(t) u_I on control point I (all directions, or along a unit d:
// -k lambda (u_I.d) d), energy 1/2 k lambda |u_I|^2, tangent k lambda I (or d d^T).
#pragma once

#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "iga/core/control_point_problem.hpp"
#include "iga/shell/kirchhoff_love_shell.hpp"

namespace iga {

class ShellProblem : public ControlPointProblem {
 public:
  explicit ShellProblem(KirchhoffLoveShell shell);

  const KirchhoffLoveShell& shell() const { return shell_; }
  /// Control point index of (i, j), u fastest.
  int point_index(int i, int j) const { return shell_.reference().index(i, j); }
  /// The control points of `row` (0: on the edge, 1: the next row inward), in the order of the
  /// edge's parameter.
  std::vector<int> edge_points(SurfaceEdge edge, int row = 0) const;

  // Constraints of single points: see ControlPointProblem (fix, prescribe, set_local_basis).
  // ---- edge conditions (see the header comment) -----------------------------------------------
  /// Fixes the given Cartesian displacement components (0, 1, 2 = x, y, z) of the edge row.
  void simply_support(SurfaceEdge edge, std::initializer_list<int> components);
  void clamp(SurfaceEdge edge);
  void symmetry(SurfaceEdge edge, const Vector3d& plane_normal);

  // ---- springs -------------------------------------------------------------------------------
  /// Spring of stiffness k curve(t) between control point `point` and its reference position,
  /// in all directions or along `direction` only.
  void add_spring(int point, double stiffness, LoadCurve curve = constant_curve(),
                  std::optional<Vector3d> direction = std::nullopt);

  // ---- loads ---------------------------------------------------------------------------------
  void add_surface_load(const Vector3d& q, LoadCurve curve = ramp());
  void add_pressure(double p, LoadCurve curve = ramp());
  void add_edge_load(SurfaceEdge edge, const Vector3d& q, LoadCurve curve = ramp());
  void add_point_load(double u, double v, const Vector3d& F, LoadCurve curve = ramp());

  /// The current surface (reference knots and weights, current control points).
  NurbsSurface current_surface(const VectorXd& u, double t) const;

  // ---- Body ------------------------------------------------------------------------------------
  std::string type() const override { return "shell"; }
  /// "shell of 64 elements (degree 2 x 2, 100 control points)".
  std::string describe() const override;
  int default_samples() const override { return 4; }
  /// Displacement x(u, v) - X(u, v) of the surface point at parameters (u, v).
  Vector3d displacement(double u, double v, const VectorXd& state, double t) const override;

 protected:
  bool model_symmetric() const override { return pressures_.empty(); }
  /// The patch's points cut as its elements are (patch_point_partition).
  void point_partition(int rank, int processes, std::vector<int>& owner,
                       std::vector<char>& reads) const override;
  /// The surface sampled on a grid, `samples` intervals per element span and direction (kGrid),
  /// with the displacement, the normal, membrane forces and moments in a local Cartesian frame
  /// (ShellStresses) and the von Mises stress; a sample where they cannot be evaluated gets
  /// zeros and the flag singular = 1.
  SampledMesh sample_model(const VectorXd& u, double t, int samples) const override;

  /// g = f_int - f_pressure + springs; tangent triplets.
  void assemble_model(std::span<const Vector3d> x, std::span<const double> s, double t, VectorXd& g,
                      std::vector<Triplet>* K) override;
  /// The pressure and spring terms (both along curves).
  bool add_load_terms(std::span<const Vector3d> x, std::span<const double> s, double t,
                      VectorXd& g) const override;

 private:
  struct Spring {
    int point = 0;
    double k = 0.0;
    LoadCurve curve;
    bool directional = false;
    Vector3d d = Vector3d::Zero();
  };
  struct Pressure {
    double p = 0.0;
    LoadCurve curve;
  };
  void add_pressure_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                          std::vector<Triplet>* K) const;
  /// The springs' forces k curve(t) (x - X) and their tangent.
  void add_spring_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                        std::vector<Triplet>* K) const;
  /// The reference normal at the edge point of each column of the edge.
  std::vector<Vector3d> edge_normals(SurfaceEdge edge) const;

  KirchhoffLoveShell shell_;
  std::vector<Spring> springs_;
  std::vector<Pressure> pressures_;
};

}  // namespace iga
