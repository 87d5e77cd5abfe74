// The interface between discretized models (rods, shells, contact) and the nonlinear solver.
// A problem assembles, for a state u of the unknowns (control point displacements, free DOFs
// only) at a pseudo-time t, the residual R(u, t) = f_int(u) - f_ext(t) (+ contact) and its
// consistent tangent K = dR/du. History (friction, [KS15] eqs. 35-36, 66) is committed only at
// converged steps.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "iga/parallel/dof_layout.hpp"

namespace iga {

class StateArchive;  // iga/core/state_archive.hpp

using Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double>;  // column major

/// What NonlinearProblem::augment found at a converged state (exact enforcement of
/// constraints by an augmented Lagrangian, e.g. contact; see NonlinearProblem::augment).
enum class AugmentStatus {
  satisfied,  ///< the constraints hold within their tolerance: commit the step
  updated,    ///< the multipliers were updated: solve the same step again
  failed,     ///< not satisfied after the allowed number of updates: the step fails
  /// a contact point went through the rigid surface in the step (a thin tool crossed): the
  /// step fails whatever the enforcement (penalty or exact)
  passed_through,
};
struct AugmentResult {
  AugmentStatus status = AugmentStatus::satisfied;
  std::string message;  ///< what was found (e.g. the largest penetration against the tolerance)
};
/// How bad an augmentation result is: passed_through 3 > failed 2 > updated 1 > satisfied 0.
inline int augment_severity(AugmentStatus s) {
  switch (s) {
    case AugmentStatus::passed_through:
      return 3;
    case AugmentStatus::failed:
      return 2;
    case AugmentStatus::updated:
      return 1;
    case AugmentStatus::satisfied:
      break;
  }
  return 0;
}
/// Joins the result of one part (a contact pair, a body) into that of the whole: the worst
/// status (augment_severity) with the messages of the parts that have it.
inline void merge_augment(AugmentResult& whole, const AugmentResult& part) {
  if (augment_severity(part.status) > augment_severity(whole.status)) {
    whole = part;
  } else if (augment_severity(part.status) == augment_severity(whole.status) &&
             !part.message.empty()) {
    whole.message += (whole.message.empty() ? "" : "; ") + part.message;
  }
}

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;

  /// Number of unknowns.
  virtual int num_dofs() const = 0;
  /// Residual and (if K != nullptr) tangent at state u and pseudo-time t. Prescribed values
  /// (displacements along load curves) are part of the problem, not of u.
  virtual void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) = 0;
  /// Whether the tangent is symmetric (e.g. false with friction): picks CHOLMOD or UMFPACK.
  virtual bool symmetric() const { return true; }
  /// Whether the problem is spread over the ranks of the run (iga/parallel): then K holds only
  /// this rank's part, which the linear solver sums over the ranks (LinearSolver::set_distributed),
  /// and R is complete as layout() says: where the problem has a layout, only at the unknowns
  /// this rank owns, and u is current only at its own unknowns and its ghosts within a step (the
  /// solvers take norms and dot products through dot() and make u current everywhere at a
  /// converged step through synchronize()); without one, R is the whole residual on every rank.
  /// Default false: K is the whole tangent.
  virtual bool distributed() const { return false; }
  /// The ownership of the unknowns of a problem spread over the ranks (DofLayout), or null: R
  /// and u the same on every rank (one process, or replicated).
  virtual const DofLayout* layout() const { return nullptr; }
  /// a . b over the unknowns (over the owners where the problem has a layout; collective then).
  double dot(const VectorXd& a, const VectorXd& b) const {
    const DofLayout* l = layout();
    return l != nullptr ? l->dot(a, b) : a.dot(b);
  }
  /// |a| (collective where the problem has a layout).
  double norm(const VectorXd& a) const {
    const DofLayout* l = layout();
    return l != nullptr ? std::sqrt(l->dot(a, a)) : a.norm();
  }
  /// Makes every entry of u its owner's value (collective where the problem has a layout; else
  /// nothing): after a converged step, before anything reads u at any point.
  void synchronize(VectorXd& u) const {
    if (const DofLayout* l = layout()) l->gather(u);
  }
  /// dR/dt at (u, t) as the one-sided difference R_t = (R(u, t + h) - R(u, t)) / h (h may be
  /// negative), where the problem can give it without assembling: where t enters R only
  /// through loads along load curves, R_t is their change alone and the internal forces, whose
  /// assembly is most of the cost, cancel. Returns false where it cannot (a prescribed motion
  /// or a moving tool that changes between t and t + h, multipliers predicted along t): the
  /// solver then assembles R(u, t + h) (arc length's dR/dt). It changes no state the solver
  /// sees: the last assembly stays the last. Default: false.
  virtual bool load_rate(const VectorXd& u, double t, double h, VectorXd& R_t) {
    (void)u, (void)t, (void)h, (void)R_t;
    return false;
  }
  /// Called after a converged step at time t with state u: commit history variables.
  virtual void commit(const VectorXd& u, double t) { (void)u, (void)t; }
  /// Called when Newton has converged at time t with state u (the state of the last assembly),
  /// before commit: a problem with multipliers (augmented Lagrangian) checks its constraints
  /// and, if they are violated, updates its multipliers (Uzawa) and returns `updated`; the
  /// solver then solves the same step again from u. Default: no multipliers, `satisfied`.
  virtual AugmentResult augment(const VectorXd& u, double t) {
    (void)u, (void)t;
    return {};
  }
  /// Called when an attempted step is undone (cutback): multipliers go back to their values at
  /// the last commit.
  virtual void restore() {}
  /// The state a restart needs besides u and t (history, multipliers, contact points' last
  /// feet), written to a writer archive after a converged step (after commit) and read from a
  /// reader archive before a resumed run: the same routine for both directions
  /// (iga/core/state_archive.hpp). Default: no such state.
  virtual void archive(StateArchive& a) { (void)a; }
  /// The round-off in |R| at the last assembly, where forces are large stiffnesses times small
  /// differences of coordinates (contact: eps_N xi3 with xi3 = (r - rho).n - R): Newton cannot
  /// go below it, so the solver accepts |R| at or below it. Default 0.
  virtual double residual_roundoff() const { return 0.0; }
  /// The near null space of the tangent at (u, t) for an algebraic multigrid preconditioner
  /// (the Krylov path's, LinearSolver::set_near_null_space): one entry per unknown, in columns
  /// that span the motions without strain, such as a body's rigid-body motions. Default: none
  /// (no columns).
  virtual Eigen::MatrixXd near_null_space(const VectorXd& u, double t) const {
    (void)u, (void)t;
    return {};
  }
  /// A short status for the progress line (e.g. "contact 24 (stick 10, slip 14)").
  virtual std::string status() const { return {}; }
};

}  // namespace iga
