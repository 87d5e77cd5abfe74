// Benchmarks of setting a model up, each over a size N with a complexity fit (every one is
// linear in N; a quadratic step shows as O(N^2)):
//   - Analysis::from_json (iga/model/analysis.hpp) on data/capstan.json with its rope refined
//     to N = 7,500 ... 60,000 arc elements: the rod, the wrap path's fit, the DofMap, the pairs
//     (a dense fit, a renumbering per fixed component, a scan of all knots per knot were
//     quadratic);
//   - make_wrap_path (geometry/constructions.hpp) alone, N arc elements (banded fit);
//   - parse_json_text (geometry/json_reader.hpp) of an object of N keys (ordered insertion
//     was quadratic) and of N unclosed brackets (the error's pointer was quadratic).
//   - the memory of a shell contact model: data/saddle.json with its plate refined to N x N
//     quadratic elements (7 x 7 contact points per element, as the paper's), the heap the model
//     holds after its construction and after one assembly of residual and tangent at the start
//     (the assembly's kept buffers and the matrix; no contact point active there), in bytes per
//     control point of the plate (glibc's mallinfo2: the heap in use, not the resident pages).
// These sizes were timed tests once; a loaded machine made them fail, so they are measured here.
// Run: build/release/bench/bench_model_setup --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true (the memory alone: --benchmark_filter=saddle_memory)
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <numbers>
#include <string>

#include "geometry/constructions.hpp"
#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

using namespace iga;

namespace {

void BM_capstan_setup(benchmark::State& state) {
  Json doc = read_json_file(std::string(IGA_SOURCE_DIR) + "/data/capstan.json");
  doc["geometry"]["rope"]["arc_elements"] = state.range(0);
  for (auto _ : state) {
    const Analysis a = Analysis::from_json(doc, "capstan_fine.json");
    benchmark::DoNotOptimize(&a);
  }
  state.SetComplexityN(state.range(0));
}

void BM_wrap_path(benchmark::State& state) {
  WrapPathSpec w;
  w.radius = 1.02;
  w.angle = std::numbers::pi;
  w.span_length = 1.0;
  w.arc_elements = static_cast<int>(state.range(0));
  w.span_elements = 3;
  for (auto _ : state) {
    const WrapPath r = make_wrap_path(w);
    benchmark::DoNotOptimize(&r);
  }
  state.SetComplexityN(state.range(0));
}

void BM_json_many_keys(benchmark::State& state) {
  const auto n = static_cast<int>(state.range(0));
  std::string text = "{";
  for (int i = 0; i < n; ++i)
    text += (i ? ",\"k" : "\"k") + std::to_string(n - i) + "\": " + std::to_string(i);
  text += "}";
  for (auto _ : state) {
    const Json j = parse_json_text(text, "keys.json");
    benchmark::DoNotOptimize(&j);
  }
  state.SetComplexityN(n);
}

void BM_json_unclosed_brackets(benchmark::State& state) {
  const std::string text(static_cast<std::size_t>(state.range(0)), '[');
  for (auto _ : state) {
    try {
      (void)parse_json_text(text, "brackets.json");
      state.SkipWithError("accepted");
    } catch (const ModelError& e) {
      benchmark::DoNotOptimize(e.what());
    }
  }
  state.SetComplexityN(state.range(0));
}

double heap_in_use() {
  return static_cast<double>(mallinfo2().uordblks);
}

void BM_saddle_memory(benchmark::State& state) {
  const auto n = static_cast<int>(state.range(0));
  Json doc = read_json_file(std::string(IGA_SOURCE_DIR) + "/data/saddle.json");
  doc["geometry"]["plate"]["refine"]["subdivide"] = n;
  const double cps = static_cast<double>((n + 2) * (n + 2));  // quadratic: n + 2 per direction
  for (auto _ : state) {
    const double h0 = heap_in_use();
    Analysis a = Analysis::from_json(doc, "saddle_fine.json");
    const double h1 = heap_in_use();
    BodySystem& sys = a.problem();
    VectorXd u = VectorXd::Zero(sys.num_dofs()), R;
    SparseMatrix K;
    sys.assemble(u, 0.0, R, &K);
    const double h2 = heap_in_use();
    state.counters["setup_B_per_cp"] = (h1 - h0) / cps;
    state.counters["assembled_B_per_cp"] = (h2 - h0) / cps;
    state.counters["control_points"] = cps;
  }
  state.SetComplexityN(n * n);
}

}  // namespace

BENCHMARK(BM_saddle_memory)
    ->RangeMultiplier(2)
    ->Range(20, 160)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();
BENCHMARK(BM_capstan_setup)
    ->RangeMultiplier(2)
    ->Range(7500, 60000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();
BENCHMARK(BM_wrap_path)
    ->RangeMultiplier(2)
    ->Range(6250, 50000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();
BENCHMARK(BM_json_many_keys)
    ->RangeMultiplier(2)
    ->Range(37500, 300000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();
BENCHMARK(BM_json_unclosed_brackets)
    ->RangeMultiplier(2)
    ->Range(1 << 17, 1 << 20)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();

BENCHMARK_MAIN();
