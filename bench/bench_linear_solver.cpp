// Benchmarks of the sparse direct solves of a shell tangent (issue 17 item 5): the n x n
// biquadratic plate of the saddle (KirchhoffLoveShell, 3 (n + 2)^2 unknowns) at its reference
// state (positive semidefinite: the rigid motions are free), with eps I added to its diagonal (eps
// = 1e-3 of the mean diagonal: the part the corner springs and the contact penalty add to the
// saddle's tangent, which makes it positive definite; only the pattern and the fill decide the
// cost). Each factorization of the same pattern, the symbolic analysis (the AMD ordering) done once
// before the loop as the solver does while the pattern is unchanged:
//   BM_Factorize/<method>/<n> (n = 20, 40, 80, 160): 0 CHOLMOD supernodal LL^T (dense blocks
//     through the BLAS), 1 CHOLMOD simplicial LL^T, 2 CHOLMOD simplicial LDL^T (the indefinite
//     path), 3 UMFPACK LU (the unsymmetric path and the last fallback), 4 iga::LinearSolver (what a
//     Newton iteration calls: CHOLMOD with supernodal or simplicial as CHOLMOD's flop count
//     decides), 5 and 6: 0 and 2 with METIS nested dissection as the only ordering, 7 and 8:
//     iga::LinearSolver with MUMPS through PETSc, LDL^T (symmetric) and LU (a build with PETSc;
//     skipped without);
//   BM_Distributed/<n>: iga::DistributedLinearSolver (MUMPS LDL^T through PETSc) over the run's
//     processes, each handing in the entries of its even block of rows (the plate's numbering
//     is row by row of control points, so a block of rows is a strip of the plate, as a cut
//     shell's block is), with the COO assembly of every factorization; run it under mpirun
//     against one process (a fixed count of iterations: every process takes part in each);
//   BM_Solve/<method>/<n>: the triangular solves of one right-hand side.
// 0 against 4 shows what LinearSolver's serial OpenMP regions around CHOLMOD save (CHOLMOD of
// SuiteSparse 5 opens regions of a fixed 4 threads in its supernodal factorization:
// iga/solvers/linear_solver.cpp, SerialRegions); n = 160 is the Newton scaling study's largest
// plate (issue 37, item 5).
// The supernodal factorization's speed is the BLAS's: compare the system's libblas.so.3
// (Debian's alternatives: reference BLAS or OpenBLAS, scripts/install-deps.sh installs
// libopenblas0-serial).
// Run: build/release/bench/bench_linear_solver --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
// and over 2 processes (MUMPS's options pass in PETSC_OPTIONS, e.g. "-mat_mumps_icntl_7 5"):
//   mpirun -n 2 build/release/bench/bench_linear_solver --benchmark_filter=Distributed
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

#include "bench/bench_ranks.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/core/sparse_assembly.hpp"
#include "iga/parallel/communicator.hpp"
#include "iga/shell/kirchhoff_love_shell.hpp"
#include "iga/solvers/distributed_solver.hpp"
#include "iga/solvers/linear_solver.hpp"

using namespace iga;

