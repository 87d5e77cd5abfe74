// The part common to a structural problem in contact with one rigid surface (RodContactProblem:
// CTRS, ShellContactProblem: STAS; [KS15]): shared ownership of the rigid surface, the contact
// integral added to the residual and tangent of the base problem (timed), its friction history
// committed only at converged load steps ((35)-(36)), the status line, and reactions that leave
// the contact state kept for output alone.
#pragma once

#include <chrono>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "iga/core/dof_map.hpp"
#include "iga/core/nonlinear_problem.hpp"

namespace iga {

/// Base: a ControlPointProblem (RodProblem, ShellProblem) constructible from its body model.
/// Integral: the contact integral (CurveContact, SurfaceContact) with assemble(x, g, K*),
/// commit(), predict(t), augment(), restore() and counts() (active, stick, slip); copyable.
template <class Base, class Integral>
class RigidContactProblem : public Base {
 public:
  const Integral& contact() const { return contact_; }
  Integral& contact() { return contact_; }
  const RigidSurface& rigid() const { return *rigid_; }

  /// Commits the contact history (the state of the last assembly, which the solver made at the
  /// converged u, t), then the base problem's.
  void commit(const VectorXd& u, double t) override {
    contact_.commit();
    Base::commit(u, t);
  }
  /// Exact enforcement (augmented Lagrange, ContactEnforcement): the integral checks the
  /// largest |gap| of the points carrying a force in the state of the last assembly (the
  /// solver's converged u) and updates its multipliers (Uzawa); penalty: always satisfied.
  AugmentResult augment(const VectorXd& u, double t) override {
    (void)u, (void)t;
    return contact_.augment();
  }
  /// The multipliers of the last commit (a step is cut back).
  void restore() override { contact_.restore(); }
  /// The contact forces' round-off (the integral's roundoff()).
  double residual_roundoff() const override { return contact_.roundoff(); }
  /// "contact 24 (stick 10, slip 14)" for the progress line.
  /// Augmented Lagrange: "contact 24 (stick 10, slip 14), |gap| 3.1e-05", the largest |gap| of
  /// a point carrying a force at the last check.
  std::string status() const override {
    const auto c = contact_.counts();
    std::string s = "contact " + std::to_string(c.active) + " (stick " + std::to_string(c.stick) +
                    ", slip " + std::to_string(c.slip) + ")";
    if (contact_.enforcement().augmented) {
      char buf[32];
      std::snprintf(buf, sizeof buf, ", |gap| %.1e", contact_.augmentation().max_gap);
      s += buf;
    }
    return s;
  }
  /// nodal_residual (the reactions at constrained points of an equilibrium state) without
  /// disturbing the contact state kept for output: nodal_residual re-evaluates the contact, and
  /// right after commit() the increments are zero, so points that slipped sit on the slip
  /// surface (Phi = 0 up to round-off) and their stick/slip flags become arbitrary.
  std::vector<Vector3d> reactions(const VectorXd& u, double t) {
    Integral kept = contact_;
    std::vector<Vector3d> r = this->nodal_residual(u, t);
    contact_ = std::move(kept);
    return r;
  }
  /// Wall time spent in the contact integral (projections, point law, its assembly) since
  /// construction, seconds; part of the solver's assembly time.
  double contact_time() const { return contact_time_; }

 protected:
  /// make(base, rigid) builds the contact integral once the base problem exists; `rigid` may be
  /// null (make reports that with the derived problem's error type).
  template <class Body, class Make>
  RigidContactProblem(Body body, std::shared_ptr<const RigidSurface> rigid, Make make)
      : Base(std::move(body)),
        rigid_(std::move(rigid)),
        contact_(make(static_cast<const Base&>(*this), rigid_.get())) {}

  void add_contributions(std::span<const Vector3d> x, double t, VectorXd& g,
                         std::vector<Triplet>* K) override {
    Base::add_contributions(x, t, g, K);
    const auto start = std::chrono::steady_clock::now();
    x_.assign(x.begin(), x.end());  // no reallocation after the first call
    contact_.predict(t);            // augmented Lagrange: the step's first multipliers
    contact_.assemble(x_, g, K);    // g_a -= int (dx/dX_a)^T f, K_ab -= its derivative
    contact_time_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

 private:
  std::shared_ptr<const RigidSurface> rigid_;
  Integral contact_;
  std::vector<Vector3d> x_;  ///< work copy of the control points (the integrals take a vector)
  double contact_time_ = 0.0;
};

}  // namespace iga
