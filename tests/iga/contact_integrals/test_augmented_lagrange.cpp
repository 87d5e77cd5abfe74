// Exact enforcement of the normal contact constraint by the augmented Lagrangian (Uzawa updates
// between Newton solves, iga/contact_integrals/contact_augmentation.hpp): the solver's
// augment/restore hook on a toy problem, a plate pressed onto a rigid plane (STAS, master and
// slave: penetration below the tolerance instead of q / eps_N, the contact force equal to the
// load), the capstan (CTRS: the penalty error at mu = 1 removed, Newton iterations at most twice
// the penalty run's), the model keys and their errors. The point law's augmented tangent is checked
// against finite differences in tests/contact/test_contact_law.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "iga/contact_integrals/rod_contact_problem.hpp"
#include "iga/contact_integrals/shell_contact_problem.hpp"
#include "iga/model/analysis.hpp"
#include "iga/solvers/roundoff_probe.hpp"
#include "tests/iga/analysis_error.hpp"
#include "tests/support/capstan.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_augmented_lagrange {

using namespace iga;

namespace {

/// R(u, t) = u - t (one unknown) with a fake multiplier: augment() asks for `updates` re-solves
/// per step (or fails after them with `fail`); counts the calls.
class ToyProblem : public NonlinearProblem {
 public:
  int updates = 2;
  bool fail = false;
  int augment_calls = 0, restores = 0, commits = 0, pending = 0;

  int num_dofs() const override { return 1; }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    R.resize(1);
    R[0] = u[0] - t;
    if (K) {
      K->resize(1, 1);
      K->setIdentity();
    }
  }
  void commit(const VectorXd&, double) override {
    ++commits;
    pending = 0;
  }
  AugmentResult augment(const VectorXd&, double) override {
    ++augment_calls;
    if (pending < updates) {
      ++pending;
      return {AugmentStatus::updated, "toy update"};
    }
    if (fail) return {AugmentStatus::failed, "toy constraint violated"};
    return {};
  }
  void restore() override {
    ++restores;
    pending = 0;
  }
};

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

/// A 2 x 2 plate (h = 0.1) lying on the rigid plane z = 0 under a uniform pressure q = 1
/// (ramped over t in [0, 1]), in-plane components fixed (frictionless contact leaves them free);
/// it starts 1e-3 into the plane so that contact holds it from the first iteration.
Json plate_on_plane(const std::string& strategy, const std::string& enforcement) {
  Json d = {
      {"format", "iga-contact-model"},
      {"version", 1},
      {"name", "plate_on_plane"},
      {"geometry",
       {{"plate",
         {{"type", "construction"},
          {"shape", "plane"},
          {"origin", {-1.0, -1.0, 0.049}},
          {"du", {2.0, 0.0, 0.0}},
          {"dv", {0.0, 2.0, 0.0}},
          {"refine", {{"elevate", 1}, {"subdivide", 2}}}}},
        {"floor", {{"type", "plane"}, {"center", {0.0, 0.0, 0.0}}, {"axis", {0.0, 0.0, 1.0}}}}}},
      {"materials", {{"plate", {{"type", "shell"}, {"E", 1e5}, {"nu", 0.3}, {"thickness", 0.1}}}}},
      {"bodies", {{"plate", {{"type", "shell"}, {"surface", "plate"}, {"material", "plate"}}}}},
      {"load_curves", {{"load", {{"type", "ramp"}, {"scale", 1.0}}}}},
      {"boundary_conditions",
       Json::array(
           {{{"type", "fix"}, {"body", "plate"}, {"points", "all"}, {"components", {0, 1}}}})},
      {"loads", Json::array({{{"type", "surface_load"},
                              {"body", "plate"},
                              {"q", {0.0, 0.0, -1.0}},
                              {"curve", "load"}}})},
      {"contact", Json::array({{{"type", "surface_to_rigid"},
                                {"body", "plate"},
                                {"rigid", "floor"},
                                {"eps_N", 1e3},
                                {"strategy", strategy},
                                {"face", "lower"},
                                {"points_per_direction", 3},
                                {"search_distance", 0.5},
                                {"enforcement", enforcement}}})},
      {"solver", {{"t_end", 1.0}, {"initial_step", 0.25}, {"max_step", 0.25}}}};
  if (enforcement == "augmented_lagrange") d["contact"][0]["penetration_tol"] = 1e-7;
  return d;
}

