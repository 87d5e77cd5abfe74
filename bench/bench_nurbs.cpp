// Benchmarks of the NURBS kernel: basis functions with derivatives (A2.3), bicubic rational
// surface evaluation with second derivatives (A4.4; knot spans or Bezier elements), and the
// least-squares fit of a rope's wrap path (constructions.hpp) against its element count. Items per
// second = evaluations (fits: elements) per second. Run: build/release/bench/bench_nurbs
// --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "geometry/bezier_surface.hpp"
#include "geometry/bspline_basis.hpp"
#include "geometry/constructions.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"

using namespace iga;

namespace {

std::vector<double> uniform_knots(int p, int n_elements) {
  std::vector<double> U(static_cast<std::size_t>(p + 1), 0.0);
  for (int e = 1; e < n_elements; ++e) U.push_back(static_cast<double>(e) / n_elements);
  U.insert(U.end(), static_cast<std::size_t>(p + 1), 1.0);
  return U;
}

std::vector<double> random_params(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = unif(rng);
  return x;
}

// find_span + ders_basis_funs for degree p, nd derivatives, 64 elements.
void BM_DersBasisFuns(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const int nd = static_cast<int>(state.range(1));
  const std::vector<double> U = uniform_knots(p, 64);
  const int n_basis = static_cast<int>(U.size()) - p - 1;
  const std::vector<double> u = random_params(4096, 1);
  BasisDerivs ders;
  std::size_t k = 0;
  for (auto _ : state) {
    const double x = u[k++ & 4095];
    const int span = find_span(n_basis, p, x, U);
    ders_basis_funs(span, x, p, nd, U, ders);
    benchmark::DoNotOptimize(ders);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DersBasisFuns)->ArgsProduct({{2, 3, 5}, {0, 2}});

// Bicubic rational 8x8 patch with non-uniform knots: point + first + second derivatives, by the
// B-spline basis of the knot spans (NurbsSurface, arg 1 = 0) or the Bernstein polynomials of
// the Bezier elements (BezierSurface, arg 1 = 1).
void BM_BicubicSurfaceDerivs(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const bool bezier = state.range(1) != 0;
  const std::vector<double> U = {0, 0, 0, 0, 0.1, 0.3, 0.45, 0.7, 1, 1, 1, 1};
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> c(-1, 1), w(0.7, 1.3);
  std::vector<Vector3d> P;
  std::vector<double> W;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      P.emplace_back(i + 0.2 * c(rng), j + 0.2 * c(rng), c(rng));
      W.push_back(w(rng));
    }
  const NurbsSurface nurbs(3, U, 3, U, P, W);
  const BezierSurface elements(nurbs);
  const Surface& s = bezier ? static_cast<const Surface&>(elements) : nurbs;
  const std::vector<double> u = random_params(4096, 3), v = random_params(4096, 4);
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t i = k++ & 4095;
    SurfaceDerivs d = s.derivs(u[i], v[i], order);
    benchmark::DoNotOptimize(d);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BicubicSurfaceDerivs)->ArgsProduct({{0, 1, 2}, {0, 1}});

// Cubic rational curve, derivatives up to order 3.
void BM_CubicCurveDerivs(benchmark::State& state) {
  const std::vector<double> U = uniform_knots(3, 16);
  const int n = static_cast<int>(U.size()) - 4;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> c(-1, 1), w(0.7, 1.3);
  std::vector<Vector3d> P;
  std::vector<double> W;
  for (int i = 0; i < n; ++i) {
    P.emplace_back(c(rng), c(rng), c(rng));
    W.push_back(w(rng));
  }
  const NurbsCurve curve(3, U, P, W);
  const std::vector<double> u = random_params(4096, 6);
  std::size_t k = 0;
  for (auto _ : state) {
    CurveDerivs d = curve.derivs(u[k++ & 4095], 3);
    benchmark::DoNotOptimize(d);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CubicCurveDerivs);

// make_wrap_path: the capstan's rope (a half turn on a unit cylinder between two straight
// spans) fitted with n arc elements and n/10 + 1 elements per span.
void BM_WrapPathFit(benchmark::State& state) {
  WrapPathSpec w;
  w.arc_elements = static_cast<int>(state.range(0));
  w.span_elements = w.arc_elements / 10 + 1;
  for (auto _ : state) {
    WrapPath path = make_wrap_path(w);
    benchmark::DoNotOptimize(path);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_WrapPathFit)->Arg(100)->Arg(1000)->Arg(3000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
