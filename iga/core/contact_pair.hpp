// A contact pair: one deformable body against one rigid surface (CTRS for rods, STAS for
// shells; [KS15]). The body (Body::attach) adds the pair's part to its Cartesian residual and
// tangent at every assembly; the pair keeps its own history (friction (35)-(36), multipliers of
// exact enforcement) and reports counts, a status and output fields.
//
// Notation: x the body's current control points; g the Cartesian residual (3 n, DOF 3 a + c,
// g = f_int - f_ext), K its tangent dg/dx as triplets; t the pseudo-time.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "iga/core/dof_map.hpp"
#include "iga/core/nonlinear_problem.hpp"
#include "iga/core/sampled_mesh.hpp"

namespace iga {

/// Contact point counts of a pair at its last assembly.
struct ContactCounts {
  int active = 0, stick = 0, slip = 0;
  double drag_ratio = 0.0;  ///< rods: friction across / along the rope (CurveContactCounts)
  int slip_back = 0;        ///< rods: slipping points pulling the other way than the most
};

/// A contact point seen from the rigid tool: its foot, the pressure and the traction the body
/// exerts there, its state (1 stick, 2 slip) and its footprint radius (1.5 times its share of
/// the body: length for rods, square root of the area for shells).
struct ContactFoot {
  Vector3d x;
  double pressure = 0.0, state = 0.0, radius = 0.0;
  Vector3d traction;
};

class ContactPair {
 public:
  virtual ~ContactPair() = default;
  /// A copy with the same state (a body's copy gets copies of its pairs).
  virtual std::unique_ptr<ContactPair> clone() const = 0;

  /// g -= contact forces at x, t; K (if not null) gets the triplets of their derivative.
  virtual void add(std::span<const Vector3d> x, double t, VectorXd& g, std::vector<Triplet>* K) = 0;
  /// Commits the history of the last assembly (a converged step).
  virtual void commit() = 0;
  /// Exact enforcement: checks the constraints at the last assembly, updates the multipliers
  /// (NonlinearProblem::augment). Penalty: satisfied.
  virtual AugmentResult augment() = 0;
  /// Multipliers back to the last commit (a step is cut back).
  virtual void restore() = 0;
  /// Round-off in |g| of the contact forces at the last assembly (NonlinearProblem).
  virtual double roundoff() const = 0;
  /// Whether the contribution to the tangent is symmetric (false with friction).
  virtual bool symmetric() const = 0;
  /// "contact 24 (stick 10, slip 14)" (and ", |gap| 3.1e-05" with exact enforcement).
  virtual std::string status() const = 0;
  virtual ContactCounts counts() const = 0;
  /// Coulomb coefficient.
  virtual double mu() const = 0;
  /// Seconds spent in add() so far.
  virtual double time() const = 0;
  /// One phrase for a model's description, e.g. "CTRS contact with a rigid surface of 1
  /// piece(s), 80 contact points".
  virtual std::string describe() const = 0;
  const RigidSurface& rigid() const { return *rigid_; }
  const std::shared_ptr<const RigidSurface>& rigid_ptr() const { return rigid_; }

  // ---- output ----------------------------------------------------------------------------------
  /// Adds the contact fields at the samples of the body's mesh (its params and elements).
  virtual void add_fields(SampledMesh& body) const = 0;
  /// The active contact points with their fields (shape kPoints).
  virtual SampledMesh points() const = 0;
  /// The active contact points seen from the tool.
  virtual std::vector<ContactFoot> feet() const = 0;

 protected:
  explicit ContactPair(std::shared_ptr<const RigidSurface> rigid) : rigid_(std::move(rigid)) {}
  ContactPair(const ContactPair&) = default;
  ContactPair& operator=(const ContactPair&) = default;

 private:
  std::shared_ptr<const RigidSurface> rigid_;  ///< shared: the pair may outlive its maker
};

}  // namespace iga
