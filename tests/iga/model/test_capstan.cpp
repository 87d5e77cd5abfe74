// The capstan (Euler-Eytelwein, [KS15] Sect. 6.3, eq. (82)) on a Kirchhoff rod with CTRS contact:
// the sliding limit T / T0 = exp(mu phi) on the exact NURBS and the analytic cylinder, the
// frictionless case T = T0 with its exact moment balance about the axis, the tangent of the
// whole RodContactProblem against central differences (stick, slip, frictionless), and the
// quadratic convergence of Newton near the solution. Set-up and parameters:
// tests/support/capstan.hpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "contact/rigid_surface.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"
#include "iga/solvers/linear_solver.hpp"
#include "tests/support/capstan.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_capstan {

using namespace iga;

namespace {

constexpr double kPi = std::numbers::pi;

CapstanParameters capstan(double mu) {
  CapstanParameters p;
  p.mu = mu;
  return p;
}

/// The rigid cone of half-angle alpha whose generator the rope of p touches along its
/// centre circle of radius rho = radius + rope_radius (the cone's apex on the -z axis).
std::shared_ptr<RigidSurface> rope_cone(const CapstanParameters& p, double alpha) {
  const double rho = p.radius + p.rope_radius, Rc = rho - p.rope_radius / std::sin(alpha);
  auto cone = std::make_shared<RigidSurface>();
  cone->add(
      Cone(Placement{Vector3d(0, 0, -Rc * std::tan(alpha)), Vector3d::UnitZ(), -Vector3d::UnitY()},
           alpha));
  return cone;
}

/// The capstan's solver settings with steps landing on t = 0.1, 0.2, ..., 1.9 whatever happens
/// between them: round-off on another processor (or the round-off probe, IGA_ROUNDOFF_PROBE) may
/// cut a step back in one run and not in another, and the runs are compared at these times.
NonlinearSolverSettings grid_settings() {
  NonlinearSolverSettings s = capstan_solver_settings();
  for (int k = 1; k < 20; ++k) s.hit_times.push_back(k / 10.0);
  return s;
}

/// Plain Newton at a fixed t from u, without commit: the equilibrium of the step from the last
/// committed state to t. Returns the residual norms; u is the last iterate.
std::vector<double> newton(RodContactProblem& prob, VectorXd& u, double t,
                           int max_iterations = 30) {
  LinearSolver ls(prob.symmetric());
  VectorXd R, du;
  SparseMatrix K;
  std::vector<double> h;
  for (int k = 0; k <= max_iterations; ++k) {
    prob.assemble(u, t, R, &K);
    h.push_back(R.norm());
    // Stop at round-off: the residual no longer decreases (|R| ~ 1e-11 for this model).
    if (h.back() < 1e-12 || (k >= 2 && h.back() >= 0.5 * h[h.size() - 2] && h.back() < 1e-9)) break;
    REQUIRE(ls.solve(K, R, du) == LinearSolveStatus::success);
    u -= du;
  }
  return h;
}

/// Per contact point: -1 inactive, 0 stick, 1 slip.
std::vector<int> contact_state(const RodContactProblem& prob) {
  std::vector<int> s;
  for (const CurveContactPoint& c : prob.contact().points())
    s.push_back(c.law.active ? (c.law.slip ? 1 : 0) : -1);
  return s;
}

/// Distance of the kinks of the contact law from the current state: min |gap| over all points
/// (activation, (34)) and min |Phi| over the active frictional points (stick/slip, (36)).
void kink_margins(const RodContactProblem& prob, double& gap, double& phi) {
  gap = phi = std::numeric_limits<double>::infinity();
  const bool friction = prob.contact().parameters().law.mu > 0.0;
  for (const CurveContactPoint& c : prob.contact().points()) {
    if (!found(c.foot.status)) continue;  // beyond the search distance: inactive, no law
    gap = std::min(gap, std::abs(c.law.gap));
    if (c.law.active && friction) phi = std::min(phi, std::abs(c.law.phi));
  }
}

/// max |K - K_fd| / max |K| with central differences of the residual, step h.
double tangent_error(RodContactProblem& prob, const VectorXd& u, double t, double h = 1e-7) {
  VectorXd R, Rp, Rm;
  SparseMatrix K;
  prob.assemble(u, t, R, &K);
  const Eigen::MatrixXd Kd(K);
  double err = 0.0;
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    VectorXd up = u, um = u;
    up[j] += h;
    um[j] -= h;
    prob.assemble(up, t, Rp, nullptr);
    prob.assemble(um, t, Rm, nullptr);
    err = std::max(err, ((Rp - Rm) / (2.0 * h) - Kd.col(j)).cwiseAbs().maxCoeff());
  }
  prob.assemble(u, t, R, nullptr);  // leave the contact state at u
  return err / Kd.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("capstan: T/T0 at full slip = exp(mu phi) for phi = pi, mu = 0, 0.1, 0.3, 0.5",
          "[iga][capstan]") {
  // [KS15] (82); BENCHMARKS.md: 1, 1.36911, 2.56633, 4.81048. The target is 0.5 %;
  // measured 2.3e-4, 2.6e-4, 2.0e-4, 4.0e-4 (10 arc elements, 3 contact points each), so the
  // bound below is 1e-3 to catch regressions.
  for (const double mu : {0.0, 0.1, 0.3, 0.5}) {
    CapstanModel m = make_capstan(capstan(mu));
    const CapstanResult r = run_capstan(m, grid_settings());  // a step lands on t = 1
    INFO("mu = " << mu << ": T/T0 = " << r.T_ratio << ", exact " << r.exact
                 << ", full slip at t = " << r.full_slip_t << ", " << r.solver.message);
    CHECK(m.fit_deviation < 1e-4);  // the C1 cubic reproduces line + arc + line
    REQUIRE(r.solver.status == NonlinearSolverStatus::stopped);  // stopped at full slip
    REQUIRE(r.full_slip);
    CHECK(r.exact == Approx(std::exp(mu * kPi)).epsilon(1e-15));
    CHECK(std::abs(r.rel_error()) <= 1e-3);
    // End of phase 1 (t = 1, B held, T0 applied at A): the rope has slid towards A over the whole
    // arc, so the reversed capstan holds there: T_B / T0 = exp(-mu phi) (measured -3.3e-4 for
    // mu = 0.3).
    int phase1_end = 0;
    for (const CapstanStep& s : r.steps)
      if (std::abs(s.t - 1.0) < 1e-9) {
        ++phase1_end;
        if (mu > 0.0) CHECK(s.slip == s.active);
        CHECK(s.T_ratio == Approx(std::exp(-mu * kPi)).epsilon(1e-3));
      }
    CHECK(phase1_end == 1);
    // The rope is practically inextensible: the largest Green-Lagrange strain is about T / EA
    // (within 5 %; 2.35e-3 for mu = 0.5).
    CHECK(r.max_axial_strain <= 1.05 * r.exact * m.parameters.T0 / m.parameters.EA);
    CHECK(r.max_axial_strain >= 0.95 * r.exact * m.parameters.T0 / m.parameters.EA);
    // The tension at B leaves along the outgoing tangent: measured wrap angle ~ phi.
    CHECK(r.wrap_angle == Approx(kPi).epsilon(2e-3));
  }
}

TEST_CASE("capstan: the analytic cylinder gives the sliding limit of the exact NURBS patch",
          "[iga][capstan]") {
  CapstanParameters p = capstan(0.3);
  CapstanModel nurbs = make_capstan(p);
  p.nurbs_cylinder = false;
  CapstanModel analytic = make_capstan(p);
  // Both pulled to the end (t = 2), their steps landing on t = 0.1, ..., 1.9: the onset of full
  // slip is each run's own (round-off may cut a step back in one run and not in the other), so
  // T/T0 is compared at the times both reached once both slide.
  const CapstanResult rn = run_capstan(nurbs, grid_settings(), nullptr, CapstanStop::kEnd);
  const CapstanResult ra = run_capstan(analytic, grid_settings(), nullptr, CapstanStop::kEnd);
  REQUIRE(rn.solver.converged());
  REQUIRE(ra.solver.converged());
  REQUIRE(rn.full_slip);  // still sliding at the end
  REQUIRE(ra.full_slip);
  const double slide_from = std::max(rn.full_slip_t, ra.full_slip_t);
  int common = 0;
  double worst = 0.0;
  for (const CapstanStep& sn : rn.steps)
    for (const CapstanStep& sa : ra.steps)
      if (sn.t >= slide_from && std::abs(sn.t - sa.t) <= 1e-12) {
        ++common;
        worst = std::max(worst, std::abs(sa.T_ratio / sn.T_ratio - 1.0));
      }
  INFO("full slip from t = " << rn.full_slip_t << " (NURBS), " << ra.full_slip_t << " (analytic); "
                             << common << " common times, largest relative "
                             << "difference of T/T0 " << worst);
  CHECK(common >= 7);  // 1.3, 1.4, ..., 2 at least
  // The NURBS cylinder is exact to round-off; the closest points differ at the level of the
  // projection tolerance only (measured: 2e-9 without the round-off probe, up to 3e-8 with its
  // seeds 1, 2, 3, the steps cut back differently in the two runs).
  CHECK(worst <= 1e-7);
  // Each run's own onset of full slip against (82).
  CHECK(std::abs(ra.plateau.onset / ra.exact - 1.0) <= 1e-3);
  CHECK(std::abs(rn.plateau.onset / rn.exact - 1.0) <= 1e-3);
}

TEST_CASE("capstan: frictionless, T = T0 at any pull, and the moments about the axis balance",
          "[iga][capstan]") {
  // mu = 0: the contact force -N n passes through the cylinder axis and the rod's internal
  // forces are objective, so the end forces balance their moments about the axis exactly:
  // T_B d_B = T0 d_A (d the lever arms). T_B = T0 needs d_A = d_B, i.e. both free spans tangent
  // to the contact circle; the discretization breaks that slowly as the rope slides (see
  // run_capstan): 0.55 % after sliding 0.05, 0.2 % after 0.02, hence the pull of 0.02 here.
  CapstanParameters p = capstan(0.0);
  p.pull = 0.02;
  CapstanModel m = make_capstan(p);
  CHECK(m.problem.symmetric());
  const CapstanResult r = run_capstan(m, capstan_solver_settings(), nullptr, CapstanStop::kEnd);
  REQUIRE(r.solver.converged());
  CHECK(r.solver.umfpack_factorizations == 0);  // symmetric positive definite: CHOLMOD
  REQUIRE(r.steps.size() >= 15);
  for (const CapstanStep& s : r.steps) {
    INFO("t = " << s.t << ": T/T0 = " << s.T_ratio);
    CHECK(s.stick == s.active);  // frictionless points count as stick
    // phase 1: T = lambda(t) T0; phase 2: T = T0
    CHECK(s.T_ratio == Approx(std::min(s.t, 1.0)).epsilon(2.5e-3));
  }
  const std::vector<Vector3d> x = m.problem.current_points(r.u, r.solver.t);
  const double dA = std::abs(x[static_cast<std::size_t>(m.end_a)].cross(m.out_a).z());
  const double dB =
      std::abs(x[static_cast<std::size_t>(m.end_b)].cross(r.reaction.normalized()).z());
  // Exact at an exact equilibrium; the converged state's residual forces R_i at the points x_i
  // add their moment about the axis, |sum x_i x R_i| <= sqrt(n) max|x_i| |R|, to T0 d_A. A step
  // converged by the energy test may keep |R| ~ 1e-9 |R_0| (the round-off probe's seed 4 with
  // libm's FMA paths masked: |R| = 2e-7, the balance off by 2.5e-8 relative).
  const double residual = r.solver.attempts.back().residual_norms.back();
  double lever = 0.0;
  for (const Vector3d& xi : x) lever = std::max(lever, xi.norm());
  const double moment_bound =
      std::sqrt(static_cast<double>(x.size())) * lever * residual / (p.T0 * dB);
  CHECK(std::abs(r.T_ratio / (dA / dB) - 1.0) <= 1e-9 + moment_bound);
  // Both lever arms are the contact radius R + r - |xi3| to within the discretization.
  CHECK(dA == Approx(p.radius + p.rope_radius).epsilon(3e-3));
  CHECK(dB == Approx(p.radius + p.rope_radius).epsilon(3e-3));
}

TEST_CASE(
    "RodContactProblem: tangent = central differences of the residual (stick, slip, "
    "frictionless)",
    "[iga][capstan][tangent]") {
  // States away from the committed history, so that the trial forces (66) have non-zero
  // increments: the history is that of the first full-slip step t_s; the state is the
  // equilibrium at t_s + dt, dt > 0 (pulled on: every point slips) or dt < 0 (pulled back a
  // little: the points stick; -0.006 keeps the arc's end point clear of gap = 0). The law's
  // kinks (gap = 0, Phi = 0) must be farther than the difference step can reach.
  struct Case {
    double mu, dt;
    const char* name;
  };
  for (const Case c :
       {Case{0.0, 0.1, "frictionless"}, Case{0.3, 0.1, "slip"}, Case{0.3, -0.006, "stick"}}) {
    CapstanModel m = make_capstan(capstan(c.mu));
    const CapstanResult r = run_capstan(m);
    REQUIRE(r.full_slip);
    VectorXd u = r.u;
    const double t = r.solver.t + c.dt;
    const std::vector<double> h = newton(m.problem, u, t);
    REQUIRE(h.back() < 1e-9);
    const CurveContactCounts n = m.problem.contact().counts();
    double gap = 0.0, phi = 0.0;
    kink_margins(m.problem, gap, phi);
    INFO(c.name << ": " << m.problem.status() << ", min |gap| " << gap << ", min |Phi| " << phi);
    REQUIRE(gap > 1e-6);
    REQUIRE(phi > 1e-2);
    if (std::string(c.name) == "slip") CHECK(n.slip == n.active);
    if (std::string(c.name) == "stick") CHECK(n.stick >= n.active - 2);
    CHECK(tangent_error(m.problem, u, t) <= 1e-6);
  }
}

TEST_CASE(
    "capstan: Newton converges quadratically near the solution, with and without friction "
    "(observed order >= 1.8)",
    "[iga][capstan][newton]") {
  // The order is measured on the last iterations of the step t_s -> t_s + 0.1 (t_s: first full
  // slip): they are re-run from u* + delta d (u* the step's solution, d a fixed unit direction)
  // and one Newton correction leaves the error e(delta) = |u_1 - u*| ~ C delta^p and the
  // residual |R(u_1)| ~ C' delta^p; p = log(e_i / e_j) / log(delta_i / delta_j), with the same
  // active and stick/slip sets at every delta as at u* (the law's kinks excluded).
  // Why not three residuals of the step's own history: with EA / EI = 2e6 the error moves
  // between stiff and soft modes from one iteration to the next, r_{k+1} / r_k^2 varies 10-100
  // times within a step and a step reaches round-off (|R| ~ 1e-11) in 3-5 iterations, so that
  // estimate scatters from 0.7 to 7 (frictionless steps) although the tangent matches the
  // differences to 1e-9; along a fixed direction C is fixed and p comes out 2.00.
  for (const double mu : {0.0, 0.3}) {
    CapstanModel m = make_capstan(capstan(mu));
    const CapstanResult r = run_capstan(m);
    REQUIRE(r.full_slip);
    VectorXd us = r.u;
    const double t = r.solver.t + 0.1;
    const std::vector<double> h = newton(m.problem, us, t);
    INFO("mu = " << mu << ": step to t = " << t << ", " << h.size() - 1 << " iterations, |R| from "
                 << h.front() << " to " << h.back());
    REQUIRE(h.back() < 1e-9);
    REQUIRE(h.size() <= 9);
    const std::vector<int> state = contact_state(m.problem);

    std::mt19937 gen(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    VectorXd d(us.size());
    for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = U(gen);
    d.normalize();
    LinearSolver ls(m.problem.symmetric());
    const std::vector<double> deltas{3e-5, 1e-5, 3e-6, 1e-6};
    std::vector<double> err, res;
    for (const double delta : deltas) {
      const VectorXd up = us + delta * d;
      VectorXd R, du;
      SparseMatrix K;
      m.problem.assemble(up, t, R, &K);
      REQUIRE(contact_state(m.problem) == state);
      REQUIRE(ls.solve(K, R, du) == LinearSolveStatus::success);
      const VectorXd u1 = up - du;
      err.push_back((u1 - us).norm());
      m.problem.assemble(u1, t, R, nullptr);
      res.push_back(R.norm());
    }
    for (std::size_t i = 0; i + 1 < deltas.size(); ++i) {
      const double p_err = std::log(err[i] / err[i + 1]) / std::log(deltas[i] / deltas[i + 1]);
      const double p_res = std::log(res[i] / res[i + 1]) / std::log(deltas[i] / deltas[i + 1]);
      INFO("delta " << deltas[i] << " -> " << deltas[i + 1] << ": e " << err[i] << " -> "
                    << err[i + 1] << " (order " << p_err << "), |R_1| " << res[i] << " -> "
                    << res[i + 1] << " (order " << p_res << ")");
      CHECK(p_err >= 1.8);
      CHECK(p_res >= 1.8);
    }
  }
}

TEST_CASE("RodContactProblem: status line, symmetry flag and bad input", "[iga][capstan]") {
  CapstanModel frictional = make_capstan(capstan(0.3));
  CHECK_FALSE(frictional.problem.symmetric());
  CapstanParameters p = capstan(0.3);
  p.eps_T = 0.0;  // no tangential penalty: no friction force, symmetric tangent
  CHECK(make_capstan(p).problem.symmetric());

  const CapstanResult r = run_capstan(frictional);
  const CurveContactCounts c = frictional.problem.contact().counts();
  const std::string status = frictional.problem.status();
  CHECK(status == "contact " + std::to_string(c.active) + " (stick " + std::to_string(c.stick) +
                      ", slip " + std::to_string(c.slip) + ")");
  REQUIRE_FALSE(r.steps.empty());
  CHECK(r.steps.back().active > 0);
  // At full slip every active point slips; reactions() leaves that state for output as it was.
  CHECK(c.slip == c.active);
  const std::vector<int> before = contact_state(frictional.problem);
  const std::vector<Vector3d> g = frictional.problem.reactions(r.u, r.solver.t);
  CHECK(contact_state(frictional.problem) == before);
  CHECK(g[static_cast<std::size_t>(frictional.end_b)] == r.reaction);

  // Parameters name the field; a null rigid surface is rejected.
  CapstanParameters bad;
  bad.EA = -3.0;
  CHECK_THROWS_WITH(make_capstan(bad), "CapstanParameters.EA: must be > 0, got -3");
  bad = CapstanParameters{};
  bad.phi = 7.0;
  CHECK_THROWS_WITH(make_capstan(bad), Catch::Contains("CapstanParameters.phi"));
  CHECK_THROWS_AS(RodContactProblem(frictional.problem.rod(), nullptr,
                                    CurveContactParameters{{1.0, 0.0, 0.0}, 0.0, 3}),
                  RodError);
}

namespace {

/// T/T0 of every converged step of a capstan pulled to t = 2 (the whole pull: points slide
/// across whatever lies under the middle of the arc) with `rigid` in place of the cylinder.
std::vector<CapstanStep> slide(double mu, std::shared_ptr<const RigidSurface> rigid) {
  CapstanParameters p = capstan(mu);
  p.rigid = std::move(rigid);
  // Contact points lie about 0.1 apart along the arc: a slide of 0.2 takes several of them
  // across the middle of the arc.
  p.pull = 0.2;
  CapstanModel m = make_capstan(p);
  // Steps land on t = 0.1, 0.2, ..., 2 whatever happens between them: a step at the edge of
  // convergence (the first steps of the pull at t ~ 1.1) may be cut back on one processor and
  // not on another, so the runs are compared at these common times, never step by step.
  NonlinearSolverSettings s = capstan_solver_settings();
  for (int k = 1; k < 20; ++k) s.hit_times.push_back(0.1 * k);
  const CapstanResult r = run_capstan(m, s, nullptr, CapstanStop::kEnd);
  REQUIRE(r.solver.converged());
  REQUIRE(r.full_slip);
  return r.steps;
}

/// The largest relative difference of T/T0 between two runs of slide() at the times both
/// reached (t = 0.1, 0.2, ..., 2: every one of them, checked; steps between them may differ).
double largest_step_difference(const std::vector<CapstanStep>& a,
                               const std::vector<CapstanStep>& b) {
  double worst = 0.0;
  int common = 0;
  for (const CapstanStep& sa : a)
    for (const CapstanStep& sb : b)
      if (std::abs(sa.t - sb.t) <= 1e-12) {
        ++common;
        worst = std::max(worst, std::abs(sb.T_ratio / sa.T_ratio - 1.0));
      }
  int hits = 0;  // steps of run a on t = 0.1 k
  for (const CapstanStep& sa : a) hits += std::abs(sa.t * 10.0 - std::round(sa.t * 10.0)) <= 1e-9;
  CHECK(hits == 20);
  CHECK(common >= 20);
  return worst;
}

std::shared_ptr<const RigidSurface> rigid_of(const Surface& s) {
  auto r = std::make_shared<RigidSurface>();
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&s))
    r->add(*n);
  else
    r->add(dynamic_cast<const AnalyticSurface&>(s));
  return r;
}

/// The NURBS sphere of radius 1 about the origin turned so that its north pole is +e_y, the
/// middle of the capstan's arc (a rotation of the homogeneous net is exact).
NurbsSurface sphere_pole_up_y() {
  const NurbsSurface s = make_sphere(Vector3d::Zero(), 1.0);
  Matrix3d Q;  // e_z -> e_y, e_y -> -e_z
  Q << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  std::vector<Vector4d> pw = s.homogeneous();
  for (Vector4d& c : pw) c.head<3>() = Q * c.head<3>();
  NurbsSurface r(s.knots_u(), s.knots_v(), pw);
  r.set_normal_sign(s.normal_sign());
  return r;
}

}  // namespace

