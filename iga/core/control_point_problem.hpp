// The common part of bodies whose unknowns are control point displacements (RodProblem,
// ShellProblem, MembraneProblem, TwistingRodProblem; the Body interface), with, for a body that
// has them, scalar unknowns beside the points (a rod's twists): DofMap's local bases, fixed /
// prescribed / tied components and fixed / prescribed scalars, dead nodal loads along load
// curves, the Cartesian residual g = f_int - f_ext (DOF 3 i + c for the points, 3 n + k for
// scalar k) with the contact pairs' part and its reduction to the free unknowns, the pairs'
// history, status and symmetry, reactions.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "iga/core/body.hpp"
#include "iga/core/dof_map.hpp"
#include "iga/core/sparse_assembly.hpp"

namespace iga {

class ControlPointProblem : public Body {
 public:
  ControlPointProblem(const ControlPointProblem& o);
  ControlPointProblem& operator=(const ControlPointProblem& o);
  ControlPointProblem(ControlPointProblem&&) noexcept = default;
  ControlPointProblem& operator=(ControlPointProblem&&) noexcept = default;
  ~ControlPointProblem() override = default;

  int num_control_points() const override { return dofs_.num_points(); }
  /// Scalar unknowns beside the points (0 but for a rod's twists).
  int num_scalars() const { return dofs_.num_scalars(); }

  // ---- constraints (components along the point's local basis) -----------------------------
  /// Sets the local basis of `point` (orthonormal columns); throws the model's error type if
  /// the point already has constrained components or Q is not orthonormal.
  void set_local_basis(int point, const Matrix3d& Q) { dofs_.set_local_basis(point, Q); }
  const Matrix3d& local_basis(int point) const { return dofs_.local_basis(point); }
  void fix(int point) { dofs_.fix(point); }
  void fix(int point, int component) { dofs_.fix(point, component); }
  /// Displacement component = value * curve(t).
  void prescribe(int point, int component, double value, LoadCurve curve = ramp()) {
    dofs_.prescribe(point, component, value, std::move(curve));
  }
  /// All three components of the displacement = d * curve(t) (d in the local basis).
  void prescribe(int point, const Vector3d& d, const LoadCurve& curve = ramp()) {
    for (int c = 0; c < 3; ++c) prescribe(point, c, d[c], curve);
  }
  /// Whether component c of point i is constrained; its free DOF index otherwise (-1 if not).
  bool constrained(int point, int component) const { return dofs_.constrained(point, component); }
  int dof(int point, int component) const { return dofs_.dof(point, component); }
  const DofMap& dof_map() const { return dofs_; }
  /// Reference position X_i of control point i.
  const Vector3d& reference_point(int i) const { return X_.at(static_cast<std::size_t>(i)); }

  // ---- NonlinearProblem ----------------------------------------------------------------------
  int num_dofs() const override { return dofs_.num_free(); }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override;
  /// The model's symmetry (model_symmetric) and every pair's.
  bool symmetric() const final;
  /// dR/dt as NonlinearProblem::load_rate: the change of the dead nodal loads and of the
  /// model's own load terms (add_load_terms) between t and t + h, reduced to the free unknowns;
  /// false where a prescribed value or a pair changes with t, or the model cannot single its
  /// load terms out.
  bool load_rate(const VectorXd& u, double t, double h, VectorXd& R_t) override;
  /// Commits the pairs' history (the state of the last assembly: the converged u, t).
  void commit(const VectorXd& u, double t) override;
  /// Every pair checks its constraints at the last assembly: `failed` if one failed, else
  /// `updated` if one updated its multipliers (messages joined), else `satisfied`.
  AugmentResult augment(const VectorXd& u, double t) override;
  void restore() override;
  /// The pairs' state, each in its section ("pair k").
  void archive(StateArchive& a) override;
  /// The largest of the pairs' round-off.
  double residual_roundoff() const override;
  /// The pairs' status lines, joined by "; ".
  std::string status() const override;
  /// The body's six rigid-body motions at its current control points x_i (translations e_k and
  /// rotations e_k x (x_i - c) about their centroid c) in its free unknowns (DofMap::reduce:
  /// the free components' shares of each motion; scalar unknowns 0).
  Eigen::MatrixXd near_null_space(const VectorXd& u, double t) const override;

  // ---- Body: contact pairs, reactions ----------------------------------------------------------
  int attach(std::unique_ptr<ContactPair> pair) override;
  int num_pairs() const override { return static_cast<int>(pairs_.size()); }
  const ContactPair& pair(int i) const override { return *pairs_.at(static_cast<std::size_t>(i)); }
  ContactPair& pair(int i) override { return *pairs_.at(static_cast<std::size_t>(i)); }
  /// The forces the constraints carry (DofMap::constraint_forces of nodal_residual: a point
  /// with tied neighbours reports theirs too, a tied point 0 along its tied components), with
  /// the pairs' state kept: nodal_residual re-evaluates the contact, and
  /// right after commit() the increments are zero, so points that slipped sit on the slip
  /// surface (Phi = 0 up to round-off) and their stick/slip flags become arbitrary.
  std::vector<Vector3d> reactions(const VectorXd& u, double t) override;
  /// The owners of the free unknowns from those of the points (point_partition): a free
  /// unknown shared by tied points goes to the owner of the first of them.
  void partition(int rank, int processes, std::vector<int>& owner,
                 std::vector<int>& reads) override;
  /// The model's samples (sample_model) with the fields of every pair added.
  SampledMesh sample(const VectorXd& u, double t, int samples) const final;