/// Newton iterations per converged step (the re-solves after each augmentation included): the
/// cost of a run compared with another's. Two runs take the same steps unless round-off cuts one
/// back somewhere (on another processor; the round-off probe's refusals), which changes their
/// number, not the work a step takes; attempts that failed are not counted.
double per_step(const NonlinearSolverResult& s) {
  double sum = 0.0;
  for (int it : s.step_iterations) sum += it;
  return sum / static_cast<double>(s.step_iterations.size());
}

}  // namespace

TEST_CASE("NonlinearSolver: augment re-solves the step, counts its iterations, restores on a cut",
          "[iga][solver][augmented]") {
  // Probe off: the steps, augmentations, commits and restores of the step control are counted.
  const RoundoffProbeOff probe_off;
  NonlinearSolverSettings s;
  s.initial_step = 0.5;
  s.max_step = 0.5;
  NonlinearSolver solver(s);
  {
    ToyProblem p;
    VectorXd u = VectorXd::Zero(1);
    const NonlinearSolverResult r = solver.solve(p, u);
    REQUIRE(r.converged());
    CHECK(r.steps == 2);
    CHECK(r.augmentations == 4);  // two updates per step
    CHECK(p.augment_calls == 6);  // + the call that found the constraints met
    // Linear: two iterations per step (the second for the energy test), the re-solves start
    // converged (|R_0| = 0: no iteration).
    CHECK(r.total_iterations == 4);
    CHECK(r.attempts.front().augmentations == 2);
    CHECK(p.commits == 2);
    CHECK(p.restores == 0);
  }
  {
    ToyProblem p;
    p.fail = true;  // never satisfied: every attempt fails, down to the minimum step
    VectorXd u = VectorXd::Zero(1);
    s.min_step = 0.1;
    solver.set_settings(s);
    const NonlinearSolverResult r = solver.solve(p, u);
    CHECK(r.status == NonlinearSolverStatus::min_step_reached);
    CHECK(r.steps == 0);
    CHECK(u[0] == 0.0);  // the last converged state
    REQUIRE(!r.attempts.empty());
    CHECK(r.attempts.front().outcome == NewtonOutcome::augmentation_failed);
    CHECK(std::string(to_string(NewtonOutcome::augmentation_failed)) == "augmentation_failed");
    CHECK_THAT(r.message, Catch::Contains("toy constraint violated"));
    CHECK(p.restores == r.cutbacks);  // multipliers restored at every cut
  }
}

TEST_CASE(
    "augmented Lagrange: a plate pressed onto a plane, penetration below the tolerance, "
    "contact force = load (STAS, master and slave)",
    "[iga][shell][contact][augmented]") {
  // Exact: the lower face rests on z = 0 and the contact pressure is q = 1, total force 4.
  // The penalty leaves the face q / eps_N = 1e-3 deep.
  for (const char* strategy : {"master", "slave"})
    for (const char* enforcement : {"penalty", "augmented_lagrange"}) {
      Analysis a = Analysis::from_json(plate_on_plane(strategy, enforcement), "plate.json");
      const AnalysisResult r = a.run();
      INFO(strategy << ", " << enforcement << ": " << r.solver.message);
      REQUIRE(r.solver.converged());
      const SurfaceContact& c = a.pair_as<SurfaceContactPair>()->contact();
      double force = 0.0, deepest = 0.0;
      int active = 0;
      for (const SurfaceContactPoint& cp : c.points()) {
        if (!cp.active) continue;
        ++active;
        force -= cp.weight * cp.N;  // N <= 0: pressure |N|
        deepest = std::max(deepest, -cp.gap);
      }
      CHECK(active == static_cast<int>(c.points().size()));
      CHECK(force == Approx(4.0).epsilon(1e-9));  // equilibrium, either enforcement
      if (std::string(enforcement) == "penalty") {
        CHECK(deepest == Approx(1e-3).epsilon(1e-6));  // q / eps_N
        CHECK(r.solver.augmentations == 0);
      } else {
        CHECK(deepest <= 1e-7);
        CHECK(c.augmentation().max_gap <= 1e-7);
        CHECK(r.solver.augmentations >= 1);
      }
    }
}

