// Shell plus STAS contact ([KS15] Sects. 2-3; eqs. (33), (37)-(39) in iga/surface_contact.cpp).
#include "iga/shell_contact_problem.hpp"

#include <chrono>
#include <utility>

namespace iga {

namespace {
const RigidSurface& checked(const std::shared_ptr<const RigidSurface>& rigid) {
  if (!rigid) throw ShellError("ShellContactProblem: the rigid surface is null");
  return *rigid;
}
SurfaceContactParameters with_thickness(SurfaceContactParameters p, const KirchhoffLoveShell& s) {
  p.thickness = s.material().thickness;
  return p;
}
}  // namespace

ShellContactProblem::ShellContactProblem(KirchhoffLoveShell shell,
                                         std::shared_ptr<const RigidSurface> rigid,
                                         SurfaceContactParameters params)
    : ShellProblem(std::move(shell)),
      rigid_(std::move(rigid)),
      contact_(this->shell().reference(), checked(rigid_), with_thickness(params, this->shell())) {}

bool ShellContactProblem::symmetric() const {
  const SurfaceContactParameters& p = contact_.parameters();
  const bool friction = p.mu > 0.0 && p.eps_t > 0.0;
  const bool slave = p.strategy == SurfaceContactStrategy::kRigidSlave;
  return !friction && !slave && ShellProblem::symmetric();
}

void ShellContactProblem::commit(const VectorXd& u, double t) {
  contact_.commit();
  ShellProblem::commit(u, t);
}

std::string ShellContactProblem::status() const {
  const SurfaceContactCounts c = contact_.counts();
  return "contact " + std::to_string(c.active) + " (stick " + std::to_string(c.stick) + ", slip " +
         std::to_string(c.slip) + ")";
}

std::vector<Vector3d> ShellContactProblem::reactions(const VectorXd& u, double t) {
  SurfaceContact kept = contact_;
  std::vector<Vector3d> r = nodal_residual(u, t);
  contact_ = std::move(kept);
  return r;
}

void ShellContactProblem::add_contributions(std::span<const Vector3d> x, double t, VectorXd& g,
                                            std::vector<Triplet>* K) {
  ShellProblem::add_contributions(x, t, g, K);
  const auto start = std::chrono::steady_clock::now();
  x_.assign(x.begin(), x.end());
  contact_.assemble(x_, g, K);  // g_a -= int (dx_c/dX_a)^T f dA, K_ab -= its derivative
  contact_time_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace iga
