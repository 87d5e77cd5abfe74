// The capstan problem of [KS15] Sect. 6.3 (Euler-Eytelwein (82)); set-up and parameter choices
// are explained in capstan.hpp.
#include "tests/support/capstan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/constructions.hpp"

namespace iga {

namespace {

constexpr double kPi = std::numbers::pi;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void require(bool ok, const char* field, const char* expected, double value) {
  if (!ok)
    throw std::invalid_argument(std::string("CapstanParameters.") + field + ": must be " +
                                expected + ", got " + num(value));
}

// The reference centre line: line + arc (helix) + line, fitted by a cubic with double knots at
// the tangent points (geometry/constructions.hpp, make_wrap_path).
WrapPath rope_path(const CapstanParameters& p) {
  WrapPathSpec w;
  w.radius = p.radius + p.rope_radius;  // gap (52) zero in the reference
  w.angle = p.phi;
  w.pitch = p.pitch;
  w.span_length = p.span_length;
  w.arc_elements = p.arc_elements;
  w.span_elements = p.span_elements;
  return make_wrap_path(w);
}

// Signed clockwise angle (about +z) from a to b, unwrapped to lie nearest to `near`.
double clockwise_angle(const Vector3d& a, const Vector3d& b, double near) {
  double w = std::atan2(-a.cross(b).z(), a.dot(b));
  while (w < near - kPi) w += 2.0 * kPi;
  while (w > near + kPi) w -= 2.0 * kPi;
  return w;
}

// The default rigid surface: a cylinder about e_z; its seam (u = 0, ref_dir -e_y) lies opposite
// the middle of the arc. Long enough for the helix and its spans: rise pitch phi / 2 pi plus the
// spans' rise.
std::shared_ptr<const RigidSurface> capstan_cylinder(const CapstanParameters& p) {
  auto rigid = std::make_shared<RigidSurface>();
  const double height = std::abs(p.pitch) * p.phi / (2.0 * kPi) + 2.0 * p.span_length + 1.0;
  if (p.nurbs_cylinder)
    rigid->add(make_cylinder(Vector3d(0, 0, -0.5 * height), Vector3d::UnitZ(), -Vector3d::UnitY(),
                             p.radius, height));
  else
    rigid->add(
        Cylinder(Placement{Vector3d::Zero(), Vector3d::UnitZ(), -Vector3d::UnitY()}, p.radius));
  return rigid;
}

}  // namespace

void CapstanParameters::validate() const {
  require(radius > 0.0, "radius", "> 0", radius);
  require(rope_radius >= 0.0, "rope_radius", ">= 0", rope_radius);
  require(phi > 0.0 && phi <= 2.0 * kPi * (1.0 + 1e-12), "phi", "in (0, 2 pi]", phi);
  require(mu >= 0.0, "mu", ">= 0", mu);
  require(T0 > 0.0, "T0", "> 0", T0);
  require(EA > 0.0, "EA", "> 0", EA);
  require(EI > 0.0, "EI", "> 0 (the free spans have no other lateral stiffness at t = 0)", EI);
  require(eps_N > 0.0, "eps_N", "> 0", eps_N);
  require(eps_T >= 0.0, "eps_T", ">= 0", eps_T);
  require(span_length > 0.0, "span_length", "> 0", span_length);
  require(arc_elements >= 1, "arc_elements", ">= 1", arc_elements);
  require(span_elements >= 1, "span_elements", ">= 1", span_elements);
  require(contact_points >= 1 && contact_points <= 16, "contact_points", "in 1..16",
          contact_points);
  require(pull >= 0.0, "pull", ">= 0", pull);
  require(std::isfinite(pitch), "pitch", "finite", pitch);
}

double CapstanParameters::exact_ratio() const {
  const double rho = radius + rope_radius, c = pitch / (2.0 * kPi);
  return std::exp(mu * phi * rho / std::sqrt(rho * rho + c * c));
}  // (83); (82) for pitch 0

CapstanModel make_capstan(const CapstanParameters& p) {
  p.validate();
  const WrapPath fit = rope_path(p);

  std::shared_ptr<const RigidSurface> rigid = p.rigid;
  if (!rigid) rigid = capstan_cylinder(p);
  RodSection section;
  section.EA = p.EA;
  section.EI1 = section.EI2 = p.EI;
  KirchhoffRod rod(fit.curve, section);
  const CurveContactParameters cp{{p.eps_N, p.eps_T, p.mu}, p.rope_radius, p.contact_points};
  CapstanModel m{p,
                 RodContactProblem(std::move(rod), rigid, cp),
                 fit.max_deviation,
                 0,
                 0,
                 Vector3d::Zero(),
                 Vector3d::Zero()};
  RodContactProblem& prob = m.problem;
  const int n = prob.num_control_points();
  m.end_a = 0;
  m.end_b = n - 1;
  // Along the fitted centre line's end tangents (within 2e-5 rad of the exact travel directions
  // fit.tangent_start / end), as the model files' "outward_tangent" (iga/model/analysis.hpp).
  const Interval D = fit.curve.domain();
  m.out_a = -fit.curve.derivs(D.lo, 1).d[1].normalized();
  m.out_b = fit.curve.derivs(D.hi, 1).d[1].normalized();

  if (p.pitch == 0.0 && p.planar)
    for (int i = 0; i < n; ++i) prob.fix(i, 2);  // planar problem
  // End A: dead load T0 along its outgoing direction, ramped over t in [0, 1].
  prob.add_point_load(fit.curve.domain().lo, p.T0 * m.out_a,
                      [](double t) { return std::min(t, 1.0); });
  // End B: pinned for t <= 1, then pulled along its outgoing direction.
  prob.prescribe(m.end_b, Vector3d(p.pull * m.out_b),
                 [](double t) { return std::clamp(t - 1.0, 0.0, 1.0); });
  return m;
}

NonlinearSolverSettings capstan_solver_settings() {
  NonlinearSolverSettings s;
  s.t0 = 0.0;
  s.t1 = 2.0;
  s.initial_step = 0.1;
  s.max_step = 0.1;
  s.min_step = 1e-5;
  s.max_iterations = 25;
  return s;
}

CapstanResult run_capstan(CapstanModel& model, NonlinearSolverSettings settings, std::ostream* log,
                          CapstanStop stop) {
  settings.t0 = 0.0;
  settings.t1 = 2.0;
  RodContactProblem& prob = model.problem;
  const CapstanParameters& p = model.parameters;
  CapstanResult res;
  res.exact = p.exact_ratio();
  NonlinearSolver solver(settings);
  solver.set_log(log);
  if (log) {
    char line[200];
    std::snprintf(line, sizeof line,
                  "capstan: mu = %g, phi = %.6g, %d control points, fitted centre line within "
                  "%.3e of line + arc + line, EI / (T0 R^2) = %.3g\n",
                  p.mu, p.phi, prob.num_control_points(), model.fit_deviation,
                  p.EI / (p.T0 * p.radius * p.radius));
    *log << line;
  }
  VectorXd u = VectorXd::Zero(prob.num_dofs());
  Vector3d reaction = Vector3d::Zero();
  std::vector<Vector3d> x;
  const KirchhoffRod& rod = prob.rod();

  auto on_step = [&](const VectorXd& uc, double t, const StepAttempt& a) {
    const CurveContactCounts c = prob.contact().counts();
    reaction = prob.reactions(uc, t)[static_cast<std::size_t>(model.end_b)];
    CapstanStep st{t, reaction.norm() / p.T0, c.active, c.stick, c.slip, a.iterations};
    st.drag_ratio = c.drag_ratio();
    st.slip_back = std::min(c.slip_positive, c.slip_negative);
    res.steps.push_back(st);
    const bool sliding =
        t > 1.0 + 1e-12 && steady_sliding(c.active, c.slip, st.slip_back, st.drag_ratio, p.mu);
    CapstanPlateau& pl = res.plateau;
    if (sliding) {
      if (res.full_slip_t < 0.0) res.full_slip_t = t;
      if (pl.steps == 0) pl = CapstanPlateau{t, st.T_ratio, st.T_ratio, st.T_ratio, st.T_ratio, 0};
      ++pl.steps;
      pl.min = std::min(pl.min, st.T_ratio);
      pl.max = std::max(pl.max, st.T_ratio);
      pl.mean += (st.T_ratio - pl.mean) / pl.steps;
    } else if (pl.steps > 0 && pl.steps < p.plateau_steps) {
      pl = CapstanPlateau{};  // interrupted before it was long enough: look for the next
    }
    res.full_slip = sliding;
    prob.current_points(uc, t, x);
    for (int e = 0; e < rod.num_elements(); ++e)
      for (int q = 0; q < rod.num_quadrature_points(e); ++q)
        res.max_axial_strain = std::max(
            res.max_axial_strain, std::abs(rod.strains(rod.quadrature_point(e, q).xi, x).eps));
    if (log) {
      char line[160];
      std::snprintf(line, sizeof line,
                    "capstan t = %.6f  T/T0 = %.6f  active %d  stick %d  slip %d\n", st.t,
                    st.T_ratio, st.active, st.stick, st.slip);
      *log << line;
    }
    return !(stop == CapstanStop::kFullSlip && res.plateau.steps >= p.plateau_steps);
  };
  res.solver = solver.solve(prob, u, on_step);
  res.u = u;
  res.reaction = reaction;
  if (!res.steps.empty()) {
    res.T_ratio = res.steps.back().T_ratio;
    res.wrap_angle = clockwise_angle(-model.out_a, reaction.normalized(), p.phi);
  }
  return res;
}

}  // namespace iga