TEST_CASE(
    "capstan: a rope over a sphere's pole slides as on its equator, step by step "
    "(spatial friction history)",
    "[iga][capstan][friction]") {
  // The arc (phi = pi, z = 0, symmetric about +e_y) on a unit sphere: along the equator (axis
  // e_z), and along a meridian whose pole +e_y lies under the middle of the arc (analytic
  // sphere with axis e_y; the NURBS sphere turned likewise). Same geometry, so the same T/T0 in
  // every step; the parameter form of the history jumped by pi at the pole (issue 12: T/T0
  // dipped by up to 10 %). mu = 1, pulled to t = 2.
  const Sphere equator(Placement{Vector3d::Zero(), Vector3d::UnitZ(), -Vector3d::UnitY()}, 1.0);
  const Sphere pole(Placement{Vector3d::Zero(), Vector3d::UnitY(), Vector3d::UnitX()}, 1.0);
  const std::vector<CapstanStep> ref = slide(1.0, rigid_of(equator));
  const double analytic = largest_step_difference(ref, slide(1.0, rigid_of(pole)));
  const double nurbs = largest_step_difference(ref, slide(1.0, rigid_of(sphere_pole_up_y())));
  INFO("largest step difference: analytic pole " << analytic << ", NURBS pole " << nurbs);
  CHECK(analytic <= 5e-3);
  CHECK(nurbs <= 5e-3);
}

