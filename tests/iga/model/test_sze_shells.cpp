// Nonlinear shell benchmarks of Sze, Liu & Lo (2004) as example models (issue 17): the hemisphere
// with an 18-degree hole (data/hemisphere_hole.json, a sphere zone built by the model format),
// whose load-deflection points at P/P_max = 0.05, 0.2, 0.5, 1 must lie within 1 % of the
// published ones. The suite runs 24 x 24 cubic elements; the mesh study (16, 24, 32) is tagged
// [.slow] and prints its table. The pinched cylinder (data/pinched_cylinder_nonlinear.json,
// arc length through its snap-backs): mesh study 24, 32, 40 [.slow], see its test case.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

struct Point {
  double load, pulled, pushed;  // P/P_max; outward at the pulled point, inward at the pushed one
};
// Sze, Liu & Lo (2004), Table for the hemispherical shell (BENCHMARKS.md).
constexpr std::array<Point, 4> kHemisphere = {
    {{0.05, 0.855, 0.955}, {0.2, 2.321, 3.261}, {0.5, 3.406, 5.902}, {1.0, 4.067, 8.178}}};

/// The model data/<file> with its patch `patch` refined into n x n elements, run to its end
/// without ParaView output.
AnalysisResult run_refined(const std::string& file, const char* patch, int n) {
  Json doc = read_json_file(kData + file);
  doc["geometry"][patch]["refine"]["subdivide"] = n;
  doc["output"]["vtk"] = "none";
  Analysis a = Analysis::from_json(doc, file);
  AnalysisResult r = a.run();
  REQUIRE(r.solver.converged());
  return r;
}

/// The hemisphere at n x n elements: the computed points at the reference loads (the model's
/// hit_times and t_end), and the worst relative deviation.
double hemisphere(int n, std::vector<Point>& computed) {
  const AnalysisResult r = run_refined("hemisphere_hole.json", "hemisphere", n);
  double worst = 0.0;
  for (const Point& ref : kHemisphere)
    for (const AnalysisStep& st : r.steps)
      if (st.t == ref.load) {
        const Point p{st.t, st.displacements.at(0).x(), -st.displacements.at(1).y()};
        computed.push_back(p);
        worst = std::max(
            {worst, std::abs(p.pulled / ref.pulled - 1.0), std::abs(p.pushed / ref.pushed - 1.0)});
      }
  REQUIRE(computed.size() == kHemisphere.size());
  return worst;
}

void print(int n, const std::vector<Point>& c) {
  for (std::size_t k = 0; k < c.size(); ++k)
    std::printf(
        "  %2d x %2d  P/P_max %.2f: pulled %.4f (%.4f, %+.2f %%), pushed %.4f (%.4f, %+.2f %%)\n",
        n, n, c[k].load, c[k].pulled, kHemisphere[k].pulled,
        100.0 * (c[k].pulled / kHemisphere[k].pulled - 1.0), c[k].pushed, kHemisphere[k].pushed,
        100.0 * (c[k].pushed / kHemisphere[k].pushed - 1.0));
}

}  // namespace

TEST_CASE("Sze, Liu & Lo: the hemisphere with a hole within 1 % of the published path (24 x 24)",
          "[iga][model][sze]") {
  std::vector<Point> c;
  const double worst = hemisphere(24, c);
  std::printf("hemisphere with an 18-degree hole, Kirchhoff-Love, cubic:\n");
  print(24, c);
  CHECK(worst < 0.01);
}

TEST_CASE("Sze, Liu & Lo: hemisphere mesh study 16, 24, 32", "[iga][model][sze][.slow]") {
  double previous = 1.0;
  for (int n : {16, 24, 32}) {
    std::vector<Point> c;
    const double worst = hemisphere(n, c);
    print(n, c);
    std::printf("  %2d x %2d  worst deviation %.2f %%\n", n, n, 100.0 * worst);
    if (n > 16) CHECK(worst < previous);  // converging towards the published path
    previous = worst;
  }
  CHECK(previous < 0.01);
}

