// A contact pair: one deformable body against one rigid surface (CTRS for rods, STAS for
// shells; [KS15]). The body (Body::attach) adds the pair's part to its Cartesian residual and
// tangent at every assembly; the pair keeps its own history (friction (35)-(36), multipliers of
// exact enforcement) and reports counts, a status and output fields.
//
// A tool may move as a rigid body (RigidMotion, contact/rigid_motion.hpp): the pair then
// works in the tool's own frame and turns its results forward (RigidContactPair::add); the
// output (points, feet, fields) is in the world frame at the pose of the last assembly.
//
// Notation: x the body's current control points, s its scalar unknowns (a rod's twists; none
// for most bodies); g the Cartesian residual (3 n + m: DOF 3 a + c for the points, 3 n + k for
// scalar k; g = f_int - f_ext), K its tangent dg/d(x, s) as triplets; t the pseudo-time;
// x = c + Q (X - c0) the tool's pose (RigidPose).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contact/rigid_motion.hpp"
#include "contact/rigid_surface.hpp"
#include "iga/core/dof_map.hpp"
#include "iga/core/nonlinear_problem.hpp"
#include "iga/core/sampled_mesh.hpp"
#include "iga/core/section_frames.hpp"

namespace iga {

/// What a body hands its contact pairs at an assembly: its current control points, its scalar
/// unknowns (their residual entries follow the points') and, for a rod whose sections turn,
/// its section frames (null otherwise). Views: valid during the call only.
struct BodyState {
  std::span<const Vector3d> x;
  std::span<const double> s;
  const SectionFrames* frames = nullptr;
};

/// Contact point counts of a pair at its last assembly.
struct ContactCounts {
  int active = 0, stick = 0, slip = 0;
};

/// What one part of a pair reports of its last assembly. A body spread over several processes
/// (BodySystem::distribute) has a part of each of its pairs on each process: the parts' tallies
/// are combined (ContactPair::combine) into the pair's whole (ContactPair::set_total). Counts,
/// the force on the tool, its moment about the origin and the round-off add up; the largest
/// |gap| of exact enforcement is the largest of the parts'; the pair slides steadily when
/// every part with contact does.
struct ContactTally {
  ContactCounts counts;
  Vector3d force = Vector3d::Zero(), moment = Vector3d::Zero();
  double roundoff = 0.0;
  double max_gap = 0.0;  ///< exact enforcement: the largest |gap| at the last check
  bool steady = true;    ///< the part slides steadily, or has no contact
};

/// A contact point seen from the rigid tool: its foot, the pressure and the traction the body
/// exerts there, its state (1 stick, 2 slip) and its footprint radius (1.5 times its share of
/// the body: length for rods, square root of the area for shells).
struct ContactFoot {
  Vector3d x;
  double pressure = 0.0, state = 0.0, radius = 0.0;
  Vector3d traction;
};

class Communicator;  // iga/parallel/communicator.hpp

class ContactPair {
 public:
  virtual ~ContactPair() = default;
  /// A copy with the same state (a body's copy gets copies of its pairs).
  virtual std::unique_ptr<ContactPair> clone() const = 0;

  /// g -= contact forces in the body's state at t; K (if not null) gets the triplets of their
  /// derivative.
  virtual void add(const BodyState& state, double t, VectorXd& g, std::vector<Triplet>* K) = 0;
  /// Whether add() at the same body state may give another g at t1 than at t0 (a tool whose
  /// pose differs, multipliers predicted along t): NonlinearProblem::load_rate then needs the
  /// assembly. By default true: a pair that does not say otherwise is assembled.
  virtual bool depends_on_time(double t0, double t1) const {
    (void)t0, (void)t1;
    return true;
  }
  /// Commits the history of the last assembly (a converged step).
  virtual void commit() = 0;
  /// Exact enforcement: checks the constraints at the last assembly, updates the multipliers
  /// (NonlinearProblem::augment). Penalty: satisfied.
  virtual AugmentResult augment() = 0;
  /// Multipliers back to the last commit (a step is cut back).
  virtual void restore() = 0;
  /// The pair's history and contact points' state for a restart (NonlinearProblem::archive).
  virtual void archive(StateArchive& a) = 0;
  /// Round-off in |g| of the contact forces at the last assembly (NonlinearProblem).
  double roundoff() const { return total_ ? total_->roundoff : local_roundoff(); }
  /// Whether the contribution to the tangent is symmetric (false with friction).
  virtual bool symmetric() const = 0;
  /// "contact 24 (stick 10, slip 14)" (and ", |gap| 3.1e-05" with exact enforcement, the
  /// largest |gap| of a point carrying a force at the last check).
  std::string status() const;
  ContactCounts counts() const { return total_ ? total_->counts : local_counts(); }
  /// Whether the pair's contact slides steadily at the last assembly: the rule of a sliding
  /// plateau, which a model selects as its stop criterion ("solver": "stop_at_full_slip_after").
  /// By default every active point slips (always, without friction); a pair refines it to its
  /// own kind of contact (a rod's: CurveContactPair, steady_sliding in curve_contact.hpp).
  bool sliding_steadily() const;