TEST_CASE(
    "capstan: a rope sliding across the seam of a cylinder and across the borders of four "
    "patches gives the single patch's T/T0 in every step",
    "[iga][capstan][friction]") {
  // The default cylinder has its seam opposite the arc; here the seam lies under the middle of
  // the arc (ref_dir +e_y), and then four patches have borders at 45 and 135 degrees, inside the
  // arc. mu = 0.5, pulled to t = 2 (the whole arc slides over them).
  const double h = 3.0;
  const Vector3d base(0, 0, -0.5 * h);
  const std::vector<CapstanStep> ref =
      slide(0.5, rigid_of(make_cylinder(base, Vector3d::UnitZ(), -Vector3d::UnitY(), 1.0, h)));
  const double seam = largest_step_difference(
      ref, slide(0.5, rigid_of(make_cylinder(base, Vector3d::UnitZ(), Vector3d::UnitY(), 1.0, h))));
  auto four = std::make_shared<RigidSurface>();
  for (int k = 0; k < 4; ++k)
    four->add(make_cylinder(base, Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, h,
                            kPi / 4 + k * kPi / 2, kPi / 4 + (k + 1) * kPi / 2));
  const double borders = largest_step_difference(ref, slide(0.5, four));
  INFO("largest step difference: seam " << seam << ", four patches " << borders);
  CHECK(seam <= 1e-6);
  CHECK(borders <= 1e-6);
}

