// Model file -> rod (+ contact) problem -> nonlinear solver -> output files. The sections and
// their keys are documented in docs/model_format.md ("Analysis sections").
#include "iga/model/analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <tuple>

#include "geometry/constructions.hpp"
#include "iga/model/model.hpp"
#include "iga/output/output_format.hpp"
#include "iga/output/vtk_writer.hpp"

namespace iga {

namespace {

namespace fs = std::filesystem;

std::string fmt(double v) {
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

/// Largest accepted "t_end" (pseudo-time).
constexpr double kMaxEndTime = 1e6;

double positive(const JsonCursor& c, bool allow_zero = false) {
  const double x = c.as_number();
  if (allow_zero ? !(x >= 0.0) : !(x > 0.0)) c.fail(allow_zero ? "must be >= 0" : "must be > 0");
  return x;
}
double number_or(const JsonCursor& o, const char* key, double fallback) {
  return o.has(key) ? o[key].as_number() : fallback;
}
/// An integer key of `o` in [lo, hi] (message `range`), or `fallback` if absent.
int int_or(const JsonCursor& o, const char* key, int fallback, int lo, int hi, const char* range) {
  if (!o.has(key)) return fallback;
  const JsonCursor c = o[key];
  const int n = c.as_int();
  if (n < lo || n > hi) c.fail(std::string("must be in ") + range);
  return n;
}
/// The penalty and friction keys of a contact pair: eps_N > 0, eps_T >= 0 (0), mu >= 0 (0).
template <class Params>
void penalty_and_friction(const JsonCursor& c, Params& p) {
  p.eps_n = positive(c["eps_N"]);
  p.eps_t = c.has("eps_T") ? positive(c["eps_T"], true) : 0.0;
  p.mu = c.has("mu") ? positive(c["mu"], true) : 0.0;
}
Vector3d vec3(const JsonCursor& c) {
  if (!c.json().is_array() || c.json().size() != 3) c.fail_type("3 components [x, y, z]");
  return Vector3d(c[0].as_number(), c[1].as_number(), c[2].as_number());
}
/// The value of `key` in `o`, which must be one of `names`.
std::string one_of(const JsonCursor& c, std::initializer_list<const char*> names) {
  const std::string s = c.as_string();
  std::string list;
  for (const char* n : names) {
    if (s == n) return s;
    list += std::string(list.empty() ? "" : ", ") + "\"" + n + "\"";
  }
  c.fail("expected one of " + list);
}
/// The enforcement keys of a contact pair: "enforcement" "penalty" (default) or
/// "augmented_lagrange" with "penetration_tol" (a length > 0, required) and
/// "max_augmentations" (1..1000, default 10) and "slip_tol" (a length > 0, optional: exact
/// stick); these only with the augmented Lagrangian.
ContactEnforcement parse_enforcement(const JsonCursor& c) {
  ContactEnforcement e;
  if (c.has("enforcement"))
    e.augmented =
        one_of(c["enforcement"], {"penalty", "augmented_lagrange"}) == "augmented_lagrange";
  if (!e.augmented) {
    for (const char* k : {"penetration_tol", "max_augmentations", "slip_tol"})
      if (c.has(k)) c[k].fail("applies only with \"enforcement\": \"augmented_lagrange\"");
    return e;
  }
  e.penetration_tol = positive(c["penetration_tol"]);
  e.max_augmentations = int_or(c, "max_augmentations", e.max_augmentations, 1, 1000, "1..1000");
  if (c.has("slip_tol")) e.slip_tol = positive(c["slip_tol"]);
  return e;
}

// ---- load curves ---------------------------------------------------------------------------

LoadCurve parse_load_curve(const JsonCursor& c) {
  c.expect_object({"type", "points", "scale", "rate", "value", "description"});
  const std::string type =
      one_of(c["type"], {"ramp", "constant", "piecewise_linear", "exponential"});
  if (type == "ramp") {
    c.expect_object({"type", "scale", "description"});
    const double a = number_or(c, "scale", 1.0);
    return [a](double t) { return a * t; };
  }
  if (type == "constant") {
    c.expect_object({"type", "value", "description"});
    return constant_curve(c["value"].as_number());
  }
  if (type == "exponential") {  // scale * exp(rate t), e.g. springs weakening over t
    c.expect_object({"type", "scale", "rate", "description"});
    const double a = number_or(c, "scale", 1.0), k = c["rate"].as_number();
    return [a, k](double t) { return a * std::exp(k * t); };
  }
  c.expect_object({"type", "points", "description"});
  const JsonCursor pc = c["points"];
  pc.expect_array(1);
  std::vector<double> ts, vs;
  for (std::size_t i = 0; i < pc.size(); ++i) {
    const std::vector<double> p = pc[i].as_numbers();
    if (p.size() != 2) pc[i].fail("expected a pair [t, value]");
    if (i > 0 && !(p[0] > ts.back())) pc[i][0].fail("times must increase");
    ts.push_back(p[0]);
    vs.push_back(p[1]);
  }
  // Linear between the points, constant beyond the ends.
  return [ts, vs](double t) {
    if (t <= ts.front()) return vs.front();
    if (t >= ts.back()) return vs.back();
    std::size_t k = 1;
    while (ts[k] < t) ++k;
    const double s = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
    return (1.0 - s) * vs[k - 1] + s * vs[k];
  };
}

/// A load curve whose value is not finite somewhere in [t0, t1] (an exponential or a scaled
/// ramp that overflows) is refused: no output may hold a non-finite number. Ramps and
/// exponentials are monotone and piecewise linear curves are bounded by their points, so the
/// ends decide; the samples in between are a guard.
void check_finite_curve(const JsonCursor& c, const LoadCurve& f, const NonlinearSolverSettings& s) {
  constexpr int n = 64;
  std::vector<double> ts = s.hit_times;
  for (int k = 0; k <= n; ++k) ts.push_back(s.t0 + (s.t1 - s.t0) * k / n);
  for (double t : ts) {
    const double v = f(t);
    if (!std::isfinite(v))
      c.fail_plain("the load curve must be finite over the run's pseudo-time [" + fmt(s.t0) + ", " +
                   fmt(s.t1) + "], got " + fmt(v) + " at t = " + fmt(t));
  }
}

struct Context {
  std::map<std::string, LoadCurve> curves;
  std::string body;  // the one body's name
  BodyKind kind = BodyKind::kRod;
  const NurbsCurve* curve = nullptr;      // rod
  const NurbsSurface* surface = nullptr;  // shell
  int n_points = 0;
  int nu = 0, nv = 0;  // shell: control points in u and v
};

LoadCurve curve_of(const JsonCursor& o, const Context& ctx) {
  if (!o.has("curve")) return ramp();
  const JsonCursor c = o["curve"];
  const auto it = ctx.curves.find(c.as_string());
  if (it == ctx.curves.end()) c.fail("names no entry of \"load_curves\"");
  return it->second;
}

void check_body(const JsonCursor& o, const Context& ctx) {
  const JsonCursor b = o["body"];
  if (b.as_string() != ctx.body) b.fail("names no body (the model's body is \"" + ctx.body + "\")");
}

/// A control point: rod "start", "end" or an index; shell [i, j] (i along u) or an index
/// i + n_u j.
int point_index(const JsonCursor& c, const Context& ctx) {
  if (ctx.kind == BodyKind::kRod && c.json().is_string()) {
    const std::string s = one_of(c, {"start", "end"});
    return s == "start" ? 0 : ctx.n_points - 1;
  }
  if (ctx.kind == BodyKind::kShell && c.json().is_array()) {
    if (c.size() != 2) c.fail_type("a control point [i, j] or an index");
    const int i = c[0].as_int(), j = c[1].as_int();
    if (i < 0 || i >= ctx.nu) c[0].fail("i must be in 0.." + std::to_string(ctx.nu - 1));
    if (j < 0 || j >= ctx.nv) c[1].fail("j must be in 0.." + std::to_string(ctx.nv - 1));
    return i + ctx.nu * j;
  }
  const int i = c.as_int();
  if (i < 0 || i >= ctx.n_points)
    c.fail("control point index must be in 0.." + std::to_string(ctx.n_points - 1));
  return i;
}

/// "all", "corners" (shell: the four corner points; rod: both ends), one point or a list.
std::vector<int> point_list(const JsonCursor& pc, const Context& ctx) {
  std::vector<int> points;
  if (pc.json().is_string() && (pc.as_string() == "all" || pc.as_string() == "corners")) {
    if (pc.as_string() == "all") {
      for (int i = 0; i < ctx.n_points; ++i) points.push_back(i);
    } else if (ctx.kind == BodyKind::kShell) {
      points = {0, ctx.nu - 1, ctx.nu * (ctx.nv - 1), ctx.nu * ctx.nv - 1};
    } else {
      points = {0, ctx.n_points - 1};
    }
  } else if (pc.json().is_array() &&
             !(ctx.kind == BodyKind::kShell && pc.size() == 2 && pc[0].json().is_number())) {
    pc.expect_array(1);
    for (std::size_t k = 0; k < pc.size(); ++k) points.push_back(point_index(pc[k], ctx));
  } else {
    points.push_back(point_index(pc, ctx));
  }
  return points;
}

std::vector<int> components(const JsonCursor& o) {
  std::vector<int> comps = {0, 1, 2};
  if (o.has("components")) {
    const JsonCursor cc = o["components"];
    cc.expect_array(1);
    comps.clear();
    for (std::size_t k = 0; k < cc.size(); ++k) {
      const int c = cc[k].as_int();
      if (c < 0 || c > 2) cc[k].fail("component must be 0, 1 or 2");
      comps.push_back(c);
    }
  }
  return comps;
}

/// Unit tangent pointing out of the curve at one of its ends.
Vector3d outward_tangent(const NurbsCurve& C, bool at_end) {
  const Interval D = C.domain();
  const Vector3d d = C.derivs(at_end ? D.hi : D.lo, 1).d[1].normalized();
  return at_end ? d : Vector3d(-d);
}

/// A vector given as [x, y, z] (key `vec_key`), or as "magnitude" along "direction", where the
/// direction is [x, y, z] or "outward_tangent" (at the curve's start or end, `where`).
Vector3d vector_value(const JsonCursor& o, const char* vec_key, const Context& ctx, int where) {
  if (o.has(vec_key)) {
    if (o.has("magnitude") || o.has("direction"))
      o.fail_plain(std::string("give either \"") + vec_key +
                   "\" or \"magnitude\" and \"direction\"");
    return vec3(o[vec_key]);
  }
  const double m = o["magnitude"].as_number();
  const JsonCursor d = o["direction"];
  if (d.json().is_string() && ctx.kind == BodyKind::kRod) {
    one_of(d, {"outward_tangent"});
    if (where != 0 && where != 1)
      d.fail("\"outward_tangent\" needs the point \"start\" or \"end\"");
    return m * outward_tangent(*ctx.curve, where == 1);
  }
  const Vector3d v = vec3(d);
  if (!(v.norm() > 0.0)) d.fail("must be a non-zero vector");
  return m * v.normalized();
}
/// "start", "end" or a parameter in the curve's domain.
double curve_parameter(const JsonCursor& c, const NurbsCurve& C) {
  const Interval D = C.domain();
  if (c.json().is_string()) return one_of(c, {"start", "end"}) == "start" ? D.lo : D.hi;
  const double xi = c.as_number();
  if (xi < D.lo || xi > D.hi)
    c.fail("parameter must lie in the curve's domain [" + std::to_string(D.lo) + ", " +
           std::to_string(D.hi) + "]");
  return xi;
}

/// 0 for "start", 1 for "end", -1 otherwise.
int end_of(const JsonCursor& c) {
  if (!c.json().is_string()) return -1;
  return c.as_string() == "start" ? 0 : c.as_string() == "end" ? 1 : -1;
}

/// {"type": "fix", "points": ..., "components": [...]} (rods and shells).
void fix_points(const JsonCursor& o, const Context& ctx, ControlPointProblem& p) {
  o.expect_object({"type", "body", "points", "components", "description"});
  const std::vector<int> comps = components(o);
  for (int i : point_list(o["points"], ctx))
    for (int c : comps)
      if (!p.constrained(i, c)) p.fix(i, c);
}

void parse_rod_boundary_condition(const JsonCursor& o, const Context& ctx, RodProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type = one_of(o["type"], {"fix", "clamp", "displacement"});
  check_body(o, ctx);
  try {
    if (type == "fix") {
      fix_points(o, ctx, p);
    } else if (type == "clamp") {
      o.expect_object({"type", "body", "end", "description"});
      const std::string e = one_of(o["end"], {"start", "end"});
      p.clamp(e == "start" ? RodEnd::kStart : RodEnd::kEnd);
    } else {
      o.expect_object(
          {"type", "body", "point", "value", "magnitude", "direction", "curve", "description"});
      const int i = point_index(o["point"], ctx);
      const Vector3d d = vector_value(o, "value", ctx, end_of(o["point"]));
      p.prescribe(i, d, curve_of(o, ctx));
    }
  } catch (const RodError& e) {
    o.fail_plain(e.what());
  }
}

void parse_rod_load(const JsonCursor& o, const Context& ctx, RodProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type = one_of(o["type"], {"point_force", "line_load", "moment"});
  check_body(o, ctx);
  auto at = [&](const JsonCursor& c) { return curve_parameter(c, *ctx.curve); };
  if (type == "point_force") {
    o.expect_object(
        {"type", "name", "body", "at", "force", "magnitude", "direction", "curve", "description"});
    p.add_point_load(at(o["at"]), vector_value(o, "force", ctx, end_of(o["at"])), curve_of(o, ctx));
  } else if (type == "line_load") {
    o.expect_object({"type", "name", "body", "q", "curve", "description"});
    p.add_line_load(vec3(o["q"]), curve_of(o, ctx));
  } else {
    o.expect_object({"type", "name", "body", "at", "moment", "curve", "description"});
    p.add_moment(at(o["at"]), vec3(o["moment"]), curve_of(o, ctx));
  }
}

std::shared_ptr<const RigidSurface> rigid_surface(const JsonCursor& rc, const GeometryModel& g) {
  try {
    return std::make_shared<RigidSurface>(RigidSurface::from_geometry(g, rc.as_string()));
  } catch (const std::invalid_argument& e) {
    rc.fail(std::string("not a rigid surface: ") + e.what());
  }
}

// ---- shell bodies -----------------------------------------------------------------------------

SurfaceEdge parse_edge(const JsonCursor& c) {
  const std::string e = one_of(c, {"u_min", "u_max", "v_min", "v_max"});
  return e == "u_min"   ? SurfaceEdge::kUMin
         : e == "u_max" ? SurfaceEdge::kUMax
         : e == "v_min" ? SurfaceEdge::kVMin
                        : SurfaceEdge::kVMax;
}

/// A parameter pair (u, v) inside the surface's domain.
Vector2d surface_parameters(const JsonCursor& c, const NurbsSurface& S) {
  const std::vector<double> uv = c.as_numbers();
  if (uv.size() != 2) c.fail_type("surface parameters [u, v]");
  const Domain2 D = S.domain();
  const Interval I[2] = {D.u, D.v};
  for (int k = 0; k < 2; ++k)
    if (uv[k] < I[k].lo || uv[k] > I[k].hi)
      c[static_cast<std::size_t>(k)].fail("parameter must lie in the surface's domain [" +
                                          std::to_string(I[k].lo) + ", " + std::to_string(I[k].hi) +
                                          "]");
  return {uv[0], uv[1]};
}

void parse_shell_boundary_condition(const JsonCursor& o, const Context& ctx, ShellProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type =
      one_of(o["type"], {"fix", "displacement", "simply_supported", "clamp", "symmetry", "spring"});
  check_body(o, ctx);
  try {
    if (type == "fix") {
      fix_points(o, ctx, p);
    } else if (type == "displacement") {
      o.expect_object(
          {"type", "body", "point", "value", "magnitude", "direction", "curve", "description"});
      p.prescribe(point_index(o["point"], ctx), vector_value(o, "value", ctx, -1),
                  curve_of(o, ctx));
    } else if (type == "simply_supported") {
      o.expect_object({"type", "body", "edge", "components", "description"});
      const std::vector<int> c = components(o);
      const SurfaceEdge e = parse_edge(o["edge"]);
      for (int k : c) p.simply_support(e, {k});
    } else if (type == "clamp") {
      o.expect_object({"type", "body", "edge", "description"});
      p.clamp(parse_edge(o["edge"]));
    } else if (type == "symmetry") {
      o.expect_object({"type", "body", "edge", "normal", "description"});
      const Vector3d n = vec3(o["normal"]);
      if (!(n.norm() > 0.0)) o["normal"].fail("must be a non-zero vector");
      p.symmetry(parse_edge(o["edge"]), n.normalized());
    } else {
      o.expect_object({"type", "body", "points", "stiffness", "curve", "direction", "description"});
      const double k = positive(o["stiffness"]);
      std::optional<Vector3d> d;
      if (o.has("direction")) {
        const Vector3d v = vec3(o["direction"]);
        if (!(v.norm() > 0.0)) o["direction"].fail("must be a non-zero vector");
        d = v.normalized();
      }
      // A spring's stiffness k curve(t); without a curve it is constant.
      const LoadCurve curve = o.has("curve") ? curve_of(o, ctx) : constant_curve();
      for (int i : point_list(o["points"], ctx)) p.add_spring(i, k, curve, d);
    }
  } catch (const ShellError& e) {
    o.fail_plain(e.what());
  }
}

void parse_shell_load(const JsonCursor& o, const Context& ctx, ShellProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type =
      one_of(o["type"], {"surface_load", "pressure", "edge_load", "point_force"});
  check_body(o, ctx);
  if (type == "surface_load") {  // dead force per reference area
    o.expect_object({"type", "name", "body", "q", "curve", "description"});
    p.add_surface_load(vec3(o["q"]), curve_of(o, ctx));
  } else if (type == "pressure") {  // follower, per current area, along +a_3
    o.expect_object({"type", "name", "body", "p", "curve", "description"});
    p.add_pressure(o["p"].as_number(), curve_of(o, ctx));
  } else if (type == "edge_load") {  // dead force per reference length
    o.expect_object({"type", "name", "body", "edge", "q", "curve", "description"});
    p.add_edge_load(parse_edge(o["edge"]), vec3(o["q"]), curve_of(o, ctx));
  } else {
    o.expect_object(
        {"type", "name", "body", "at", "force", "magnitude", "direction", "curve", "description"});
    const Vector2d uv = surface_parameters(o["at"], *ctx.surface);
    p.add_point_load(uv[0], uv[1], vector_value(o, "force", ctx, -1), curve_of(o, ctx));
  }
}

ShellMaterial parse_shell_material(const JsonCursor& m) {
  m.expect_object({"type", "E", "nu", "thickness", "description"});
  ShellMaterial s;
  s.E = positive(m["E"]);
  const JsonCursor n = m["nu"];
  s.nu = n.as_number();
  if (!(s.nu > -1.0 && s.nu < 0.5)) n.fail("must be in (-1, 0.5)");
  s.thickness = positive(m["thickness"]);
  return s;
}

RodSection parse_rod_material(const JsonCursor& m) {
  const std::string type = one_of(m["type"], {"rod", "rod_circular"});
  RodSection s;
  if (type == "rod_circular") {
    m.expect_object({"type", "E", "radius", "description"});
    return RodSection::circular(positive(m["E"]), positive(m["radius"]));
  }
  m.expect_object({"type", "EA", "EI", "EI1", "EI2", "ref_direction", "description"});
  s.EA = positive(m["EA"]);
  if (m.has("EI")) {
    if (m.has("EI1") || m.has("EI2")) m.fail_plain("give either \"EI\" or \"EI1\" and \"EI2\"");
    s.EI1 = s.EI2 = positive(m["EI"], true);
  } else {
    s.EI1 = positive(m["EI1"], true);
    s.EI2 = positive(m["EI2"], true);
  }
  if (m.has("ref_direction")) s.ref_direction = vec3(m["ref_direction"]);
  return s;
}

NonlinearSolverSettings parse_solver(const JsonCursor& s, double& stop_after, int& slip_steps) {
  s.expect_object({"t_end", "initial_step", "max_step", "min_step", "max_steps", "max_iterations",
                   "tol_residual_rel", "tol_residual_abs", "tol_residual_scaled", "tol_energy_rel",
                   "divergence_ratio", "max_residual_increases", "stop_at_full_slip_after",
                   "full_slip_steps", "hit_times", "easy_iterations", "growth_factor",
                   "cutback_factor", "description"});
  NonlinearSolverSettings n;
  n.t0 = 0.0;
  if (s.has("t_end")) {
    n.t1 = positive(s["t_end"]);
    // Pseudo-time is a load parameter, not a physical time: scale the load curves instead.
    if (n.t1 > kMaxEndTime)
      s["t_end"].fail("must be at most " + fmt(kMaxEndTime) +
                      " (pseudo-time; scale the load curves instead)");
  }
  n.initial_step = s.has("initial_step") ? positive(s["initial_step"]) : 0.1 * n.t1;
  n.max_step = s.has("max_step") ? positive(s["max_step"]) : n.t1;
  n.min_step = s.has("min_step") ? positive(s["min_step"]) : 1e-6 * n.t1;
  if (s.has("max_steps")) {
    const JsonCursor c = s["max_steps"];
    n.max_steps = c.as_int();
    if (n.max_steps < 1) c.fail("must be >= 1");
  }
  if (s.has("max_iterations")) {
    const JsonCursor c = s["max_iterations"];
    n.max_iterations = c.as_int();
    if (n.max_iterations < 1) c.fail("must be >= 1");
  }
  if (s.has("tol_residual_rel")) n.tol_residual_rel = positive(s["tol_residual_rel"]);
  if (s.has("tol_residual_abs")) n.tol_residual_abs = positive(s["tol_residual_abs"], true);
  if (s.has("tol_residual_scaled"))
    n.tol_residual_scaled = positive(s["tol_residual_scaled"], true);
  if (s.has("tol_energy_rel")) n.tol_energy_rel = positive(s["tol_energy_rel"], true);
  if (s.has("divergence_ratio")) {  // a step fails when |R_k| > divergence_ratio |R_0|
    const JsonCursor c = s["divergence_ratio"];
    n.divergence_ratio = c.as_number();
    if (!(n.divergence_ratio > 1.0)) c.fail("must be > 1");
  }
  if (s.has("max_residual_increases")) {  // ... or |R| grew this many times in a row (0: off)
    const JsonCursor c = s["max_residual_increases"];
    n.max_residual_increases = c.as_int();
    if (n.max_residual_increases < 0) c.fail("must be >= 0");
  }
  if (s.has("stop_at_full_slip_after")) stop_after = positive(s["stop_at_full_slip_after"], true);
  if (s.has("full_slip_steps")) {  // consecutive steps of steady sliding before stopping
    const JsonCursor c = s["full_slip_steps"];
    slip_steps = c.as_int();
    if (slip_steps < 1) c.fail("must be >= 1");
  }
  if (s.has("easy_iterations")) {  // a step converged in <= this many iterations grows the next
    const JsonCursor c = s["easy_iterations"];
    n.easy_iterations = c.as_int();
    if (n.easy_iterations < 0) c.fail("must be >= 0");
  }
  if (s.has("growth_factor")) n.growth_factor = positive(s["growth_factor"]);
  if (s.has("cutback_factor")) n.cutback_factor = positive(s["cutback_factor"]);
  if (s.has("hit_times")) {  // times the steps land on (snapshots)
    const JsonCursor h = s["hit_times"];
    h.expect_array();
    n.hit_times = h.as_numbers();
    for (std::size_t k = 0; k < n.hit_times.size(); ++k)
      if (!(n.hit_times[k] > n.t0 && n.hit_times[k] < n.t1))
        h[k].fail("must lie inside (0, t_end) = (0, " + fmt(n.t1) + ")");
  }
  try {
    n.validate();
  } catch (const std::invalid_argument& e) {
    s.fail_plain(e.what());
  }
  return n;
}

AnalysisOutput parse_output(const JsonCursor& o, const Context& ctx) {
  o.expect_object({"vtk", "reactions", "monitors", "samples_per_element", "description"});
  AnalysisOutput out;
  if (o.has("vtk")) {
    const std::string v = one_of(o["vtk"], {"none", "last", "all"});
    out.vtk = v == "none"  ? AnalysisOutput::Vtk::kNone
              : v == "all" ? AnalysisOutput::Vtk::kAll
                           : AnalysisOutput::Vtk::kLast;
  }
  if (o.has("reactions")) {
    const JsonCursor r = o["reactions"];
    r.expect_array();
    for (std::size_t k = 0; k < r.size(); ++k) out.reactions.push_back(point_index(r[k], ctx));
  }
  if (o.has("monitors")) {  // [{"name": "centre", "at": xi or [u, v]}]
    const JsonCursor ml = o["monitors"];
    ml.expect_array();
    for (std::size_t k = 0; k < ml.size(); ++k) {
      const JsonCursor m = ml[k];
      m.expect_object({"name", "at", "description"});
      AnalysisMonitor mon;
      mon.name = m["name"].as_string();
      if (mon.name.empty() || mon.name.find_first_of(",\"\n") != std::string::npos)
        m["name"].fail("must be a non-empty name without commas, quotes or line breaks");
      if (ctx.kind == BodyKind::kShell) {
        const Vector2d uv = surface_parameters(m["at"], *ctx.surface);
        mon.u = uv[0];
        mon.v = uv[1];
      } else {
        mon.u = curve_parameter(m["at"], *ctx.curve);
      }
      out.monitors.push_back(mon);
    }
  }
  if (o.has("samples_per_element")) {
    const JsonCursor c = o["samples_per_element"];
    out.samples_per_element = c.as_int();
    if (out.samples_per_element < 1 || out.samples_per_element > 1000) c.fail("must be in 1..1000");
  }
  return out;
}

}  // namespace

namespace {

/// Calls f on every entry of the array root[key] (if present).
template <class F>
void for_each_entry(const JsonCursor& root, const char* key, F f) {
  if (!root.has(key)) return;
  const JsonCursor list = root[key];
  list.expect_array();
  for (std::size_t k = 0; k < list.size(); ++k) f(list[k]);
}

/// The rod body, its contact pair, boundary conditions and loads.
std::unique_ptr<RodProblem> build_rod(const JsonCursor& root, const JsonCursor& b, Context& ctx,
                                      const GeometryModel& geometry, const JsonCursor& materials,
                                      std::shared_ptr<const RigidSurface>& rigid_out,
                                      RodContactProblem*& contact_out) {
  b.expect_object(
      {"type", "curve", "material", "quadrature_points", "bending", "stress_free", "description"});
  const JsonCursor cc = b["curve"];
  ctx.curve = geometry.curve(cc.as_string());
  if (ctx.curve == nullptr) cc.fail("names no curve of the geometry section");
  // The size bound of constructed curves holds for explicit ones too (docs/model_format.md).
  if (const long n = static_cast<long>(ctx.curve->knots().breaks().size()) - 1;
      n > kMaxCurveElements)
    cc.fail("the curve has " + std::to_string(n) + " elements, above the limit of " +
            std::to_string(kMaxCurveElements) + " of a rod body");
  const JsonCursor mc = b["material"];
  if (!materials.has(mc.as_string())) mc.fail("names no entry of \"materials\"");
  const JsonCursor mat = materials[mc.as_string()];
  if (one_of(mat["type"], {"rod", "rod_circular", "shell"}) == "shell")
    mc.fail("names a shell material; a rod needs type \"rod\" or \"rod_circular\"");
  const RodSection section = parse_rod_material(mat);
  RodOptions opt;
  opt.quadrature_points = int_or(b, "quadrature_points", 0, 0, 20, "0..20 (0: p + 1)");
  if (b.has("bending"))
    opt.bending =
        one_of(b["bending"], {"transported_frame", "curvature_magnitude"}) == "transported_frame"
            ? BendingMeasure::kTransportedFrame
            : BendingMeasure::kCurvatureMagnitude;
  if (b.has("stress_free"))
    opt.straight_stress_free = one_of(b["stress_free"], {"reference", "straight"}) == "straight";
  std::optional<KirchhoffRod> rod;
  try {
    rod.emplace(*ctx.curve, section, opt);
  } catch (const std::invalid_argument& e) {
    b.fail_plain(e.what());
  }
  ctx.n_points = rod->num_control_points();

  std::unique_ptr<RodProblem> problem;
  if (root.has("contact") && root["contact"].size() == 1) {
    const JsonCursor c = root["contact"][0];
    // The type first: a shell's contact keys would otherwise be reported as unknown keys.
    if (one_of(c["type"], {"curve_to_rigid", "surface_to_rigid"}) != "curve_to_rigid")
      c["type"].fail("a rod's contact is \"curve_to_rigid\"");
    c.expect_object({"name", "type", "body", "rigid", "eps_N", "eps_T", "mu", "radius",
                     "points_per_element", "enforcement", "penetration_tol", "max_augmentations",
                     "slip_tol", "description"});
    check_body(c, ctx);
    rigid_out = rigid_surface(c["rigid"], geometry);
    ContactParameters cp;
    penalty_and_friction(c, cp);
    cp.radius = c.has("radius") ? positive(c["radius"], true) : 0.0;
    const ContactEnforcement enforcement = parse_enforcement(c);
    const int ppe = int_or(c, "points_per_element", 3, 1, 16, "1..16");
    auto p = std::make_unique<RodContactProblem>(std::move(*rod), rigid_out, cp, ppe);
    p->contact().set_enforcement(enforcement);  // validated by parse_enforcement
    contact_out = p.get();
    problem = std::move(p);
  } else {
    problem = std::make_unique<RodProblem>(std::move(*rod));
  }
  for_each_entry(root, "boundary_conditions",
                 [&](const JsonCursor& o) { parse_rod_boundary_condition(o, ctx, *problem); });
  for_each_entry(root, "loads", [&](const JsonCursor& o) { parse_rod_load(o, ctx, *problem); });
  return problem;
}

/// The shell body, its contact pair, boundary conditions, springs and loads.
std::unique_ptr<ShellProblem> build_shell(const JsonCursor& root, const JsonCursor& b, Context& ctx,
                                          const GeometryModel& geometry,
                                          const JsonCursor& materials,
                                          std::shared_ptr<const RigidSurface>& rigid_out,
                                          ShellContactProblem*& contact_out) {
  b.expect_object({"type", "surface", "material", "quadrature_points", "description"});
  const JsonCursor sc = b["surface"];
  ctx.surface = dynamic_cast<const NurbsSurface*>(geometry.surface(sc.as_string()));
  if (ctx.surface == nullptr) sc.fail("names no NURBS surface of the geometry section");
  // A shell costs about 50 KB per control point to set up (its element matrices): the bound
  // of constructed surfaces holds for explicit ones too (docs/model_format.md).
  if (const long n = static_cast<long>(ctx.surface->num_u()) * ctx.surface->num_v();
      n > kMaxSurfaceControlPoints)
    sc.fail("the surface has " + std::to_string(n) + " control points, above the limit of " +
            std::to_string(kMaxSurfaceControlPoints) + " of a shell body");
  const JsonCursor mc = b["material"];
  if (!materials.has(mc.as_string())) mc.fail("names no entry of \"materials\"");
  const JsonCursor mat = materials[mc.as_string()];
  if (one_of(mat["type"], {"rod", "rod_circular", "shell"}) != "shell")
    mc.fail("names a rod material; a shell needs type \"shell\"");
  ShellOptions opt;
  opt.quadrature_points = int_or(b, "quadrature_points", 0, 0, 20, "0..20 (0: p + 1)");
  std::optional<KirchhoffLoveShell> shell;
  try {
    shell.emplace(*ctx.surface, parse_shell_material(mat), opt);
  } catch (const std::invalid_argument& e) {
    sc.fail(e.what());
  }
  ctx.nu = ctx.surface->num_u();
  ctx.nv = ctx.surface->num_v();
  ctx.n_points = ctx.nu * ctx.nv;

  std::unique_ptr<ShellProblem> problem;
  if (root.has("contact") && root["contact"].size() == 1) {
    const JsonCursor c = root["contact"][0];
    if (one_of(c["type"], {"curve_to_rigid", "surface_to_rigid"}) != "surface_to_rigid")
      c["type"].fail("a shell's contact is \"surface_to_rigid\"");
    c.expect_object({"name", "type", "body", "rigid", "eps_N", "eps_T", "mu", "strategy", "face",
                     "points_per_direction", "search_distance", "enforcement", "penetration_tol",
                     "slip_tol", "max_augmentations", "description"});
    check_body(c, ctx);
    rigid_out = rigid_surface(c["rigid"], geometry);
    for (const Surface* piece : geometry.surfaces_of(c["rigid"].as_string()))
      if (piece == ctx.surface)
        c["rigid"].fail("is (or holds) the shell's own surface \"" + sc.as_string() +
                        "\"; the rigid surface must be another surface");
    SurfaceContactParameters cp;
    penalty_and_friction(c, cp);
    if (c.has("strategy"))
      cp.strategy = one_of(c["strategy"], {"master", "slave"}) == "master"
                        ? SurfaceContactStrategy::kRigidMaster
                        : SurfaceContactStrategy::kRigidSlave;
    if (c.has("face")) {
      const std::string f = one_of(c["face"], {"lower", "upper", "mid"});
      cp.face = f == "lower"   ? ShellFace::kLower
                : f == "upper" ? ShellFace::kUpper
                               : ShellFace::kMid;
    }
    cp.points_per_direction =
        int_or(c, "points_per_direction", cp.points_per_direction, 1, 20, "1..20");
    if (c.has("search_distance")) cp.search_distance = positive(c["search_distance"]);
    const ContactEnforcement enforcement = parse_enforcement(c);
    try {
      auto p = std::make_unique<ShellContactProblem>(std::move(*shell), rigid_out, cp);
      p->contact().set_enforcement(enforcement);  // validated by parse_enforcement
      contact_out = p.get();
      problem = std::move(p);
    } catch (const std::invalid_argument& e) {
      c.fail_plain(e.what());
    }
  } else {
    problem = std::make_unique<ShellProblem>(std::move(*shell));
  }
  for_each_entry(root, "boundary_conditions",
                 [&](const JsonCursor& o) { parse_shell_boundary_condition(o, ctx, *problem); });
  for_each_entry(root, "loads", [&](const JsonCursor& o) { parse_shell_load(o, ctx, *problem); });
  return problem;
}

}  // namespace

Analysis Analysis::from_json(const Json& doc, const std::string& file) {
  const Model model = parse_model(doc, file);  // format, version, geometry, known sections
  const JsonCursor root(doc, file);
  Analysis a;
  a.name_ = model.name;
  a.geometry_ = model.geometry;
  if (!root.has("bodies")) root.fail_plain("missing required key \"bodies\" (nothing to analyse)");

  Context ctx;
  if (root.has("load_curves")) {
    const JsonCursor lc = root["load_curves"];
    if (!lc.json().is_object()) lc.fail_type("an object of named load curves");
    for (const std::string& k : lc.keys()) {
      ctx.curves[k] = parse_load_curve(lc[k]);
      a.curves_.emplace_back(k, ctx.curves[k]);
    }
  }
  const Json no_materials = Json::object();
  const JsonCursor materials =
      root.has("materials") ? root["materials"] : JsonCursor(no_materials, file);
  if (!materials.json().is_object()) materials.fail_type("an object of named materials");
  for (const std::string& k : materials.keys()) {  // every entry is checked, used or not
    const JsonCursor m = materials[k];
    if (one_of(m["type"], {"rod", "rod_circular", "shell"}) == "shell")
      parse_shell_material(m);
    else
      parse_rod_material(m);
  }

  // The body: one rod or one shell in this version.
  const JsonCursor bodies = root["bodies"];
  if (!bodies.json().is_object() || bodies.size() != 1)
    bodies.fail_type("an object with exactly one named body (one deformable body per model)");
  ctx.body = bodies.keys().front();
  a.body_ = ctx.body;
  const JsonCursor b = bodies[ctx.body];
  if (!b.json().is_object()) b.fail_type("an object with a \"type\" key");
  ctx.kind = one_of(b["type"], {"rod", "shell"}) == "rod" ? BodyKind::kRod : BodyKind::kShell;
  a.kind_ = ctx.kind;
  if (root.has("contact")) {  // at most one pair, the body against a rigid surface
    const JsonCursor cl = root["contact"];
    cl.expect_array();
    if (cl.size() > 1)
      cl.fail_plain("one contact pair per model in this version, got " + std::to_string(cl.size()));
  }
  if (ctx.kind == BodyKind::kRod) {
    auto p = build_rod(root, b, ctx, a.geometry_, materials, a.rigid_, a.rod_contact_);
    a.rod_ = p.get();
    a.problem_ = std::move(p);
  } else {
    auto p = build_shell(root, b, ctx, a.geometry_, materials, a.rigid_, a.shell_contact_);
    a.shell_ = p.get();
    a.problem_ = std::move(p);
  }
  if (root.has("solver"))
    a.settings_ = parse_solver(root["solver"], a.stop_full_slip_after_, a.full_slip_steps_);
  // Every load curve, used or not (steps.csv has a column for each), must stay finite over the
  // run's pseudo-time.
  for (const auto& [name, curve] : a.curves_)
    check_finite_curve(root["load_curves"][name], curve, a.settings_);
  if (root.has("output")) a.output_ = parse_output(root["output"], ctx);
  if (a.output_.samples_per_element == 0)
    a.output_.samples_per_element = ctx.kind == BodyKind::kRod ? 16 : 4;
  if (a.problem_->num_dofs() == 0)
    root["boundary_conditions"].fail_plain("every degree of freedom is constrained");
  return a;
}

Analysis Analysis::load(const std::string& path) {
  return from_json(read_json_file(path), path);
}

RodProblem& Analysis::rod_problem() {
  if (rod_ == nullptr) throw std::logic_error("Analysis::rod_problem: the body is a shell");
  return *rod_;
}

ShellProblem& Analysis::shell_problem() {
  if (shell_ == nullptr) throw std::logic_error("Analysis::shell_problem: the body is a rod");
  return *shell_;
}

std::string Analysis::describe() const {
  std::ostringstream s;
  if (rod_) {
    s << "rod of " << rod_->rod().num_elements() << " elements (degree " << rod_->rod().degree()
      << ", ";
  } else {
    const NurbsSurface& S = shell_->shell().reference();
    s << "shell of " << shell_->shell().num_elements() << " elements (degree " << S.degree_u()
      << " x " << S.degree_v() << ", ";
  }
  s << problem_->num_control_points() << " control points), " << problem_->num_dofs()
    << " unknowns";
  if (rod_contact_)
    s << ", CTRS contact with a rigid surface of " << rigid_->num_patches() << " piece(s), "
      << rod_contact_->contact().points().size() << " contact points";
  if (shell_contact_) {
    const SurfaceContactParameters& p = shell_contact_->contact().parameters();
    s << ", STAS contact (rigid "
      << (p.strategy == SurfaceContactStrategy::kRigidMaster ? "master" : "slave")
      << ", mu = " << p.mu << ") with a rigid surface of " << rigid_->num_patches() << " piece(s), "
      << shell_contact_->contact().points().size() << " contact points";
  }
  s << ", t in [" << settings_.t0 << ", " << settings_.t1 << "]";
  return s.str();
}

ContactCounts Analysis::contact_counts() const {
  if (rod_contact_) {
    const CurveContactCounts c = rod_contact_->contact().counts();
    return {c.active, c.stick, c.slip, c.drag_ratio(), std::min(c.slip_positive, c.slip_negative)};
  }
  if (shell_contact_) {
    const SurfaceContactCounts c = shell_contact_->contact().counts();
    return {c.active, c.stick, c.slip};
  }
  return {};
}

double Analysis::contact_mu() const {
  if (rod_contact_) return rod_contact_->contact().parameters().mu;
  if (shell_contact_) return shell_contact_->contact().parameters().mu;
  return 0.0;
}

double Analysis::contact_time() const {
  if (rod_contact_) return rod_contact_->contact_time();
  if (shell_contact_) return shell_contact_->contact_time();
  return 0.0;
}

Vector3d Analysis::displacement(const AnalysisMonitor& m, const VectorXd& u, double t) const {
  if (shell_) return shell_->displacement(m.u, m.v, u, t);
  const std::vector<Vector3d> x = rod_->current_points(u, t);
  return rod_->rod().point(m.u, x) - rod_->rod().reference().point(m.u);
}

std::vector<Vector3d> Analysis::reactions(const VectorXd& u, double t) {
  const std::vector<Vector3d> all = rod_contact_     ? rod_contact_->reactions(u, t)
                                    : shell_contact_ ? shell_contact_->reactions(u, t)
                                                     : problem_->nodal_residual(u, t);
  std::vector<Vector3d> r;
  for (int i : output_.reactions) r.push_back(all[static_cast<std::size_t>(i)]);
  return r;
}

namespace {

/// The rod's centre line sampled per element, with axial force and curvature. A sample where
/// the strains cannot be evaluated (a zero tangent, e.g. at an end whose first two control
/// points coincide) gets zero force and curvature and the flag singular = 1.
/// Contact fields on the rod, per element: the line pressure -N (force per reference length),
/// the pulling and dragging tractions T (69), B (70), each the mean of the element's contact
/// points weighted as in the contact integral (what the penalty resolves: point by point the
/// values oscillate about it within an element), and the state 0 apart, 1 stick, 2 slip (2 if
/// any point of the element slides, 1 if one sticks).
struct RodContactFields {
  double pressure = 0.0, T = 0.0, B = 0.0, state = 0.0;
};

RodContactFields rod_contact_fields(const CurveContact& contact, const Interval& I) {
  RodContactFields f;
  double w = 0.0;
  for (const CurveContactPoint& cp : contact.points()) {
    if (cp.eta < I.lo || cp.eta > I.hi) continue;
    w += cp.weight;
    if (!cp.law.active) continue;
    f.pressure += cp.weight * -cp.N;
    f.T += cp.weight * cp.T;
    f.B += cp.weight * cp.B;
    f.state = std::max(f.state, cp.law.slip ? 2.0 : 1.0);
  }
  if (w > 0.0) {
    f.pressure /= w;
    f.T /= w;
    f.B /= w;
  }
  return f;
}

void write_rod_vtk(const std::string& path, const KirchhoffRod& rod, const std::vector<Vector3d>& x,
                   int samples, const std::string& title, const CurveContact* contact) {
  std::vector<Vector3d> line;
  std::vector<double> force, curvature, singular;
  std::vector<double> pressure, traction_T, traction_B, state;
  for (int e = 0; e < rod.num_elements(); ++e) {
    const Interval I = rod.element_range(e);
    const RodContactFields cf = contact ? rod_contact_fields(*contact, I) : RodContactFields{};
    for (int k = (e == 0 ? 0 : 1); k <= samples; ++k) {
      const double xi = I.lo + (I.hi - I.lo) * k / samples;
      line.push_back(rod.point(xi, x));
      double n = 0.0, kappa = 0.0;
      bool ok = true;
      try {
        const RodStrains st = rod.strains(xi, x);
        n = st.axial_force;
        kappa = st.curvature;
        ok = std::isfinite(n) && std::isfinite(kappa);
      } catch (const std::exception&) {
        ok = false;
      }
      force.push_back(ok ? n : 0.0);
      curvature.push_back(ok ? kappa : 0.0);
      singular.push_back(ok ? 0.0 : 1.0);
      pressure.push_back(cf.pressure);
      traction_T.push_back(cf.T);
      traction_B.push_back(cf.B);
      state.push_back(cf.state);
    }
  }
  VtkPointData d;
  d.scalars = {{"axial_force", force}, {"curvature", curvature}, {"singular", singular}};
  if (contact) {
    d.scalars.push_back({"contact_pressure", pressure});
    d.scalars.push_back({"contact_traction_T", traction_T});
    d.scalars.push_back({"contact_traction_B", traction_B});
    d.scalars.push_back({"contact_state", state});
  }
  write_vtk_polydata(path, line, true, d, title);
}

/// Parameters of a grid over the element spans: `samples` intervals per span.
std::vector<double> span_samples(const std::vector<double>& breaks, int samples) {
  std::vector<double> s;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
    for (int i = (k == 0 ? 0 : 1); i <= samples; ++i)
      s.push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * i / samples);
  return s;
}

/// Contact fields over the shell (issue 12 item 6): the pressure -N, the tangential traction on
/// the shell T_vector, the gap xi3 and the state (0 apart, 1 stick, 2 slip) of the element's
/// n x n contact (Gauss) points, evaluated anywhere in the element. N of the contact law (34) and
/// T_vector are forces per reference area: the contact integral weights them with cp.weight, the
/// Gauss weight times the reference area element. The interpolation:
///  - where all points of the element are in contact and in one state (pressure and traction
///    are smooth there): tensor-product Lagrange interpolation through the points' parameters,
///    f(u, v) = sum_ij f_ij l_i(u) l_j(v), l_i(u) = prod_{k != i} (u - u_k) / (u_i - u_k). It
///    reproduces a field of degree n - 1 in each parameter, e.g. the penalty pressure on a flat
///    tool, eps_N times the gap of a polynomial shell, up to the rational part of the normal;
///  - where the edge of the contact zone or of a stick zone runs through the element (a kink
///    between the points: a polynomial through them would overshoot): piecewise bilinear between
///    the neighbouring points, held constant from the outer points to the element's edges.
/// The pressure is clamped at >= 0; the state is the nearest point's. The gap is interpolated
/// among the points that have a foot within the search distance (the others have no gap); where
/// none has, it is unknown: 0 and gap_known = false.
class ShellContactField {
 public:
  ShellContactField(const SurfaceContact& contact, const NurbsSurface& S)
      : contact_(contact), bu_(S.knots_u().breaks()), bv_(S.knots_v().breaks()) {
    const std::size_t nu = bu_.size() - 1, nv = bv_.size() - 1;
    elements_.resize(nu * nv);
    for (const SurfaceContactPoint& cp : contact.points()) {
      const auto e = static_cast<std::size_t>(cp.element);
      if (e < elements_.size()) elements_[e].points.push_back(&cp);
    }
    for (Element& el : elements_) {
      for (const SurfaceContactPoint* p : el.points) {
        el.u.push_back(p->uv[0]);
        el.v.push_back(p->uv[1]);
      }
      for (std::vector<double>* a : {&el.u, &el.v}) {
        std::sort(a->begin(), a->end());
        a->erase(std::unique(a->begin(), a->end()), a->end());
      }
      el.grid.assign(el.u.size() * el.v.size(), nullptr);
      for (const SurfaceContactPoint* p : el.points) {
        const auto i = std::lower_bound(el.u.begin(), el.u.end(), p->uv[0]) - el.u.begin();
        const auto j = std::lower_bound(el.v.begin(), el.v.end(), p->uv[1]) - el.v.begin();
        el.grid[static_cast<std::size_t>(j) * el.u.size() + static_cast<std::size_t>(i)] = p;
      }
      // Smooth: a complete tensor grid of points, all in contact, all in the same state.
      el.smooth = !el.points.empty() && el.points.size() == el.grid.size() &&
                  std::none_of(el.grid.begin(), el.grid.end(),
                               [](const SurfaceContactPoint* p) { return p == nullptr; });
      for (const SurfaceContactPoint* p : el.points)
        el.smooth = el.smooth && p->active && state(*p) == state(*el.points.front());
    }
  }