TEST_CASE(
    "augmented Lagrange: the capstan at mu = 1 loses the penalty error (CTRS), within "
    "twice the Newton iterations",
    "[iga][capstan][augmented]") {
  // Penalty at the default mesh: +0.41 % (the penetration T / (rho eps_N) ~ 1.1e-2 at the
  // tight end). Augmented, penetration_tol 1e-4: measured +0.066 %; what is left is the
  // discretization (10 arc elements; +0.007 % with 20, -0.025 % with 40) and reading T/T0 at
  // the first step of full slip (docs/contact.md, "Enforcement").
  CapstanParameters p;
  p.mu = 1.0;
  // Steps land on t = 0.1, 0.2, ..., 1.9 whatever cutbacks happen between (round-off on another
  // processor; the round-off probe): T/T0 is read at the first step of full slip, which lies
  // at most a grid step beyond the onset, as without cutbacks.
  NonlinearSolverSettings s = capstan_solver_settings();
  for (int k = 1; k < 20; ++k) s.hit_times.push_back(k / 10.0);
  CapstanModel pen = make_capstan(p);
  const CapstanResult rp = run_capstan(pen, s);
  REQUIRE(rp.full_slip);
  CHECK(rp.rel_error() > 3e-3);  // the penalty error the option removes
  CapstanModel al = make_capstan(p);
  ContactEnforcement e;
  e.augmented = true;
  e.penetration_tol = 1e-4;
  al.problem.contact().set_enforcement(e);
  const CapstanResult ra = run_capstan(al, s);
  INFO("penalty " << rp.rel_error() << " (" << rp.solver.total_iterations
                  << " iterations), augmented " << ra.rel_error() << " ("
                  << ra.solver.total_iterations << " iterations, " << ra.solver.augmentations
                  << " augmentations)");
  REQUIRE(ra.full_slip);
  CHECK(std::abs(ra.rel_error()) < 1e-3);
  CHECK(ra.solver.augmentations > 0);
  // Per converged step (see per_step): round-off may cut a step back in one run only.
  INFO("Newton iterations per converged step: penalty " << per_step(rp.solver) << ", augmented "
                                                        << per_step(ra.solver));
  CHECK(per_step(ra.solver) <= 2.0 * per_step(rp.solver));
  double deepest = 0.0;
  for (const CurveContactPoint& cp : al.problem.contact().points())
    if (cp.law.active) deepest = std::max(deepest, -cp.law.gap);
  CHECK(deepest <= 1e-4);
}

TEST_CASE("augmented Lagrange: the model keys and their errors (file, path, value)",
          "[iga][analysis][errors][augmented]") {
  const Json rod = test::cubic_penalty_capstan(read_json_file(kData + "capstan.json"));
  const Json shell = read_json_file(kData + "saddle.json");
  for (const Json* base : {&rod, &shell}) {
    auto error = [&](auto&& edit) { return test::analysis_error(*base, edit); };
    CHECK(error([](Json& d) { d["contact"][0]["enforcement"] = "penalty"; }) == "no error");
    CHECK(error([](Json& d) {
            d["contact"][0]["enforcement"] = "augmented_lagrange";
            d["contact"][0]["penetration_tol"] = 1e-4;
            d["contact"][0]["max_augmentations"] = 5;
          }) == "no error");
    CHECK_THAT(error([](Json& d) { d["contact"][0]["enforcement"] = "lagrange"; }),
               Catch::Contains("m.json: /contact/0/enforcement: expected one of \"penalty\", "
                               "\"augmented_lagrange\""));
    CHECK_THAT(error([](Json& d) { d["contact"][0]["enforcement"] = "augmented_lagrange"; }),
               Catch::Contains("m.json: /contact/0") && Catch::Contains("penetration_tol"));
    CHECK_THAT(error([](Json& d) {
                 d["contact"][0]["enforcement"] = "augmented_lagrange";
                 d["contact"][0]["penetration_tol"] = -1e-4;
               }),
               Catch::Contains("m.json: /contact/0/penetration_tol: must be > 0"));
    CHECK_THAT(error([](Json& d) {
                 d["contact"][0]["enforcement"] = "augmented_lagrange";
                 d["contact"][0]["penetration_tol"] = 1e-4;
                 d["contact"][0]["max_augmentations"] = 0;
               }),
               Catch::Contains("m.json: /contact/0/max_augmentations: must be in 1..1000"));
    CHECK_THAT(error([](Json& d) { d["contact"][0]["penetration_tol"] = 1e-4; }),
               Catch::Contains("m.json: /contact/0/penetration_tol: applies only with "
                               "\"enforcement\": \"augmented_lagrange\""));
    CHECK_THAT(error([](Json& d) { d["contact"][0]["max_augmentations"] = 3; }),
               Catch::Contains("m.json: /contact/0/max_augmentations: applies only with"));
  }
  CapstanModel m = make_capstan(CapstanParameters{});
  CurveContact& contact = m.problem.contact();
  ContactEnforcement bad;
  bad.augmented = true;
  CHECK_THROWS_WITH(contact.set_enforcement(bad),
                    Catch::Contains("penetration_tol must be > 0 and finite"));
  bad.penetration_tol = 1e-3;
  bad.max_augmentations = 0;
  CHECK_THROWS_WITH(contact.set_enforcement(bad),
                    Catch::Contains("max_augmentations must be >= 1"));
}

