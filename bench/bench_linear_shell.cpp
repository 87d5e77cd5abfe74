// The linear analysis path (solver "analysis": "linear", iga/solvers/nonlinear_solver.hpp)
// against today's Newton path on the same linear benchmarks: the Scordelis-Lo roof
// (data/scordelis_lo.json) and the pinched cylinder (data/pinched_cylinder.json), at n x n
// elements of degree p (n = 16, 32, 64; p = 2, 3), whole runs from the model document: set-up
// (Analysis::from_json: the shell's quadrature and the problem) plus the solve.
//   linear: one assembly, one factorization, one solve, at the full load;
//   newton: the Newton path as the models ran before the linear path, Scordelis-Lo at 1e-5 of
//           its load (linear to 2e-6; the monitor scaled back), the pinched cylinder at the
//           full load (linear to 2e-6), with tol_residual_abs 1e-4 (the models' 1e-5 is below
//           the round-off floor at 64^2): 3 assemblies and 2 factorizations.
// Each benchmark reports the run's counts (assemblies, factorizations, solves), the monitor
// (-u_z, against the model's reference) and the seconds of set-up and solve. With
// IGA_GISMO_KL set to G+Smo's kl_linear driver (bench/gismo/, see its README), each linear
// case also runs gsKLShell's linear solve on the same mesh and degree in the same benchmark
// run and reports its seconds and the ratio (gismo_s / ours).
// Run: build/release/bench/bench_linear_shell --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The model of case c (0 Scordelis-Lo, 1 pinched cylinder) at n x n elements of degree p,
/// linear or Newton; `scale` the factor of its monitor back to the full load.
Json model(int c, int n, int p, bool linear, double& scale) {
  Json d = read_json_file(kData + (c == 0 ? "scordelis_lo.json" : "pinched_cylinder.json"));
  const char* surface = c == 0 ? "roof" : "cylinder";
  // The rational quadratic arc (u) times a line (v), elevated to degree p in both.
  d["geometry"][surface]["refine"] = {{"elevate", {p - 2, p - 1}}, {"subdivide", n}};
  d["output"]["vtk"] = "none";
  scale = 1.0;
  if (linear) {
    d["solver"]["analysis"] = "linear";
  } else {
    d["solver"]["analysis"] = "nonlinear";
    // The residual's round-off floor grows with the mesh (1.45e-5 for Scordelis-Lo at 64^2,
    // p = 2, above the models' 1e-5): Newton would never stop there.
    d["solver"]["tol_residual_abs"] = 1e-4;
    if (c == 0) {  // the load at 1e-5, as the model ran on the Newton path
      scale = 1e-5;
      d["load_curves"]["load_factor"]["scale"] = scale;
    }
  }
  return d;
}

/// gsKLShell's linear run of the same case through the driver at IGA_GISMO_KL: its total
/// seconds, or a negative value without the driver (or when it fails).
double gismo_seconds(int c, int n, int p, double& monitor) {
  const char* exe = std::getenv("IGA_GISMO_KL");
  if (exe == nullptr || *exe == '\0') return -1.0;
  const std::string cmd = std::string(exe) + " --case " + (c == 0 ? "scordelis" : "pinched") +
                          " --n " + std::to_string(n) + " --degree " + std::to_string(p);
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return -1.0;
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), pipe.get()) != nullptr) out += buf.data();
  try {
    const Json j = Json::parse(out.substr(out.find('{')));
    monitor = j.at("monitor").get<double>();
    return j.at("time_total_s").get<double>();
  } catch (const std::exception&) {
    return -1.0;
  }
}

// Args: case (0 Scordelis-Lo, 1 pinched cylinder), n, p, path (1 linear, 0 Newton).
void BM_linear_shell(benchmark::State& state) {
  const int c = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const int p = static_cast<int>(state.range(2));
  const bool linear = state.range(3) == 1;
  double scale = 1.0;
  const Json doc = model(c, n, p, linear, scale);
  double setup = 0.0, solve = 0.0, monitor = 0.0, gismo = 0.0, gismo_monitor = 0.0;
  int gismo_runs = 0, dofs = 0;
  NonlinearSolverResult last;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    Analysis a = Analysis::from_json(doc, "bench.json");
    setup += seconds_since(t0);
    dofs = a.problem().num_dofs();
    const auto t1 = std::chrono::steady_clock::now();
    const AnalysisResult r = a.run();
    solve += seconds_since(t1);
    if (!r.solver.converged()) {
      state.SkipWithError(r.solver.message.c_str());
      return;
    }
    monitor = -r.steps.back().displacements.at(0).z() / scale;
    last = r.solver;
    if (linear) {  // G+Smo's run of the same case, timed outside ours
      state.PauseTiming();
      double m = 0.0;
      const double g = gismo_seconds(c, n, p, m);
      if (g >= 0.0) gismo += g, gismo_monitor = m, ++gismo_runs;
      state.ResumeTiming();
    }
  }
  const auto it = static_cast<double>(state.iterations());
  state.counters["dofs"] = dofs;
  state.counters["assemblies"] = last.assemblies;
  state.counters["factorizations"] = last.cholmod_factorizations + last.ldlt_factorizations +
                                     last.umfpack_factorizations + last.petsc_factorizations;
  state.counters["solves"] = last.total_iterations;
  state.counters["monitor"] = monitor;
  state.counters["setup_s"] = setup / it;
  state.counters["solve_s"] = solve / it;
  if (gismo_runs > 0) {
    state.counters["gismo_s"] = gismo / gismo_runs;
    state.counters["gismo_monitor"] = gismo_monitor;
    state.counters["gismo_ratio"] = (gismo / gismo_runs) / ((setup + solve) / it);
  }
  state.SetLabel(std::string(c == 0 ? "scordelis_lo" : "pinched_cylinder") + " " +
                 std::to_string(n) + "^2 p=" + std::to_string(p) +
                 (linear ? " linear" : " newton"));
}

void cases(benchmark::internal::Benchmark* b) {
  for (int c : {0, 1})
    for (int n : {16, 32, 64})
      for (int p : {2, 3})
        for (int linear : {1, 0}) b->Args({c, n, p, linear});
}
BENCHMARK(BM_linear_shell)->Apply(cases)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
