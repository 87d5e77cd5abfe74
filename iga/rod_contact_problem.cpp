// Rod plus CTRS contact ([KS15] Sects. 4-5; eqs. (77)-(78) in iga/curve_contact.cpp).
#include "iga/rod_contact_problem.hpp"

#include <chrono>

#include <utility>

namespace iga {

namespace {
const RigidSurface& checked(const std::shared_ptr<const RigidSurface>& rigid) {
  if (!rigid) throw RodError("RodContactProblem: the rigid surface is null");
  return *rigid;
}
}  // namespace

RodContactProblem::RodContactProblem(KirchhoffRod rod, std::shared_ptr<const RigidSurface> rigid,
                                     const ContactParameters& params, int points_per_element)
    : RodProblem(std::move(rod)),
      rigid_(std::move(rigid)),
      contact_(this->rod().reference(), checked(rigid_), params, points_per_element) {}

bool RodContactProblem::symmetric() const {
  const ContactParameters& p = contact_.parameters();
  const bool friction = p.mu > 0.0 && p.eps_t > 0.0;
  return !friction && RodProblem::symmetric();
}

void RodContactProblem::commit(const VectorXd& u, double t) {
  contact_.commit();
  RodProblem::commit(u, t);
}

std::string RodContactProblem::status() const {
  const CurveContactCounts c = contact_.counts();
  return "contact " + std::to_string(c.active) + " (stick " + std::to_string(c.stick) + ", slip " +
         std::to_string(c.slip) + ")";
}

std::vector<Vector3d> RodContactProblem::reactions(const VectorXd& u, double t) {
  CurveContact kept = contact_;  // ~100 bytes per contact point
  std::vector<Vector3d> r = nodal_residual(u, t);
  contact_ = std::move(kept);
  return r;
}

void RodContactProblem::add_contributions(std::span<const Vector3d> x, double t, VectorXd& g,
                                          std::vector<Triplet>* K) {
  RodProblem::add_contributions(x, t, g, K);
  const auto start = std::chrono::steady_clock::now();
  x_.assign(x.begin(), x.end());  // no reallocation after the first call
  contact_.assemble(x_, g, K);    // g_a -= int R_a f ds, K_ab -= int R_a R_b df/dr ds
  contact_time_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace iga