TEST_CASE(
    "capstan: a free 3-D rope on a cone takes its first step and slides near "
    "exp(phi sqrt(mu^2 - cos^2 alpha) / sin alpha)",
    "[iga][capstan][friction]") {
  // A cone about e_z whose generator makes the angle alpha with the plane z = 0 (outward
  // normal n = sin(alpha) e_r - cos(alpha) e_z), placed so that the capstan's centre line
  // (radius rho = R + r in the plane z = 0) lies at the distance r from it; the rope is free in
  // 3-D. Per unit length the tension needs the radial force T / rho = |N| sin(alpha), and the
  // axial part |N| cos(alpha) of the normal force must be carried by friction: the rope holds
  // for mu >= cos(alpha). Sliding along a fixed planar arc, the friction mu |N| splits into the
  // axial |N| cos(alpha) and dT/ds = |N| sqrt(mu^2 - cos^2 alpha), so that at full slip
  //   T / T0 = exp(phi sqrt(mu^2 - cos^2 alpha) / sin alpha)   (2.1823 here).
  // Measured: at t = 1 (loaded, B held) the whole arc slides towards A, T_B / T0 = 0.4718
  // (1 / 2.1195); at the onset of full slip under the pull T / T0 = 2.1229 (-2.7 %), then it
  // creeps up (2.156 at the end of the pull 0.05; pulled 0.4 it passes 2.18 and reaches 2.25):
  // the rope also slides down the cone, which changes its wrap in 3-D, so the planar closed
  // form is an estimate within a few per cent, checked as such.
  // The step of first contact used to carry no friction (no history before the first commit),
  // which left the rope without axial support: Newton diverged in the first step.
  const double alpha = 80.0 * kPi / 180.0, mu = 0.3;
  CapstanParameters p = capstan(mu);
  p.planar = false;
  p.rigid = rope_cone(p, alpha);
  CapstanModel m = make_capstan(p);
  const CapstanResult r = run_capstan(m, grid_settings(), nullptr, CapstanStop::kEnd);  // t = 1 hit
  INFO("status " << r.solver.message);
  REQUIRE(r.solver.converged());
  // Sliding, but not steadily along itself (steady_sliding): the friction across the rope,
  // |N| cos(alpha) against |N| sqrt(mu^2 - cos^2 alpha) along it, holds it on the cone.
  REQUIRE(!r.full_slip);
  const double c = std::cos(alpha);
  const CapstanStep& last = r.steps.back();
  INFO("drag ratio at the end " << last.drag_ratio);
  CHECK(last.stick == 0);
  CHECK(last.slip > 0);
  CHECK(last.drag_ratio == Approx(c / std::sqrt(mu * mu - c * c)).epsilon(0.1));
  const double exact = std::exp(p.phi * std::sqrt(mu * mu - c * c) / std::sin(alpha));
  double loaded = 0.0, onset = 0.0;
  for (const CapstanStep& s : r.steps) {
    if (std::abs(s.t - 1.0) < 1e-12) loaded = s.T_ratio;
    if (onset == 0.0 && s.t > 1.0 && s.stick == 0 && s.slip > 0) onset = s.T_ratio;
  }
  INFO("exact " << exact << ", loaded " << loaded << ", onset " << onset << ", end " << r.T_ratio);
  CHECK(loaded * exact == Approx(1.0).epsilon(0.05));
  CHECK(onset == Approx(exact).epsilon(0.05));
  CHECK(r.T_ratio == Approx(exact).epsilon(0.05));
  CHECK(r.T_ratio > onset);  // it creeps up as the rope slides down the cone
}