  // ---- state <-> geometry ----------------------------------------------------------------------
  /// Current control points x_i = X_i + Q_i d_i(u, t).
  std::vector<Vector3d> current_points(const VectorXd& u, double t) const;
  /// x_i - X_i.
  std::vector<Vector3d> control_point_displacements(const VectorXd& u, double t) const override;
  void current_points(const VectorXd& u, double t, std::vector<Vector3d>& x) const;
  /// The scalar unknowns s_k(u, t).
  std::vector<double> current_scalars(const VectorXd& u, double t) const;
  /// The generalized forces the scalars' constraints carry (the entries 3 n + k of the
  /// Cartesian residual; a twist's: the torque about the tangent), ~0 at free scalars of an
  /// equilibrium state; the pairs' state kept, as reactions().
  std::vector<double> scalar_reactions(const VectorXd& u, double t);
  /// f_int - f_ext (+ contributions) per control point, Cartesian: the reactions at the
  /// constrained points of an equilibrium state, ~0 at free components.
  std::vector<Vector3d> nodal_residual(const VectorXd& u, double t);
  /// External work-conjugate force of the dead loads at t (3 n + m, Cartesian), for tests.
  VectorXd dead_load(double t) const;

 protected:
  /// `owner` and `fail` as for DofMap; X the reference control points; `num_scalars` scalar
  /// unknowns beside them.
  ControlPointProblem(std::vector<Vector3d> X, std::string owner, DofMap::FailFn fail,
                      int num_scalars = 0);

  /// The model's part of the Cartesian residual g (3 n + m; on entry g is empty) at the
  /// control points x and scalars s: internal forces (g = f_int, resized), configuration-
  /// dependent loads (g -= f_ext); tangent triplets d g / d(x, s) appended to *K if
  /// K != nullptr. Dead nodal loads are subtracted afterwards by the base.
  virtual void assemble_model(std::span<const Vector3d> x, std::span<const double> s, double t,
                              VectorXd& g, std::vector<Triplet>* K) = 0;
  /// The terms of assemble_model's g that depend on t at fixed x and s (loads along load
  /// curves that follow the configuration, springs whose stiffness follows a curve), added to g
  /// (3 n + m entries) at t; f_int must not depend on t. Returns false where the model cannot
  /// single them out (the default): load_rate then leaves dR/dt to an assembly.
  virtual bool add_load_terms(std::span<const Vector3d> x, std::span<const double> s, double t,
                              VectorXd& g) const {
    (void)x, (void)s, (void)t, (void)g;
    return false;
  }
  /// The body's section frames, handed to its contact pairs with its state (a rod whose
  /// sections turn, BodyState); null by default.
  virtual const SectionFrames* section_frames() const { return nullptr; }
  /// Whether the model's own tangent (without the pairs) is symmetric.
  virtual bool model_symmetric() const { return true; }
  /// The body sampled with its own fields, params and elements set (Body::sample).
  virtual SampledMesh sample_model(const VectorXd& u, double t, int samples) const = 0;
  /// The owner of each control point of a body cut over `processes` and whether this process's
  /// part reads it (Body::partition). Default: the body cannot be cut (std::logic_error).
  virtual void point_partition(int rank, int processes, std::vector<int>& owner,
                               std::vector<char>& reads) const;
  /// Whether this process adds the terms of control point i alone (a nodal load, a spring): the
  /// point's owner in a body cut by partition(), else the process of Body::share's point_terms.
  bool adds_point_terms(int i) const {
    return point_terms_.empty() ? share().point_terms : point_terms_[static_cast<std::size_t>(i)];
  }
  /// A dead load: fixed nodal forces scaled by curve(t). `split`: the forces are this
  /// process's part of the load (integrated over its elements), added by every process;
  /// otherwise the whole load, each point's force added by the process that adds its terms
  /// (adds_point_terms).
  void add_nodal_load(std::vector<std::pair<int, Vector3d>> forces, LoadCurve curve,
                      bool split = false);
  /// Nodal forces f_i from a dense per-point array (zero entries dropped).
  void add_nodal_load(const std::vector<Vector3d>& f, LoadCurve curve, bool split = false);
  const std::vector<Vector3d>& reference_points() const { return X_; }
  /// A rod's end crossing a symmetry plane of normal n at right angles (the reference tangent
  /// x_i1 - x_i0 along n): the end point i0 stays in the plane and its neighbour i1 moves with
  /// it in the plane's directions (RodProblem::symmetry explains it); errors through fail,
  /// prefixed with `who`.
  void end_symmetry(int i0, int i1, const Vector3d& n, const std::string& who, DofMap::FailFn fail);

  DofMap dofs_;

 private:
  struct NodalLoad {
    std::vector<std::pair<int, Vector3d>> forces;
    LoadCurve curve;
    bool split = false;  ///< this process's part of the load (add_nodal_load)
  };
  /// g -= the dead nodal loads at t (this process's share of them).
  void subtract_dead_loads(double t, VectorXd& g) const;
  /// Cartesian residual g and (optionally) Cartesian triplets at x.
  void assemble_cartesian(const VectorXd& u, double t, bool tangent);
  /// The Cartesian residual at (u, t) evaluated with copies of the pairs (their state kept).
  VectorXd residual_keeping_pairs(const VectorXd& u, double t);

  std::vector<Vector3d> X_;
  std::vector<NodalLoad> dead_loads_;
  std::vector<std::unique_ptr<ContactPair>> pairs_;
  // Work storage reused between assemble() calls.
  std::vector<Vector3d> x_;
  std::vector<double> s_;
  VectorXd g_;
  std::vector<Triplet> cart_triplets_;  // the tangent's, reduced in place to the free unknowns
  std::size_t cart_size_ = 0;           // their number at the last assembly (before reduction)
  PatternAssembler assembler_;          // K from them, its pattern kept
  std::vector<char> point_terms_;  // per point: this process adds its terms (partition; empty: all)
};

}  // namespace iga
