// Run by the suite under mpirun (tests/CMakeLists.txt): NonlinearSolver on a problem spread
// over the ranks (NonlinearProblem::distributed): a chain of n hardening springs, node 0 held,
// a force F t at the last node; spring e between nodes e and e + 1 has the force
// k d + c d^3 (d its stretch), the springs in contiguous blocks per rank. Each rank assembles
// its springs: the residual is summed over the ranks, the tangent stays in parts that MUMPS sums
// (LinearSolver::set_distributed). Every spring carries F, so every stretch solves
// k d + c d^3 = F and u_i = i d: the end state must match that closed form and the same chain
// solved whole on one process with SuiteSparse, under load control and arc length. Exit 0 on
// every rank when all hold.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "iga/core/nonlinear_problem.hpp"
#include "iga/parallel/communicator.hpp"
#include "iga/solvers/nonlinear_solver.hpp"

namespace {

class SpringChain final : public iga::NonlinearProblem {
 public:
  /// `spread`: this rank assembles its block of springs (else all of them, alone).
  SpringChain(int n, bool spread) : n_(n), spread_(spread) {}
  int num_dofs() const override { return n_; }
  bool distributed() const override { return spread_ && iga::world().size() > 1; }
  void assemble(const iga::VectorXd& u, double t, iga::VectorXd& R, iga::SparseMatrix* K) override {
    const iga::Communicator& w = iga::world();
    const int p = distributed() ? w.size() : 1, r = distributed() ? w.rank() : 0;
    R.setZero(n_);
    std::vector<Eigen::Triplet<double>> trip;
    // Spring e joins node e and e + 1 (node 0 held; unknown i - 1 is node i).
    for (int e = r * n_ / p; e < (r + 1) * n_ / p; ++e) {
      const double ua = e == 0 ? 0.0 : u[e - 1], ub = u[e], d = ub - ua;
      const double f = kK * d + kC * d * d * d, s = kK + 3.0 * kC * d * d;
      if (e > 0) R[e - 1] -= f;
      R[e] += f;
      if (e > 0) {
        trip.emplace_back(e - 1, e - 1, s);
        trip.emplace_back(e - 1, e, -s);
        trip.emplace_back(e, e - 1, -s);
      }
      trip.emplace_back(e, e, s);
    }
    if (r == p - 1) R[n_ - 1] -= kF * t;  // the load, once
    if (distributed()) w.sum(std::span<double>(R.data(), static_cast<std::size_t>(R.size())));
    if (K) {
      K->resize(n_, n_);
      K->setFromTriplets(trip.begin(), trip.end());
    }
  }
  static constexpr double kK = 2.0, kC = 5.0, kF = 3.0;

 private:
  int n_;
  bool spread_;
};

}  // namespace

int main(int argc, char** argv) {
  const iga::ParallelSession session(argc, argv);
  const iga::Communicator& w = iga::world();
  int errors = 0;
  const auto expect = [&](bool ok, const std::string& what) {
    if (!ok) {
      std::fprintf(stderr, "[rank %d] %s\n", w.rank(), what.c_str());
      ++errors;
    }
  };
  const auto relative = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3e", x);
    return std::string(buf);
  };
  // The stretch of every spring: k d + c d^3 = F (Newton on the scalar equation).
  double d = 0.5;
  for (int k = 0; k < 50; ++k)
    d -= (SpringChain::kK * d + SpringChain::kC * d * d * d - SpringChain::kF) /
         (SpringChain::kK + 3.0 * SpringChain::kC * d * d);
  const int n = 57;
  for (const iga::PathControl control : {iga::PathControl::load, iga::PathControl::arc_length}) {
    const std::string name = control == iga::PathControl::load ? "load control" : "arc length";
    iga::NonlinearSolverSettings s;
    s.control = control;
    // Each step's Newton iteration is taken to round-off: with the default residual tolerance
    // (1e-8 of |R_0|) a spread run and the run alone may stop one iteration apart (their sums
    // round differently; under the round-off probe their corrections are perturbed by 1e-10)
    // and then differ by up to ~1e-8 of the state: CI's probe run failed so, 1e-10 asked. One
    // more quadratic iteration from there reaches round-off.
    s.tol_residual_rel = 1e-12;
    s.tol_residual_scaled = 1e-12;
    s.initial_step = 0.25;
    s.linear_method = iga::LinearMethod::mumps;
    SpringChain spread(n, true);
    iga::NonlinearSolver solver(s);
    iga::VectorXd u = iga::VectorXd::Zero(n);
    const iga::NonlinearSolverResult r = solver.solve(spread, u);
    expect(r.converged(), name + ": " + r.message);
    s.linear_method = iga::LinearMethod::suitesparse;
    SpringChain whole(n, false);
    iga::NonlinearSolver alone(s);
    iga::VectorXd v = iga::VectorXd::Zero(n);
    expect(alone.solve(whole, v).converged(), name + ": the chain alone");
    expect((u - v).norm() <= 1e-10 * v.norm(),
           name + ": differs from the chain alone by " + relative((u - v).norm() / v.norm()));
    double worst = 0.0;
    for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(u[i] - (i + 1) * d));
    expect(worst <= 1e-9 * n * d, name + ": differs from the closed form by " + relative(worst));
    expect(solver.linear_solver().distributed() == (w.size() > 1), name + ": distributed solves");
  }
  const long long failed = w.sum(static_cast<long long>(errors));
  if (w.root()) std::printf("mpi_newton: %d ranks, %lld failures\n", w.size(), failed);
  return failed == 0 ? 0 : 1;
}
