// Benchmarks of issue 15: reading the CAD files of data/cad (OpenCASCADE's reader and the
// conversion to our surfaces), and the cost of trimming on projections: the closest point onto
// a trimmed face (the base's foot, then the even-odd test over the loops) against the same
// untrimmed surface, for points whose foot lies inside the loops (the cost of the trim check
// alone). Items per second = points.
// Run: build/release/bench/bench_cad --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "cad/cad_import.hpp"
#include "contact/rigid_surface.hpp"
#include "tests/support/projection_reference.hpp"

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

void BM_ImportCad(benchmark::State& state, const char* file) {
  for (auto _ : state) {
    const CadImport imp = import_cad(kData + "cad/" + file, "tool");
    benchmark::DoNotOptimize(imp.entities.data());
  }
}
BENCHMARK_CAPTURE(BM_ImportCad, cylinder_step, "cylinder.step")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ImportCad, cylinder_iges, "cylinder.igs")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ImportCad, torus_step, "torus.step")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ImportCad, bspline_face, "bspline_face.step")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ImportCad, plate_with_hole, "plate_with_hole.step")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ImportCad, sheave_v30, "sheave_v30.step")->Unit(benchmark::kMillisecond);

/// The bicubic free-form patch of data/freeform_bicubic.json trimmed by its rectangle and a
/// hole: a circle of radius 0.2 of the parameter square about its centre (1000-point polygon).
TrimmedSurface holed(const NurbsSurface& s) {
  const Domain2 d = s.domain();
  const Vector2d c(0.5 * (d.u.lo + d.u.hi), 0.5 * (d.v.lo + d.v.hi));
  const double ru = 0.2 * (d.u.hi - d.u.lo), rv = 0.2 * (d.v.hi - d.v.lo);
  TrimmedSurface::Loop outer = {
      {d.u.lo, d.v.lo}, {d.u.hi, d.v.lo}, {d.u.hi, d.v.hi}, {d.u.lo, d.v.hi}};
  TrimmedSurface::Loop hole;
  for (int k = 0; k < 1000; ++k) {
    const double t = 2 * std::numbers::pi * k / 1000;
    hole.emplace_back(c[0] + ru * std::cos(t), c[1] + rv * std::sin(t));
  }
  return {s, {outer, hole}, {}, 0.0};
}

/// Points within 5 % of the size of the surface whose feet lie inside the region (their
/// parameters outside the hole by a margin).
std::vector<Vector3d> points(const NurbsSurface& s) {
  std::mt19937 g(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Domain2 d = s.domain();
  std::vector<Vector3d> out;
  while (out.size() < 2000) {
    const double a = U(g), b = U(g);
    if (std::hypot(a - 0.5, b - 0.5) < 0.25) continue;
    const double u = d.u.lo + a * (d.u.hi - d.u.lo), v = d.v.lo + b * (d.v.hi - d.v.lo);
    const SurfaceDerivs sd = s.derivs(u, v, 1);
    out.push_back(sd.S + 0.05 * (2 * U(g) - 1) * sd.Su.cross(sd.Sv).normalized());
  }
  return out;
}

void BM_ClosestPoint(benchmark::State& state, bool trimmed) {
  const NurbsSurface s = test::data_surface("freeform_bicubic.json");
  RigidSurface rs;
  if (trimmed)
    rs.add(holed(s));
  else
    rs.add(s);
  const std::vector<Vector3d> x = points(s);
  for (auto _ : state)
    for (const Vector3d& p : x) benchmark::DoNotOptimize(rs.closest_point(p).point);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(x.size()));
}
BENCHMARK_CAPTURE(BM_ClosestPoint, untrimmed, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ClosestPoint, trimmed_foot_inside, true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