namespace {

struct CylinderPoint {
  double load, wa, ub;  // P/P_max; -W_A under the load, U_B at the side of the mid-section
};
// Sze, Liu & Lo (2004), the pinched cylinder with rigid diaphragms (BENCHMARKS.md).
constexpr std::array<CylinderPoint, 4> kCylinder = {
    {{0.1, 23.164, -2.391}, {0.2, 56.373, 10.448}, {0.5, 73.790, 25.381}, {1.0, 83.102, 34.272}}};

/// The pinched cylinder at n x n elements under arc length: every state of the path at the
/// reference loads (the path may cross a load more than once: snap-backs), in path order.
std::vector<CylinderPoint> cylinder(int n) {
  const AnalysisResult r = run_refined("pinched_cylinder_nonlinear.json", "cylinder", n);
  std::vector<CylinderPoint> c;
  for (const AnalysisStep& st : r.steps)
    for (const CylinderPoint& ref : kCylinder)
      if (st.t == ref.load)
        c.push_back({st.t, -st.displacements.at(0).z(), st.displacements.at(1).x()});
  return c;
}

const CylinderPoint& reference(double load) {
  for (const CylinderPoint& p : kCylinder)
    if (p.load == load) return p;
  FAIL("no reference point at " << load);
  return kCylinder[0];
}

}  // namespace

// The Kirchhoff-Love cylinder converges (24 -> 32 -> 40) to a path close to, but not on, the
// published one (Sze et al.: ABAQUS S4R, shear deformable, one mesh): -W_A within 1 % from
// P/P_max = 0.2 on and 2 % at 0.1, U_B 3-7 % above the table (the same sign and shape; the
// snap-backs around P/P_max = 0.2 and 0.5 are where the meshes differ most). The checks are
// those: at 40 x 40, the last state at each reference load (the path that goes on to P_max),
// -W_A within 1 % at 0.5 and 1.0 and within 2 % at 0.1 and 0.2, U_B within 8 %; and the end
// point converging: 32 -> 40 moves -W_A and U_B by less than 0.5 %.
TEST_CASE("Sze, Liu & Lo: pinched cylinder mesh study 24, 32, 40 (arc length)",
          "[iga][model][sze][.slow]") {
  std::printf("pinched cylinder with rigid diaphragms, Kirchhoff-Love, cubic, arc length:\n");
  std::vector<CylinderPoint> last;
  std::vector<CylinderPoint> previous_end;
  for (int n : {24, 32, 40}) {
    const std::vector<CylinderPoint> c = cylinder(n);
    for (const CylinderPoint& p : c) {
      const CylinderPoint& ref = reference(p.load);
      std::printf(
          "  %2d x %2d  P/P_max %.1f: -W_A %8.3f (%7.3f, %+6.2f %%), U_B %8.3f (%7.3f, %+6.2f "
          "%%)\n",
          n, n, p.load, p.wa, ref.wa, 100.0 * (p.wa / ref.wa - 1.0), p.ub, ref.ub,
          100.0 * (p.ub / ref.ub - 1.0));
    }
    REQUIRE(!c.empty());
    REQUIRE(c.back().load == 1.0);
    if (n == 32) previous_end = {c.back()};
    last = c;
  }
  for (const CylinderPoint& ref : kCylinder) {
    const CylinderPoint* p = nullptr;
    for (const CylinderPoint& q : last)
      if (q.load == ref.load) p = &q;
    REQUIRE(p != nullptr);
    CHECK(std::abs(p->wa / ref.wa - 1.0) < (ref.load >= 0.5 ? 0.01 : 0.02));
    CHECK(std::abs(p->ub / ref.ub - 1.0) < 0.08);
  }
  REQUIRE(previous_end.size() == 1);
  CHECK(std::abs(last.back().wa / previous_end[0].wa - 1.0) < 0.005);
  CHECK(std::abs(last.back().ub / previous_end[0].ub - 1.0) < 0.005);
}
