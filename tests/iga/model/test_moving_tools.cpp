// Rigid tools that move (issue 14, item 3): a belt on a driven drum reaches T0 e^{+-mu phi} at
// its anchored end depending on the sense of rotation and first sticks under a small one, the
// drum's torque balances the tensions; the contact of a pair whose tool and body are moved
// together by a large rigid motion is the same, turned (residual, states, force on the tool);
// its tangent for a moving, rotating tool equals central differences of its residual in stick
// and in slip; the capstan carried by a large rigid motion as a whole (drum, anchor and load
// following it) gives the T/T0 of the still one; the "rigid_motions" section is checked like
// every other.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "iga/contact_integrals/curve_contact_pair.hpp"
#include "iga/model/analysis.hpp"
#include "iga/rod/kirchhoff_rod.hpp"
#include "tests/iga/analysis_error.hpp"
#include "tests/iga/fd_tangent.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_moving_tools {

using namespace iga;

namespace {

namespace fs = std::filesystem;

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";
constexpr double kMu = 0.3, kT0 = 10.0, kRho = 1.02;  // data/driven_drum.json

AnalysisResult run_drum(Analysis& a, const std::string& dir = {}) {
  return a.run(nullptr, dir);
}

/// data/driven_drum.json with the drum turned by up to `angle` over t in [1, 2], run to t_end.
Json drum(double angle, double t_end = 2.0) {
  Json doc = read_json_file(kData + "driven_drum.json");
  doc["rigid_motions"]["cylinder"]["rotation"]["angle"] = angle;
  doc["solver"]["t_end"] = t_end;
  doc["output"]["vtk"] = "last";
  return doc;
}

/// A contact pair as the "Contact" of test::tangent_error: assemble = add at a fixed t.
struct PairAtTime {
  ContactPair& pair;
  double t;
  void assemble(const std::vector<Vector3d>& x, VectorXd& R, std::vector<Triplet>* K) {
    pair.add(BodyState{x, {}, nullptr}, t, R, K);
  }
};

/// test::tangent_error, leaving out the columns whose central difference crosses a kink of the
/// contact law: where the pair's counts of active, sticking and sliding points at x + s e_j or
/// x - s e_j differ from those at x, the difference is no derivative. Each column is compared
/// with the differences of steps from h down to h / 100, the nearest taken: a point sliding at an
/// end of the arc, where the pressure and the cone are small, bends the law's return map sharply
/// (truncation error at h), while the multipliers' round-off limits the smaller step elsewhere.
/// `skipped`: the columns left out (a kink within both steps).
double tangent_error_off_kinks(PairAtTime& c, const std::vector<Vector3d>& x, double h,
                               int& skipped) {
  test::residual(c, x);
  const ContactCounts at_x = c.pair.counts();
  const auto same_counts = [&] {
    const ContactCounts n = c.pair.counts();
    return n.active == at_x.active && n.stick == at_x.stick && n.slip == at_x.slip;
  };
  return test::tangent_error(c, x, {h, h / 3, h / 10, h / 30, h / 100}, same_counts, &skipped);
}

}  // namespace