TEST_CASE(
    "augmented Lagrange: the coarse saddle runs (STAS, master), |gap| below the tolerance, "
    "within twice the penalty's Newton iterations",
    "[iga][shell][contact][saddle][augmented]") {
  // data/saddle.json with its app/quick overrides, frictionless. The penalty's largest |gap|
  // reaches 3.3e-4 (local N ~ 50-80 at eps_N = 2.5e5); tolerance 3e-5. Below about 1.2e-5 the
  // updates stall late in the run (multipliers at 576 Gauss points for 100 control points;
  // docs/contact.md). Measured: 156 Newton iterations (penalty), 289 (augmented).
  Json doc = read_json_file(kData + "saddle.json");
  for (const auto& [ptr, value] : doc["app"]["quick"].items()) doc[JsonPointer(ptr)] = value;
  Analysis pen = Analysis::from_json(doc, "saddle.json");
  const AnalysisResult rp = pen.run();
  REQUIRE(rp.solver.converged());
  doc["contact"][0]["enforcement"] = "augmented_lagrange";
  doc["contact"][0]["penetration_tol"] = 3e-5;
  Analysis al = Analysis::from_json(doc, "saddle.json");
  const AnalysisResult ra = al.run();
  INFO("penalty " << rp.solver.total_iterations << " iterations, augmented "
                  << ra.solver.total_iterations << " (" << ra.solver.augmentations
                  << " augmentations): " << ra.solver.message);
  REQUIRE(ra.solver.converged());
  double worst = 0.0;
  for (const SurfaceContactPoint& cp : al.pair_as<SurfaceContactPair>()->contact().points())
    if (cp.active) worst = std::max(worst, std::abs(cp.gap));
  CHECK(worst <= 3e-5);
  // Per converged step (see per_step): round-off may cut a step back in one run only.
  INFO("Newton iterations per converged step: penalty "
       << per_step(rp.solver) << " (" << rp.solver.steps << " steps), augmented "
       << per_step(ra.solver) << " (" << ra.solver.steps << " steps)");
  CHECK(per_step(ra.solver) <= 2.0 * per_step(rp.solver));
  // the centre deflection moves by about the penalty's penetration there (2e-4 of 2.65)
  CHECK(ra.steps.back().displacements.at(0).z() ==
        Approx(rp.steps.back().displacements.at(0).z()).epsilon(1e-3));
}

