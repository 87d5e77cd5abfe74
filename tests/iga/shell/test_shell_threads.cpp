// The shell's assembly on several OpenMP threads (issue 17, item 4): the same internal forces and
// tangent triplets, bit for bit, with 1 and 2 threads (each element writes its own slots, the
// forces are summed in element order by one thread), on a mesh above the parallel threshold.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/shell/kirchhoff_love_shell.hpp"
#include "tests/iga/same_bits.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_shell_threads {

using namespace iga;

TEST_CASE("KirchhoffLoveShell: assembly on 1 and 2 threads is the same bit for bit",
          "[iga][shell][threads]") {
  NurbsSurface s =
      make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0, 0.0, 1.5);
  s = subdivide(elevate_degree(s, 1, 2), 12, 12);
  const KirchhoffLoveShell shell(s, {1e4, 0.3, 0.02});
  REQUIRE(shell.num_elements() >= kParallelElements);
  std::vector<Vector3d> x = shell.reference_points();
  for (std::size_t i = 0; i < x.size(); ++i)  // a deformed state
    x[i] += 0.01 * Vector3d(std::sin(1.0 + i), std::cos(2.0 * i), std::sin(0.5 * i));
  Eigen::VectorXd f1, f2;
  std::vector<Triplet> T1, T2;
  test::on_threads(1, [&] { shell.assemble(x, f1, &T1); });
  test::on_threads(2, [&] { shell.assemble(x, f2, &T2); });
  REQUIRE(f1.size() == f2.size());
  REQUIRE(T1.size() == T2.size());
  CHECK(f1.norm() > 0.0);
  CHECK(test::count_differences(f1, f2, T1, T2) == 0);
}

}  // namespace test_shell_threads