TEST_CASE("moving tools: a belt on a driven drum carries T0 e^{+-mu phi} at its anchored end",
          "[iga][analysis][moving_tools]") {
  const double phi = std::numbers::pi;
  for (const double angle : {0.05, -0.05}) {
    Analysis a = Analysis::from_json(drum(angle), "driven_drum.json");
    const std::string dir = test::fresh_out_dir("moving_tools", angle > 0 ? "towards" : "away");
    const AnalysisResult r = run_drum(a, dir);
    REQUIRE(r.full_slip);
    REQUIRE(r.steps.back().t > 1.0);  // the drum has turned
    const double ratio = r.steps.back().reactions.at(0).norm() / kT0;
    const double exact = std::exp((angle > 0 ? kMu : -kMu) * phi);
    INFO("turned by " << angle << ": T_B / T0 = " << ratio << ", exact " << exact);
    CHECK(std::abs(ratio / exact - 1.0) < 5e-3);  // the issue's bound
    CHECK(std::abs(ratio / exact - 1.0) < 5e-4);  // what exact enforcement gives
    // The torque on the drum about its axis balances the tensions of the two spans, whose
    // lines of action are tangent to the rope's centre circle: M_z = -(T_B - T_A) rho.
    const auto [F, M] = r.steps.back().tool_loads.at(0);
    CHECK(M.z() == Approx(-(ratio - 1.0) * kT0 * kRho).epsilon(2e-3));
    CHECK(F.norm() == Approx((ratio + 1.0) * kT0).epsilon(2e-3));  // both spans along -y
    // The moving drum is written where it is, a series rigid.pvd (vtk "all" in the data file is
    // switched off here: the last step's files only).
    CHECK(fs::exists(fs::path(dir) / "last_rigid.vts"));
    CHECK(test::slurp(fs::path(dir) / "steps.csv").find("rope_on_drum_Mz") != std::string::npos);
  }
  // A small rotation first: part of the arc sticks and T_B lies between the two limits.
  Analysis a = Analysis::from_json(drum(2e-4, 1.1), "driven_drum.json");
  const AnalysisResult r = run_drum(a);
  REQUIRE(r.solver.status == NonlinearSolverStatus::converged);
  const double ratio = r.steps.back().reactions.at(0).norm() / kT0;
  INFO("after turning by 2e-5: " << a.pair(0).status() << ", T_B / T0 = " << ratio);
  // Part of the arc sticks. How much is not asked: after so small a turn most points lie near
  // the slip surface, where round-off and the step sequence decide the branch (the round-off
  // probe's seeds 0, 1 and 4 with libm's FMA paths masked leave 42, 56 and 4 of 61 sticking);
  // the tension between the two sliding limits below is what the sticking part gives.
  CHECK(r.steps.back().contact.stick > 0);
  CHECK(ratio > std::exp(-kMu * phi) * 1.01);
  CHECK(ratio < std::exp(kMu * phi) * 0.99);
}

TEST_CASE(
    "moving tools: tool and body moved together give the same contact, turned, and the tangent "
    "of a moving, rotating tool equals central differences (stick and slip)",
    "[iga][analysis][moving_tools][tangent]") {
  // The state: the first steps of the drum turning by up to 0.05 (t = 1.1, the arc slides);
  // the pair evaluated at t1 = t + 0.02 (turned on: every point slides) or t1 = t - 0.002
  // (turned back by 1e-4: every point sticks), so that the trial forces (66) have increments
  // and the law's kinks are farther than the difference step reaches (as the capstan's test).
  Analysis a = Analysis::from_json(drum(0.05, 1.1), "driven_drum.json");
  const AnalysisResult r = run_drum(a);
  REQUIRE(r.solver.status != NonlinearSolverStatus::failed);
  auto& rod = dynamic_cast<RodProblem&>(a.body(0));
  const std::vector<Vector3d> x = rod.current_points(r.u, r.solver.t);
  struct Case {
    double dt, h;  // h: the difference step (stick: round-off of the multipliers below 1e-6)
    const char* name;
  };
  for (const Case c : {Case{-0.002, 1e-5, "stick"}, Case{0.02, 1e-6, "slip"}}) {
    const double t1 = r.solver.t + c.dt;
    // The world: a large rigid motion G (turn about a skew axis, then a shift) of both the
    // body and the tool, x' = G x; the tool's motion becomes G o pose(t1), held fixed.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Vector3d(1, 2, 3).normalized()).matrix();
    const Vector3d shift(3.0, -2.0, 5.0);
    const RigidPose p1 = a.pair(0).pose(t1);
    const Eigen::AngleAxisd turn(Eigen::Matrix3d(R * p1.Q));
    auto moved_motion = std::make_shared<RigidMotion>();
    moved_motion->set_rotation(p1.c0, turn.axis(), turn.angle(), [](double) { return 1.0; });
    moved_motion->set_translation(R * p1.c + shift - p1.c0, [](double) { return 1.0; });
    std::unique_ptr<ContactPair> still = a.body(0).pair(0).clone();
    std::unique_ptr<ContactPair> moved = a.body(0).pair(0).clone();
    moved->set_motion(moved_motion);
    std::vector<Vector3d> xm = x;
    for (Vector3d& y : xm) y = R * y + shift;

    PairAtTime ps{*still, t1}, pm{*moved, t1};
    const VectorXd g = test::residual(ps, x), gm = test::residual(pm, xm);
    VectorXd g_turned = g;
    for (Eigen::Index i = 0; i < g.size(); i += 3) g_turned.segment<3>(i) = R * g.segment<3>(i);
    INFO(c.name << ": " << still->status() << " / moved: " << moved->status());
    REQUIRE(g.norm() > 0.0);
    CHECK((gm - g_turned).norm() <= 1e-10 * g.norm());
    const ContactCounts n = still->counts(), nm = moved->counts();
    CHECK(nm.active == n.active);
    CHECK(nm.stick == n.stick);
    CHECK(nm.slip == n.slip);
    // Every point sticks (slides) but a few at the arc's ends: the run's friction history
    // depends on its steps, which round-off changes (issue 34), and a point at an end may stick
    // with a traction that turning back pushes out of the cone (seen: up to 3 of 61).
    if (std::string(c.name) == "stick") CHECK(n.stick >= n.active - 4);
    if (std::string(c.name) == "slip") CHECK(n.slip >= n.active - 4);
    CHECK((moved->tool_force() - R * still->tool_force()).norm() <=
          1e-10 * still->tool_force().norm());
    // The tangent of the moving, rotating tool against central differences, where they cross
    // no kink of the law (a point at an end of the arc, near the cone or the gap's sign, may
    // change its state within h: at most two control points' columns).
    int skipped_m = 0, skipped_s = 0;
    CHECK(tangent_error_off_kinks(pm, xm, c.h, skipped_m) <= 1e-6);
    CHECK(tangent_error_off_kinks(ps, x, c.h, skipped_s) <= 1e-6);
    CHECK(skipped_m <= 6);
    CHECK(skipped_s <= 6);
  }
}

