// JSON parsing of the analysis sections (docs/model_format.md, "Analysis sections") that all body
// types share: load curves, rigid motions, the parts of boundary conditions, loads and contact
// pairs common to every body (points, vectors, curves, tools), the solver and output sections.
// The body types' own readers: rod_body.cpp, shell_body.cpp, membrane_body.cpp (body_types.hpp).
// Every error names the file, the JSON path and the value.
#include "iga/model/sections.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <numbers>
#include <optional>
#include <ostream>
#include <sstream>
#include <tuple>
#include <type_traits>

#include "geometry/constructions.hpp"
#include "geometry/number_text.hpp"
#include "iga/model/model.hpp"
#include "iga/output/output_format.hpp"
#include "iga/output/vtk_writer.hpp"
#include "iga/parallel/communicator.hpp"

namespace iga::model_detail {

namespace fs = std::filesystem;

std::string fmt(double v) {
  return num_text(v, 10);
}

/// Largest accepted "t_end" (pseudo-time).
constexpr double kMaxEndTime = 1e6;

double positive(const JsonCursor& c, bool allow_zero) {
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
Vector3d vec3(const JsonCursor& c) {
  if (!c.json().is_array() || c.json().size() != 3) c.fail_type("3 components [x, y, z]");
  return Vector3d(c[0].as_number(), c[1].as_number(), c[2].as_number());
}
std::string column_name(const JsonCursor& c) {
  std::string name = c.as_string();
  if (name.empty() || name.find_first_of(",\"\n") != std::string::npos)
    c.fail("must be a non-empty name without commas, quotes or line breaks");
  return name;
}
/// The value of `key` in `o`, which must be one of `names`.
std::string one_of(const JsonCursor& c, const std::vector<std::string>& names) {
  std::string s = c.as_string();
  std::string list;
  for (const std::string& n : names) {
    if (s == n) return s;
    list += list.empty() ? "\"" : ", \"";
    list += n;
    list += '"';
  }
  c.fail("expected one of " + list);
}

std::string one_of(const JsonCursor& c, std::initializer_list<const char*> names) {
  return one_of(c, std::vector<std::string>(names.begin(), names.end()));
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

LoadCurve curve_of(const JsonCursor& o, const Context& ctx) {
  if (!o.has("curve")) return ramp();
  const JsonCursor c = o["curve"];
  const auto it = ctx.curves.find(c.as_string());
  if (it == ctx.curves.end()) c.fail("names no entry of \"load_curves\"");
  return it->second;
}

void check_body(const JsonCursor& o, const Context& ctx) {
  const JsonCursor b = o["body"];
  const std::string name = b.as_string();
  if (std::find(ctx.bodies.begin(), ctx.bodies.end(), name) != ctx.bodies.end()) return;
  if (ctx.bodies.size() == 1)
    b.fail("names no body (the model's body is \"" + ctx.bodies[0] + "\")");
  std::string list;
  for (const std::string& n : ctx.bodies) list += (list.empty() ? "\"" : ", \"") + n + "\"";
  b.fail("names no body (the model's bodies are " + list + ")");
}

void check_entry_bodies(const JsonCursor& root, const Context& ctx) {
  for (const char* key : {"boundary_conditions", "loads", "contact"}) {
    if (!root.has(key)) continue;
    const JsonCursor list = root[key];
    list.expect_array();
    for (std::size_t k = 0; k < list.size(); ++k) {
      const JsonCursor o = list[k];
      if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
      check_body(o, ctx);
    }
  }
}

int point_index(const JsonCursor& c, const Context& ctx) {
  const BodyShape& shape = ctx.shape;
  if (shape.named_point)
    if (const int i = shape.named_point(c); i >= 0) return i;
  const int i = c.as_int();
  if (i < 0 || i >= shape.n_points)
    c.fail("control point index must be in 0.." + std::to_string(shape.n_points - 1));
  return i;
}

std::vector<int> point_list(const JsonCursor& pc, const Context& ctx) {
  const BodyShape& shape = ctx.shape;
  std::vector<int> points;
  if (pc.json().is_string() && (pc.as_string() == "all" || pc.as_string() == "corners")) {
    if (pc.as_string() == "all")
      for (int i = 0; i < shape.n_points; ++i) points.push_back(i);
    else
      points = shape.corners;
  } else if (pc.json().is_array() && !(shape.array_is_point && shape.array_is_point(pc))) {
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

Vector3d vector_value(const JsonCursor& o, const char* vec_key, const Context& ctx, int where) {
  if (o.has(vec_key)) {
    if (o.has("magnitude") || o.has("direction"))
      o.fail_plain(std::string("give either \"") + vec_key +
                   "\" or \"magnitude\" and \"direction\"");
    return vec3(o[vec_key]);
  }
  const double m = o["magnitude"].as_number();
  const JsonCursor d = o["direction"];
  if (d.json().is_string() && ctx.shape.named_direction)
    return m * ctx.shape.named_direction(d, where);
  const Vector3d v = vec3(d);
  if (!(v.norm() > 0.0)) d.fail("must be a non-zero vector");
  return m * v.normalized();
}
/// 0 for "start", 1 for "end", -1 otherwise.
int end_of(const JsonCursor& c) {
  if (!c.json().is_string()) return -1;
  return c.as_string() == "start" ? 0 : c.as_string() == "end" ? 1 : -1;
}

/// The moving tool an entry follows ("motion": a key of "rigid_motions"); null without the key.
std::shared_ptr<const RigidMotion> motion_of(const JsonCursor& o, const Context& ctx) {
  if (!o.has("motion")) return nullptr;
  const JsonCursor m = o["motion"];
  const auto it = ctx.motions.find(m.as_string());
  if (it == ctx.motions.end()) m.fail("names no entry of \"rigid_motions\"");
  return it->second;
}

/// A displacement given in the frame of a moving tool: the point is carried by the tool's
/// motion, x(t) = c(t) + Q(t) (X + d curve(t) - c0) (an anchor on a turning drum; d = 0: the
/// point is fixed to the tool). Each component is prescribed along its own curve.
void prescribe_following(const JsonCursor& o, ControlPointProblem& p, int i, const Vector3d& d,
                         const LoadCurve& curve, const std::shared_ptr<const RigidMotion>& m) {
  if (!p.local_basis(i).isIdentity(0.0))
    o.fail_plain("a point with a local basis (a symmetry or clamp condition) cannot follow a tool");
  const Vector3d X = p.reference_point(i);
  for (int c = 0; c < 3; ++c)
    p.prescribe(i, c, 1.0, [m, X, d, curve, c](double t) {
      return (m->pose(t).to_world(X + d * curve(t)) - X)[c];
    });
}

/// {"type": "fix", "points": ..., "components": [...]} (rods and shells).
void fix_points(const JsonCursor& o, const Context& ctx, ControlPointProblem& p) {
  o.expect_object({"type", "body", "points", "components", "description"});
  const std::vector<int> comps = components(o);
  for (int i : point_list(o["points"], ctx))
    for (int c : comps)
      if (!p.constrained(i, c)) p.fix(i, c);
}

/// The rigid surface named at rc, shared by every pair that names it (ctx.rigids).
std::shared_ptr<const RigidSurface> rigid_surface(const JsonCursor& rc, const GeometryModel& g,
                                                  const Context& ctx) {
  const std::string name = rc.as_string();
  if (ctx.rigids) {
    const auto it = ctx.rigids->find(name);
    if (it != ctx.rigids->end()) return it->second;
  }
  std::shared_ptr<const RigidSurface> r;
  try {
    r = std::make_shared<RigidSurface>(RigidSurface::from_geometry(g, name));
  } catch (const std::invalid_argument& e) {
    rc.fail(std::string("not a rigid surface: ") + e.what());
  }
  if (ctx.rigids) ctx.rigids->emplace(name, r);
  return r;
}

std::map<std::string, std::shared_ptr<const RigidMotion>> parse_rigid_motions(
    const JsonCursor& section, const Context& ctx, const GeometryModel& geometry) {
  if (!section.json().is_object()) section.fail_type("an object of rigid tools by name");
  std::map<std::string, std::shared_ptr<const RigidMotion>> motions;
  for (const std::string& name : section.keys()) {
    const JsonCursor m = section[name];
    m.expect_object({"rotation", "translation", "description"});
    bool surface = false;
    try {
      surface = !geometry.surfaces_of(name).empty();
    } catch (const std::out_of_range&) {  // a curve, or no entity of that name
    }
    if (!surface)
      m.fail_plain("\"" + name + "\" is no surface or patch group of the geometry section");
    if (!m.has("rotation") && !m.has("translation"))
      m.fail_plain("give a \"rotation\", a \"translation\" or both");
    auto motion = std::make_shared<RigidMotion>();
    if (m.has("rotation")) {  // about `axis` through `point` by angle * curve(t)
      const JsonCursor r = m["rotation"];
      r.expect_object({"point", "axis", "angle", "curve", "description"});
      const Vector3d axis = vec3(r["axis"]);
      if (!(axis.norm() > 0.0)) r["axis"].fail("must be a non-zero vector");
      motion->set_rotation(vec3(r["point"]), axis, r["angle"].as_number(), curve_of(r, ctx));
    }
    if (m.has("translation")) {  // by vector * curve(t), after the rotation
      const JsonCursor tr = m["translation"];
      tr.expect_object({"vector", "curve", "description"});
      motion->set_translation(vec3(tr["vector"]), curve_of(tr, ctx));
    }
    motions.emplace(name, std::move(motion));
  }
  return motions;
}

namespace {

// An integer entry of s, when given, at least `min`, into `out`.
void read_int(const JsonCursor& s, const char* key, int min, int& out) {
  if (!s.has(key)) return;
  const JsonCursor c = s[key];
  out = c.as_int();
  if (out < min) c.fail("must be >= " + std::to_string(min));
}

// "reference": [{"label", "points": [[x, y], ...]}, ...], published points of a plot.
std::vector<AnalysisOutput::Reference> plot_reference(const JsonCursor& r) {
  r.expect_array(1);
  std::vector<AnalysisOutput::Reference> out;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const JsonCursor e = r[k];
    e.expect_object({"label", "points", "description"});
    AnalysisOutput::Reference ref{e["label"].as_string(), {}};
    const JsonCursor pts = e["points"];
    pts.expect_array(1);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::vector<double> xy = pts[i].as_numbers();
      if (xy.size() != 2) pts[i].fail("must be a point [x, y]");
      ref.points.push_back({xy[0], xy[1]});
    }
    out.push_back(std::move(ref));
  }
  return out;
}

}  // namespace

namespace {
/// "linear_solver": SuiteSparse, or PETSc's MUMPS or Krylov solvers (a build with PETSc).
LinearMethod linear_method(const JsonCursor& c) {
  const std::string m = one_of(c, {"suitesparse", "mumps", "krylov"});
  if (m == "suitesparse") return LinearMethod::suitesparse;
  if (!parallel_build())
    c.fail("\"" + m + "\" needs PETSc, and this build has none (IGA_WITH_PETSC=OFF)");
  return m == "mumps" ? LinearMethod::mumps : LinearMethod::krylov;
}
}  // namespace

namespace {
/// "analysis": "auto" (default): the linear path while certified by the residual test
/// (AnalysisKind), Newton for arc length and (Analysis::from_json) for contact; "linear": linear
/// theory (load control only); "nonlinear": Newton.
AnalysisKind analysis_kind(const JsonCursor& s, PathControl control) {
  const bool arc = control == PathControl::arc_length;
  if (!s.has("analysis")) return arc ? AnalysisKind::nonlinear : AnalysisKind::certified;
  const JsonCursor c = s["analysis"];
  const std::string kind = one_of(c, {"auto", "linear", "nonlinear"});
  if (kind == "nonlinear" || (kind == "auto" && arc)) return AnalysisKind::nonlinear;
  if (kind == "auto") return AnalysisKind::certified;
  if (arc)
    c.fail(
        "\"linear\" needs load control: arc length follows a nonlinear path (\"control\": "
        "\"arc_length\")");
  return AnalysisKind::linear;
}
}  // namespace

NonlinearSolverSettings parse_solver(const JsonCursor& s, double& stop_after, int& slip_steps) {
  s.expect_object({"t_end",
                   "initial_step",
                   "max_step",
                   "min_step",
                   "max_steps",
                   "max_iterations",
                   "tol_residual_rel",
                   "tol_residual_abs",
                   "tol_residual_scaled",
                   "tol_energy_rel",
                   "divergence_ratio",
                   "max_residual_increases",
                   "stop_at_full_slip_after",
                   "full_slip_steps",
                   "hit_times",
                   "easy_iterations",
                   "growth_factor",
                   "cutback_factor",
                   "predictor",
                   "control",
                   "desired_iterations",
                   "max_turn_deg",
                   "linear_solver",
                   "analysis",
                   "description"});
  NonlinearSolverSettings n;
  if (s.has("linear_solver")) n.linear_method = linear_method(s["linear_solver"]);
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
  read_int(s, "max_steps", 1, n.max_steps);
  read_int(s, "max_iterations", 1, n.max_iterations);
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
  // ... or |R| grew this many times in a row (0: off)
  read_int(s, "max_residual_increases", 0, n.max_residual_increases);
  if (s.has("stop_at_full_slip_after")) stop_after = positive(s["stop_at_full_slip_after"], true);
  // consecutive steps of steady sliding before stopping
  read_int(s, "full_slip_steps", 1, slip_steps);
  // a step converged in <= this many iterations grows the next
  read_int(s, "easy_iterations", 0, n.easy_iterations);
  if (s.has("growth_factor")) n.growth_factor = positive(s["growth_factor"]);
  if (s.has("control"))  // load (or displacement) control, or arc length through limit points
    n.control = one_of(s["control"], {"load", "arc_length"}) == "arc_length"
                    ? PathControl::arc_length
                    : PathControl::load;
  // arc length: iterations per step the step size aims at
  read_int(s, "desired_iterations", 1, n.desired_iterations);
  if (s.has("max_turn_deg")) {  // arc length: the largest turn of a step from its predictor
    const JsonCursor c = s["max_turn_deg"];
    n.max_turn_deg = c.as_number();
    if (!(n.max_turn_deg > 0.0 && n.max_turn_deg <= 180.0)) c.fail("must be in (0, 180]");
  }
  n.analysis = analysis_kind(s, n.control);
  if (s.has("predictor"))
    n.secant_predictor = one_of(s["predictor"], {"none", "secant"}) == "secant";
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

/// The body an output entry names ({"body": name, ...}); without "body" the model's only body
/// (with several: an error at the entry).
const Context& body_of_entry(const JsonCursor& e, const std::vector<Context>& bodies) {
  if (!e.json().is_object() || !e.has("body")) {
    if (bodies.size() > 1) e.fail_plain("the model has several bodies: name the entry's \"body\"");
    return bodies.front();
  }
  const JsonCursor b = e["body"];
  for (const Context& c : bodies)
    if (c.body == b.as_string()) return c;
  check_body(e, bodies.front());  // fails, listing the bodies
  return bodies.front();
}

namespace {
/// "field_format": a registered output format that writes fields (iga/output/output_sink.hpp),
/// not the steps table's or the summary's.
std::string field_format(const JsonCursor& c) {
  std::vector<std::string> fields;
  for (const std::string& f : output_format_names())
    if (f != "csv" && f != "summary") fields.push_back(f);
  return one_of(c, fields);
}
/// "vtk": when the field series are written.
AnalysisOutput::Vtk field_times(const JsonCursor& c) {
  const std::string v = one_of(c, {"none", "last", "all"});
  return v == "none"  ? AnalysisOutput::Vtk::kNone
         : v == "all" ? AnalysisOutput::Vtk::kAll
                      : AnalysisOutput::Vtk::kLast;
}
}  // namespace

AnalysisOutput parse_output(const JsonCursor& o, const std::vector<Context>& bodies) {
  o.expect_object({"vtk", "field_format", "reactions", "monitors", "samples_per_element", "plots",
                   "restart_every", "description"});
  AnalysisOutput out;
  if (o.has("field_format")) out.field_format = field_format(o["field_format"]);
  if (o.has("restart_every")) {
    const JsonCursor c = o["restart_every"];
    out.restart_every = c.as_int();
    if (out.restart_every < 0)
      c.fail("must be >= 0 (0: a restart file only when the run stops early)");
  }
  if (o.has("plots")) {  // [{"x", "y", "file", ["title"]}], drawn by iga run
    const JsonCursor pl = o["plots"];
    pl.expect_array();
    for (std::size_t k = 0; k < pl.size(); ++k) {
      const JsonCursor p = pl[k];
      p.expect_object({"x", "y", "file", "title", "reference", "description"});
      AnalysisOutput::Plot plot{p["x"].as_string(),
                                p["y"].as_string(),
                                p["file"].as_string(),
                                p.has("title") ? p["title"].as_string() : std::string(),
                                {}};
      if (p.has("reference")) plot.reference = plot_reference(p["reference"]);
      const std::string& f = plot.file;
      if (f.size() < 5 || f.substr(f.size() - 4) != ".png" ||
          f.find_first_of("/\\\"") != std::string::npos)
        p["file"].fail("must be a file name ending in .png, without a folder");
      out.plots.push_back(plot);
    }
  }
  if (o.has("vtk")) out.vtk = field_times(o["vtk"]);
  if (o.has("reactions")) {
    const JsonCursor r = o["reactions"];
    r.expect_array();
    for (std::size_t k = 0; k < r.size(); ++k) {
      // a control point of the only body, or {"body": name, "point": ...}
      const Context& ctx = body_of_entry(r[k], bodies);
      if (r[k].json().is_object()) {
        r[k].expect_object({"body", "point", "description"});
        out.reactions.push_back({point_index(r[k]["point"], ctx), ctx.body_index});
      } else {
        out.reactions.push_back({point_index(r[k], ctx), ctx.body_index});
      }
    }
  }
  if (o.has("monitors")) {  // [{"name": "centre", "at": xi or [u, v]}]
    const JsonCursor ml = o["monitors"];
    ml.expect_array();
    for (std::size_t k = 0; k < ml.size(); ++k) {
      const JsonCursor m = ml[k];
      m.expect_object({"name", "at", "body", "description"});
      const Context& ctx = body_of_entry(m, bodies);
      AnalysisMonitor mon;
      mon.body = ctx.body_index;
      mon.name = column_name(m["name"]);
      const Vector2d uv = ctx.shape.parameters(m["at"]);
      mon.u = uv[0];
      mon.v = uv[1];
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

/// The column of a plot's term "[factor*]column" or "-column" (spaces around it dropped);
/// ModelError at c when the factor is not a number.
std::string plot_term_column(const JsonCursor& c, const std::string& term) {
  std::string column = term;
  if (const auto star = term.find('*'); star != std::string::npos) {
    const std::string factor = term.substr(0, star);
    char* end = nullptr;
    const double f = std::strtod(factor.c_str(), &end);
    if (factor.empty() || end != factor.c_str() + factor.size() || !std::isfinite(f))
      c.fail("a term is [factor*]column with a number as factor");
    column = term.substr(star + 1);
  } else if (!term.empty() && term[0] == '-') {
    column = term.substr(1);
  }
  column.erase(0, column.find_first_not_of(' '));
  column.erase(column.find_last_not_of(' ') + 1);
  return column;
}

void check_plot_columns(const JsonCursor& o, const AnalysisOutput& out,
                        const std::vector<std::string>& columns) {
  std::string list;  // for the message
  for (const std::string& name : columns) list += (list.empty() ? "" : ", ") + name;
  for (std::size_t k = 0; k < out.plots.size(); ++k)
    for (const char* axis : {"x", "y"}) {
      const JsonCursor c = o["plots"][k][axis];
      std::istringstream terms(c.as_string());
      std::string t;
      int n = 0;
      while (std::getline(terms, t, ';')) {
        ++n;
        const std::string column = plot_term_column(c, t);
        if (std::find(columns.begin(), columns.end(), column) == columns.end())
          c.fail("\"" + column + "\" is no column of steps.csv (" + list + ")");
      }
      const bool x = std::string(axis) == "x";
      if (n == 0 || (x && n > 1))
        c.fail(x ? "expected one term [factor*]column"
                 : "expected terms [factor*]column separated by ';'");
    }
}

JsonCursor body_material(const JsonCursor& b, const JsonCursor& materials,
                         const std::vector<std::string>& types, const std::string& body_type) {
  const JsonCursor mc = b["material"];
  if (!materials.has(mc.as_string())) mc.fail("names no entry of \"materials\"");
  JsonCursor mat = materials[mc.as_string()];
  const std::string type = mat["type"].as_string();
  if (std::find(types.begin(), types.end(), type) == types.end()) {
    std::string list;
    for (const std::string& t : types) {
      list += list.empty() ? "\"" : " or \"";
      list += t;
      list += '"';
    }
    mc.fail("names a material of type \"" + type + "\"; a " + body_type + " needs type " + list);
  }
  return mat;
}

}  // namespace iga::model_detail