  struct Value {
    double pressure = 0.0, gap = 0.0, state = 0.0;
    Vector3d traction = Vector3d::Zero();
    bool gap_known = false;
  };

  Value at(double u, double v) const {
    const std::size_t iu = span_of(bu_, u), iv = span_of(bv_, v);
    const Element& el = elements_[iv * (bu_.size() - 1) + iu];
    if (el.u.empty() || el.v.empty()) return {};
    Value out = el.smooth ? lagrange(el, u, v) : bilinear(el, u, v);
    out.pressure = std::max(0.0, out.pressure);
    return out;
  }

 private:
  struct Element {
    std::vector<const SurfaceContactPoint*> points;
    std::vector<double> u, v;                      ///< sorted abscissae of the points
    std::vector<const SurfaceContactPoint*> grid;  ///< [j * u.size() + i]
    bool smooth = false;  ///< all points in contact, in one state: Lagrange interpolation
    const SurfaceContactPoint* point(std::size_t i, std::size_t j) const {
      return grid[j * u.size() + i];
    }
  };

  double state(const SurfaceContactPoint& p) const {
    return !p.active ? 0.0 : contact_.sticks(p) ? 1.0 : 2.0;
  }

  /// The Lagrange basis through the abscissae a at x: l_i(x) = prod_{k != i} (x - a_k) / (a_i -
  /// a_k).
  static std::vector<double> lagrange_basis(const std::vector<double>& a, double x) {
    std::vector<double> l(a.size(), 1.0);
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t k = 0; k < a.size(); ++k)
        if (k != i) l[i] *= (x - a[k]) / (a[i] - a[k]);
    return l;
  }