TEST_CASE(
    "moving tools: the capstan moved and turned as a whole during the run gives the T/T0 of the "
    "still one",
    "[iga][analysis][moving_tools]") {
  // Drum, the anchor B (pulled along its tangent, in the drum's frame) and the dead load T0 at
  // A (turning with the drum) carried by a large rigid motion from t = 0.5 on (T0 half applied):
  // a quarter turn over t in [0.5, 2] about the z axis through (3, 1, 0) and a shift by
  // (-2, 4, 0) (in the rope's plane: its z components stay fixed). Both runs go to t = 1.3 (the
  // arc slides from t ~ 1.05) with the secant predictor, which lets the moving one start each
  // step where the motion takes the rope; their step sizes differ (the moving one's are ~10
  // times smaller), so they agree to the solver's and the augmentation's tolerances. Steps land
  // on t = 0.1, ..., 1.2 in both: they are compared at those and the end, once both slide.
  Json still = read_json_file(kData + "capstan.json");
  still["solver"].erase("stop_at_full_slip_after");
  still["solver"]["t_end"] = 1.3;
  still["solver"]["predictor"] = "secant";
  Json grid = Json::array();
  for (int k = 1; k < 13; ++k) grid.push_back(k / 10.0);
  still["solver"]["hit_times"] = grid;
  Json moved = still;
  moved["load_curves"]["carry"] =
      Json::parse(R"({"type": "piecewise_linear", "points": [[0.5, 0], [2, 1]]})");
  moved["rigid_motions"] = Json::parse(R"({"cylinder": {
      "rotation": {"point": [3, 1, 0], "axis": [0, 0, 1], "angle": 1.5707963267948966,
                   "curve": "carry"},
      "translation": {"vector": [-2, 4, 0], "curve": "carry"}}})");
  moved["boundary_conditions"][1]["motion"] = "cylinder";
  moved["loads"][0]["motion"] = "cylinder";
  Analysis a = Analysis::from_json(still, "capstan.json");
  Analysis b = Analysis::from_json(moved, "moved.json");
  const AnalysisResult ra = a.run(), rb = b.run();
  REQUIRE(ra.solver.status == NonlinearSolverStatus::converged);
  REQUIRE(rb.solver.status == NonlinearSolverStatus::converged);
  const double ta = ra.steps.back().reactions.at(0).norm() / kT0;
  const double tb = rb.steps.back().reactions.at(0).norm() / kT0;
  INFO("T/T0 at t = 1.3: still " << ta << " (" << ra.steps.size() << " steps), moved " << tb << " ("
                                 << rb.steps.size() << " steps)");
  CHECK(ra.steps.back().contact.slip == ra.steps.back().contact.active);  // sliding
  CHECK(rb.steps.back().contact.slip == rb.steps.back().contact.active);
  int common = 0;
  double worst = 0.0;
  for (const AnalysisStep& sa : ra.steps)
    for (const AnalysisStep& sb : rb.steps)
      if (sa.t > 1.15 && std::abs(sa.t - sb.t) <= 1e-12) {  // 1.2 and 1.3: both slide
        ++common;
        const double Ta = sa.reactions.at(0).norm(), Tb = sb.reactions.at(0).norm();
        UNSCOPED_INFO("t = " << sa.t << ": T/T0 still " << Ta / kT0 << ", moved " << Tb / kT0);
        worst = std::max(worst, std::abs(Tb / Ta - 1.0));
      }
  CHECK(common == 2);
  // Within 2e-5 when only the motion changes the steps. With steps cut back elsewhere on the
  // path by round-off (the round-off probe, seeds 1, 2, 3: 1.3e-4, 1.6e-4, 0.9e-4) the runs
  // reach the sliding state by other paths through stick and slip, and with exact enforcement
  // each step's augmentations stop wherever the gap is within penetration_tol = 1e-4, so the
  // state depends on the path at that level (the penalty capstan of test_many_bodies.cpp agrees
  // to 1e-6 at common times whatever the paths). Hence 3e-4 here, and for the force on the drum.
  CHECK(worst < 3e-4);
  // The drum has moved: the force on it is the still one turned by the quarter turn so far.
  const Vector3d Fa = ra.steps.back().tool_loads.at(0).first;
  const Vector3d Fb = rb.steps.back().tool_loads.at(0).first;
  const double angle = 1.5707963267948966 * (1.3 - 0.5) / 1.5;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle, Vector3d::UnitZ()).matrix();
  INFO("|Fb - Q Fa| / |Fa| = " << (Fb - Q * Fa).norm() / Fa.norm());
  CHECK((Fb - Q * Fa).norm() < 3e-4 * Fa.norm());  // 1e-4 without path differences (above)
}

