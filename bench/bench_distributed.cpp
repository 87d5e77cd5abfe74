// A shell contact model on one process against the same model spread over several (issue 36):
// the plate of data/saddle.json refined to n x n bicubic elements (n = IGA_BENCH_ELEMENTS,
// default 100: 103 x 103 control points, 31,827 unknowns, 49 contact points per element),
// pressed onto the saddle. Once, outside the timings: the model is built (its memory counted)
// and run to t = 300 in steps of 50, a state with contact (the plate touches at about
// t = 200). Then, at that state:
//   BM_Assembly:        the residual and tangent (the elements and the contact points of this
//                       process, the residual summed over the processes, the pairs' tallies);
//   BM_LinearSolve:     one factorization and solve of that tangent by the run's solver (on
//                       one process SuiteSparse by default, IGA_BENCH_SOLVER=mumps for MUMPS;
//                       over several processes MUMPS, the parts summed by PETSc);
//   BM_NewtonIteration: both, as one Newton iteration does.
// Counters (rank 0's; the others' are printed): setup_MB the resident memory the model's
// construction added, peak_MB the process's peak resident memory (VmHWM) after the run.
// Printed per process besides: the resident memory before the model (the libraries, MPI's and
// PETSc's), what the run holds live (the resident memory after malloc_trim gave the freed
// memory back), and the peaks of one assembly and of one factorization and solve at the
// run's end, each from the live memory before it (VmHWM restarted through
// /proc/self/clear_refs).
// Every process runs the same fixed iterations (the collectives must match); only rank 0
// reports.
// Run, one process and two:
//   OMP_NUM_THREADS=1 build/release/bench/bench_distributed --benchmark_repetitions=5
//   OMP_NUM_THREADS=1 mpirun -n 2 build/release/bench/bench_distributed --benchmark_repetitions=5
// (add --benchmark_report_aggregates_only=true for the medians only).
#include <benchmark/benchmark.h>

#include <malloc.h>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "bench/bench_ranks.hpp"
#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"
#include "iga/parallel/communicator.hpp"
#include "iga/solvers/linear_solver.hpp"

using namespace iga;

namespace {

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}

/// A line of /proc/self/status in MB ("VmRSS", "VmHWM").
double status_mb(const std::string& key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind(key + ":", 0) == 0) return std::atof(line.c_str() + key.size() + 1) / 1024.0;
  return 0.0;
}

/// Restarts the process's peak resident memory (VmHWM) at its current resident memory.
void reset_peak() {
  std::ofstream("/proc/self/clear_refs") << "5";
}

struct Fixture {
  std::optional<Analysis> analysis;
  VectorXd u, R;
  double t = 0.0;
  SparseMatrix K;
  LinearSolver solver;
  double setup_mb = 0.0, peak_mb = 0.0;
  double base_mb = 0.0, live_mb = 0.0, assembly_peak_mb = 0.0, solve_peak_mb = 0.0;
};

void assemble(Fixture& f);
void solve(Fixture& f);