  /// A smooth element: f(u, v) = sum_ij f_ij l_i(u) l_j(v) (every point active, with a foot).
  Value lagrange(const Element& el, double u, double v) const {
    const std::vector<double> lu = lagrange_basis(el.u, u), lv = lagrange_basis(el.v, v);
    Value out;
    for (std::size_t j = 0; j < el.v.size(); ++j)
      for (std::size_t i = 0; i < el.u.size(); ++i) {
        const SurfaceContactPoint& p = *el.point(i, j);
        const double w = lu[i] * lv[j];
        out.pressure += w * -p.N;
        out.traction += w * p.T_vector;
        out.gap += w * p.gap;
      }
    out.state = state(*el.points.front());
    out.gap_known = true;
    return out;
  }

  /// An element with a contact or stick edge: bilinear between the 4 neighbouring points, the
  /// outer points' values held to the element's edges.
  Value bilinear(const Element& el, double u, double v) const {
    const auto [i0, i1, s] = bracket(el.u, u);
    const auto [j0, j1, r] = bracket(el.v, v);
    const double w[4] = {(1 - s) * (1 - r), s * (1 - r), (1 - s) * r, s * r};
    const SurfaceContactPoint* corner[4] = {el.point(i0, j0), el.point(i1, j0), el.point(i0, j1),
                                            el.point(i1, j1)};
    Value out;
    int nearest = 0;
    double wgap = 0.0;  // the weight of the corners with a gap
    for (int k = 0; k < 4; ++k) {
      if (w[k] > w[nearest]) nearest = k;
      const SurfaceContactPoint* p = corner[k];
      if (p == nullptr) return Value{};  // an incomplete element (not expected): no field
      if (found(p->foot.status)) {
        wgap += w[k];
        out.gap += w[k] * p->gap;
      }
      if (!p->active) continue;
      out.pressure += w[k] * -p->N;
      out.traction += w[k] * p->T_vector;
    }
    out.gap_known = wgap > 0.0;
    out.gap = out.gap_known ? out.gap / wgap : 0.0;
    out.state = state(*corner[nearest]);
    return out;
  }