TEST_CASE(
    "moving tools: a plate indented by a sphere that moves down has the point-load slope of "
    "Timoshenko, master and slave agree into large deflection",
    "[iga][analysis][moving_tools]") {
  // data/indented_plate.json: simply supported square plate a = 1, h = 0.01, E = 1e7,
  // nu = 0.3; central point load: w = alpha P a^2 / D, alpha = 0.01160 (Timoshenko &
  // Woinowsky-Krieger 1959, Table 23). The first step (travel 6e-4, w = 0.04 h) is linear.
  const double E = 1e7, h = 0.01, nu = 0.3, D = E * h * h * h / (12.0 * (1.0 - nu * nu));
  Json doc = read_json_file(kData + "indented_plate.json");
  doc["solver"]["t_end"] = 0.3;
  doc["solver"]["max_step"] = 0.1;
  doc["solver"]["hit_times"] = {0.1, 0.2};  // common times of both runs, whatever their steps
  doc["output"]["vtk"] = "none";
  std::vector<std::vector<std::pair<double, double>>> paths;  // (t, P) per strategy
  for (const char* strategy : {"master", "slave"}) {
    doc["contact"][0]["strategy"] = strategy;
    Analysis a = Analysis::from_json(doc, "indented_plate.json");
    const AnalysisResult r = a.run();
    REQUIRE(r.solver.status == NonlinearSolverStatus::converged);
    const AnalysisStep& first = r.steps.front();
    REQUIRE(first.t <= 0.02 + 1e-12);  // 0.02, or less where it was cut back
    const double P = first.tool_loads.at(0).first.z(), w = -first.displacements.at(0).z();
    INFO(strategy << ": P = " << P << ", w = " << w << ", w D / (P a^2) = " << w * D / P);
    CHECK(w < 0.05 * h);                                // linear range
    CHECK(w * D / P == Approx(0.01160).epsilon(0.01));  // the issue's bound: 1 %
    std::vector<std::pair<double, double>> path;
    for (const AnalysisStep& st : r.steps) path.emplace_back(st.t, st.tool_loads.at(0).first.z());
    paths.push_back(path);
    // Large deflection at the end: w ~ h, the plate stiffer than linear (membrane forces).
    const AnalysisStep& last = r.steps.back();
    const double wl = -last.displacements.at(0).z(), Pl = last.tool_loads.at(0).first.z();
    CHECK(wl > 0.5 * h);
    CHECK(wl * D / Pl < 0.95 * 0.01160);
  }
  // At the times both runs reached (their adaptive steps may differ: round-off decides a
  // cutback here and there), the end t = 0.3 among them.
  int common = 0;
  bool end = false;
  for (const auto& [tm, Pm] : paths[0])
    for (const auto& [ts, Ps] : paths[1]) {
      if (std::abs(ts - tm) > 1e-12) continue;
      INFO("t = " << tm << ": master P " << Pm << ", slave " << Ps);
      CHECK(std::abs(Ps / Pm - 1.0) < 5e-3);
      ++common;
      end = end || std::abs(tm - 0.3) <= 1e-12;
    }
  CHECK(common >= 3);
  CHECK(end);
}

