// Nonlinear shell benchmarks of Sze, Liu & Lo (2004) as example models (issue 17): the hemisphere
// with an 18-degree hole (data/hemisphere_hole.json, a sphere zone built by the model format),
// whose load-deflection points at P/P_max = 0.05, 0.2, 0.5, 1 must lie within 1 % of the
// published ones. The suite runs 24 x 24 cubic elements; the mesh study (16, 24, 32) is tagged
// [.slow] and prints its table. The pinched cylinder (data/pinched_cylinder_nonlinear.json,
// arc length through its snap-backs): mesh study, cubic and quartic [.slow], see its test case. The
// hinged roof of Sabir & Lock (data/hinged_roof.json, both thicknesses): arc length through both
// load limit points, the first maximum against the published one.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"
#include "iga/solvers/roundoff_probe.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_sze_shells {

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

struct Point {
  double load, pulled, pushed;  // P/P_max; outward at the pulled point, inward at the pushed one
};
// Sze, Liu & Lo (2004), Table for the hemispherical shell (BENCHMARKS.md).
constexpr std::array<Point, 4> kHemisphere = {
    {{0.05, 0.855, 0.955}, {0.2, 2.321, 3.261}, {0.5, 3.406, 5.902}, {1.0, 4.067, 8.178}}};

