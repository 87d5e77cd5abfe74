// A deformable body of a model (a Kirchhoff rod, a Kirchhoff-Love shell): it owns its block of
// unknowns and, as a NonlinearProblem over that block, assembles its internal forces and
// tangent with its conditions and loads and the contact pairs attached to it; it reports
// reactions and displacements at parameters, and hands sampled output fields to a writer.
// A model (BodySystem) holds several bodies; the driver (iga/model) sees only this interface.
//
// Notation: u the body's unknowns (its free DOFs), t the pseudo-time; x the current control
// points; (u, v) body parameters (rods: u only); "samples" the points per element (and
// direction) of the output.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "iga/core/contact_pair.hpp"
#include "iga/core/nonlinear_problem.hpp"
#include "iga/core/sampled_mesh.hpp"

namespace iga {

/// This process's share of a body in a run over several processes (BodySystem::distribute).
struct BodyShare {
  /// Whether this process assembles the body: all of it, or the part it built (a shell's block
  /// of elements, with its pairs' contact points in them). A body that another process assembles
  /// whole gives a zero residual and no tangent here.
  bool assembles = true;
  /// Whether this process adds the terms of single control points (dead nodal loads, springs):
  /// one of the processes that assemble the body.
  bool point_terms = true;
};

class Body : public NonlinearProblem {
 public:
  /// This process's share of the body; by default all of it (one process).
  const BodyShare& share() const { return share_; }
  void set_share(const BodyShare& s) { share_ = s; }

  /// A body cut over `processes` (BodySystem::distribute, after set_share): owner[k] the process
  /// that owns each of its unknowns k (the same on every process) and, appended to `reads`, the
  /// unknowns this process's part reads or adds to (DofLayout). From then on this process adds
  /// the terms of single control points (nodal loads, springs) at the points it owns. Default:
  /// the body cannot be cut (std::logic_error).
  virtual void partition(int rank, int processes, std::vector<int>& owner, std::vector<int>& reads);

  /// "rod", "shell": the kind of body, for file names and summaries.
  virtual std::string type() const = 0;
  /// One phrase, e.g. "rod of 8 elements (degree 3, 11 control points)".
  virtual std::string describe() const = 0;
  virtual int num_control_points() const = 0;
  /// Output points per element (and direction) when the user asks for none.
  virtual int default_samples() const = 0;
  /// Displacement of the body point at parameters (pu, pv) (rods: pu) in the state (u, t).
  virtual Vector3d displacement(double pu, double pv, const VectorXd& u, double t) const = 0;
  /// Displacements of the control points (Cartesian, one per point) in the state (u, t).
  virtual std::vector<Vector3d> control_point_displacements(const VectorXd& u, double t) const = 0;
  /// f_int - f_ext + contact per control point, Cartesian, in the state (u, t), without
  /// disturbing the contact state kept for output: the reactions at constrained points.
  virtual std::vector<Vector3d> reactions(const VectorXd& u, double t) = 0;
  /// The body sampled at `samples` points per element (and direction), with its fields and
  /// those of its contact pairs.
  virtual SampledMesh sample(const VectorXd& u, double t, int samples) const = 0;

  /// Adds a contact pair: its part joins the residual, tangent, history and status of the body.
  /// Returns its index.
  virtual int attach(std::unique_ptr<ContactPair> pair) = 0;
  virtual int num_pairs() const = 0;
  virtual const ContactPair& pair(int i) const = 0;
  virtual ContactPair& pair(int i) = 0;

 private:
  BodyShare share_;
};

}  // namespace iga