namespace {

/// The tangent of the n x n biquadratic plate (20 x 20, h = 0.2, E = 2.5e5, nu = 0.3: the
/// saddle's) at the reference state, plus eps I; built once per n.
const SparseMatrix& plate_tangent(int n) {
  static std::map<int, SparseMatrix> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  NurbsSurface s = make_plane_patch(Vector3d(-10, -10, 0), Vector3d(20, 0, 0), Vector3d(0, 20, 0));
  s = subdivide(elevate_degree(s, 1, 1), n, n);
  const KirchhoffLoveShell shell(s, {2.5e5, 0.3, 0.2});
  const std::vector<Vector3d>& x = shell.reference_points();
  Eigen::VectorXd f;
  std::vector<Triplet> T;
  shell.assemble(x, f, &T);
  SparseMatrix K(shell.num_dofs(), shell.num_dofs());
  K.setFromTriplets(T.begin(), T.end());
  const double eps = 1e-3 * K.diagonal().cwiseAbs().mean();
  for (int i = 0; i < K.rows(); ++i) K.coeffRef(i, i) += eps;
  K.makeCompressed();
  return cache.emplace(n, std::move(K)).first->second;
}

using Supernodal = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;
using SimplicialLlt = Eigen::CholmodSimplicialLLT<SparseMatrix, Eigen::Lower>;
using SimplicialLdlt = Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Lower>;
using Lu = Eigen::UmfPackLU<SparseMatrix>;

/// A CHOLMOD decomposition ordered by METIS nested dissection only (CHOLMOD's default tries
/// AMD, then METIS where AMD's fill is high).
template <class Base>
class Metis : public Base {
 public:
  Metis() {
    this->cholmod().nmethods = 1;
    this->cholmod().method[0].ordering = CHOLMOD_METIS;
    this->cholmod().postorder = 1;
  }
};

const char* method_name(int m) {
  static const char* names[] = {"cholmod_supernodal_llt",
                                "cholmod_simplicial_llt",
                                "cholmod_simplicial_ldlt",
                                "umfpack_lu",
                                "LinearSolver",
                                "cholmod_supernodal_llt_metis",
                                "cholmod_simplicial_ldlt_metis",
                                "mumps_ldlt",
                                "mumps_lu"};
  return names[m];
}

/// Factorizations (solve == false) or triangular solves (solve == true) of decomposition `D`.
template <class Decomposition>
void run(benchmark::State& state, const SparseMatrix& K, bool solve) {
  Decomposition D;
  D.analyzePattern(K);
  // CHOLMOD's count of the factorization's floating-point operations (its analysis), beside
  // MUMPS's RINFOG(1) (-mat_mumps_icntl_4 2): what the orderings cost
  if constexpr (requires { D.cholmod(); }) state.counters["flops"] = D.cholmod().fl;
  D.factorize(K);
  if (D.info() != Eigen::Success) {
    state.SkipWithError("factorization failed");
    return;
  }
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
  Eigen::VectorXd x;
  for (auto _ : state) {
    if (solve) {
      x = D.solve(b);
      benchmark::DoNotOptimize(x.data());
    } else {
      D.factorize(K);
      benchmark::DoNotOptimize(D.info());
    }
  }
  if (solve && (K * x - b).cwiseAbs().maxCoeff() > 1e-6 * b.cwiseAbs().maxCoeff())
    state.SkipWithError("inaccurate solution");
}

void run_linear_solver(benchmark::State& state, const SparseMatrix& K, bool solve,
                       LinearMethod method = LinearMethod::suitesparse, bool symmetric = true) {
  LinearSolver solver(symmetric);
  if (method != LinearMethod::suitesparse) {
    if (!parallel_build()) {
      state.SkipWithError("no PETSc in this build");
      return;
    }
    solver.set_method(method);
  }
  if (solver.factorize(K) != LinearSolveStatus::success) {
    state.SkipWithError(solver.message().c_str());
    return;
  }
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
  Eigen::VectorXd x;
  for (auto _ : state) {
    if (solve)
      benchmark::DoNotOptimize(solver.solve(b, x));
    else
      benchmark::DoNotOptimize(solver.factorize(K));
  }
  state.counters["reused_analysis"] = solver.reused_analysis() ? 1 : 0;
}

void bench(benchmark::State& state, bool solve) {
  const int method = static_cast<int>(state.range(0));
  const SparseMatrix& K = plate_tangent(static_cast<int>(state.range(1)));
  state.SetLabel(method_name(method));
  switch (method) {
    case 0:
      run<Supernodal>(state, K, solve);
      break;
    case 1:
      run<SimplicialLlt>(state, K, solve);
      break;
    case 2:
      run<SimplicialLdlt>(state, K, solve);
      break;
    case 3:
      run<Lu>(state, K, solve);
      break;
    case 5:
      run<Metis<Supernodal>>(state, K, solve);
      break;
    case 6:
      run<Metis<SimplicialLdlt>>(state, K, solve);
      break;
    case 7:
      run_linear_solver(state, K, solve, LinearMethod::mumps, true);
      break;
    case 8:
      run_linear_solver(state, K, solve, LinearMethod::mumps, false);
      break;
    default:
      run_linear_solver(state, K, solve);
  }
  state.counters["dofs"] = static_cast<double>(K.rows());
}

void BM_Factorize(benchmark::State& state) {
  bench(state, false);
}
void BM_Solve(benchmark::State& state) {
  bench(state, true);
}

/// Factorizations by DistributedLinearSolver over world(): this process's even block of rows.
void BM_Distributed(benchmark::State& state) {
  if (!parallel_build()) {
    state.SkipWithError("no PETSc in this build");
    return;
  }
  const SparseMatrix& K = plate_tangent(static_cast<int>(state.range(0)));
  const Communicator& w = world();
  const Eigen::Index first = K.rows() * w.rank() / w.size();
  const Eigen::Index last = K.rows() * (w.rank() + 1) / w.size();
  std::vector<Triplet> mine;
  for (Eigen::Index c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (it.row() >= first && it.row() < last)
        mine.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  SparseMatrix part(K.rows(), K.cols());  // this process's part, as LinearSolver hands it in
  part.setFromTriplets(mine.begin(), mine.end());
  part.makeCompressed();
  DistributedLinearSolver solver(LinearMethod::mumps);
  const int n = static_cast<int>(K.rows());
  if (solver.factorize(part, true) != LinearSolveStatus::success) {
    state.SkipWithError(solver.message().c_str());
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(solver.factorize(part, true));
  state.counters["dofs"] = static_cast<double>(n);
  state.counters["processes"] = w.size();
}

BENCHMARK(BM_Distributed)
    ->Arg(20)
    ->Arg(40)
    ->Arg(80)
    ->Arg(160)
    ->Iterations(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_Factorize)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7, 8}, {20, 40, 80, 160}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Solve)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7, 8}, {20, 40, 80, 160}})
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  const ParallelSession session(argc, argv);
  benchmark::Initialize(&argc, argv);
  bench::run_on_every_rank();
  return 0;
}