TEST_CASE(
    "augmented Lagrange: ShellContactProblem tangent = central differences with non-zero "
    "multipliers (saddle, master and slave, with and without friction)",
    "[iga][shell][contact][tangent][augmented][heavy]") {
  // The slave strategy's augmented force f = eps_N xi3 n - lambda_N sigma n and its derivative
  // are written in iga/contact_integrals/surface_contact.cpp (the master strategy uses the CTRS
  // law, checked in tests/contact/test_contact_law.cpp); checked here on the whole problem.
  for (const char* strategy : {"master", "slave"})
    for (const double mu : {0.0, 0.125}) {
      Json doc = read_json_file(kData + "saddle.json");
      for (const auto& [ptr, value] : doc["app"]["quick"].items()) doc[JsonPointer(ptr)] = value;
      doc["contact"][0]["mu"] = mu;
      doc["contact"][0]["eps_T"] = mu > 0.0 ? 2.5e5 : 0.0;
      doc["contact"][0]["strategy"] = strategy;
      doc["contact"][0]["enforcement"] = "augmented_lagrange";
      doc["contact"][0]["penetration_tol"] = 3e-5;
      doc["solver"]["t_end"] = 600.0;
      doc["solver"]["hit_times"] = Json::array();
      Analysis a = Analysis::from_json(doc, "saddle.json");
      const AnalysisResult r = a.run();
      REQUIRE(r.solver.converged());
      ShellProblem& p = a.body_as<ShellProblem>();  // with the contact pair attached
      const SurfaceContact& contact = a.pair_as<SurfaceContactPair>()->contact();
      int with_multiplier = 0;
      for (const SurfaceContactPoint& cp : contact.points())
        if (cp.lambda_n < 0.0) ++with_multiplier;
      REQUIRE(with_multiplier > 20);
      std::mt19937 g(3);
      std::uniform_real_distribution<double> U(-1.0, 1.0);
      VectorXd u = r.u;
      for (Eigen::Index k = 0; k < u.size(); ++k) u[k] += 2e-5 * U(g);
      // Central differences as in tests/iga/test_shell_contact_problem.cpp, but h = 1e-8: with
      // friction some sliding points have small trial forces (strongly curved slip direction),
      // and h = 1e-7 gives a relative error of 2.4e-5 that falls 100-fold with h = 1e-8 (the h^2
      // of central differences, not a kink or a wrong term; frictionless: 6e-9 either way).
      const double t = 610.0, h = 1e-8;
      VectorXd R;
      SparseMatrix K;
      p.assemble(u, t, R, &K);
      const Eigen::MatrixXd Kd(K);
      double err = 0.0;
      for (Eigen::Index j = 0; j < u.size(); ++j) {
        VectorXd up = u, um = u, Rp, Rm;
        up[j] += h;
        um[j] -= h;
        p.assemble(up, t, Rp, nullptr);
        p.assemble(um, t, Rm, nullptr);
        err = std::max(err, ((Rp - Rm) / (2.0 * h) - Kd.col(j)).cwiseAbs().maxCoeff());
      }
      err /= Kd.cwiseAbs().maxCoeff();
      INFO(strategy << ", mu = " << mu << ": " << p.status() << ", " << with_multiplier
                    << " points with a multiplier, relative error " << err);
      CHECK(err < 1e-5);
    }
}