  // ---- a pair spread over several processes --------------------------------------------------
  /// This process's part of the last assembly.
  ContactTally local_tally() const;
  /// The whole pair's figures (the parts' tallies combined): counts(), roundoff(), status(),
  /// sliding_steadily(), tool_force() and tool_moment() report them until the next add().
  void set_total(const ContactTally& total) { total_ = total; }
  /// The whole pair's largest |gap| at the last check of exact enforcement (after the
  /// assembly's tallies were combined), for status().
  void set_total_gap(double gap) {
    if (total_) total_->max_gap = gap;
  }
  /// This pair is one part of a pair spread over the processes of `comm` (its body is cut
  /// into blocks, BodySystem::distribute; comm outlives the pair): what it decides from the
  /// whole pair (exact enforcement's updates) it decides over all parts, each process calling
  /// the same collective operations. By default nothing is decided so.
  virtual void spread(const Communicator& comm) { (void)comm; }
  /// The tallies of parts combined into the whole's.
  static ContactTally combine(const ContactTally& a, const ContactTally& b);
  /// Coulomb coefficient.
  virtual double mu() const = 0;
  /// Seconds spent in add() so far.
  virtual double time() const = 0;
  /// One phrase for a model's description, e.g. "CTRS contact with a rigid surface of 1
  /// piece(s), 80 contact points".
  virtual std::string describe() const = 0;
  /// The rigid surface in its own frame (as given in the model).
  const RigidSurface& rigid() const { return *rigid_; }
  const std::shared_ptr<const RigidSurface>& rigid_ptr() const { return rigid_; }

  // ---- a moving tool ---------------------------------------------------------------------------
  /// The tool's prescribed motion (null: it stands still); shared by the pairs of one tool.
  void set_motion(std::shared_ptr<const RigidMotion> motion) { motion_ = std::move(motion); }
  const RigidMotion* motion() const { return motion_.get(); }
  /// The tool's pose at t (the identity without motion).
  RigidPose pose(double t) const { return motion_ ? motion_->pose(t) : RigidPose{}; }
  /// The pose of the last assembly.
  const RigidPose& pose() const { return pose_; }
  /// The force the body exerts on the tool at the last assembly (world frame; minus the
  /// contact forces on the body), and its moment about the point p.
  const Vector3d& tool_force() const { return total_ ? total_->force : force_; }
  Vector3d tool_moment(const Vector3d& p) const {
    return total_ ? Vector3d(total_->moment - p.cross(total_->force))
                  : Vector3d(moment_ - p.cross(force_));
  }

  // ---- output (world frame, the pose of the last assembly) -------------------------------------
  /// Adds the contact fields at the samples of the body's mesh (its params and elements).
  void add_fields(SampledMesh& body) const;
  /// The active contact points with their fields (shape kPoints).
  SampledMesh points() const;
  /// The active contact points seen from the tool.
  std::vector<ContactFoot> feet() const;

 protected:
  explicit ContactPair(std::shared_ptr<const RigidSurface> rigid) : rigid_(std::move(rigid)) {}
  ContactPair(const ContactPair&) = default;
  ContactPair& operator=(const ContactPair&) = default;

  /// This process's part of the figures above (counts(), roundoff(), sliding_steadily()).
  virtual ContactCounts local_counts() const = 0;
  virtual double local_roundoff() const = 0;
  virtual bool local_sliding_steadily() const;
  /// Exact enforcement: the largest |gap| of a point carrying a force at the last check;
  /// penalty: none.
  virtual std::optional<double> checked_gap() const = 0;
  /// An assembly starts: the whole's figures of the last one are void.
  void clear_total() { total_.reset(); }

  /// The output above in the tool's frame, as the contact integral holds it.
  virtual void add_tool_fields(SampledMesh& body) const = 0;
  virtual SampledMesh tool_points() const = 0;
  virtual std::vector<ContactFoot> tool_feet() const = 0;

  /// Set by add(): the pose, and the force on the tool and its moment about the origin.
  RigidPose pose_;
  Vector3d force_ = Vector3d::Zero(), moment_ = Vector3d::Zero();

 private:
  std::shared_ptr<const RigidSurface> rigid_;  ///< shared: the pair may outlive its maker
  std::shared_ptr<const RigidMotion> motion_;
  std::optional<ContactTally> total_;  ///< set_total's, until the next add()
};

}  // namespace iga