  static std::size_t span_of(const std::vector<double>& b, double x) {
    const auto k = std::upper_bound(b.begin(), b.end(), x) - b.begin() - 1;
    return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(k, 0, std::ssize(b) - 2));
  }
  /// The neighbours of x among the sorted abscissae a and the weight of the upper one.
  static std::tuple<std::size_t, std::size_t, double> bracket(const std::vector<double>& a,
                                                              double x) {
    if (x <= a.front()) return {0, 0, 0.0};
    if (x >= a.back()) return {a.size() - 1, a.size() - 1, 0.0};
    const auto k = static_cast<std::size_t>(std::upper_bound(a.begin(), a.end(), x) - a.begin());
    return {k - 1, k, (x - a[k - 1]) / (a[k] - a[k - 1])};
  }
  const SurfaceContact& contact_;
  std::vector<double> bu_, bv_;
  std::vector<Element> elements_;
};

/// The shell's surface sampled per element, with displacement, normal and stress resultants. A
/// sample where the normal or the stresses cannot be evaluated (a degenerate point: a collapsed
/// edge, a pole) gets a zero normal and zero stresses and the flag singular = 1. With contact:
/// contact_pressure, contact_traction, contact_gap, contact_state (ShellContactField) and the
/// flag contact_undefined = 1 where the gap is unknown (no point near has a foot) or a value is
/// not finite; such values are written as 0.
void write_shell_vtk(const std::string& path, const KirchhoffLoveShell& shell,
                     const std::vector<Vector3d>& x, int samples, const std::string& title,
                     const SurfaceContact* contact) {
  const NurbsSurface& S = shell.reference();
  const std::vector<double> us = span_samples(S.knots_u().breaks(), samples);
  const std::vector<double> vs = span_samples(S.knots_v().breaks(), samples);
  std::vector<Vector3d> pts, disp, normal, nloc, mloc;
  std::vector<double> von_mises, singular;
  std::optional<ShellContactField> field;
  if (contact) field.emplace(*contact, S);
  std::vector<double> c_pressure, c_gap, c_state, c_undefined;
  std::vector<Vector3d> c_traction;
  for (double v : vs)
    for (double u : us) {
      if (field) {
        const ShellContactField::Value cv = field->at(u, v);
        const bool finite =
            std::isfinite(cv.pressure) && std::isfinite(cv.gap) && cv.traction.allFinite();
        c_pressure.push_back(finite ? cv.pressure : 0.0);
        c_gap.push_back(finite ? cv.gap : 0.0);
        c_traction.push_back(finite ? cv.traction : Vector3d::Zero());
        c_state.push_back(cv.state);
        c_undefined.push_back(finite && cv.gap_known ? 0.0 : 1.0);
      }
      const Vector3d p = shell.point(u, v, x);
      pts.push_back(p);
      disp.push_back(p - S.point(u, v));
      Vector3d nrm = Vector3d::Zero(), nl = Vector3d::Zero(), ml = Vector3d::Zero();
      double vm = 0.0;
      bool ok = true;
      try {
        nrm = shell.normal(u, v, x);
        const ShellStresses st = shell.stresses(u, v, x);
        nl = st.membrane_force_local;
        ml = st.moment_local;
        vm = st.von_mises;
        ok = nrm.allFinite() && nrm.norm() > 0.5 && nl.allFinite() && ml.allFinite() &&
             std::isfinite(vm);
      } catch (const std::exception&) {
        ok = false;
      }
      normal.push_back(ok ? nrm : Vector3d::Zero());
      nloc.push_back(ok ? nl : Vector3d::Zero());
      mloc.push_back(ok ? ml : Vector3d::Zero());
      von_mises.push_back(ok ? vm : 0.0);
      singular.push_back(ok ? 0.0 : 1.0);
    }
  VtkPointData d;
  d.scalars = {{"von_mises", von_mises}, {"singular", singular}};
  d.vectors = {{"displacement", disp},
               {"normal", normal},
               {"membrane_force_N11_N22_N12", nloc},
               {"moment_M11_M22_M12", mloc}};
  if (field) {
    d.scalars.push_back({"contact_pressure", c_pressure});
    d.scalars.push_back({"contact_gap", c_gap});
    d.scalars.push_back({"contact_state", c_state});
    d.scalars.push_back({"contact_undefined", c_undefined});
    d.vectors.push_back({"contact_traction", c_traction});
  }
  write_vtk_grid(path, pts, static_cast<int>(us.size()), static_cast<int>(vs.size()), d, title);
}

