// Rod plus CTRS contact ([KS15] Sects. 4-5; eqs. (77)-(78) in
// iga/contact_integrals/curve_contact.cpp).
#include "iga/contact_integrals/rod_contact_problem.hpp"

#include <utility>

namespace iga {

RodContactProblem::RodContactProblem(KirchhoffRod rod, std::shared_ptr<const RigidSurface> rigid,
                                     const ContactParameters& params, int points_per_element)
    : RigidContactProblem(
          std::move(rod), std::move(rigid), [&](const RodProblem& p, const RigidSurface* r) {
            if (r == nullptr) throw RodError("RodContactProblem: the rigid surface is null");
            return CurveContact(p.rod().reference(), *r, params, points_per_element);
          }) {}

bool RodContactProblem::symmetric() const {
  const ContactParameters& p = contact().parameters();
  const bool friction = p.mu > 0.0 && p.eps_t > 0.0;
  return !friction && RodProblem::symmetric();
}

}  // namespace iga
