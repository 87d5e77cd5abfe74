// A build without PETSc (IGA_WITH_PETSC=OFF): no distributed solver; see
// iga/solvers/distributed_solver.hpp.
#include <stdexcept>

#include "iga/solvers/distributed_solver.hpp"

namespace iga {

struct DistributedLinearSolver::Impl {};

DistributedLinearSolver::DistributedLinearSolver(LinearMethod /*method*/) {
  throw std::runtime_error(
      "DistributedLinearSolver needs PETSc, and this build has none (IGA_WITH_PETSC=OFF)");
}
DistributedLinearSolver::~DistributedLinearSolver() = default;
LinearSolveStatus DistributedLinearSolver::factorize(const Eigen::SparseMatrix<double>&, bool) {
  return LinearSolveStatus::invalid_input;
}
LinearSolveStatus DistributedLinearSolver::factorize(int,
                                                     const std::vector<Eigen::Triplet<double>>&,
                                                     bool) {
  return LinearSolveStatus::invalid_input;
}
LinearSolveStatus DistributedLinearSolver::solve(const Eigen::VectorXd&, Eigen::VectorXd&) {
  return LinearSolveStatus::not_factorized;
}
void DistributedLinearSolver::set_near_null_space(const Eigen::MatrixXd& /*Z*/) {}
void DistributedLinearSolver::set_layout(const DofLayout* /*layout*/) {}
const std::string& DistributedLinearSolver::message() const {
  static const std::string none = "no PETSc";
  return none;
}
int DistributedLinearSolver::negative_pivots() const {
  return -1;
}
bool DistributedLinearSolver::reused_analysis() const {
  return false;
}
std::pair<int, int> DistributedLinearSolver::owned_rows() const {
  return {0, 0};
}

}  // namespace iga
