// Common NonlinearProblem part of rotation-free models; see control_point_problem.hpp.
#include "iga/core/control_point_problem.hpp"

namespace iga {

ControlPointProblem::ControlPointProblem(std::vector<Vector3d> X, std::string owner,
                                         DofMap::FailFn fail)
    : dofs_(static_cast<int>(X.size()), std::move(owner), fail), X_(std::move(X)) {}

void ControlPointProblem::add_nodal_load(std::vector<std::pair<int, Vector3d>> forces,
                                         LoadCurve curve) {
  dead_loads_.push_back(NodalLoad{std::move(forces), std::move(curve)});
}

void ControlPointProblem::add_nodal_load(const std::vector<Vector3d>& f, LoadCurve curve) {
  std::vector<std::pair<int, Vector3d>> forces;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f[i].squaredNorm() > 0.0) forces.emplace_back(static_cast<int>(i), f[i]);
  add_nodal_load(std::move(forces), std::move(curve));
}

void ControlPointProblem::current_points(const VectorXd& u, double t,
                                         std::vector<Vector3d>& x) const {
  dofs_.current_points(X_, u, t, x);
}

std::vector<Vector3d> ControlPointProblem::current_points(const VectorXd& u, double t) const {
  std::vector<Vector3d> x;
  current_points(u, t, x);
  return x;
}

VectorXd ControlPointProblem::dead_load(double t) const {
  VectorXd f = VectorXd::Zero(3 * static_cast<Eigen::Index>(X_.size()));
  for (const NodalLoad& L : dead_loads_) {
    const double lam = L.curve(t);
    for (const auto& [i, F] : L.forces) f.segment<3>(3 * i) += lam * F;
  }
  return f;
}

void ControlPointProblem::assemble_cartesian(const VectorXd& u, double t, bool tangent) {
  current_points(u, t, x_);
  cart_triplets_.clear();
  std::vector<Triplet>* K = tangent ? &cart_triplets_ : nullptr;
  assemble_model(x_, t, g_, K);  // g = f_int (- configuration-dependent loads)
  for (const NodalLoad& L : dead_loads_) {
    const double lam = L.curve(t);
    for (const auto& [i, F] : L.forces) g_.segment<3>(3 * i) -= lam * F;  // g -= f_ext
  }
  add_contributions(x_, t, g_, K);
}

void ControlPointProblem::assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) {
  assemble_cartesian(u, t, K != nullptr);
  dofs_.reduce(g_, R);  // R = P^T g
  if (!K) return;
  free_triplets_.clear();
  dofs_.reduce(cart_triplets_, free_triplets_);  // K_free = P^T K_cart P
  K->resize(dofs_.num_free(), dofs_.num_free());
  K->setFromTriplets(free_triplets_.begin(), free_triplets_.end());
}

std::vector<Vector3d> ControlPointProblem::nodal_residual(const VectorXd& u, double t) {
  assemble_cartesian(u, t, false);
  std::vector<Vector3d> r(X_.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = g_.segment<3>(3 * static_cast<Eigen::Index>(i));
  return r;
}

}  // namespace iga