Fixture& fixture() {
  static const std::unique_ptr<Fixture> f = [] {
    auto x = std::make_unique<Fixture>();
    const int n = env_int("IGA_BENCH_ELEMENTS", 100);
    Json doc = read_json_file(std::string(IGA_SOURCE_DIR) + "/data/saddle.json");
    // IGA_BENCH_ELEVATE: the saddle's bilinear plate raised by this (default 2: bicubic; 1: the
    // model's own biquadratic elements, the Newton scaling study of issue 37, item 5)
    doc["geometry"]["plate"]["refine"] = {{"elevate", env_int("IGA_BENCH_ELEVATE", 2)},
                                          {"subdivide", n}};
    // to t = 300 in steps of 50 (the plate touches the saddle at about t = 200)
    doc["solver"]["t_end"] = 300;
    doc["solver"]["initial_step"] = 50;
    doc["solver"]["max_step"] = 50;
    doc["solver"]["hit_times"] = Json::array();
    if (const char* s = std::getenv("IGA_BENCH_SOLVER")) doc["solver"]["linear_solver"] = s;
    doc["output"] = {{"vtk", "none"}};
    const double before = status_mb("VmRSS");
    x->base_mb = before;
    x->analysis.emplace(Analysis::from_json(doc, "saddle_bench.json", world()));
    x->setup_mb = status_mb("VmRSS") - before;
    const AnalysisResult r = x->analysis->run();
    x->u = r.u;
    x->t = r.solver.t;
    x->solver.set_method(x->analysis->solver_settings().linear_method);
    x->solver.set_distributed(x->analysis->problem().distributed(),
                              x->analysis->problem().layout());
    x->peak_mb = status_mb("VmHWM");
    // what the run holds: the resident memory once the allocator gave back what was freed
    malloc_trim(0);
    x->live_mb = status_mb("VmRSS");
    // the peaks of one assembly and of one factorization and solve at that state, each from
    // the resident memory before it (the kernel's VmHWM restarted: /proc/self/clear_refs)
    reset_peak();
    assemble(*x);
    x->assembly_peak_mb = status_mb("VmHWM");
    reset_peak();
    solve(*x);
    x->solve_peak_mb = status_mb("VmHWM");
    if (world().root())
      std::printf(
          "saddle %d x %d, degree %d, %d unknowns, %d process(es): %zu steps to t = %g, "
          "active contact points %d\n",
          n, n, 1 + env_int("IGA_BENCH_ELEVATE", 2), x->analysis->problem().num_dofs(),
          world().size(), r.steps.size(), x->t, x->analysis->contact_counts().active);
    return x;
  }();
  return *f;
}

void counters(benchmark::State& state, const Fixture& f) {
  state.counters["setup_MB"] = f.setup_mb;
  state.counters["peak_MB"] = f.peak_mb;
}

void assemble(Fixture& f) {
  f.analysis->problem().assemble(f.u, f.t, f.R, &f.K);
}

void solve(Fixture& f) {
  VectorXd du;
  if (f.solver.factorize(f.K) != LinearSolveStatus::success ||
      f.solver.solve(f.R, du) != LinearSolveStatus::success)
    std::fprintf(stderr, "bench_distributed: the solve failed: %s\n", f.solver.message().c_str());
  benchmark::DoNotOptimize(du.data());
}

void BM_Assembly(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) assemble(f);
  counters(state, f);
}

void BM_LinearSolve(benchmark::State& state) {
  Fixture& f = fixture();
  assemble(f);
  for (auto _ : state) solve(f);
  counters(state, f);
}

void BM_NewtonIteration(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    assemble(f);
    solve(f);
  }
  counters(state, f);
}

// Fixed iterations: every process must make the same collective calls.
BENCHMARK(BM_Assembly)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_LinearSolve)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
BENCHMARK(BM_NewtonIteration)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  const ParallelSession session(argc, argv);
  benchmark::Initialize(&argc, argv);
  fixture();  // the model and its state, before any timing
  const Fixture& f = fixture();
  // Each process's memory, in rank order, printed by rank 0.
  char mine[256];
  std::snprintf(mine, sizeof mine,
                "rank %d: before the model %.0f MB, setup %.0f MB, peak of the run %.0f MB, live "
                "after it %.0f MB, peak of an assembly %.0f MB, of a factorization and solve "
                "%.0f MB",
                world().rank(), f.base_mb, f.setup_mb, f.peak_mb, f.live_mb, f.assembly_peak_mb,
                f.solve_peak_mb);
  for (const std::string& line : world().gather(mine)) std::printf("%s\n", line.c_str());
  // What each process owns and reads of others (DofLayout): the values one exchange of a
  // residual's parts sends, against the whole residual the replicated state summed.
  if (const DofLayout* L = fixture().analysis->problem().layout()) {
    std::snprintf(mine, sizeof mine,
                  "rank %d: owns %zu of %d unknowns, %zu ghosts; an exchange sends %lld values",
                  world().rank(), L->owned().size(), L->size(), L->ghosts().size(),
                  L->sent_per_exchange());
    for (const std::string& line : world().gather(mine)) std::printf("%s\n", line.c_str());
  }
  bench::run_on_every_rank();
  return 0;
}
