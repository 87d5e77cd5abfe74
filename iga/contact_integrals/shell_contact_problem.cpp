// Shell plus STAS contact ([KS15] Sects. 2-3; eqs. (33), (37)-(39) in
// iga/contact_integrals/surface_contact.cpp).
#include "iga/contact_integrals/shell_contact_problem.hpp"

#include <utility>

namespace iga {

ShellContactProblem::ShellContactProblem(KirchhoffLoveShell shell,
                                         std::shared_ptr<const RigidSurface> rigid,
                                         SurfaceContactParameters params)
    : RigidContactProblem(std::move(shell), [&](const ShellProblem& p) {
        if (rigid == nullptr) throw ShellError("ShellContactProblem: the rigid surface is null");
        params.thickness = p.shell().material().thickness;
        return std::make_unique<SurfaceContactPair>(p.shell().reference(), rigid, params);
      }) {}

}  // namespace iga