/// A contact point seen from the rigid tool: its foot, the pressure and traction the body
/// exerts there, its state (1 stick, 2 slip) and its footprint radius.
struct ToolFoot {
  Vector3d x;
  double pressure, state, radius;
  Vector3d traction;
};

/// The contact on a grid of a rigid piece (issue 12 item 6): every grid node takes the weighted
/// mean of the feet within their footprint radius h of it, weight (1 - d/h)^2, and 0 where no
/// foot reaches (the state: the foot of the largest weight). h is 1.5 times the point's share of
/// the body (sqrt of its area for shells, its length for rods), at least 0.75 times the grid's
/// spacing so that every foot reaches a node. A transfer for viewing, not a conservative one:
/// the mean keeps the pressure level of a uniform contact, and the field falls to 0 within h of
/// the contact zone's edge (rods: a band of width about 2h along the rope). The feet are sorted
/// into cubic cells of the largest h, so a node looks at the 27 cells around its own only.
VtkPointData tool_fields(const std::vector<Vector3d>& grid, double spacing,
                         const std::vector<ToolFoot>& feet) {
  std::vector<double> pressure(grid.size(), 0.0), state(grid.size(), 0.0);
  std::vector<Vector3d> traction(grid.size(), Vector3d::Zero());
  // The cells: key floor(x / c) per coordinate, c the largest footprint radius.
  double c = 0.75 * spacing;
  for (const ToolFoot& f : feet)
    if (std::isfinite(f.radius)) c = std::max(c, f.radius);
  using Cell = std::array<long long, 3>;
  const auto cell_of = [c](const Vector3d& x) {
    Cell k;
    for (int i = 0; i < 3; ++i)  // clamped: a far or huge coordinate stays a valid key
      k[static_cast<std::size_t>(i)] =
          static_cast<long long>(std::clamp(std::floor(x[i] / c), -1e15, 1e15));
    return k;
  };
  std::vector<std::pair<Cell, std::size_t>> sorted;  // (cell, foot), by cell
  if (c > 0.0 && std::isfinite(c))
    for (std::size_t i = 0; i < feet.size(); ++i)
      if (feet[i].x.allFinite()) sorted.push_back({cell_of(feet[i].x), i});
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t g = 0; g < grid.size(); ++g) {
    if (sorted.empty() || !grid[g].allFinite()) continue;
    double wsum = 0.0, wmax = 0.0;
    const Cell home = cell_of(grid[g]);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const Cell key{home[0] + dx, home[1] + dy, home[2] + dz};
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair{key, std::size_t{0}});
          for (; it != sorted.end() && it->first == key; ++it) {
            const ToolFoot& f = feet[it->second];
            const double h = std::max(f.radius, 0.75 * spacing);
            const double d = (grid[g] - f.x).norm();
            if (!(d < h)) continue;
            const double w = (1.0 - d / h) * (1.0 - d / h);
            wsum += w;
            pressure[g] += w * f.pressure;
            traction[g] += w * f.traction;
            if (w > wmax) {
              wmax = w;
              state[g] = f.state;
            }
          }
        }
    if (wsum > 0.0) {  // a non-finite value (a foot's): 0 and non_finite = 1 (write_vtk_grid)
      pressure[g] /= wsum;
      traction[g] /= wsum;
    }
  }
  VtkPointData d;
  d.scalars = {{"contact_pressure", pressure}, {"contact_state", state}};
  d.vectors = {{"contact_traction", traction}};
  return d;
}