TEST_CASE(
    "NormalAugmentation: Uzawa update, predictor from the last two commits, penalty raised "
    "when the updates stall",
    "[iga][contact][augmented]") {
  struct P : ContactMultipliers {
    P(bool a, double g, double n) : active(a), gap(g), N(n) {}
    bool active;
    double gap, N;
    bool stick = false;
    double slip = 0.0;
    Vector3d T = Vector3d::Zero();
  };
  std::vector<P> pts{{true, -2e-3, -5.0}, {true, 1e-4, -1.0}, {false, 0.3, 0.0}};
  ContactEnforcement e;
  e.augmented = true;
  e.penetration_tol = 1e-3;
  e.max_augmentations = 3;
  NormalAugmentation aug;
  auto update = [&] {
    return aug.update(
        pts, e, AugmentResult{}, [](const P& p) { return p.active; },
        [](const P& p) { return p.gap; }, [](const P& p) { return p.N; },
        [](const P& p) { return p.stick; }, [](const P& p) { return p.slip; },
        [](const P& p) { return p.T; });
  };
  // |gap| 2e-3 > tol: lambda_N <- N at active points, 0 elsewhere
  pts[2].lambda_n = -7.0;
  AugmentResult r = update();
  CHECK(r.status == AugmentStatus::updated);
  CHECK(aug.max_gap == 2e-3);
  CHECK(pts[0].lambda_n == -5.0);
  CHECK(pts[1].lambda_n == -1.0);
  CHECK(pts[2].lambda_n == 0.0);
  CHECK(aug.eps_scale == 1.0);
  // the same |gap| again (stalled): eps_N x 4
  r = update();
  CHECK(r.status == AugmentStatus::updated);
  CHECK(aug.eps_scale == 4.0);
  // below the tolerance: satisfied, nothing changes
  pts[0].gap = -0.99e-3;
  pts[1].gap = 1e-4;
  r = update();
  CHECK(r.status == AugmentStatus::satisfied);  // 0.99e-3 <= tol
  pts[0].gap = -1.5e-3;
  r = update();
  CHECK(r.status == AugmentStatus::updated);
  CHECK(aug.eps_scale == 16.0);  // 1.5e-3 > 0.5 * 2e-3: stalled again
  r = update();
  CHECK(r.status == AugmentStatus::failed);  // max_augmentations = 3 reached
  CHECK_THAT(r.message, Catch::Contains("after 3 augmentations"));
  // Exact stick (slip_tol): the gaps within tolerance, a sticking point 2e-3 from its anchor:
  // updated, lambda_T <- T at the active points (0 elsewhere), the law then carries lambda_T;
  // a sliding point's slip does not count; a commit clears the flag.
  aug = NormalAugmentation();
  e.slip_tol = 1e-3;
  pts[0].gap = -1e-4;
  pts[0].stick = true;
  pts[0].slip = 2e-3;
  pts[0].T = Vector3d(1.0, 2.0, 0.0);
  pts[1].stick = false;
  pts[1].slip = 0.5;  // sliding
  pts[1].T = Vector3d(0.0, 3.0, 0.0);
  pts[2].lambda_t = Vector3d(4.0, 0.0, 0.0);  // apart
  r = update();
  CHECK(r.status == AugmentStatus::updated);
  CHECK_THAT(r.message, Catch::Contains("stick slip 2.000e-03 > slip_tol 1.000e-03"));
  CHECK(aug.max_slip == 2e-3);
  CHECK(aug.tangential);
  CHECK(pts[0].lambda_t == pts[0].T);
  CHECK(pts[1].lambda_t == pts[1].T);
  CHECK(pts[2].lambda_t == Vector3d::Zero());
  CHECK(aug.eps_scale == 1.0);  // the normal gaps were within tolerance
  pts[0].slip = 0.9e-3;
  CHECK(update().status == AugmentStatus::satisfied);
  aug.commit(pts);
  CHECK(!aug.tangential);
  e.slip_tol = 0.0;
  // predictor: commits at t = 1 (lambda -1) and t = 2 (lambda -2), prediction at t = 3: -3
  aug = NormalAugmentation();
  auto predict = [&](double t) { aug.predict(pts, e, t); };
  auto commit = [&] { aug.commit(pts); };
  for (P& p : pts) p = P(true, 0.0, 0.0);
  predict(1.0);
  for (P& p : pts) p.lambda_n = -1.0;
  commit();
  predict(2.0);
  CHECK(pts[0].lambda_n == -1.0);  // one commit only: no extrapolation
  for (P& p : pts) p.lambda_n = -2.0;
  commit();
  predict(3.0);
  CHECK(pts[0].lambda_n == Approx(-3.0).epsilon(1e-15));
  predict(2.0);
  CHECK(pts[0].lambda_n == -2.0);  // at the committed time: the committed multiplier
  predict(0.0);
  CHECK(pts[0].lambda_n == 0.0);  // clipped to <= 0
  // penalty: nothing changes
  ContactEnforcement off;
  pts[0].lambda_n = 0.0;
  aug.predict(pts, off, 3.0);
  CHECK(pts[0].lambda_n == 0.0);
}

