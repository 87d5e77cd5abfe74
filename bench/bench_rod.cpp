// Benchmarks of the rods (iga/rod/): one global assembly (forces + consistent tangent into
// triplets) of a 64-element straight rod in a slightly bent and twisted state, for the
// torsion-free rod (written-out derivatives) and the rod with torsion (small jets joined by
// the chain rule, iga/rod/twisting_rod.hpp "Derivatives"), degrees 2 and 3. The rod with
// torsion assembles on all OpenMP threads from 16 elements on: compare on one core with
//   OMP_NUM_THREADS=1 build/release/bench/bench_rod
//   --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <vector>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/rod/twisting_rod.hpp"

using namespace iga;

namespace {

constexpr int kElements = 64;

NurbsCurve rod_curve(int p) {
  return subdivide(elevate_degree(make_line(Vector3d::Zero(), Vector3d(1, 0, 0)), p - 1),
                   kElements);
}

RodSection section() {
  RodSection s;
  s.EA = 1e5;
  s.EI1 = 10.0;
  s.EI2 = 1.0;
  s.GJ = 1.0;
  s.ref_direction = Vector3d::UnitY();
  return s;
}

std::vector<Vector3d> bent(const NurbsCurve& c) {
  std::vector<Vector3d> x = c.control_points();
  for (Vector3d& v : x) v += Vector3d(0.0, 0.01 * v.x() * v.x(), 0.02 * v.x() * v.x() * v.x());
  return x;
}

void BM_TorsionFreeRodAssembly(benchmark::State& state) {
  const NurbsCurve c = rod_curve(static_cast<int>(state.range(0)));
  const KirchhoffRod rod(c, section());
  const std::vector<Vector3d> x = bent(c);
  Eigen::VectorXd f;
  std::vector<Triplet> K;
  for (auto _ : state) {
    K.clear();
    rod.assemble(x, f, &K);
    benchmark::DoNotOptimize(K.data());
  }
  state.counters["us_per_element"] = benchmark::Counter(
      kElements, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TorsionFreeRodAssembly)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

void BM_TwistingRodAssembly(benchmark::State& state) {
  const NurbsCurve c = rod_curve(static_cast<int>(state.range(0)));
  const TwistingRod rod(c, section());
  const std::vector<Vector3d> x = bent(c);
  std::vector<double> alpha(static_cast<std::size_t>(rod.num_knots()));
  for (std::size_t k = 0; k < alpha.size(); ++k) alpha[k] = 0.05 * static_cast<double>(k);
  Eigen::VectorXd f;
  std::vector<Triplet> K;
  for (auto _ : state) {
    K.clear();
    rod.assemble(x, alpha, f, &K);
    benchmark::DoNotOptimize(K.data());
  }
  state.counters["us_per_element"] = benchmark::Counter(
      kElements, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TwistingRodAssembly)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