/// The model data/<file> with its patch `patch` refined into n x n elements (and `edit`
/// applied), run to its end without ParaView output.
AnalysisResult run_refined(const std::string& file, const char* patch, int n,
                           const std::function<void(Json&)>& edit = {}) {
  Json doc = read_json_file(kData + file);
  doc["geometry"][patch]["refine"]["subdivide"] = n;
  doc["output"]["vtk"] = "none";
  if (edit) edit(doc);
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
          "[iga][model][sze][heavy]") {
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
std::vector<CylinderPoint> cylinder(int n, const std::function<void(Json&)>& edit = {}) {
  const AnalysisResult r = run_refined("pinched_cylinder_nonlinear.json", "cylinder", n, edit);
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

// The Kirchhoff-Love cylinder's path, cubic 32, 48, 64 and quartic 32, 48 elements. Before the
// first limit point (P/P_max = 0.1) and at P_max the finest two agree to 0.1 % (cubic 64:
// 23.615, -2.458 and 83.622, 35.632; quartic 48: 23.617, -2.458 and 83.636, 35.598): that is the
// converged path, and it lies above the published one (Sze et al.: ABAQUS S4R, shear deformable,
// one mesh) by 2.0 % (-W_A) and 2.8 % (U_B) at 0.1 and 0.6 %, 3.9 % at P_max. Coarser meshes
// scatter around it by a few per cent (quartic 32 happens to end within 1 % of the table: 83.162,
// 34.611). Around 0.2 and 0.5 the path snaps back (several states at one load, folds forming at
// mesh-dependent loads); the last state at each load is compared there, -W_A only. Checked: the
// finest two agree within 0.3 % at 0.1 and 1.0; against the table -W_A within 2 % at 0.1, 3 % at
// 0.2, 1 % at 0.5 and 1.0, U_B within 5 % at 0.1 and 1.0. The strains reach 5 % under the load
// at 0.1 and 15-24 % at the folds at P_max; the neo-Hookean law (cubic 64) moves the path by less
// than 1 % at 0.1 and 1.0 (23.445, -2.436; 83.873, 35.551): the law is not what separates the
// path from the table. (At 40 x 40 its end point happened to lie within 1 % of the table.)
TEST_CASE("Sze, Liu & Lo: pinched cylinder mesh study, cubic 32, 48, 64, quartic 32, 48",
          "[iga][model][sze][.slow]") {
  std::printf("pinched cylinder with rigid diaphragms, Kirchhoff-Love, arc length:\n");
  struct Mesh {
    int degree, n;
  };
  std::vector<std::vector<CylinderPoint>> finest;
  for (const Mesh m : {Mesh{3, 32}, Mesh{3, 48}, Mesh{3, 64}, Mesh{4, 32}, Mesh{4, 48}}) {
    const std::vector<CylinderPoint> c = cylinder(m.n, [&m](Json& d) {
      d["geometry"]["cylinder"]["refine"]["elevate"] = {m.degree - 2, m.degree - 1};
    });
    for (const CylinderPoint& p : c) {
      const CylinderPoint& ref = reference(p.load);
      std::printf(
          "  p = %d, %2d x %2d  P/P_max %.1f: -W_A %8.3f (%7.3f, %+6.2f %%), U_B %8.3f (%7.3f, "
          "%+6.2f %%)\n",
          m.degree, m.n, m.n, p.load, p.wa, ref.wa, 100.0 * (p.wa / ref.wa - 1.0), p.ub, ref.ub,
          100.0 * (p.ub / ref.ub - 1.0));
    }
    REQUIRE(!c.empty());
    REQUIRE(c.back().load == 1.0);
    if (m.n == 64 || (m.degree == 4 && m.n == 48)) finest.push_back(c);
  }
  REQUIRE(finest.size() == 2);
  const std::vector<CylinderPoint> nh =
      cylinder(64, [](Json& d) { d["materials"]["shell"]["law"] = "neo_hookean"; });
  REQUIRE(!nh.empty());
  REQUIRE(nh.back().load == 1.0);
  // The last state at each reference load (the path that goes on to P_max).
  const auto at = [](const std::vector<CylinderPoint>& c, double load) {
    const CylinderPoint* p = nullptr;
    for (const CylinderPoint& q : c)
      if (q.load == load) p = &q;
    REQUIRE(p != nullptr);
    return *p;
  };
  for (double load : {0.1, 1.0}) {
    const CylinderPoint a = at(finest[0], load), b = at(finest[1], load), c = at(nh, load);
    std::printf(
        "  neo-Hookean p = 3, 64 x 64  P/P_max %.1f: -W_A %8.3f (%+6.2f %% from St. "
        "Venant-Kirchhoff), U_B %8.3f (%+6.2f %%)\n",
        load, c.wa, 100.0 * (c.wa / a.wa - 1.0), c.ub, 100.0 * (c.ub / a.ub - 1.0));
    CHECK(std::abs(a.wa / b.wa - 1.0) < 0.003);
    CHECK(std::abs(a.ub / b.ub - 1.0) < 0.003);
    CHECK(std::abs(c.wa / a.wa - 1.0) < 0.01);
    CHECK(std::abs(c.ub / a.ub - 1.0) < 0.01);
  }
  for (const std::vector<CylinderPoint>& c : finest)
    for (const CylinderPoint& ref : kCylinder) {
      const CylinderPoint p = at(c, ref.load);
      const double tol_wa = ref.load == 0.1 ? 0.02 : ref.load == 0.2 ? 0.03 : 0.01;
      CHECK(std::abs(p.wa / ref.wa - 1.0) < tol_wa);
      if (ref.load == 0.1 || ref.load == 1.0) CHECK(std::abs(p.ub / ref.ub - 1.0) < 0.05);
    }
}

namespace {

// Sze, Liu & Lo (2004), Table 9 (isotropic hinged roofs, P_max = 3000): the first maximum of
// P/P_max along the path and the centre deflection W_C there.
struct RoofReference {
  double h, load, wc;
};
constexpr std::array<RoofReference, 2> kRoof = {{{12.7, 0.7421, 11.293}, {6.35, 0.1953, 12.892}}};

struct RoofPath {
  double max_load = 0.0, max_wc = 0.0;  // the first load maximum (the sampled state)
  double min_load = 0.0, min_wc = 0.0;  // the load minimum after it
  double load_at_wc = 0.0;  // the load where W_C first reaches the published W_C (interpolated)
  bool snaps_back = false;  // W_C decreases somewhere along the path
};

/// The hinged roof of thickness h at n x n cubic elements under arc length to P_max.
RoofPath roof(const RoofReference& ref, int n) {
  const AnalysisResult r = run_refined("hinged_roof.json", "roof", n, [&](Json& doc) {
    doc["materials"]["shell"]["thickness"] = ref.h;
  });
  auto wc = [&](std::size_t k) { return -r.steps[k].displacements.at(0).z(); };
  const std::vector<LoadLimitPoint> limits = load_limit_points(r.steps);
  REQUIRE(limits.size() == 2);  // a maximum, then a minimum, then up to P_max
  REQUIRE(limits[0].maximum);
  REQUIRE_FALSE(limits[1].maximum);
  RoofPath p;
  p.max_load = r.steps[limits[0].index].t;
  p.max_wc = wc(limits[0].index);
  p.min_load = r.steps[limits[1].index].t;
  p.min_wc = wc(limits[1].index);
  double w0 = 0.0, t0 = 0.0;  // the unloaded state
  bool found = false;
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const double w1 = wc(k), t1 = r.steps[k].t;
    if (!found && w0 < ref.wc && w1 >= ref.wc) {
      p.load_at_wc = t0 + (t1 - t0) * (ref.wc - w0) / (w1 - w0);
      found = true;
    }
    if (w1 < w0) p.snaps_back = true;
    w0 = w1;
    t0 = t1;
  }
  REQUIRE(found);
  std::printf(
      "  h = %5.2f %2d x %2d: maximum P/P_max %.4f (%.4f, %+.2f %%) at W_C %.3f; P/P_max at "
      "W_C = %.3f: %.4f (%+.2f %%); minimum %.4f at W_C %.3f; %s\n",
      ref.h, n, n, p.max_load, ref.load, 100.0 * (p.max_load / ref.load - 1.0), p.max_wc, ref.wc,
      p.load_at_wc, 100.0 * (p.load_at_wc / ref.load - 1.0), p.min_load, p.min_wc,
      p.snaps_back ? "snaps back in W_C" : "W_C rising throughout");
  return p;
}

// The published table gives the path as sampled states; its first maximum (load and W_C) is the
// point compared. The load maximum is flat in W_C (dP/dW_C = 0), so W_C at a sampled maximum is
// ill-conditioned: the checks are the maximum load, and the load on our path at the published
// W_C, both within 1 %. The path must pass a maximum and then a minimum (the thin roof's minimum
// below zero: it holds itself snapped through) and rise again to P_max; the thin roof also snaps
// back in W_C, the thick one does not (the published curves' shapes).
void check_roof(const RoofReference& ref, const RoofPath& p) {
  CHECK(std::abs(p.max_load / ref.load - 1.0) < 0.01);
  CHECK(std::abs(p.load_at_wc / ref.load - 1.0) < 0.01);
  CHECK(p.min_wc > p.max_wc);
  CHECK(p.min_load < 0.25 * p.max_load);
  CHECK((p.min_load < 0.0) == (ref.h < 10.0));
  CHECK(p.snaps_back == (ref.h < 10.0));
}

}  // namespace

TEST_CASE("Sze, Liu & Lo: the hinged roof through both limit points, the first maximum within 1 %",
          "[iga][model][sze][heavy]") {
  std::printf("hinged cylindrical roof (Sabir & Lock), Kirchhoff-Love, cubic, arc length:\n");
  for (const RoofReference& ref : kRoof) check_roof(ref, roof(ref, 8));
}

// 4 x 4 is within 0.3 % of the finer meshes; 8 x 8 and 16 x 16 agree to 1e-3 in the maximum
// and in the load at the published W_C, to 0.5 % in the minimum. The limit points are sampled
// states (the arc's steps fall differently on each mesh, a part of these differences); the thin
// roof's minimum lies on a sharp turn of the path, where the sampling is coarsest.
TEST_CASE("Sze, Liu & Lo: hinged roof mesh study 4, 8, 16", "[iga][model][sze][.slow]") {
  std::printf("hinged cylindrical roof (Sabir & Lock), Kirchhoff-Love, cubic, arc length:\n");
  for (const RoofReference& ref : kRoof) {
    const RoofPath coarse = roof(ref, 4);
    const RoofPath medium = roof(ref, 8);
    const RoofPath fine = roof(ref, 16);
    check_roof(ref, fine);
    CHECK(std::abs(coarse.max_load / fine.max_load - 1.0) < 3e-3);
    CHECK(std::abs(medium.max_load / fine.max_load - 1.0) < 1e-3);
    CHECK(std::abs(medium.min_load / fine.min_load - 1.0) < 5e-3);
    CHECK(std::abs(medium.load_at_wc / fine.load_at_wc - 1.0) < 1e-3);
  }
}

// Load control cannot follow the roof past its first maximum: the step that crosses it lands on
// the far branch (W_C from about 8 to 27) and is reported as a jump (its increment is many times
// the tangent's prediction; every other step's within 25 % of it), with the warning in the log.
TEST_CASE("Load control over the hinged roof's limit point: the jump is reported",
          "[iga][model][sze]") {
  // Probe off: the ratios of each step's jump to its predictor are the step control's own
  // measure, and a cut-back step changes them.
  const RoundoffProbeOff probe_off;
  Json doc = read_json_file(kData + "hinged_roof.json");
  doc["output"]["vtk"] = "none";
  doc["solver"]["control"] = "load";
  Analysis a = Analysis::from_json(doc, "hinged_roof.json");
  std::ostringstream log;
  std::vector<double> ratios, wc;
  const AnalysisResult r = a.run(&log, "", [&](const VectorXd&, double, const AnalysisStep& st) {
    wc.push_back(-st.displacements.at(0).z());
    return true;
  });
  REQUIRE(r.solver.converged());  // it reaches P_max, on the far branch
  for (const StepAttempt& at : r.solver.attempts)
    if (at.outcome == NewtonOutcome::converged) ratios.push_back(at.jump_ratio);
  REQUIRE(ratios.size() == wc.size());
  CHECK(r.solver.jumps == 1);
  int jumped = -1;
  for (std::size_t k = 0; k < ratios.size(); ++k) {
    if (ratios[k] > kJumpRatio)
      jumped = static_cast<int>(k);
    else
      CHECK(ratios[k] < 1.25);
  }
  REQUIRE(jumped > 0);
  const auto j = static_cast<std::size_t>(jumped);
  CHECK(wc[j - 1] < 11.293);  // before the published maximum's deflection
  CHECK(wc[j] > 19.5);        // beyond the minimum's: on the far branch
  CHECK_THAT(log.str(), Catch::Contains("jump:") && Catch::Contains("arc_length"));
}

}  // namespace test_sze_shells
