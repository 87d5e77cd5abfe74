// Benchmarks of the STAS contact integral (iga/contact_integrals/surface_contact.hpp) at the size
// of [KS15] Sect. 6.1-6.2: a 20 x 20 plate (20 x 20 bicubic elements, 7 x 7 contact points per
// element, 19,600 points) lying on the rigid hyperboloid z = a x y, a = 2.5e-2, over [-10, 10]^2,
// every point penetrating by 0.01 (all active). One iteration = one assemble. Arguments:
//   strategy (0 master, 1 slave), tangent (0 residual only, 1 residual and triplets),
//   rigid (0 bilinear NURBS patch, 1 analytic Hyperboloid).
// BM_SurfaceContactWarm: the steady state of a Newton iteration (every point warm-started from
// its last foot). BM_SurfaceContactCold: a fresh SurfaceContact per iteration (every point goes
// through the broad phase and a cold projection). BM_SurfaceContactPairMoving: the same warm
// assembly through the SurfaceContactPair, its tool still or moved (turned by 0.3 about the z
// axis through (1, 2, 0) and shifted) with the plate moved alike (the same contact): the cost
// of working in the tool's frame (points mapped back, residual and tangent turned forward).
// Items per second = contact points per second. Run:
// build/release/bench/bench_surface_contact --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/contact_integrals/surface_contact.hpp"
#include "iga/contact_integrals/surface_contact_pair.hpp"

using namespace iga;

namespace {

constexpr double kA = 2.5e-2, kHalf = 10.0, kH = 0.2, kDelta = 0.01;

// The bicubic plate following z = a x y (bilinear, hence exact) with its lower face at
// z = a x y - delta.
NurbsSurface plate() {
  std::vector<Vector3d> P = {
      {-kHalf, -kHalf, 0}, {kHalf, -kHalf, 0}, {-kHalf, kHalf, 0}, {kHalf, kHalf, 0}};
  NurbsSurface s(1, {0, 0, 1, 1}, 1, {0, 0, 1, 1}, P);
  s = subdivide(elevate_degree(s, 2, 2), 20, 20);
  std::vector<Vector3d> X = s.control_points();
  for (Vector3d& q : X) q.z() = kA * q.x() * q.y() - kDelta + 0.5 * kH;
  return NurbsSurface(3, s.knots_u().knots(), 3, s.knots_v().knots(), X);
}

RigidSurface rigid(int kind) {
  RigidSurface r;
  if (kind == 0)
    r.add(make_bilinear_hyperboloid(kA, -12.0, 12.0, -12.0, 12.0));
  else
    r.add(Hyperboloid(Placement{}, kA));
  return r;
}

SurfaceContactParameters parameters(const benchmark::State& state) {
  SurfaceContactParameters p;
  p.law.eps_n = 2.5e5;
  p.law.eps_t = 2.5e5;
  p.law.mu = 0.125;
  p.strategy = state.range(0) == 0 ? SurfaceContactStrategy::kRigidMaster
                                   : SurfaceContactStrategy::kRigidSlave;
  p.face = ShellFace::kLower;
  p.thickness = kH;
  p.points_per_direction = 7;
  p.search_distance = 1.0;
  return p;
}

void BM_SurfaceContactWarm(benchmark::State& state) {
  const NurbsSurface ref = plate();
  const RigidSurface body = rigid(static_cast<int>(state.range(2)));
  SurfaceContact sc(ref, body, parameters(state));
  const std::vector<Vector3d> x = ref.control_points();
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  std::vector<Eigen::Triplet<double>> K;
  sc.assemble(x, R, nullptr);
  sc.commit();  // friction history: the points stick
  std::vector<Eigen::Triplet<double>>* Kp = state.range(1) ? &K : nullptr;
  for (auto _ : state) {
    K.clear();
    sc.assemble(x, R, Kp);
    benchmark::DoNotOptimize(R.data());
  }
  const SurfaceContactCounts c = sc.counts();
  state.counters["active"] = c.active;
  state.counters["failed"] = c.failed;
  state.counters["triplets"] = static_cast<double>(K.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sc.points().size()));
}

void BM_SurfaceContactCold(benchmark::State& state) {
  const NurbsSurface ref = plate();
  const RigidSurface body = rigid(static_cast<int>(state.range(2)));
  const std::vector<Vector3d> x = ref.control_points();
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  std::size_t n = 0;
  for (auto _ : state) {
    SurfaceContact sc(ref, body, parameters(state));
    sc.assemble(x, R, nullptr);
    n = sc.points().size();
    benchmark::DoNotOptimize(R.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

void BM_SurfaceContactPairMoving(benchmark::State& state) {
  const NurbsSurface ref = plate();
  auto body = std::make_shared<const RigidSurface>(rigid(0));
  SurfaceContactParameters p = parameters(state);
  p.strategy = SurfaceContactStrategy::kRigidMaster;
  SurfaceContactPair pair(ref, body, p);
  std::vector<Vector3d> x = ref.control_points();
  if (state.range(0)) {
    auto m = std::make_shared<RigidMotion>();
    m->set_rotation(Vector3d(1, 2, 0), Vector3d::UnitZ(), 0.3, [](double) { return 1.0; });
    m->set_translation(Vector3d(0.5, -0.25, 0.1), [](double) { return 1.0; });
    const RigidPose pose = m->pose(1.0);
    for (Vector3d& q : x) q = pose.to_world(q);
    pair.set_motion(m);
  }
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  std::vector<Eigen::Triplet<double>> K;
  pair.add(BodyState{x, {}, nullptr}, 1.0, R, nullptr);
  pair.commit();
  std::vector<Eigen::Triplet<double>>* Kp = state.range(1) ? &K : nullptr;
  for (auto _ : state) {
    K.clear();
    R.setZero();
    pair.add(BodyState{x, {}, nullptr}, 1.0, R, Kp);
    benchmark::DoNotOptimize(R.data());
  }
  state.counters["active"] = pair.counts().active;
  state.counters["triplets"] = static_cast<double>(K.size());
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(pair.contact().points().size()));
}

}  // namespace

BENCHMARK(BM_SurfaceContactPairMoving)
    ->ArgNames({"moving", "tangent"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceContactWarm)
    ->ArgNames({"slave", "tangent", "analytic"})
    ->ArgsProduct({{0, 1}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceContactCold)
    ->ArgNames({"slave", "tangent", "analytic"})
    ->ArgsProduct({{0, 1}, {0}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
