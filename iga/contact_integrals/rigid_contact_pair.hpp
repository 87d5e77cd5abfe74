// The part common to the contact pairs of a body with one rigid surface (CurveContactPair:
// CTRS, SurfaceContactPair: STAS; [KS15]): the contact integral added to the body's residual and
// tangent (timed), its friction history committed only at converged load steps ((35)-(36)),
// exact enforcement by augmentation, the status line; a moving tool (the integral evaluated in
// the tool's frame, turned forward).
//
// Notation: x the body's control points, g its Cartesian residual (3 n + m with m scalar
// unknowns, g = f_int - f_ext), K the triplets of dg/d(x, s); t the pseudo-time.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "iga/core/contact_pair.hpp"
#include "iga/parallel/communicator.hpp"

namespace iga {

/// Integral: the contact integral (CurveContact, SurfaceContact) with assemble(BodyState, g, K*),
/// commit(), predict(t), augment(), restore(), roundoff(), enforcement(), augmentation() and
/// counts() (active, stick, slip); copyable.
template <class Integral>
class RigidContactPair : public ContactPair {
 public:
  const Integral& contact() const { return contact_; }
  Integral& contact() { return contact_; }

  /// The contact integral in the tool's frame at the pose of t: the control points mapped
  /// back, X_a = c0 + Q^T (x_a - c) (a rigid map: the body's geometry, tangents and normals
  /// move with it), the integral's residual g_a and tangent blocks K_ab turned forward,
  /// Q g_a and Q K_ab Q^T (the map's derivative dX/dx = Q^T is constant at fixed t; the
  /// integral turns the blocks as it emits them, set_turn). The friction history the integral
  /// keeps is thus in the tool's frame and moves with it.
  void add(const BodyState& state, double t, VectorXd& g, std::vector<Triplet>* K) override {
    const auto start = std::chrono::steady_clock::now();
    clear_total();
    pose_ = pose(t);
    const std::span<const Vector3d> x = state.x;
    x_.resize(x.size());  // no reallocation after the first call
    for (std::size_t a = 0; a < x.size(); ++a) x_[a] = pose_.to_tool(x[a]);
    g_.setZero(g.size());
    const bool turn = pose_.turns();
    contact_.set_turn(pose_.Q);  // the tangent's blocks emitted turned forward, Q K_ab Q^T
    contact_.predict(t);         // augmented Lagrange: the step's first multipliers
    // g_a -= int (dx/dX_a)^T f, K_ab -= its derivative
    contact_.assemble(BodyState{x_, state.s, state.frames}, g_, K);
    force_.setZero();
    moment_.setZero();
    for (std::size_t a = 0; a < x.size(); ++a) {
      const auto i = static_cast<Eigen::Index>(3 * a);
      const Vector3d ga = turn ? Vector3d(pose_.Q * g_.segment<3>(i)) : Vector3d(g_.segment<3>(i));
      g.segment<3>(i) += ga;
      force_ += ga;  // g_a = -f_a: the force on the tool
      moment_ += x[a].cross(ga);
    }
    // The scalars' entries (a rod's twists: moments about its centre line) are no forces on
    // the tool and are not turned.
    const auto n3 = static_cast<Eigen::Index>(3 * x.size());
    g.tail(g.size() - n3) += g_.tail(g.size() - n3);
    time_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  /// The integral works in the tool's frame at the pose of t, and exact enforcement predicts
  /// the step's first multipliers from t (predict): g depends on t where the pose differs
  /// between t0 and t1 (bit for bit) or the multipliers are augmented.
  bool depends_on_time(double t0, double t1) const override {
    if (contact_.enforcement().augmented) return true;
    if (!motion()) return false;
    const RigidPose a = pose(t0), b = pose(t1);
    return a.Q != b.Q || a.c != b.c || a.c0 != b.c0;
  }
  void commit() override { contact_.commit(); }
  /// Exact enforcement (augmented Lagrange, ContactEnforcement): the integral checks the
  /// largest |gap| of the points carrying a force in the state of the last assembly (the
  /// solver's converged u) and updates its multipliers (Uzawa); penalty: always satisfied.
  AugmentResult augment() override { return contact_.augment(); }
  /// One part of the pair on each process (a cut body): the augmentation's decisions are taken
  /// over all parts (the largest gap and slip of the whole pair).
  void spread(const Communicator& comm) override {
    contact_.set_parts_maximum([&comm](std::span<double> v) { comm.max(v); });
  }
  void restore() override { contact_.restore(); }
  void archive(StateArchive& a) override { contact_.archive(a); }
  double time() const override { return time_; }
  double mu() const override { return contact_.parameters().law.mu; }

 protected:
  RigidContactPair(std::shared_ptr<const RigidSurface> rigid, Integral contact)
      : ContactPair(std::move(rigid)), contact_(std::move(contact)) {}
  double local_roundoff() const override { return contact_.roundoff(); }
  std::optional<double> checked_gap() const override {
    if (!contact_.enforcement().augmented) return std::nullopt;
    return contact_.augmentation().max_gap;
  }

 private:
  Integral contact_;
  std::vector<Vector3d> x_;  ///< the control points in the tool's frame
  VectorXd g_;               ///< the integral's residual in the tool's frame
  double time_ = 0.0;
};

}  // namespace iga
