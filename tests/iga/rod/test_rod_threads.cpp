// The rods' assembly on several OpenMP threads (issue 17, item 4): the same internal forces and
// tangent triplets, bit for bit, with 1 and 2 threads (each element writes its own slots, the
// forces are summed in element order by one thread), on rods above the parallel thresholds.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/rod/kirchhoff_rod.hpp"
#include "iga/rod/twisting_rod.hpp"
#include "tests/iga/same_bits.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_rod_threads {

using namespace iga;

namespace {

/// A quarter circle of radius 2, cubic, in n elements.
NurbsCurve arc(int n) {
  const NurbsCurve c = make_circular_arc(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                         2.0, 0.0, std::numbers::pi / 2);
  return subdivide(elevate_degree(c, 1), n);
}

/// The reference points moved out of the plane and along it (a deformed state).
std::vector<Vector3d> deformed(std::vector<Vector3d> x) {
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] += 0.01 * Vector3d(std::sin(1.0 + i), std::cos(2.0 * i), std::sin(0.5 * i));
  return x;
}

}  // namespace

TEST_CASE("KirchhoffRod: assembly on 1 and 2 threads is the same bit for bit",
          "[iga][rod][threads]") {
  const KirchhoffRod rod(arc(kParallelRodElements + 32), RodSection::circular(1e5, 0.02));
  REQUIRE(rod.num_elements() >= kParallelRodElements);
  const std::vector<Vector3d> x = deformed(rod.reference().control_points());
  Eigen::VectorXd f1, f2;
  std::vector<Triplet> T1, T2;
  test::on_threads(1, [&] { rod.assemble(x, f1, &T1); });
  test::on_threads(2, [&] { rod.assemble(x, f2, &T2); });
  REQUIRE(f1.size() == f2.size());
  REQUIRE(T1.size() == T2.size());
  CHECK(f1.norm() > 0.0);
  CHECK(test::count_differences(f1, f2, T1, T2) == 0);
  // The forces alone (no tangent; element_forces, another computation than element_tangent's,
  // so compared to round-off, not bit for bit) are the tangent pass's.
  Eigen::VectorXd f3;
  test::on_threads(2, [&] { rod.assemble(x, f3, nullptr); });
  REQUIRE(f3.size() == f1.size());
  CHECK((f3 - f1).cwiseAbs().maxCoeff() <= 1e-12 * f1.cwiseAbs().maxCoeff());
}

TEST_CASE("TwistingRod: assembly on 1 and 2 threads is the same bit for bit",
          "[iga][rod][threads]") {
  RodSection s = RodSection::circular(1e5, 0.02);
  s.GJ = 0.8 * s.EI1;
  const TwistingRod rod(arc(kParallelTwistingRodElements + 8), s);
  REQUIRE(rod.num_elements() >= kParallelTwistingRodElements);
  const std::vector<Vector3d> x = deformed(rod.reference().control_points());
  std::vector<double> alpha(static_cast<std::size_t>(rod.num_knots()));
  for (std::size_t k = 0; k < alpha.size(); ++k) alpha[k] = 0.05 * std::sin(0.7 * k);
  Eigen::VectorXd f1, f2;
  std::vector<Triplet> T1, T2;
  test::on_threads(1, [&] { rod.assemble(x, alpha, f1, &T1); });
  test::on_threads(2, [&] { rod.assemble(x, alpha, f2, &T2); });
  REQUIRE(f1.size() == f2.size());
  REQUIRE(T1.size() == T2.size());
  CHECK(f1.norm() > 0.0);
  CHECK(test::count_differences(f1, f2, T1, T2) == 0);
}

}  // namespace test_rod_threads