TEST_CASE(
    "NormalAugmentation over the parts of a spread pair: the whole pair's largest gap and slip "
    "decide, and a point through the tool on any part stops every part's update",
    "[iga][contact][augmented]") {
  struct P : ContactMultipliers {
    bool active = true;
    double gap = 0.0, N = 0.0;
  };
  ContactEnforcement e;
  e.augmented = true;
  e.penetration_tol = 1e-3;
  e.max_augmentations = 5;
  // Two parts of one pair (as on two processes): each part's maxima go through parts_max,
  // which here takes them to the maximum with the other part's last values.
  std::vector<P> a(2), b(2);
  a[0].gap = -2e-4, a[0].N = -1.0, a[1].gap = 1e-4, a[1].N = -0.5;  // within the tolerance
  b[0].gap = -3e-3, b[0].N = -4.0, b[1].active = false;             // not
  NormalAugmentation pa, pb;
  std::array<double, 3> other{};  // the other part's (through, gap, slip)
  int calls = 0;
  pa.parts_max = [&](std::span<double> v) {
    ++calls;
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = std::max(v[k], other[k]);
  };
  const auto update = [&](NormalAugmentation& aug, std::vector<P>& pts, AugmentResult through) {
    return aug.update(
        pts, e, through, [](const P& p) { return p.active; }, [](const P& p) { return p.gap; },
        [](const P& p) { return p.N; }, [](const P&) { return false; },
        [](const P&) { return 0.0; }, [](const P&) { return Vector3d::Zero(); });
  };
  // Alone, part a is satisfied; with part b's gap it updates its multipliers as the whole does.
  REQUIRE(update(pb, b, {}).status == AugmentStatus::updated);
  other = {0.0, pb.max_gap, 0.0};
  const AugmentResult r = update(pa, a, {});
  CHECK(calls == 1);
  CHECK(r.status == AugmentStatus::updated);
  CHECK(pa.max_gap == 3e-3);
  CHECK_THAT(r.message, Catch::Contains("contact gap 3.000e-03"));
  CHECK(a[0].lambda_n == -1.0);
  CHECK(a[1].lambda_n == -0.5);
  CHECK(pa.step_updates == 1);
  // A point through the surface on the other part: this part is satisfied and keeps its
  // multipliers (the other reports the pass-through, the step is cut on every part).
  a[0].N = -9.0;
  other = {1.0, 0.0, 0.0};
  CHECK(update(pa, a, {}).status == AugmentStatus::satisfied);
  CHECK(a[0].lambda_n == -1.0);
  CHECK(calls == 2);
  // This part's pass-through comes back as it is, after the same collective call.
  const AugmentResult through{AugmentStatus::passed_through, "1 contact point(s) went through"};
  other = {0.0, 0.0, 0.0};
  CHECK(update(pa, a, through).status == AugmentStatus::passed_through);
  CHECK(calls == 3);
  // The penalty decides nothing over the parts: no collective call.
  ContactEnforcement off;
  CHECK(pa.update(
              a, off, through, [](const P& p) { return p.active; },
              [](const P& p) { return p.gap; }, [](const P& p) { return p.N; },
              [](const P&) { return false; }, [](const P&) { return 0.0; },
              [](const P&) { return Vector3d::Zero(); })
            .status == AugmentStatus::passed_through);
  CHECK(calls == 3);
}

namespace {

/// A straight rod (EA = 100) on a rough rigid plane, pressed by q = 1 per length, pulled at
/// its end A along itself by F = 0.5 < mu q L (mu = 0.5, L = 2); the far end B held along x.
/// It starts 1e-6 above the plane (at gap 0 round-off would pick the points first in contact).
Json rough_bar_model() {
  return Json::parse(R"({
    "format": "iga-contact-model", "version": 1, "name": "rough_bar",
    "geometry": {
      "bar": {"type": "construction", "shape": "line", "start": [0, 0, 0.050001], "end": [2, 0, 0.050001],
              "degree": 3, "elements": 40},
      "ground": {"type": "plane", "center": [0, 0, 0], "axis": [0, 0, 1]}
    },
    "materials": {"bar": {"type": "rod", "EA": 100.0, "EI": 1e-3}},
    "bodies": {"bar": {"type": "rod", "curve": "bar", "material": "bar"}},
    "load_curves": {"press": {"type": "piecewise_linear", "points": [[0, 0], [1, 1]]},
                    "pull": {"type": "piecewise_linear", "points": [[1, 0], [2, 1]]}},
    "boundary_conditions": [{"type": "fix", "body": "bar", "points": "all", "components": [1]},
                            {"type": "fix", "body": "bar", "points": "end", "components": [0]}],
    "loads": [{"type": "line_load", "body": "bar", "q": [0, 0, -1.0], "curve": "press"},
              {"type": "point_force", "body": "bar", "at": "start", "force": [-0.5, 0, 0],
               "curve": "pull"}],
    "contact": [{"type": "curve_to_rigid", "body": "bar", "rigid": "ground", "eps_N": 1e4,
                 "eps_T": 1e3, "mu": 0.5, "radius": 0.05, "points_per_element": 4}],
    "solver": {"t_end": 2.0, "initial_step": 0.1, "max_step": 0.1},
    "output": {"vtk": "none", "reactions": ["end"], "monitors": [{"name": "A", "at": "start"}]}
  })");
}

}  // namespace

