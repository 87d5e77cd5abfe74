// Benchmarks of the broad phase of the contact search (contact/contact_search.hpp): query
// points x Bezier element boxes of a subdivided NURBS torus, CGAL box_intersection_d ([ZE02])
// and the grid RigidBoxIndex (built once, queries timed) against a prebuilt CGAL::AABB_tree over
// the same enlarged boxes and the O(n m) brute force. Points lie on and near the torus
// (|offset| <= 0.05 along the normal), the search distance is 0.05. Items per second = query points
// per second; the counter "pairs" is the number of candidate pairs found. Run:
// build-cgal/bench/bench_contact_search --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <utility>
#include <vector>

#include "contact/contact_search.hpp"
#include "geometry/constructions.hpp"
#include "geometry/differential_geometry.hpp"
#include "geometry/refinement.hpp"

using namespace iga;

namespace {

constexpr double kR = 2.0, kr = 0.5, kOffset = 0.05, kDistance = 0.05;

/// The torus has 4 x 4 quadratic elements; subdivide into 16 * parts_u * parts_v
/// = n_elements, parts_u >= parts_v as close as possible (128: 4 x 2, 1024: 8 x 8).
NurbsSurface torus_with(int n_elements) {
  const int parts = n_elements / 16;
  int pv = static_cast<int>(std::sqrt(static_cast<double>(parts)));
  while (parts % pv != 0) --pv;
  return subdivide(make_torus(Vector3d::Zero(), Vector3d::UnitZ(), kR, kr), parts / pv, pv);
}

std::vector<Box3> element_boxes(const NurbsSurface& s) {
  std::vector<Box3> boxes;
  for (const BezierPatch& b : bezier_extract(s)) boxes.push_back(bounding_box(b));
  return boxes;
}

std::vector<Vector3d> points_near(const NurbsSurface& s, std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0), off(-kOffset, kOffset);
  const Domain2 D = s.domain();
  std::vector<Vector3d> p(n);
  for (Vector3d& x : p) {
    const double u = D.u.lo + u01(rng) * (D.u.hi - D.u.lo);
    const double v = D.v.lo + u01(rng) * (D.v.hi - D.v.lo);
    const SurfaceDerivs d = s.derivs(u, v, 1);
    x = d.S + off(rng) * surface_frame(d).n;
  }
  return p;
}

struct Setup {
  std::vector<Box3> boxes;
  std::vector<Vector3d> points;
};
Setup setup(const benchmark::State& state) {
  const NurbsSurface s = torus_with(static_cast<int>(state.range(1)));
  return Setup{element_boxes(s), points_near(s, static_cast<std::size_t>(state.range(0)), 7)};
}

void report(benchmark::State& state, const Setup& c, std::size_t pairs) {
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(c.points.size()));
  state.counters["elements"] = static_cast<double>(c.boxes.size());
  state.counters["pairs"] = static_cast<double>(pairs);
}

void BM_BroadPhaseCgal(benchmark::State& state) {
  const Setup c = setup(state);
  std::size_t pairs = 0;
  for (auto _ : state) {
    std::vector<SearchPair> r = broad_phase(c.points, c.boxes, kDistance);
    pairs = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  report(state, c, pairs);
}

// The index is built once (the rigid surface does not move); only the queries are timed.
void BM_RigidBoxIndexQuery(benchmark::State& state) {
  const Setup c = setup(state);
  const RigidBoxIndex index(c.boxes, kDistance);
  std::size_t pairs = 0;
  for (auto _ : state) {
    std::vector<SearchPair> r = index.query(c.points);
    pairs = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  report(state, c, pairs);
}

// Build + query, for a rigid surface that changes every search.
void BM_RigidBoxIndexBuildQuery(benchmark::State& state) {
  const Setup c = setup(state);
  std::size_t pairs = 0;
  for (auto _ : state) {
    const RigidBoxIndex index(c.boxes, kDistance);
    std::vector<SearchPair> r = index.query(c.points);
    pairs = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  report(state, c, pairs);
}

// CGAL::AABB_tree over the element boxes enlarged by the distance (Iso_cuboid_3 primitives),
// built once; one all_intersected_primitives per point, the ids sorted per point as the
// other methods give them.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct BoxPrimitive {
  using Id = int;
  using Datum = Kernel::Iso_cuboid_3;
  using Point = Kernel::Point_3;
  using Item = std::pair<int, Datum>;
  BoxPrimitive() = default;
  explicit BoxPrimitive(std::vector<Item>::const_iterator it) : id_(it->first), box_(it->second) {}
  Id id() const { return id_; }
  const Datum& datum() const { return box_; }
  Point reference_point() const { return box_.min(); }

 private:
  Id id_ = 0;
  Datum box_;
};
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, BoxPrimitive>>;

void BM_AabbTreeQuery(benchmark::State& state) {
  const Setup c = setup(state);
  std::vector<BoxPrimitive::Item> items;
  for (std::size_t e = 0; e < c.boxes.size(); ++e) {
    const Vector3d lo = c.boxes[e].lo - Vector3d::Constant(kDistance);
    const Vector3d hi = c.boxes[e].hi + Vector3d::Constant(kDistance);
    items.emplace_back(static_cast<int>(e),
                       BoxPrimitive::Datum(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()));
  }
  AabbTree tree(items.cbegin(), items.cend());
  tree.build();
  std::size_t pairs = 0;
  std::vector<int> ids;
  for (auto _ : state) {
    std::vector<SearchPair> r;
    for (std::size_t q = 0; q < c.points.size(); ++q) {
      ids.clear();
      const Vector3d& x = c.points[q];
      tree.all_intersected_primitives(Kernel::Point_3(x.x(), x.y(), x.z()),
                                      std::back_inserter(ids));
      std::sort(ids.begin(), ids.end());
      for (int e : ids) r.push_back({static_cast<int>(q), e});
    }
    pairs = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  report(state, c, pairs);
}

void BM_BroadPhaseBruteForce(benchmark::State& state) {
  const Setup c = setup(state);
  std::size_t pairs = 0;
  for (auto _ : state) {
    std::vector<SearchPair> r = broad_phase_brute_force(c.points, c.boxes, kDistance);
    pairs = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  report(state, c, pairs);
}

// (points, elements): 1e3, 1e4, 1e5 points x 128 (~1e2) and 1024 (~1e3) torus elements.
void scaling(benchmark::internal::Benchmark* b) {
  for (std::int64_t n : {1000, 10000, 100000})
    for (std::int64_t m : {128, 1024}) b->Args({n, m});
  b->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(BM_BroadPhaseCgal)->Apply(scaling);
BENCHMARK(BM_RigidBoxIndexQuery)->Apply(scaling);
BENCHMARK(BM_RigidBoxIndexBuildQuery)->Apply(scaling);
BENCHMARK(BM_AabbTreeQuery)->Apply(scaling);
// At most 1e5 x 1024 ~ 1e8 box tests (~0.15 s): all sizes are run.
BENCHMARK(BM_BroadPhaseBruteForce)->Apply(scaling);
BENCHMARK_MAIN();