TEST_CASE(
    "moving tools: a ring crushed between two plates has delta = (pi/4 - 2/pi) P R^3 / EI, then "
    "a contact zone that grows to a flat",
    "[iga][analysis][moving_tools]") {
  // data/ring_between_plates.json: a quarter ring (R = 1, EI = 1, EA = 1e6, quartic elements)
  // with symmetry at both ends; the upper plate moves down by 0.4. Diametral point loads P on a
  // thin ring (Timoshenko; Roark): the loaded diameter shortens by (pi/4 - 2/pi) P R^3 / EI,
  // the other lengthens by (4 - pi) / (2 pi) P R^3 / EI. P: twice the quarter's plate force.
  Json doc = read_json_file(kData + "ring_between_plates.json");
  doc["output"]["vtk"] = "none";
  Analysis a = Analysis::from_json(doc, "ring_between_plates.json");
  const AnalysisResult r = a.run();
  REQUIRE(r.solver.status == NonlinearSolverStatus::converged);
  const double pi = std::numbers::pi;
  // The step at t = 0.005 (a hit time of the model: a step lands on it even after a cutback).
  const auto at_hit = [](const AnalysisResult& run) -> const AnalysisStep& {
    for (const AnalysisStep& st : run.steps)
      if (std::abs(st.t - 0.005) <= 1e-12) return st;
    FAIL("no step at t = 0.005");
    return run.steps.front();
  };
  const AnalysisStep& first = at_hit(r);
  const double P = 2.0 * first.tool_loads.at(0).first.y();
  const double dv = -2.0 * first.displacements.at(0).y(), dh = 2.0 * first.displacements.at(1).x();
  INFO("P = " << P << ", shortening " << dv << ", lengthening " << dh);
  CHECK(dv < 0.01);  // small deflection
  CHECK(dv / P == Approx(pi / 4 - 2 / pi).epsilon(0.01));
  CHECK(dh / P == Approx((4 - pi) / (2 * pi)).epsilon(0.01));
  // Large deflection: the contact zone grows from a point to a flat (many active points), the
  // ring softens first (the secant compliance grows) and the plate's force keeps rising.
  const AnalysisStep& last = r.steps.back();
  CHECK(first.contact.active <= 2);
  CHECK(last.contact.active >= 8);
  CHECK(-2.0 * last.displacements.at(0).y() == Approx(0.8).epsilon(0.01));  // plate travel 0.4
  double previous = 0.0;
  for (const AnalysisStep& st : r.steps) {
    CHECK(st.tool_loads.at(0).first.y() > previous);
    previous = st.tool_loads.at(0).first.y();
  }
  // The same model turned by 30 degrees about z (symmetry planes no longer normal to a
  // coordinate axis: the conditions take the local-basis path) gives the same state at
  // t = 0.005.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(pi / 6, Vector3d::UnitZ()).matrix();
  auto turn = [&](Json& v) {
    const Vector3d w = Q * Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    v = {w.x(), w.y(), w.z()};
  };
  Json turned = doc;
  for (Json& q : turned["geometry"]["ring"]["control_points"]) turn(q);
  turn(turned["geometry"]["plate"]["center"]);
  turn(turned["geometry"]["plate"]["axis"]);
  turned["geometry"]["plate"]["ref_dir"] = {1, 0, 0};
  turn(turned["geometry"]["plate"]["ref_dir"]);
  for (int k : {0, 1}) turn(turned["boundary_conditions"][k]["normal"]);
  turn(turned["rigid_motions"]["plate"]["translation"]["vector"]);
  turned["solver"]["t_end"] = 0.005;
  turned["solver"].erase("hit_times");
  Analysis b = Analysis::from_json(turned, "turned.json");
  const AnalysisResult rb = b.run();
  REQUIRE(rb.solver.status == NonlinearSolverStatus::converged);
  const AnalysisStep& first_b = at_hit(rb);
  const Vector3d Fb = first_b.tool_loads.at(0).first;
  CHECK((Fb - Q * first.tool_loads.at(0).first).norm() < 1e-6 * Fb.norm());
  CHECK((first_b.displacements.at(0) - Q * first.displacements.at(0)).norm() <
        1e-6 * first.displacements.at(0).norm());
}

