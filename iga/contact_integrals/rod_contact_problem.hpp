// A Kirchhoff rod in contact with a rigid surface: RodProblem with a CurveContactPair attached,
// the CTRS contact integral of [KS15] Sects. 4-5 (see ../shared/paper/EQUATIONS.md §3-4 and
// iga/contact_integrals/curve_contact.hpp), with the friction history committed only at
// converged load steps (35)-(36), (66).
//
// Residual and tangent, in the Cartesian DOFs of RodProblem (DOF 3 a + k, g = f_int - f_ext):
//   g_a -= int R_a f ds,   dg_a/dx_b -= int R_a R_b (df/dr) ds      (77), (78a-b)
// f the point force of contact/contact_law.hpp on the rope's centre line.
//
// Notation (symbol -> code): eps_N, eps_T, mu (34)-(36) -> CurveContactParameters::law eps_n,
// eps_t, mu; rope radius R (52) -> CurveContactParameters::radius; N, T, B (68)-(70) ->
// CurveContactPoint::N, T, B.
#pragma once

#include <memory>

#include "contact/rigid_surface.hpp"
#include "iga/contact_integrals/curve_contact_pair.hpp"
#include "iga/contact_integrals/rigid_contact_problem.hpp"
#include "iga/rod/kirchhoff_rod.hpp"

namespace iga {

/// RodProblem whose residual includes the contact of the rod's centre line with one rigid
/// surface. The pair shares ownership of the rigid surface, so the problem may be moved and
/// outlive the caller's handle.
class RodContactProblem : public RigidContactProblem<RodProblem, CurveContactPair> {
 public:
  /// The contact's parameters as CurveContact takes them (std::invalid_argument out of their
  /// ranges); `rigid` must not be null (RodError).
  RodContactProblem(KirchhoffRod rod, std::shared_ptr<const RigidSurface> rigid,
                    const CurveContactParameters& params);
};

}  // namespace iga
