// Model file -> rod (+ contact) problem -> nonlinear solver -> output files. The sections and
// their keys are documented in docs/model_format.md ("Analysis sections").
#include "iga/analysis.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>

#include "iga/model.hpp"
#include "iga/vtk_writer.hpp"

namespace iga {

namespace {

namespace fs = std::filesystem;

double positive(const JsonCursor& c, bool allow_zero = false) {
  const double x = c.as_number();
  if (allow_zero ? !(x >= 0.0) : !(x > 0.0)) c.fail(allow_zero ? "must be >= 0" : "must be > 0");
  return x;
}
double number_or(const JsonCursor& o, const char* key, double fallback) {
  return o.has(key) ? o[key].as_number() : fallback;
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

// ---- load curves ---------------------------------------------------------------------------

LoadCurve parse_load_curve(const JsonCursor& c) {
  c.expect_object({"type", "points", "scale", "rate", "value", "description"});
  const std::string type = one_of(c["type"], {"ramp", "constant", "piecewise_linear", "exponential"});
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

struct Context {
  std::map<std::string, LoadCurve> curves;
  std::string body;  // the one body's name
  const NurbsCurve* curve = nullptr;
  int n_points = 0;
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

/// "start", "end" or a control point index.
int point_index(const JsonCursor& c, const Context& ctx) {
  if (c.json().is_string()) {
    const std::string s = one_of(c, {"start", "end"});
    return s == "start" ? 0 : ctx.n_points - 1;
  }
  const int i = c.as_int();
  if (i < 0 || i >= ctx.n_points)
    c.fail("control point index must be in 0.." + std::to_string(ctx.n_points - 1));
  return i;
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
      o.fail_plain(std::string("give either \"") + vec_key + "\" or \"magnitude\" and \"direction\"");
    return vec3(o[vec_key]);
  }
  const double m = o["magnitude"].as_number();
  const JsonCursor d = o["direction"];
  if (d.json().is_string()) {
    one_of(d, {"outward_tangent"});
    if (where != 0 && where != 1) d.fail("\"outward_tangent\" needs the point \"start\" or \"end\"");
    return m * outward_tangent(*ctx.curve, where == 1);
  }
  const Vector3d v = vec3(d);
  if (!(v.norm() > 0.0)) d.fail("must be a non-zero vector");
  return m * v.normalized();
}
/// 0 for "start", 1 for "end", -1 otherwise.
int end_of(const JsonCursor& c) {
  if (!c.json().is_string()) return -1;
  return c.as_string() == "start" ? 0 : c.as_string() == "end" ? 1 : -1;
}

void parse_boundary_condition(const JsonCursor& o, const Context& ctx, RodProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type = one_of(o["type"], {"fix", "clamp", "displacement"});
  check_body(o, ctx);
  try {
    if (type == "fix") {
      o.expect_object({"type", "body", "points", "components", "description"});
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
      std::vector<int> points;
      const JsonCursor pc = o["points"];
      if (pc.json().is_string() && pc.as_string() == "all") {
        for (int i = 0; i < ctx.n_points; ++i) points.push_back(i);
      } else if (pc.json().is_array()) {
        for (std::size_t k = 0; k < pc.size(); ++k) points.push_back(point_index(pc[k], ctx));
      } else {
        points.push_back(point_index(pc, ctx));
      }
      for (int i : points)
        for (int c : comps)
          if (!p.constrained(i, c)) p.fix(i, c);
    } else if (type == "clamp") {
      o.expect_object({"type", "body", "end", "description"});
      const std::string e = one_of(o["end"], {"start", "end"});
      p.clamp(e == "start" ? RodEnd::kStart : RodEnd::kEnd);
    } else {
      o.expect_object({"type", "body", "point", "value", "magnitude", "direction", "curve",
                       "description"});
      const int i = point_index(o["point"], ctx);
      const Vector3d d = vector_value(o, "value", ctx, end_of(o["point"]));
      p.prescribe(i, d, curve_of(o, ctx));
    }
  } catch (const RodError& e) {
    o.fail_plain(e.what());
  }
}

void parse_load(const JsonCursor& o, const Context& ctx, RodProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type = one_of(o["type"], {"point_force", "line_load", "moment"});
  check_body(o, ctx);
  const Interval D = ctx.curve->domain();
  auto at = [&](const JsonCursor& c) -> double {
    if (c.json().is_string()) return one_of(c, {"start", "end"}) == "start" ? D.lo : D.hi;
    const double xi = c.as_number();
    if (xi < D.lo || xi > D.hi)
      c.fail("parameter must lie in the curve's domain [" + std::to_string(D.lo) + ", " +
             std::to_string(D.hi) + "]");
    return xi;
  };
  if (type == "point_force") {
    o.expect_object({"type", "name", "body", "at", "force", "magnitude", "direction", "curve",
                     "description"});
    p.add_point_load(at(o["at"]), vector_value(o, "force", ctx, end_of(o["at"])), curve_of(o, ctx));
  } else if (type == "line_load") {
    o.expect_object({"type", "name", "body", "q", "curve", "description"});
    p.add_line_load(vec3(o["q"]), curve_of(o, ctx));
  } else {
    o.expect_object({"type", "name", "body", "at", "moment", "curve", "description"});
    p.add_moment(at(o["at"]), vec3(o["moment"]), curve_of(o, ctx));
  }
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

NonlinearSolverSettings parse_solver(const JsonCursor& s, double& stop_after) {
  s.expect_object({"t_end", "initial_step", "max_step", "min_step", "max_steps", "max_iterations",
                   "tol_residual_rel", "tol_residual_abs", "tol_energy_rel",
                   "stop_at_full_slip_after", "description"});
  NonlinearSolverSettings n;
  n.t0 = 0.0;
  if (s.has("t_end")) n.t1 = positive(s["t_end"]);
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
  if (s.has("tol_energy_rel")) n.tol_energy_rel = positive(s["tol_energy_rel"], true);
  if (s.has("stop_at_full_slip_after")) stop_after = positive(s["stop_at_full_slip_after"], true);
  try {
    n.validate();
  } catch (const std::invalid_argument& e) {
    s.fail_plain(e.what());
  }
  return n;
}

AnalysisOutput parse_output(const JsonCursor& o, const Context& ctx) {
  o.expect_object({"vtk", "reactions", "samples_per_element", "description"});
  AnalysisOutput out;
  if (o.has("vtk")) {
    const std::string v = one_of(o["vtk"], {"none", "last", "all"});
    out.vtk = v == "none" ? AnalysisOutput::Vtk::kNone
              : v == "all" ? AnalysisOutput::Vtk::kAll
                           : AnalysisOutput::Vtk::kLast;
  }
  if (o.has("reactions")) {
    const JsonCursor r = o["reactions"];
    r.expect_array();
    for (std::size_t k = 0; k < r.size(); ++k) out.reactions.push_back(point_index(r[k], ctx));
  }
  if (o.has("samples_per_element")) {
    const JsonCursor c = o["samples_per_element"];
    out.samples_per_element = c.as_int();
    if (out.samples_per_element < 1 || out.samples_per_element > 1000) c.fail("must be in 1..1000");
  }
  return out;
}

std::string fmt(double v) {
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
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
    for (const std::string& k : lc.keys()) ctx.curves[k] = parse_load_curve(lc[k]);
  }
  std::map<std::string, RodSection> materials;
  if (root.has("materials")) {
    const JsonCursor mc = root["materials"];
    if (!mc.json().is_object()) mc.fail_type("an object of named materials");
    for (const std::string& k : mc.keys()) materials[k] = parse_rod_material(mc[k]);
  }

  // The body: one rod in this version.
  const JsonCursor bodies = root["bodies"];
  if (!bodies.json().is_object() || bodies.size() != 1)
    bodies.fail_type("an object with exactly one named body (one deformable body per model)");
  ctx.body = bodies.keys().front();
  const JsonCursor b = bodies[ctx.body];
  b.expect_object({"type", "curve", "material", "quadrature_points", "bending", "description"});
  one_of(b["type"], {"rod"});
  const JsonCursor cc = b["curve"];
  ctx.curve = a.geometry_.curve(cc.as_string());
  if (ctx.curve == nullptr) cc.fail("names no curve of the geometry section");
  const JsonCursor mc = b["material"];
  const auto mat = materials.find(mc.as_string());
  if (mat == materials.end()) mc.fail("names no entry of \"materials\"");
  RodOptions opt;
  if (b.has("quadrature_points")) {
    const JsonCursor q = b["quadrature_points"];
    opt.quadrature_points = q.as_int();
    if (opt.quadrature_points < 0 || opt.quadrature_points > 20) q.fail("must be in 0..20 (0: p + 1)");
  }
  if (b.has("bending"))
    opt.bending = one_of(b["bending"], {"transported_frame", "curvature_magnitude"}) ==
                          "transported_frame"
                      ? BendingMeasure::kTransportedFrame
                      : BendingMeasure::kCurvatureMagnitude;
  std::optional<KirchhoffRod> rod;
  try {
    rod.emplace(*ctx.curve, mat->second, opt);
  } catch (const std::invalid_argument& e) {
    b.fail_plain(e.what());
  }
  ctx.n_points = rod->num_control_points();

  // Contact: at most one pair, the body against a rigid surface of the geometry.
  if (root.has("contact")) {
    const JsonCursor cl = root["contact"];
    cl.expect_array();
    if (cl.size() > 1) cl.fail_plain("one contact pair per model in this version, got " + std::to_string(cl.size()));
    if (cl.size() == 1) {
      const JsonCursor c = cl[0];
      c.expect_object({"name", "type", "body", "rigid", "eps_N", "eps_T", "mu", "radius",
                       "points_per_element", "description"});
      one_of(c["type"], {"curve_to_rigid"});
      check_body(c, ctx);
      std::shared_ptr<RigidSurface> rigid;
      const JsonCursor rc = c["rigid"];
      try {
        rigid = std::make_shared<RigidSurface>(RigidSurface::from_geometry(a.geometry_, rc.as_string()));
      } catch (const std::invalid_argument& e) {
        rc.fail(std::string("not a rigid surface: ") + e.what());
      }
      ContactParameters cp;
      cp.eps_n = positive(c["eps_N"]);
      cp.eps_t = c.has("eps_T") ? positive(c["eps_T"], true) : 0.0;
      cp.mu = c.has("mu") ? positive(c["mu"], true) : 0.0;
      cp.radius = c.has("radius") ? positive(c["radius"], true) : 0.0;
      int ppe = 3;
      if (c.has("points_per_element")) {
        const JsonCursor pc = c["points_per_element"];
        ppe = pc.as_int();
        if (ppe < 1 || ppe > 16) pc.fail("must be in 1..16");
      }
      auto p = std::make_unique<RodContactProblem>(std::move(*rod), rigid, cp, ppe);
      a.contact_ = p.get();
      a.problem_ = std::move(p);
    }
  }
  if (!a.problem_) a.problem_ = std::make_unique<RodProblem>(std::move(*rod));

  if (root.has("boundary_conditions")) {
    const JsonCursor bc = root["boundary_conditions"];
    bc.expect_array();
    for (std::size_t k = 0; k < bc.size(); ++k) parse_boundary_condition(bc[k], ctx, *a.problem_);
  }
  if (root.has("loads")) {
    const JsonCursor lc = root["loads"];
    lc.expect_array();
    for (std::size_t k = 0; k < lc.size(); ++k) parse_load(lc[k], ctx, *a.problem_);
  }
  if (root.has("solver")) a.settings_ = parse_solver(root["solver"], a.stop_full_slip_after_);
  if (root.has("output")) a.output_ = parse_output(root["output"], ctx);
  if (a.problem_->num_dofs() == 0) root["boundary_conditions"].fail_plain("every degree of freedom is constrained");
  return a;
}

Analysis Analysis::load(const std::string& path) {
  return from_json(read_json_file(path), path);
}

std::vector<Vector3d> Analysis::reactions(const VectorXd& u, double t) {
  const std::vector<Vector3d> all = contact_ ? contact_->reactions(u, t) : problem_->nodal_residual(u, t);
  std::vector<Vector3d> r;
  for (int i : output_.reactions) r.push_back(all[static_cast<std::size_t>(i)]);
  return r;
}

std::vector<std::string> Analysis::write_vtk(const std::string& dir, const std::string& stem,
                                             const VectorXd& u, double t) {
  const KirchhoffRod& rod = problem_->rod();
  const std::vector<Vector3d> x = problem_->current_points(u, t);
  std::vector<Vector3d> line;
  std::vector<double> force, curvature;
  for (int e = 0; e < rod.num_elements(); ++e) {
    const Interval I = rod.element_range(e);
    const int n = output_.samples_per_element;
    for (int k = (e == 0 ? 0 : 1); k <= n; ++k) {
      const double xi = I.lo + (I.hi - I.lo) * k / n;
      line.push_back(rod.point(xi, x));
      const RodStrains s = rod.strains(xi, x);
      force.push_back(s.axial_force);
      curvature.push_back(s.curvature);
    }
  }
  VtkPointData d;
  d.scalars = {{"axial_force", force}, {"curvature", curvature}};
  std::vector<std::string> files{stem + "_rod.vtk"};
  write_vtk_polydata((fs::path(dir) / files[0]).string(), line, true, d, name_ + " rod, t = " + fmt(t));
  if (contact_) {
    std::vector<Vector3d> pts, normal;
    std::vector<double> N, T, B, slip;
    for (const CurveContactPoint& cp : contact_->contact().points()) {
      if (!cp.law.active) continue;
      pts.push_back(cp.x);
      normal.push_back(cp.law.normal);
      N.push_back(cp.N);
      T.push_back(cp.T);
      B.push_back(cp.B);
      slip.push_back(cp.law.slip ? 1.0 : 0.0);
    }
    VtkPointData cd;
    cd.scalars = {{"N", N}, {"T", T}, {"B", B}, {"slip", slip}};
    cd.vectors = {{"normal", normal}};
    files.push_back(stem + "_contact.vtk");
    write_vtk_polydata((fs::path(dir) / files[1]).string(), pts, false, cd,
                       name_ + " contact points, t = " + fmt(t));
  }
  return files;
}

AnalysisResult Analysis::run(std::ostream* log, const std::string& out_dir) {
  AnalysisResult res;
  NonlinearSolver solver(settings_);
  solver.set_log(log);
  std::ofstream csv;
  std::unique_ptr<VtkCollection> pvd_rod, pvd_contact;
  if (!out_dir.empty()) {
    fs::create_directories(out_dir);
    csv.open(fs::path(out_dir) / "steps.csv");
    if (!csv) throw std::runtime_error(out_dir + "/steps.csv: cannot write file");
    csv << "step,t,iterations,active,stick,slip";
    for (int i : output_.reactions)
      for (const char* c : {"x", "y", "z", "norm"}) csv << ",R" << i << "_" << c;
    csv << "\n" << std::setprecision(12);
    if (output_.vtk != AnalysisOutput::Vtk::kNone) {
      pvd_rod = std::make_unique<VtkCollection>((fs::path(out_dir) / "rod.pvd").string());
      if (contact_) pvd_contact = std::make_unique<VtkCollection>((fs::path(out_dir) / "contact.pvd").string());
    }
  }
  auto vtk = [&](const VectorXd& u, double t, const std::string& stem) {
    const std::vector<std::string> f = write_vtk(out_dir, stem, u, t);
    pvd_rod->add(t, f[0]);
    if (pvd_contact) pvd_contact->add(t, f[1]);
  };
  VectorXd u = VectorXd::Zero(problem_->num_dofs());
  auto on_step = [&](const VectorXd& uc, double t, const StepAttempt& at) {
    AnalysisStep st;
    st.t = t;
    st.iterations = at.iterations;
    if (contact_) st.contact = contact_->contact().counts();
    if (!output_.reactions.empty()) st.reactions = reactions(uc, t);
    res.steps.push_back(st);
    if (csv.is_open()) {
      csv << res.steps.size() << "," << t << "," << st.iterations << "," << st.contact.active << ","
          << st.contact.stick << "," << st.contact.slip;
      for (const Vector3d& r : st.reactions) csv << "," << r.x() << "," << r.y() << "," << r.z() << "," << r.norm();
      csv << std::endl;  // flushed: a run that stops midway keeps its rows
      if (output_.vtk == AnalysisOutput::Vtk::kAll)
        vtk(uc, t, "step" + std::to_string(res.steps.size()));
    }
    if (contact_ && stop_full_slip_after_ >= 0.0 && t > stop_full_slip_after_ + 1e-12) {
      const bool sliding = contact_->contact().parameters().mu == 0.0 ||
                           (st.contact.active > 0 && st.contact.slip == st.contact.active);
      if (sliding) {
        res.full_slip = true;
        if (log) *log << "full slip at t = " << t << ": stopping\n";
        return false;
      }
    }
    return true;
  };
  res.solver = solver.solve(*problem_, u, on_step);
  res.u = u;
  res.contact_time = contact_ ? contact_->contact_time() : 0.0;
  if (!out_dir.empty()) {
    if (output_.vtk == AnalysisOutput::Vtk::kLast && !res.steps.empty()) vtk(u, res.solver.t, "last");
    Json s = Json::object();
    s["name"] = name_;
    s["status"] = to_string(res.solver.status);
    s["message"] = res.solver.message;
    s["t"] = res.solver.t;
    s["steps"] = res.solver.steps;
    s["cutbacks"] = res.solver.cutbacks;
    s["newton_iterations"] = res.solver.total_iterations;
    s["dofs"] = problem_->num_dofs();
    s["full_slip"] = res.full_slip;
    s["time_total_s"] = res.solver.time_total;
    s["time_assembly_s"] = res.solver.time_assembly;
    s["time_contact_s"] = res.contact_time;
    s["time_linear_solve_s"] = res.solver.time_linear_solve;
    std::ofstream(fs::path(out_dir) / "summary.json") << format_json(s) << "\n";
  }
  return res;
}

void apply_override(Json& doc, const std::string& file, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || assignment.empty() || assignment[0] != '/')
    throw std::invalid_argument("--set expects /json/pointer=value, got '" + assignment + "'");
  const JsonPointer ptr(assignment.substr(0, eq));
  if (!doc.contains(ptr)) throw ModelError(file, ptr.to_string(), "--set names no existing entry");
  doc[ptr] = parse_json_text(assignment.substr(eq + 1), "--set " + assignment.substr(0, eq));
}

}  // namespace iga
