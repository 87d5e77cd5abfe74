// A Kirchhoff-Love shell in contact with a rigid surface: ShellProblem plus the STAS contact
// integral of [KS15] Sects. 2-3 (see ../shared/paper/EQUATIONS.md §1, §3, §5 and
// iga/contact_integrals/surface_contact.hpp), with the friction history committed only at converged
// load steps (35)-(36).
//
// Residual and tangent, in the Cartesian DOFs of ShellProblem (DOF 3 a + k, g = f_int - f_ext):
//   g_a -= int (dx_c/dX_a)^T f dA,   K_ab -= int d/dX_b [(dx_c/dX_a)^T f] dA      (33), (37)-(39)
// f the contact force on the contact point x_c of the shell's face
// (iga/contact_integrals/surface_contact.hpp).
//
// Notation (symbol -> code): eps_N, eps_T, mu -> SurfaceContactParameters eps_n, eps_t, mu;
// h -> thickness (taken from the shell's material); the face s = -1, 0, +1 -> ShellFace.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"
#include "iga/contact_integrals/rigid_contact_problem.hpp"
#include "iga/contact_integrals/surface_contact_pair.hpp"
#include "iga/shell/shell_problem.hpp"

namespace iga {

/// ShellProblem whose residual includes the contact of one face of the shell with one rigid
/// surface (commit, status, reactions, contact time: RigidContactProblem). The problem shares
/// ownership of the rigid surface, so it may be moved and outlive the caller's handle.
class ShellContactProblem : public RigidContactProblem<ShellProblem, SurfaceContactPair> {
 public:
  /// `params.thickness` is replaced by the shell's thickness. Throws ShellError if `rigid` is
  /// null, std::invalid_argument (from SurfaceContact) for invalid parameters.
  ShellContactProblem(KirchhoffLoveShell shell, std::shared_ptr<const RigidSurface> rigid,
                      SurfaceContactParameters params);
};

}  // namespace iga