TEST_CASE("capstan: the line pressure along the arc at full slip is T0 exp(mu theta) / rho",
          "[iga][capstan][output]") {
  // At full slip the tension along the arc is T0 e^{mu theta} (theta from the tangent point of
  // the loaded end A), and a rope of tension T on a circle of radius rho presses with T / rho
  // per unit length. -N of the contact points is a force per reference length. Point by point
  // it oscillates about that by a few per cent within each element (first Gauss point high, the
  // others low: the penalty resolves the pressure only weakly, in the element's polynomial
  // space); its mean over an element, weighted as in the contact integral, is the resolved
  // pressure (the output field contact_pressure on the rod, iga/model/analysis.cpp) and is compared
  // here, away from the
  // lift-off zones at the tangent points (bending: sqrt(EI / T) ~ 0.03; elements reaching
  // within 0.15 rad of an end excluded). Measured (penalty, default mesh): within 0.8 % at
  // mu = 0.3 and 4.4 % at mu = 1, where the deviation grows towards the tight end (a known
  // limit, not understood yet: T/T0 itself is within 0.41 %; the penetration |N| / eps_N ~
  // 7e-3 there explains about 0.7 %). With the augmented Lagrangian the point values are
  // rougher still (multipliers at Gauss points outnumber the unknowns), so the field is
  // checked with the penalty. The bounds pin today's accuracy: 1 % and 5 %.
  for (double mu : {0.3, 1.0}) {
    CapstanParameters p = capstan(mu);
    CapstanModel m = make_capstan(p);
    const CapstanResult r = run_capstan(m);
    REQUIRE(r.full_slip);
    const double rho = p.radius + p.rope_radius, theta_a = 0.5 * kPi + 0.5 * p.phi;
    const auto& points = m.problem.contact().points();
    const std::size_t per = static_cast<std::size_t>(p.contact_points);
    double worst = 0.0;
    int checked = 0;
    for (std::size_t e = 0; e + per <= points.size(); e += per) {
      double w = 0.0, pressure = 0.0, exact = 0.0;
      bool inside = true;
      for (std::size_t k = e; k < e + per; ++k) {
        const CurveContactPoint& cp = points[k];
        const double theta = theta_a - std::atan2(cp.x.y(), cp.x.x());
        inside = inside && theta >= 0.15 && theta <= p.phi - 0.15 && cp.law.active;
        w += cp.weight;
        pressure += cp.weight * -cp.N;
        exact += cp.weight * p.T0 * std::exp(mu * theta) / rho;
      }
      if (!inside) continue;
      worst = std::max(worst, std::abs(pressure / exact - 1.0));
      UNSCOPED_INFO("element " << e / per << ": mean pressure " << pressure / w << ", exact "
                               << exact / w);
      ++checked;
    }
    INFO("mu " << mu << ": " << checked << " elements, worst relative deviation " << worst);
    CHECK(checked >= 7);
    CHECK(worst <= (mu < 0.5 ? 1e-2 : 5e-2));
  }
}

