// Benchmarks of the Kirchhoff-Love shell (iga/shell/kirchhoff_love_shell.hpp) on a 20 x 20 bicubic
// plate (randomly perturbed current state): the element tangent (forces + consistent tangent,
// 16 Gauss points, 48 x 48) per element (by degree; by law), and one global assembly into triplets
// plus the sparse matrix (setFromTriplets, or the pattern kept: PatternAssembler). Run:
// build/release/bench/bench_shell --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/core/sparse_assembly.hpp"
#include "iga/shell/kirchhoff_love_shell.hpp"

using namespace iga;

namespace {

KirchhoffLoveShell plate(int n, int p, ShellLaw law = ShellLaw::kSaintVenantKirchhoff) {
  NurbsSurface s = make_plane_patch(Vector3d::Zero(), Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  s = subdivide(elevate_degree(s, p - 1, p - 1), n, n);
  return KirchhoffLoveShell(s, {1e6, 0.3, 0.01, law, 5});
}

std::vector<Vector3d> perturbed(const std::vector<Vector3d>& X) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-0.01, 0.01);
  std::vector<Vector3d> x = X;
  for (Vector3d& xi : x) xi += Vector3d(d(rng), d(rng), d(rng));
  return x;
}

// Element tangents of the shell, one element after another; items = elements.
void time_element_tangents(benchmark::State& state, const KirchhoffLoveShell& shell) {
  const std::vector<Vector3d> x = perturbed(shell.reference_points());
  ShellElementVector f;
  ShellElementMatrix K;
  int e = 0;
  for (auto _ : state) {
    shell.element_tangent(e, x, f, K);
    benchmark::DoNotOptimize(K.data());
    e = (e + 1) % shell.num_elements();
  }
  state.SetItemsProcessed(state.iterations());
}

// Element tangent of a 20 x 20 plate of degree p; items = elements.
void BM_ShellElementTangent(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const KirchhoffLoveShell shell = plate(20, p);
  time_element_tangents(state, shell);
}
BENCHMARK(BM_ShellElementTangent)->Arg(2)->Arg(3)->Arg(4);

// Element tangent of the 20 x 20 bicubic plate by law: 0 St. Venant-Kirchhoff (closed-form
// thickness integration), 1 neo-Hookean (5 points through the thickness); items = elements.
void BM_ShellElementTangentLaw(benchmark::State& state) {
  const ShellLaw law =
      state.range(0) == 0 ? ShellLaw::kSaintVenantKirchhoff : ShellLaw::kNeoHookean;
  const KirchhoffLoveShell shell = plate(20, 3, law);
  time_element_tangents(state, shell);
}
BENCHMARK(BM_ShellElementTangentLaw)->Arg(0)->Arg(1);

// One global assembly (forces + triplets + setFromTriplets) of the 20 x 20 bicubic plate.
void BM_ShellAssembly20x20Bicubic(benchmark::State& state) {
  const KirchhoffLoveShell shell = plate(20, 3);
  const std::vector<Vector3d> x = perturbed(shell.reference_points());
  Eigen::VectorXd f;
  std::vector<Triplet> T;
  Eigen::SparseMatrix<double> K(shell.num_dofs(), shell.num_dofs());
  for (auto _ : state) {
    T.clear();
    shell.assemble(x, f, &T);
    K.setFromTriplets(T.begin(), T.end());
    benchmark::DoNotOptimize(K.valuePtr());
  }
  state.counters["elements"] = shell.num_elements();
  state.counters["dofs"] = shell.num_dofs();
}
BENCHMARK(BM_ShellAssembly20x20Bicubic)->Unit(benchmark::kMillisecond);

// The element loop alone (forces and triplets, the part on all OpenMP threads) of the same plate;
// the rest of BM_ShellAssembly20x20Bicubic is setFromTriplets, on one thread.
void BM_ShellElements20x20Bicubic(benchmark::State& state) {
  const KirchhoffLoveShell shell = plate(20, 3);
  const std::vector<Vector3d> x = perturbed(shell.reference_points());
  Eigen::VectorXd f;
  std::vector<Triplet> T;
  for (auto _ : state) {
    T.clear();
    shell.assemble(x, f, &T);
    benchmark::DoNotOptimize(T.data());
  }
  state.counters["elements"] = shell.num_elements();
}
BENCHMARK(BM_ShellElements20x20Bicubic)->Unit(benchmark::kMillisecond);

// The sparse matrix from the triplets of one assembly of the same plate: setFromTriplets (arg 0,
// a sort every Newton iteration) or PatternAssembler with the pattern kept from the last call
// (arg 1, the same triplet sequence: only the values are summed in).
void BM_ShellSparseMatrix20x20Bicubic(benchmark::State& state) {
  const KirchhoffLoveShell shell = plate(20, 3);
  const std::vector<Vector3d> x = perturbed(shell.reference_points());
  Eigen::VectorXd f;
  std::vector<Triplet> T;
  shell.assemble(x, f, &T);
  Eigen::SparseMatrix<double> K(shell.num_dofs(), shell.num_dofs());
  PatternAssembler assembler;
  const bool kept = state.range(0) != 0;
  for (auto _ : state) {
    if (kept)
      assembler.assemble(T, shell.num_dofs(), shell.num_dofs(), K);
    else
      K.setFromTriplets(T.begin(), T.end());
    benchmark::DoNotOptimize(K.valuePtr());
  }
  state.counters["triplets"] = static_cast<double>(T.size());
}
BENCHMARK(BM_ShellSparseMatrix20x20Bicubic)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
