// A Kirchhoff-Love shell in contact with a rigid surface: ShellProblem plus the STAS contact
// integral of [KS15] Sects. 2-3 (see ../shared/paper/EQUATIONS.md §1, §3, §5 and
// iga/surface_contact.hpp), with the friction history committed only at converged load steps
// (35)-(36).
//
// Residual and tangent, in the Cartesian DOFs of ShellProblem (DOF 3 a + k, g = f_int - f_ext):
//   g_a -= int (dx_c/dX_a)^T f dA,   K_ab -= int d/dX_b [(dx_c/dX_a)^T f] dA      (33), (37)-(39)
// f the contact force on the contact point x_c of the shell's face (iga/surface_contact.hpp).
//
// Notation (symbol -> code): eps_N, eps_T, mu -> SurfaceContactParameters eps_n, eps_t, mu;
// h -> thickness (taken from the shell's material); the face s = -1, 0, +1 -> ShellFace.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "iga/shell_problem.hpp"
#include "iga/surface_contact.hpp"

namespace iga {

/// ShellProblem whose residual includes the contact of one face of the shell with one rigid
/// surface. The problem shares ownership of the rigid surface (the contact integral keeps a
/// pointer to it), so the problem may be moved and outlive the caller's handle.
class ShellContactProblem : public ShellProblem {
 public:
  /// `params.thickness` is replaced by the shell's thickness. Throws ShellError if `rigid` is
  /// null, std::invalid_argument (from SurfaceContact) for invalid parameters.
  ShellContactProblem(KirchhoffLoveShell shell, std::shared_ptr<const RigidSurface> rigid,
                      SurfaceContactParameters params);

  const SurfaceContact& contact() const { return contact_; }
  SurfaceContact& contact() { return contact_; }
  const RigidSurface& rigid() const { return *rigid_; }

  /// Friction (mu > 0 and eps_T > 0) makes the tangent non-symmetric ((38)-(39)); so does the
  /// slave strategy (the ray direction depends on the shell's control points, (5)).
  bool symmetric() const override;
  /// Commits the contact history (the state of the last assembly, made at the converged u, t).
  void commit(const VectorXd& u, double t) override;
  /// "contact 240 (stick 100, slip 140)" for the progress line.
  std::string status() const override;

  /// The reactions (nodal_residual) of an equilibrium state, without disturbing the contact
  /// state kept for output (see RodContactProblem::reactions).
  std::vector<Vector3d> reactions(const VectorXd& u, double t);

  /// Wall time spent in the contact integral since construction, seconds; part of the solver's
  /// assembly time.
  double contact_time() const { return contact_time_; }

 protected:
  void add_contributions(std::span<const Vector3d> x, double t, VectorXd& g,
                         std::vector<Triplet>* K) override;

 private:
  std::shared_ptr<const RigidSurface> rigid_;
  SurfaceContact contact_;
  std::vector<Vector3d> x_;  ///< work copy of the control points (SurfaceContact takes a vector)
  double contact_time_ = 0.0;
};

}  // namespace iga
