// Shell plus STAS contact ([KS15] Sects. 2-3; eqs. (33), (37)-(39) in
// iga/contact_integrals/surface_contact.cpp).
#include "iga/contact_integrals/shell_contact_problem.hpp"

#include <utility>

namespace iga {

ShellContactProblem::ShellContactProblem(KirchhoffLoveShell shell,
                                         std::shared_ptr<const RigidSurface> rigid,
                                         SurfaceContactParameters params)
    : RigidContactProblem(std::move(shell), std::move(rigid),
                          [&](const ShellProblem& p, const RigidSurface* r) {
                            if (r == nullptr)
                              throw ShellError("ShellContactProblem: the rigid surface is null");
                            params.thickness = p.shell().material().thickness;
                            return SurfaceContact(p.shell().reference(), *r, params);
                          }) {}

bool ShellContactProblem::symmetric() const {
  const SurfaceContactParameters& p = contact().parameters();
  const bool friction = p.mu > 0.0 && p.eps_t > 0.0;
  const bool slave = p.strategy == SurfaceContactStrategy::kRigidSlave;
  return !friction && !slave && ShellProblem::symmetric();
}

}  // namespace iga