/// The 41 x 41 grid of a bounded rigid piece (empty for an unbounded one) and its spacing.
constexpr int kToolGrid = 41;
std::pair<std::vector<Vector3d>, double> tool_grid(const Surface& S) {
  const Domain2 D = S.domain();
  if (!std::isfinite(D.u.lo) || !std::isfinite(D.u.hi) || !std::isfinite(D.v.lo) ||
      !std::isfinite(D.v.hi))
    return {};
  constexpr int n = kToolGrid;
  std::vector<Vector3d> pts;
  pts.reserve(n * n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k)
      pts.push_back(S.derivs(D.u.lo + (D.u.hi - D.u.lo) * k / (n - 1),
                             D.v.lo + (D.v.hi - D.v.lo) * j / (n - 1), 0)
                        .S);
  double spacing = 0.0;  // the largest distance between neighbouring nodes
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      const Vector3d& p = pts[static_cast<std::size_t>(j * n + k)];
      if (k + 1 < n)
        spacing = std::max(spacing, (pts[static_cast<std::size_t>(j * n + k + 1)] - p).norm());
      if (j + 1 < n)
        spacing = std::max(spacing, (pts[static_cast<std::size_t>((j + 1) * n + k)] - p).norm());
    }
  return {std::move(pts), spacing};
}

}  // namespace

