// The map between a body's unknowns and its free unknowns: the displacements of its control
// points and, for a body that has them, scalar unknowns beside the points (a rod's twist
// angles). Local bases per control point, fixed and prescribed components along load curves,
// tied components (one unknown shared by two points), fixed and prescribed scalars, the
// reduction of Cartesian residuals and tangent triplets to the free unknowns. Shared by every
// ControlPointProblem (rods, shells, membranes).
//
// Notation: d_i displacement of control point i in its local basis Q_i (orthonormal columns),
// x_i = X_i + Q_i d_i; s_k scalar unknown k (its value, reference 0); g Cartesian residual
// (3 n + m: DOF 3 i + c for the points, 3 n + k for scalar k); R = P^T g the free residual with
// P the columns Q_i(:, c) (times the tie sign) of the free components and the unit columns of
// the free scalars. Free unknowns are numbered point by point, then the scalars.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "geometry/derivatives.hpp"

namespace iga {

using Eigen::VectorXd;
using Triplet = Eigen::Triplet<double>;

/// Load curve lambda(t) of pseudo-time t scaling a load or a prescribed displacement.
using LoadCurve = std::function<double(double)>;
/// lambda(t) = t.
inline LoadCurve ramp() {
  return [](double t) { return t; };
}
/// lambda(t) = c.
inline LoadCurve constant_curve(double c = 1.0) {
  return [c](double) { return c; };
}

/// Constraint bookkeeping of n control points. Errors are reported through `fail`, which
/// throws the owner's exception type (RodError, ShellError) with the message.
class DofMap {
 public:
  using FailFn = void (*)(const std::string& message);
  /// `owner` prefixes messages ("RodProblem", "ShellProblem"); `num_scalars` scalar unknowns
  /// after the points.
  DofMap(int num_points, std::string owner, FailFn fail, int num_scalars = 0);

  int num_points() const { return static_cast<int>(points_.size()); }
  int num_scalars() const { return static_cast<int>(scalars_.size()); }
  /// Entries of the Cartesian residual: 3 n + m.
  int num_cartesian() const { return 3 * num_points() + num_scalars(); }
  int num_free() const {
    refresh();
    return num_free_;
  }

  /// Sets the local basis of `point` (orthonormal columns); fails if the point already has
  /// constrained or tied components or Q is not orthonormal.
  void set_local_basis(int point, const Matrix3d& Q);
  const Matrix3d& local_basis(int point) const;
  bool rotated(int point) const { return points_[static_cast<std::size_t>(point)].rotated; }
  void fix(int point);
  void fix(int point, int component);
  /// Displacement component = value * curve(t).
  void prescribe(int point, int component, double value, LoadCurve curve);
  /// The local component of `point` whose axis is parallel to d (+-, |cos| > 1 - 1e-10), or
  /// -1; *sign (if given) is +1 or -1.
  int axis_along(int point, const Vector3d& d, double* sign = nullptr) const;
  /// Fixes the displacement along d: an existing parallel local axis, else (no constraints or
  /// ties on the point yet) a new local basis with axis 2 along d; fails otherwise.
  void fix_along(int point, const Vector3d& d);
  /// Component `component` of `slave` equals component `master_component` of `master`
  /// (their axes must be parallel; an antiparallel pair is tied with sign -1). A tied component
  /// that is also constrained keeps its constraint. Chains of ties are followed.
  void tie(int slave, int component, int master, int master_component);

  bool constrained(int point, int component) const;
  /// Free DOF index of a component (-1 if constrained; a tied slave gives its master's index).
  int dof(int point, int component) const;

  /// Whether a prescribed value (a point's component or a scalar) differs between t0 and t1,
  /// value curve(t0) != value curve(t1) bit for bit: then the current points or scalars at the
  /// same u differ.
  bool prescribed_moves(double t0, double t1) const;

  // ---- scalar unknowns (k in [0, num_scalars())) ----------------------------------------------
  void fix_scalar(int k);
  /// s_k = value * curve(t).
  void prescribe_scalar(int k, double value, LoadCurve curve);
  bool scalar_constrained(int k) const;
  /// Free DOF index of scalar k (-1 if constrained).
  int scalar_dof(int k) const;
  /// The scalars s_k(u, t) (resized to num_scalars()); u must have num_free() entries.
  void current_scalars(const VectorXd& u, double t, std::vector<double>& s) const;