TEST_CASE(
    "capstan: a rope pulled round a V-groove slides at exp(mu phi / sin alpha) on a "
    "plateau found by the steady-sliding rule",
    "[iga][capstan][friction]") {
  // The planar rope (z fixed) on a cone whose generator makes the angle alpha with the rope's
  // plane: one flank of a V-groove of half-angle alpha (the rope's plane is the groove's
  // mid-plane). The normal force |N| per unit length has the in-plane radial part
  // |N| sin(alpha) = T / rho, the friction mu |N| = dT/ds, so T / T0 = exp(mu phi / sin alpha)
  // (the V-belt law) at steady sliding. When the pull starts, every contact point slips at
  // once, but the rope still sinks into the groove: much of the friction drags across the rope
  // (B, (70)) and props it up, and T / T0 is far below the limit. The rule of the old full-slip
  // stop (every active point slips) fired there; steady_sliding waits until the friction lies
  // along the rope.
  const double alpha = 30.0 * kPi / 180.0, mu = 0.3;
  CapstanParameters p = capstan(mu);
  p.pull = 0.1;
  p.plateau_steps = 3;
  p.rigid = rope_cone(p, alpha);
  CapstanModel m = make_capstan(p);
  // A step lands on t = 1.1, the first tenth of the pull, whatever steps lead there (the first
  // pulled step may be cut back on one processor and not on another).
  NonlinearSolverSettings settings = capstan_solver_settings();
  settings.hit_times = {1.1};
  const CapstanResult r = run_capstan(m, settings);  // stops after the plateau's third step
  INFO("status " << r.solver.message);
  const double exact = std::exp(mu * p.phi / std::sin(alpha));
  double all_slip = 0.0;  // T / T0 at t = 1.1, where every point slips
  for (const CapstanStep& s : r.steps) {
    INFO("t " << s.t << " T/T0 " << s.T_ratio << " slip " << s.slip << "/" << s.active << " drag "
              << s.drag_ratio << " back " << s.slip_back);
    if (std::abs(s.t - 1.1) <= 1e-12 && s.slip == s.active) all_slip = s.T_ratio;
  }
  REQUIRE(all_slip > 0.0);
  const CapstanPlateau& pl = r.plateau;
  INFO("exact " << exact << ", every point slipping first at " << all_slip << ", plateau from t = "
                << pl.t << ": onset " << pl.onset << ", mean " << pl.mean << ", spread "
                << pl.spread() << " over " << pl.steps << " steps; wrap angle " << r.wrap_angle
                << " (exp(mu wrap / sin alpha) = " << std::exp(mu * r.wrap_angle / std::sin(alpha))
                << ")");
  CHECK(all_slip < 0.6 * exact);  // the old rule: 49 % low
  REQUIRE(pl.steps == 3);
  CHECK(pl.onset == Approx(exact).epsilon(0.01));
  CHECK(pl.mean == Approx(exact).epsilon(0.01));
  CHECK(pl.spread() < 0.002);
}

}  // namespace test_capstan