std::vector<std::string> Analysis::write_vtk(const std::string& dir, const std::string& stem,
                                             const VectorXd& u, double t) {
  const std::vector<Vector3d> x = problem_->current_points(u, t);
  const int n = output_.samples_per_element > 0 ? output_.samples_per_element : (rod_ ? 16 : 4);
  std::vector<std::string> files;
  if (rod_) {
    files.push_back(stem + "_rod.vtk");
    write_rod_vtk((fs::path(dir) / files[0]).string(), rod_->rod(), x, n,
                  name_ + " rod, t = " + fmt(t), rod_contact_ ? &rod_contact_->contact() : nullptr);
  } else {
    files.push_back(stem + "_shell.vtk");
    write_shell_vtk((fs::path(dir) / files[0]).string(), shell_->shell(), x, n,
                    name_ + " shell, t = " + fmt(t),
                    shell_contact_ ? &shell_contact_->contact() : nullptr);
  }
  VtkPointData cd, td;
  std::vector<Vector3d> pts, feet, foot_traction;
  std::vector<double> foot_pressure, foot_state, foot_radius;
  if (rod_contact_) {
    std::vector<Vector3d> normal;
    std::vector<double> N, T, B, slip;
    for (const CurveContactPoint& cp : rod_contact_->contact().points()) {
      if (!cp.law.active) continue;
      feet.push_back(cp.law.foot);
      foot_pressure.push_back(-cp.N);
      foot_traction.push_back(-cp.law.T_vector);  // on the tool: opposite to the rope's
      foot_state.push_back(cp.law.slip ? 2.0 : 1.0);
      foot_radius.push_back(1.5 * cp.weight);  // its length share of the rope
      pts.push_back(cp.x);
      normal.push_back(cp.law.normal);
      N.push_back(cp.N);
      T.push_back(cp.T);
      B.push_back(cp.B);
      slip.push_back(cp.law.slip ? 1.0 : 0.0);
    }
    cd.scalars = {{"N", N}, {"T", T}, {"B", B}, {"slip", slip}};
    cd.vectors = {{"normal", normal}};
  } else if (shell_contact_) {
    std::vector<Vector3d> normal, ft;
    std::vector<double> N, gap, slip;
    for (const SurfaceContactPoint& cp : shell_contact_->contact().points()) {
      if (!cp.active) continue;
      feet.push_back(cp.foot.point);
      foot_pressure.push_back(-cp.N);
      foot_traction.push_back(-cp.T_vector);  // on the tool: opposite to the shell's
      foot_state.push_back(shell_contact_->contact().sticks(cp) ? 1.0 : 2.0);
      foot_radius.push_back(1.5 * std::sqrt(cp.weight));  // its area share of the shell
      pts.push_back(cp.x);
      normal.push_back(cp.normal);
      ft.push_back(cp.T_vector);
      N.push_back(cp.N);
      gap.push_back(cp.gap);
      slip.push_back(shell_contact_->contact().sticks(cp) ? 0.0 : 1.0);
    }
    cd.scalars = {{"N", N}, {"gap", gap}, {"slip", slip}};
    cd.vectors = {{"shell_normal", normal}, {"tangential_force", ft}};
  }
  if (has_contact()) {
    files.push_back(stem + "_contact.vtk");
    write_vtk_polydata((fs::path(dir) / files[1]).string(), pts, false, cd,
                       name_ + " contact points, t = " + fmt(t));
    // The same contact seen from the rigid tool: its surface points (the feet) with the
    // pressure, the traction the body exerts on the tool, and the state (1 stick, 2 slip).
    files.push_back(stem + "_tool_contact.vtk");
    td.scalars = {{"contact_pressure", foot_pressure}, {"contact_state", foot_state}};
    td.vectors = {{"tangential_traction", foot_traction}};
    write_vtk_polydata((fs::path(dir) / files[2]).string(), feet, false, td,
                       name_ + " contact on the rigid tool, t = " + fmt(t));
    // ... and as fields on a grid of each bounded piece of the tool (tool_fields).
    std::vector<ToolFoot> tf;
    for (std::size_t k = 0; k < feet.size(); ++k)
      tf.push_back({feet[k], foot_pressure[k], foot_state[k], foot_radius[k], foot_traction[k]});
    for (int i = 0; i < rigid_->num_patches(); ++i) {
      const auto [grid, spacing] = tool_grid(rigid_->patch(i));
      if (grid.empty()) continue;
      files.push_back(stem + "_tool" + (rigid_->num_patches() == 1 ? "" : "_" + std::to_string(i)) +
                      ".vtk");
      write_vtk_grid((fs::path(dir) / files.back()).string(), grid, kToolGrid, kToolGrid,
                     tool_fields(grid, spacing, tf),
                     name_ + " contact on rigid piece " + std::to_string(i) + ", t = " + fmt(t));
    }
  }
  return files;
}

bool Analysis::write_rigid_vtk(const std::string& dir, const std::string& stem) const {
  if (!rigid_) return false;
  // One 41 x 41 grid per bounded piece: <stem>.vtk for a single piece, else <stem>_<i>.vtk.
  int written = 0;
  for (int i = 0; i < rigid_->num_patches(); ++i) {
    const std::vector<Vector3d> pts = tool_grid(rigid_->patch(i)).first;
    if (pts.empty()) continue;
    constexpr int n = kToolGrid;
    const std::string file =
        rigid_->num_patches() == 1 ? stem + ".vtk" : stem + "_" + std::to_string(i) + ".vtk";
    write_vtk_grid((fs::path(dir) / file).string(), pts, n, n, {}, name_ + " rigid surface");
    ++written;
  }
  return written > 0;
}