TEST_CASE(
    "augmented Lagrange with slip_tol: a bar pulled on a rough plane sticks exactly beyond the "
    "slip zone, its end moves by the closed form (the penalty: +10 %)",
    "[iga][contact][augmented][friction]") {
  // Exact stick: the friction mu q acts over the slip zone 0 <= X <= a = F / (mu q) next to A,
  // where the axial force N = F - mu q X falls to 0; beyond it the bar neither moves nor
  // stretches, and B carries nothing. The rod's law: S = EA eps (Green-Lagrange), the true force
  // N = lambda S with the stretch lambda, so (lambda^3 - lambda) / 2 = N / EA, and A moves by
  // u_A = int_0^a (lambda(N(X)) - 1) dX (2.48762e-3; the small-strain F^2 / (2 EA mu q) =
  // 2.5e-3). The penalty's stick creeps by |T| / eps_T: a shear lag of length sqrt(EA / eps_T)
  // = 0.32 spreads the force past a, and A moves 10 % more.
  const double EA = 100.0, F = 0.5, mq = 0.5, a = F / mq;
  auto stretch = [&](double N) {
    double lo = 0.5, hi = 2.0;
    for (int k = 0; k < 200; ++k) {
      const double m = 0.5 * (lo + hi);
      ((m * m * m - m) / 2.0 < N / EA ? lo : hi) = m;
    }
    return 0.5 * (lo + hi);
  };
  double exact = 0.0;  // Simpson, 2000 intervals
  const int n = 2000;
  for (int k = 0; k <= n; ++k) {
    const double X = a * k / n, wgt = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    exact += wgt * (stretch(F - mq * X) - 1.0) * a / (3.0 * n);
  }
  auto run = [](Json d) {
    Analysis an = Analysis::from_json(d, "rough_bar.json");
    AnalysisResult r = an.run();
    INFO(r.solver.message);
    REQUIRE(r.solver.t == Approx(2.0));
    return r;
  };
  const AnalysisResult pen = run(rough_bar_model());
  Json al = rough_bar_model();
  al["contact"][0]["enforcement"] = "augmented_lagrange";
  al["contact"][0]["penetration_tol"] = 1e-6;
  al["contact"][0]["slip_tol"] = 1e-6;
  al["contact"][0]["max_augmentations"] = 50;
  const AnalysisResult aug = run(al);
  const double u_pen = -pen.steps.back().displacements[0].x();
  const double u_al = -aug.steps.back().displacements[0].x();
  const double leak_pen = pen.steps.back().reactions[0].norm() / F;
  const double leak_al = aug.steps.back().reactions[0].norm() / F;
  INFO("u_A exact " << exact << ", penalty " << u_pen << ", augmented " << u_al
                    << "; B's share of F: penalty " << leak_pen << ", augmented " << leak_al
                    << "; Newton iterations " << pen.solver.total_iterations << " / "
                    << aug.solver.total_iterations);
  CHECK(exact == Approx(2.48762e-3).epsilon(1e-5));
  CHECK(u_pen / exact - 1.0 > 0.05);           // the penalty's creep: +10 %
  CHECK(std::abs(u_al / exact - 1.0) < 5e-4);  // measured +2.5e-5
  CHECK(leak_pen > 5e-3);                      // 1 % of F reaches B
  CHECK(leak_al < 1e-5);                       // exact stick: nothing does
  // Uzawa on the stick constraint converges slowly where the bar is much stiffer than eps_T
  // per contact point (EA / h = 2000 against eps_T w = 12.5): eps_T is raised within each step.
  // Measured 231 iterations in 20 steps, against the penalty's 44 (mostly one iteration a step:
  // the penalty problem is nearly linear here, so the ratio says little). Per converged step
  // (the steps are adaptive: a step cut back on another processor adds steps, not work per
  // step): at most 17.5 on average.
  int converged_iterations = 0;
  for (const int it : aug.solver.step_iterations) converged_iterations += it;
  INFO(converged_iterations << " iterations in " << aug.solver.steps << " converged steps");
  CHECK(converged_iterations <= 17.5 * aug.solver.steps);
  // the slip zone: the sliding points lie in X < a (the first half of the bar)
  const ContactCounts& c = aug.steps.back().contact;
  CHECK(std::abs(c.slip - c.active / 2) <= 2);
}

}  // namespace test_augmented_lagrange
