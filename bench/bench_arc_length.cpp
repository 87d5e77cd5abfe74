// Arc length's dR/dt (iga/solvers/nonlinear_solver.hpp) taken from the loads alone
// (NonlinearProblem::load_rate, the default) against the one-sided difference of an extra
// residual assembly at t + h per iteration (NonlinearSolverSettings::rate_from_loads = false,
// the path before issue 37, item 5), whole runs of the arc-length models:
//   - data/arch_snap.json: a rod arch through both limit points (16 cubic elements);
//   - data/hinged_roof.json: Sabir & Lock's roof through both limit points, cubic, at its
//     8 x 8 elements and at 16 x 16;
//   - data/pinched_cylinder_nonlinear.json at 16 x 16 up to t = 0.3 (past its first fold).
// Each reports the run's assemblies, those without the tangent, the rates from the loads, the
// steps and Newton iterations, the monitor at the end and the seconds of the solve; the two
// paths of a model run in the same program run, so their ratio is read off one table.
// Run: build/release/bench/bench_arc_length --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

/// Model c: 0 the arch, 1 the roof 8 x 8, 2 the roof 16 x 16, 3 the pinched cylinder.
Json model(int c, std::string& label) {
  Json d;
  switch (c) {
    case 0:
      d = read_json_file(kData + "arch_snap.json");
      label = "arch_snap";
      break;
    case 1:
    case 2:
      d = read_json_file(kData + "hinged_roof.json");
      d["geometry"]["roof"]["refine"]["subdivide"] = c == 1 ? 8 : 16;
      label = c == 1 ? "hinged_roof 8^2" : "hinged_roof 16^2";
      break;
    default:
      d = read_json_file(kData + "pinched_cylinder_nonlinear.json");
      d["geometry"]["cylinder"]["refine"]["subdivide"] = 16;
      d["solver"]["t_end"] = 0.3;
      d["solver"]["hit_times"] = {0.1, 0.2};
      label = "pinched_cylinder 16^2 to t=0.3";
      break;
  }
  d["output"]["vtk"] = "none";
  return d;
}

// Args: model (see model()), path (1 dR/dt from the loads, 0 by an assembly).
void BM_arc_length(benchmark::State& state) {
  const int c = static_cast<int>(state.range(0));
  const bool loads = state.range(1) == 1;
  std::string label;
  const Json doc = model(c, label);
  NonlinearSolverResult last;
  double monitor = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    Analysis a = Analysis::from_json(doc, "bench.json");
    a.solver_settings().rate_from_loads = loads;
    state.ResumeTiming();
    const AnalysisResult r = a.run();
    if (!r.solver.converged()) {
      state.SkipWithError(r.solver.message.c_str());
      return;
    }
    last = r.solver;
    const Vector3d d = r.steps.back().displacements.at(0);
    monitor = d.norm();
  }
  state.counters["assemblies"] = last.assemblies;
  state.counters["residual_only"] = last.residual_assemblies;
  state.counters["load_rates"] = last.load_rates;
  state.counters["steps"] = last.steps;
  state.counters["iterations"] = last.total_iterations;
  state.counters["monitor"] = monitor;
  state.counters["assembly_s"] = last.time_assembly;
  state.SetLabel(label + (loads ? " rate from loads" : " rate by assembly"));
}

void cases(benchmark::internal::Benchmark* b) {
  for (int c : {0, 1, 2, 3})
    for (int loads : {1, 0}) b->Args({c, loads});
}
BENCHMARK(BM_arc_length)->Apply(cases)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