AnalysisResult Analysis::run(std::ostream* log, const std::string& out_dir,
                             const AnalysisStepCallback& user_callback) {
  AnalysisResult res;
  NonlinearSolver solver(settings_);
  solver.set_log(log);
  std::ofstream csv;
  std::unique_ptr<VtkCollection> pvd_body, pvd_contact;
  const std::string body_file = rod_ ? "rod" : "shell";
  // An error after the start (output of a converged step, the problem's history update, the
  // user's callback, the last ParaView files) ends the run with status `failed` and this message;
  // summary.json and the rows written so far stay.
  std::string error;
  if (!out_dir.empty()) {
    fs::create_directories(out_dir);
    csv.open(fs::path(out_dir) / "steps.csv");
    if (!csv) throw std::runtime_error(out_dir + "/steps.csv: cannot write file");
    csv << "step,t,iterations,active,stick,slip";
    for (int i : output_.reactions)
      for (const char* c : {"x", "y", "z", "norm"}) csv << ",R" << i << "_" << c;
    for (const AnalysisMonitor& m : output_.monitors)
      for (const char* c : {"ux", "uy", "uz"}) csv << "," << m.name << "_" << c;
    for (const auto& [name, curve] : curves_) csv << "," << name;
    csv << "\n";
    if (output_.vtk != AnalysisOutput::Vtk::kNone) {
      pvd_body =
          std::make_unique<VtkCollection>((fs::path(out_dir) / (body_file + ".pvd")).string());
      if (has_contact())
        pvd_contact = std::make_unique<VtkCollection>((fs::path(out_dir) / "contact.pvd").string());
      try {
        write_rigid_vtk(out_dir, "rigid");
      } catch (const std::exception& e) {
        error = std::string("writing the rigid surface's ParaView file: ") + e.what();
      }
    }
  }
  // The tool's contact fields: one series per bounded piece, tool.pvd or tool_<i>.pvd.
  std::map<std::string, VtkCollection> pvd_tool;
  auto vtk = [&](const VectorXd& u, double t, const std::string& stem) {
    const std::vector<std::string> f = write_vtk(out_dir, stem, u, t);
    pvd_body->add(t, f[0]);
    if (pvd_contact) pvd_contact->add(t, f[1]);
    for (std::size_t k = 3; k < f.size(); ++k) {
      const std::string series = f[k].substr(stem.size() + 1, f[k].size() - stem.size() - 5);
      auto it = pvd_tool.find(series);
      if (it == pvd_tool.end())
        it = pvd_tool
                 .emplace(series, VtkCollection((fs::path(out_dir) / (series + ".pvd")).string()))
                 .first;
      it->second.add(t, f[k]);
    }
  };
  VectorXd u = VectorXd::Zero(problem_->num_dofs());
  int sliding_steps = 0;  // consecutive steps of steady sliding (the plateau so far)
  auto on_step = [&](const VectorXd& uc, double t, const StepAttempt& at) {
    try {
      AnalysisStep st;
      st.t = t;
      st.iterations = at.iterations;
      st.contact = contact_counts();
      if (!output_.reactions.empty()) st.reactions = reactions(uc, t);
      for (const AnalysisMonitor& m : output_.monitors)
        st.displacements.push_back(displacement(m, uc, t));
      res.steps.push_back(st);
      if (csv.is_open()) {
        // csv_number: a non-finite value is an empty cell, never nan or inf.
        csv << res.steps.size() << "," << csv_number(t) << "," << st.iterations << ","
            << st.contact.active << "," << st.contact.stick << "," << st.contact.slip;
        for (const Vector3d& r : st.reactions)
          csv << "," << csv_number(r.x()) << "," << csv_number(r.y()) << "," << csv_number(r.z())
              << "," << csv_number(r.norm());
        for (const Vector3d& d : st.displacements)
          csv << "," << csv_number(d.x()) << "," << csv_number(d.y()) << "," << csv_number(d.z());
        for (const auto& [name, curve] : curves_) csv << "," << csv_number(curve(t));
        csv << std::endl;  // flushed: a run that stops midway keeps its rows
        if (output_.vtk == AnalysisOutput::Vtk::kAll)
          vtk(uc, t, "step" + std::to_string(res.steps.size()));
      }
      // The caller sees every converged step, the one that completes the plateau too.
      if (user_callback && !user_callback(uc, t, st)) return false;
      if (has_contact() && stop_full_slip_after_ >= 0.0 && t > stop_full_slip_after_ + 1e-12) {
        const ContactCounts& c = st.contact;
        if (steady_sliding(c.active, c.slip, c.slip_back, c.drag_ratio, contact_mu())) {
          if (++sliding_steps >= full_slip_steps_) {
            res.full_slip = true;
            if (log) *log << "full slip at t = " << t << ": stopping\n";
            return false;
          }
        } else {
          sliding_steps = 0;  // the plateau is a run of consecutive sliding steps
        }
      }
      return true;
    } catch (const std::exception& e) {
      error = "output of the step at t = " + fmt(t) + ": " + e.what();
      return false;
    }
  };
  if (error.empty()) {
    try {
      res.solver = solver.solve(*problem_, u, on_step);
    } catch (const std::exception& e) {  // from commit(): u is the last converged state
      error = e.what();
      res.solver.t = res.steps.empty() ? settings_.t0 : res.steps.back().t;
      res.solver.steps = static_cast<int>(res.steps.size());
    }
  }
  res.u = u;
  res.contact_time = contact_time();
  if (!out_dir.empty() && error.empty() && output_.vtk == AnalysisOutput::Vtk::kLast &&
      !res.steps.empty()) {
    try {
      vtk(u, res.solver.t, "last");
    } catch (const std::exception& e) {
      error = std::string("writing the ParaView files of the last step: ") + e.what();
    }
  }
  if (!error.empty()) {
    res.solver.status = NonlinearSolverStatus::failed;
    res.solver.message = error + "; the state is the last converged one, t = " + fmt(res.solver.t);
    if (log) *log << "run failed: " << res.solver.message << "\n";
  }
  if (!out_dir.empty()) {
    Json s = Json::object();
    s["name"] = name_;
    s["body"] = rod_ ? "rod" : "shell";
    s["status"] = to_string(res.solver.status);
    s["message"] = res.solver.message;
    s["t"] = json_number(res.solver.t);
    s["steps"] = res.solver.steps;
    s["cutbacks"] = res.solver.cutbacks;
    s["newton_iterations"] = res.solver.total_iterations;
    s["dofs"] = problem_->num_dofs();
    s["full_slip"] = res.full_slip;
    s["time_total_s"] = json_number(res.solver.time_total);
    s["time_assembly_s"] = json_number(res.solver.time_assembly);
    s["time_contact_s"] = json_number(res.contact_time);
    s["time_linear_solve_s"] = json_number(res.solver.time_linear_solve);
    std::ofstream(fs::path(out_dir) / "summary.json") << format_json(s) << "\n";
  }
  return res;
}

namespace {

/// RFC 6901: every '~' is followed by 0 or 1. Checked before nlohmann parses a pointer, so
/// that the message is ours and names the pointer.
bool escapes_valid(const std::string& pointer) {
  for (std::size_t i = 0; i < pointer.size(); ++i)
    if (pointer[i] == '~' &&
        (i + 1 == pointer.size() || (pointer[i + 1] != '0' && pointer[i + 1] != '1')))
      return false;
  return true;
}

/// doc.contains(p), false also where nlohmann throws (an array index beyond size_t).
bool has_entry(const Json& doc, const JsonPointer& p) {
  try {
    return doc.contains(p);
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

}  // namespace

void apply_override(Json& doc, const std::string& file, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  const std::string text = assignment.substr(0, eq);  // the pointer, or all of a bad assignment
  if (eq == std::string::npos || text.empty() || text[0] != '/')
    throw ModelError("--set", "",
                     "expected /json/pointer=value (e.g. /solver/max_steps=50), got " +
                         short_dump(Json(assignment), 80));
  if (!escapes_valid(text))
    throw ModelError("--set", "",
                     "\"" + text +
                         "\" is not a JSON pointer: '~' must be followed by 0 or 1 (~0 stands "
                         "for '~', ~1 for '/')");
  const JsonPointer ptr(text);
  if (!has_entry(doc, ptr)) {
    // A new key is allowed where its parent object exists; the loader then accepts the key or
    // rejects it as unknown at its own path.
    const JsonPointer parent = ptr.parent_pointer();
    if (!has_entry(doc, parent))
      throw ModelError(file, ptr.to_string(),
                       "--set: no such entry, and its parent " +
                           (parent.empty() ? std::string("(the root)") : parent.to_string()) +
                           " does not exist either");
    if (!doc.at(parent).is_object())
      throw ModelError(file, ptr.to_string(),
                       "--set: no such entry; a new key can only be added to an object, and " +
                           parent.to_string() + " is " + describe_json(doc.at(parent)));
  }
  Json value = parse_json_text(assignment.substr(eq + 1), "--set " + text);
  doc[ptr] = std::move(value);
}

JsonPointer model_pointer(const JsonCursor& c, const Json& doc) {
  const std::string s = c.as_string();
  if (s.empty() || s[0] != '/' || !escapes_valid(s))
    c.fail("expected a JSON pointer (\"/section/key\", ~0 for '~' and ~1 for '/')");
  const JsonPointer p(s);
  if (!has_entry(doc, p)) c.fail("names no entry of the model");
  return p;
}

}  // namespace iga