  /// Current control points x_i = X_i + Q_i d_i(u, t); u must have num_free() entries.
  void current_points(std::span<const Vector3d> X, const VectorXd& u, double t,
                      std::vector<Vector3d>& x) const;
  /// R = P^T g (g: num_cartesian() entries; R resized to num_free()).
  void reduce(const VectorXd& g, VectorXd& R) const;
  /// The forces the constraints carry, from the Cartesian nodal forces g_i (one per point, e.g.
  /// f_int - f_ext at an equilibrium state): per point, the sum over its local components c of
  /// F_ic Q_i(:, c), where F_ic is the generalized force of the component, g_i . Q_i(:, c), plus
  /// that of every component tied to it (times the tie's sign: a tie moves its force to the end
  /// of its chain); a tied component's own entry is 0. So a prescribed point whose neighbours
  /// are tied to it reports the whole force its prescription carries, free components report ~0
  /// at equilibrium, and the sum over all points keeps the sum of g (tied axes are parallel).
  std::vector<Vector3d> constraint_forces(const std::vector<Vector3d>& g) const;
  /// K_free = P^T K_cart P, triplet by triplet (appended to `free`; rows and columns of the
  /// Cartesian numbering, scalars at 3 n + k).
  void reduce(const std::vector<Triplet>& cart, std::vector<Triplet>& free) const;
  /// The same in place: `t` holds P^T K_cart P's triplets after the call. A triplet between two
  /// points without local axes gives at most one (kept in its place); those of rotated points
  /// and scalars, spread over several, come after them (so no second list of the whole size is
  /// kept: the tangent's triplets are most of an assembly's memory).
  void reduce_in_place(std::vector<Triplet>& t) const;

 private:
  struct Prescribed {
    double value = 0.0;
    LoadCurve curve;  ///< empty: fixed (value 0)
  };
  struct Component {
    int prescribed = -1;  ///< own constraint: index into prescribed_, or -1
    int tie_point = -1;   ///< tied to (tie_point, tie_component), or -1
    int tie_component = -1;
    double tie_sign = 1.0;
    // Resolved by renumber() (mutable: renumbered lazily, on first use after a change):
    mutable int free = -1;      ///< free DOF index, or -1
    mutable int resolved = -1;  ///< prescribed index after following ties, or -1
    mutable double sign = 1.0;  ///< d_c = sign * u[free] or sign * prescribed value
    bool master = false;        ///< another component is tied to this one
  };
  struct PointDofs {
    Matrix3d Q = Matrix3d::Identity();
    bool rotated = false;
    std::array<Component, 3> c{};
  };

  void check_point(int point, const char* what) const;
  void check_scalar(int k, const char* what) const;
  /// reduce() of a triplet between two points without local axes: 1 and its image in `out`, or
  /// 0 if a side is constrained (no image); -1 for a rotated point's or a scalar's (several).
  int reduce_plain(const Triplet& tr, Triplet& out) const;
  /// reduce() of one triplet (appended to `free`).
  void reduce_triplet(const Triplet& tr, std::vector<Triplet>& free) const;
  /// reduce() of a triplet whose row or column is a scalar's.
  void reduce_scalar_triplet(const Triplet& tr, std::vector<Triplet>& free) const;
  void check_component(int component) const;
  void constrain(int point, int component, Prescribed p);
  /// Sets the constraint of a component whose index into prescribed_ is `index` (-1: none yet).
  void set_prescribed(int& index, Prescribed p);
  /// Numbers the free unknowns and resolves ties. Constraining and tying only mark the map
  /// stale; the readers call refresh(), so that n constraints cost O(n), not O(n^2).
  void renumber() const;
  void refresh() const {
    if (stale_) renumber();
  }
  /// Column weight of component (point, c) in Cartesian direction a.
  double axis(const PointDofs& P, int a, int c) const {
    return P.rotated ? P.Q(a, c) : (a == c ? 1.0 : 0.0);
  }

  std::string owner_;
  FailFn fail_;
  std::vector<PointDofs> points_;
  std::vector<Component> scalars_;  ///< own constraints only (no ties)
  std::vector<Prescribed> prescribed_;
  mutable int num_free_ = 0;
  mutable bool stale_ = false;
  /// Per Cartesian component 3 i + a of the points: its free DOF where point i has no local
  /// axes (its sign in plain_sign_), -1 where it is constrained, -2 for a rotated point's;
  /// renumber() fills them (reduce_in_place's lookup: no division, no call per triplet).
  mutable std::vector<int> plain_free_;
  mutable std::vector<double> plain_sign_;
};

}  // namespace iga