TEST_CASE("moving tools: the rigid_motions section is checked with file, path and value",
          "[iga][analysis][moving_tools][errors]") {
  const Json base = read_json_file(kData + "driven_drum.json");
  auto error = [&](auto&& edit) { return test::analysis_error(base, edit); };
  CHECK_THAT(error([](Json& d) { d["rigid_motions"]["rope"] = d["rigid_motions"]["cylinder"]; }),
             Catch::Contains("m.json: /rigid_motions/rope: \"rope\" is no surface or patch group "
                             "of the geometry section"));
  CHECK_THAT(error([](Json& d) {
               d["geometry"]["plate"] =
                   Json::parse(R"({"type": "plane", "center": [0, 0, 0], "axis": [0, 0, 1]})");
               d["rigid_motions"]["plate"] = d["rigid_motions"]["cylinder"];
             }),
             Catch::Contains("m.json: /rigid_motions/plate: no contact pair names the rigid "
                             "surface \"plate\""));
  CHECK_THAT(error([](Json& d) { d["rigid_motions"]["cylinder"] = Json::object(); }),
             Catch::Contains("m.json: /rigid_motions/cylinder: give a \"rotation\", a "
                             "\"translation\" or both"));
  CHECK_THAT(
      error([](Json& d) {
        d["rigid_motions"]["cylinder"]["rotation"]["axis"] = {0, 0, 0};
      }),
      Catch::Contains("m.json: /rigid_motions/cylinder/rotation/axis: must be a non-zero vector"));
  CHECK_THAT(error([](Json& d) { d["rigid_motions"]["cylinder"]["rotation"]["curve"] = "spin"; }),
             Catch::Contains("m.json: /rigid_motions/cylinder/rotation/curve: names no entry of "
                             "\"load_curves\""));
  CHECK_THAT(error([](Json& d) {
               d["rigid_motions"]["cylinder"]["shift"] = {0, 0, 1};
             }),
             Catch::Contains("m.json: /rigid_motions/cylinder/shift: unknown key \"shift\""));
  CHECK_THAT(error([](Json& d) {
               d["rigid_motions"]["cylinder"]["translation"] = Json::parse(R"({"vector": [0, 0]})");
             }),
             Catch::Contains("m.json: /rigid_motions/cylinder/translation/vector"));
  const Json ring = read_json_file(kData + "ring_between_plates.json");
  CHECK_THAT(test::analysis_error(ring,
                                  [](Json& d) {
                                    d["boundary_conditions"][0]["normal"] = {0, 1, 0};
                                  }),
             Catch::Contains("m.json: /boundary_conditions/0: RodProblem::symmetry: the rod's end "
                             "tangent is not along the plane's normal"));
  CHECK_THAT(error([](Json& d) { d["loads"][0]["motion"] = "drum"; }),
             Catch::Contains("m.json: /loads/0/motion: names no entry of \"rigid_motions\", got "
                             "\"drum\""));
  CHECK(error([](Json& d) {
          d["rigid_motions"]["cylinder"]["translation"] =
              Json::parse(R"({"vector": [0, 0, 0.1], "curve": "turn"})");
        }) == "no error");
}

TEST_CASE("moving tools: arc length through contact changes ends where load control does",
          "[iga][analysis][moving_tools][arc_length]") {
  // The ring crushed between plates (data/ring_between_plates.json) driven by the plate's motion:
  // no dR/dt until the plate touches (load steps), then arc length while the contact zone grows
  // point by point (active sets change inside the steps); the force on the plate at t = 1 is
  // the load-controlled run's.
  Json doc = read_json_file(kData + "ring_between_plates.json");
  doc["output"]["vtk"] = "none";
  doc["solver"].erase("hit_times");
  Analysis load = Analysis::from_json(doc, "ring_between_plates.json");
  const AnalysisResult rl = load.run();
  REQUIRE(rl.solver.converged());
  doc["solver"]["control"] = "arc_length";
  Analysis arc = Analysis::from_json(doc, "ring_between_plates.json");
  const AnalysisResult ra = arc.run();
  REQUIRE(ra.solver.converged());
  CHECK(ra.solver.t == 1.0);
  CHECK(ra.steps.size() < rl.steps.size());
  int changes = 0;  // steps whose active set differs from the step before
  for (std::size_t k = 1; k < ra.steps.size(); ++k)
    changes += ra.steps[k].contact.active != ra.steps[k - 1].contact.active;
  CHECK(changes >= 3);
  const double Fl = rl.steps.back().tool_loads.at(0).first.y();
  const double Fa = ra.steps.back().tool_loads.at(0).first.y();
  CHECK(Fa == Approx(Fl).epsilon(1e-6));
  CHECK(ra.steps.back().contact.active == rl.steps.back().contact.active);
}

}  // namespace test_moving_tools
