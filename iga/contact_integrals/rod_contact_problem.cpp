// Rod plus CTRS contact ([KS15] Sects. 4-5; eqs. (77)-(78) in
// iga/contact_integrals/curve_contact.cpp).
#include "iga/contact_integrals/rod_contact_problem.hpp"

#include <utility>

namespace iga {

RodContactProblem::RodContactProblem(KirchhoffRod rod, std::shared_ptr<const RigidSurface> rigid,
                                     const CurveContactParameters& params)
    : RigidContactProblem(std::move(rod), [&](const RodProblem& p) {
        if (rigid == nullptr) throw RodError("RodContactProblem: the rigid surface is null");
        return std::make_unique<CurveContactPair>(p.rod().reference(), rigid, params);
      }) {}

}  // namespace iga
