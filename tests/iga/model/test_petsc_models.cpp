// Models solved with PETSc's MUMPS ("solver": {"linear_solver": "mumps"}) against the same
// models with SuiteSparse: the arch through its limit points (arc length: symmetric indefinite
// tangents, MUMPS's LDL^T), the plate indented by a sphere (STAS) and a rod rolled up into a
// circle. Only models whose end state does not depend on the path are compared at the solvers'
// tolerance: two runs need not take the same steps (the round-off probe refuses steps on
// purpose), and friction, or an augmented Lagrangian that stops updating at a tolerance, make
// the end state depend on them (two_ropes differs by 5e-5 so).
// (MUMPS's LU on non-symmetric systems: tests/iga/solvers/test_petsc_solver.cpp.) The
// monitors, reactions and tool loads at the end agree to the solvers' tolerance; the run takes
// PETSc's factorizations only. A build without PETSc refuses the choice at its JSON path.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "iga/model/analysis.hpp"
#include "iga/parallel/communicator.hpp"
#include "tests/iga/analysis_error.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_petsc_models {

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

AnalysisResult run(const std::string& file, const char* method) {
  Json doc = read_json_file(kData + file);
  doc["solver"]["linear_solver"] = method;
  // To t_end: where a run stops at the sliding plateau depends on its steps.
  doc["solver"].erase("stop_at_full_slip_after");
  if (doc.contains("output")) doc["output"]["vtk"] = "none";
  Analysis a = Analysis::from_json(doc, file);
  return a.run();
}

/// max |a_i - b_i| over the entries, over max |a_i|: the largest difference relative to the
/// quantity's scale (components near zero compared at that scale).
double difference(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b) {
  REQUIRE(a.size() == b.size());
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, (a[i] - b[i]).cwiseAbs().maxCoeff());
    scale = std::max(scale, a[i].cwiseAbs().maxCoeff());
  }
  return scale > 0.0 ? diff / scale : diff;
}

}  // namespace

TEST_CASE("Models with MUMPS: the end state of SuiteSparse's run, to the solvers' tolerance",
          "[iga][model][petsc]") {
  if (!parallel_build()) {
    const std::string e =
        test::analysis_error(read_json_file(kData + "arch_snap.json"),
                             [](Json& d) { d["solver"]["linear_solver"] = "mumps"; });
    CHECK_THAT(e,
               Catch::Contains("/solver/linear_solver") && Catch::Contains("IGA_WITH_PETSC=OFF"));
    return;
  }
  for (const char* file : {"arch_snap.json", "indented_plate.json", "rollup.json"}) {
    INFO(file);
    const AnalysisResult s = run(file, "suitesparse"), m = run(file, "mumps");
    REQUIRE(s.solver.converged());
    REQUIRE(m.solver.converged());
    CHECK(m.solver.petsc_factorizations > 0);
    CHECK(m.solver.cholmod_factorizations + m.solver.ldlt_factorizations +
              m.solver.umfpack_factorizations ==
          0);
    CHECK(s.solver.petsc_factorizations == 0);
    const AnalysisStep &a = s.steps.back(), &b = m.steps.back();
    CHECK(b.t == Approx(a.t).epsilon(1e-12));
    // Newton's tolerance (relative 1e-8 of the residual, the scaled and energy tests) bounds
    // how far two converged states may differ: 1e-7 of each quantity's scale.
    CHECK(difference(a.displacements, b.displacements) < 1e-7);
    CHECK(difference(a.reactions, b.reactions) < 1e-7);
    std::vector<Vector3d> fa, fb;
    for (const auto& [f, mo] : a.tool_loads) fa.push_back(f);
    for (const auto& [f, mo] : b.tool_loads) fb.push_back(f);
    CHECK(difference(fa, fb) < 1e-7);
    // Two runs need not have the same active points where a point is on the edge of contact.
    CHECK(std::abs(b.contact.active - a.contact.active) <= std::max(1, a.contact.active / 100));
  }
}

}  // namespace test_petsc_models
