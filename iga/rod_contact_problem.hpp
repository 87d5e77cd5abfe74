// A Kirchhoff rod in contact with a rigid surface: RodProblem plus the CTRS contact integral of
// [KS15] Sects. 4-5 (see ../shared/paper/EQUATIONS.md §3-4 and iga/curve_contact.hpp), with the
// friction history committed only at converged load steps (35)-(36), (66).
//
// Residual and tangent, in the Cartesian DOFs of RodProblem (DOF 3 a + k, g = f_int - f_ext):
//   g_a -= int R_a f ds,   dg_a/dx_b -= int R_a R_b (df/dr) ds      (77), (78a-b)
// f the point force of contact/contact_law.hpp on the rope's centre line.
//
// Notation (symbol -> code): eps_N, eps_T, mu, rope radius R (52) -> ContactParameters eps_n,
// eps_t, mu, radius; N, T, B (68)-(70) -> CurveContactPoint::N, T, B.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "iga/curve_contact.hpp"
#include "iga/kirchhoff_rod.hpp"

namespace iga {

/// RodProblem whose residual includes the contact of the rod's centre line with one rigid
/// surface. The problem shares ownership of the rigid surface (the contact integral keeps a
/// pointer to it), so the problem may be moved and outlive the caller's handle.
class RodContactProblem : public RodProblem {
 public:
  /// `points_per_element` contact (Gauss) points per rod element, in 1..16 (else
  /// std::invalid_argument from CurveContact); `rigid` must not be null (RodError).
  RodContactProblem(KirchhoffRod rod, std::shared_ptr<const RigidSurface> rigid,
                    const ContactParameters& params, int points_per_element);

  const CurveContact& contact() const { return contact_; }
  CurveContact& contact() { return contact_; }
  const RigidSurface& rigid() const { return *rigid_; }

  /// Friction (mu > 0 and eps_T > 0) makes the tangent non-symmetric ((38)-(39)).
  bool symmetric() const override;
  /// Commits the contact history (the state of the last assembly, which the solver made at the
  /// converged u, t), then the rod's.
  void commit(const VectorXd& u, double t) override;
  /// "contact 24 (stick 10, slip 14)" for the progress line.
  std::string status() const override;

  /// RodProblem::nodal_residual (the reactions at constrained points of an equilibrium state)
  /// without disturbing the contact state kept for output. nodal_residual itself re-evaluates
  /// the contact: right after commit() the increments are zero, so points that slipped sit on
  /// the slip surface (Phi = 0 up to round-off) and their stick/slip flags become arbitrary.
  std::vector<Vector3d> reactions(const VectorXd& u, double t);

  /// Wall time spent in the contact integral (projections, point law, its assembly) since
  /// construction, seconds; part of the solver's assembly time.
  double contact_time() const { return contact_time_; }

 protected:
  void add_contributions(std::span<const Vector3d> x, double t, VectorXd& g,
                         std::vector<Triplet>* K) override;

 private:
  std::shared_ptr<const RigidSurface> rigid_;
  CurveContact contact_;
  std::vector<Vector3d> x_;  ///< work copy of the control points (CurveContact takes a vector)
  double contact_time_ = 0.0;
};

}  // namespace iga
