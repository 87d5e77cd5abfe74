// Model file -> rod (+ contact) problem -> nonlinear solver -> output files. The sections and
// their keys are documented in docs/model_format.md ("Analysis sections").
#include "iga/model/analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <tuple>

#include "geometry/constructions.hpp"
#include "iga/core/partition.hpp"
#include "iga/model/body_types.hpp"
#include "iga/model/model.hpp"
#include "iga/model/sections.hpp"
#include "iga/output/output_format.hpp"

namespace iga {

namespace {

/// Contact is an inequality: no linear path solves it. "auto" takes Newton; "linear" is refused
/// at its key.
void newton_for_contact(const JsonCursor& root, NonlinearSolverSettings& s) {
  if (s.analysis == AnalysisKind::linear)
    root["solver"]["analysis"].fail(
        "a model with contact pairs is not linear (contact is an inequality): use "
        "\"nonlinear\" or \"auto\"");
  s.analysis = AnalysisKind::nonlinear;
}

}  // namespace

namespace fs = std::filesystem;
using namespace model_detail;

namespace {

// The direction of the load factor along the path: update(t) after each converged step returns
// +1 when the step before it was a maximum of t, -1 a minimum, 0 otherwise (or no direction
// yet; a step at the same t keeps the direction).
class LoadDirection {
 public:
  int update(double t) {
    const double dt = t - last_t_;
    const bool first = !started_;
    started_ = true;
    last_t_ = t;
    if (first || dt == 0.0) return 0;
    const int d = dt > 0.0 ? 1 : -1;
    const int turned = (direction_ != 0 && d != direction_) ? direction_ : 0;
    direction_ = d;
    return turned;
  }

 private:
  double last_t_ = 0.0;
  int direction_ = 0;
  bool started_ = false;
};

/// The process of each body over P processes (BodySystem::distribute): -1 for a cut body,
/// whose work all processes share; the others whole to the least loaded process, in the
/// file's order, weighed by their control points.
std::vector<int> owners(const std::vector<std::unique_ptr<Body>>& bodies,
                        const std::vector<bool>& cut, int P) {
  std::vector<double> load(static_cast<std::size_t>(P), 0.0), work;
  for (std::size_t b = 0; b < cut.size(); ++b) {
    const double n = bodies[b]->num_control_points();
    if (cut[b])
      for (double& l : load) l += n / P;
    else
      work.push_back(n);
  }
  const std::vector<int> whole = assign_whole(work, load);
  std::vector<int> owner;
  owner.reserve(cut.size());
  for (std::size_t b = 0, k = 0; b < cut.size(); ++b) owner.push_back(cut[b] ? -1 : whole[k++]);
  return owner;
}

}  // namespace

std::string restart_file_of(const std::string& path, int rank) {
  return rank == 0 ? path : path + "." + std::to_string(rank);
}

std::vector<LoadLimitPoint> load_limit_points(const std::vector<AnalysisStep>& steps) {
  std::vector<LoadLimitPoint> out;
  LoadDirection direction;
  std::size_t previous = 0;  // the last step whose t differs from the one before it
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const int turned = direction.update(steps[k].t);
    if (turned != 0) out.push_back({previous, turned > 0});
    if (k == 0 || steps[k].t != steps[k - 1].t) previous = k;
  }
  return out;
}

Analysis Analysis::from_json(const Json& doc, const std::string& file, const Communicator& comm) {
  if (comm.size() == 1) return build(doc, file, comm);
  // Over several processes a model error may be one process's alone (its block of a shell
  // above the bound): every process throws the first failing process's error, so that none
  // goes on alone. Its file, pointer and message travel in one string.
  constexpr char kSep = '\x1f';
  std::optional<Analysis> built;
  std::string why;
  try {
    built.emplace(build(doc, file, comm));
  } catch (const ModelError& e) {
    why = e.file() + kSep + e.pointer() + kSep + e.message();
  } catch (const std::exception& e) {
    why = std::string(2, kSep) + e.what();
  }
  const std::string first = comm.first_message(why);
  if (first.empty()) return std::move(*built);
  const std::size_t i = first.find(kSep), j = first.find(kSep, i + 1);
  if (i == 0) throw std::runtime_error(first.substr(j + 1));
  throw ModelError(first.substr(0, i), first.substr(i + 1, j - i - 1), first.substr(j + 1));
}

Analysis Analysis::build(const Json& doc, const std::string& file, const Communicator& comm) {
  const Model model = parse_model(doc, file);  // format, version, geometry, known sections
  const JsonCursor root(doc, file);
  Analysis a;
  a.name_ = model.name;
  a.geometry_ = model.geometry;
  if (!root.has("bodies")) root.fail_plain("missing required key \"bodies\" (nothing to analyse)");

  Context ctx;
  std::map<std::string, std::shared_ptr<const RigidSurface>> rigids;
  ctx.rigids = &rigids;
  if (root.has("load_curves")) {
    const JsonCursor lc = root["load_curves"];
    if (!lc.json().is_object()) lc.fail_type("an object of named load curves");
    for (const std::string& k : lc.keys()) {
      // each curve is a column of steps.csv: its name must not be one of the fixed columns
      for (const char* fixed : {"step", "t", "lambda", "iterations", "active", "stick", "slip"})
        if (k == fixed)
          lc[k].fail_plain("\"" + k +
                           "\" is a column of steps.csv already: name the curve "
                           "otherwise");
      ctx.curves[k] = parse_load_curve(lc[k]);
      a.curves_.emplace_back(k, ctx.curves[k]);
    }
  }
  const Json no_materials = Json::object();
  const JsonCursor materials =
      root.has("materials") ? root["materials"] : JsonCursor(no_materials, file);
  if (!materials.json().is_object()) materials.fail_type("an object of named materials");
  for (const std::string& k : materials.keys()) {  // every entry is checked, used or not
    check_material(materials[k]);
  }

  // The bodies, each built by the reader of its type (body_types.hpp) with the conditions,
  // loads and contact pairs that name it; every such entry must name one of them.
  const JsonCursor bodies = root["bodies"];
  if (!bodies.json().is_object() || bodies.size() == 0)
    bodies.fail_type("an object of named bodies (at least one)");
  ctx.bodies = bodies.keys();
  check_entry_bodies(root, ctx);
  if (root.has("rigid_motions"))
    ctx.motions = parse_rigid_motions(root["rigid_motions"], ctx, a.geometry_);
  a.system_ = std::make_unique<BodySystem>();
  std::vector<Context> read;  // each body's context, for the output section
  std::vector<bool> cut;      // each body's: cut over the processes
  for (const std::string& name : bodies.keys()) {
    Context bc = ctx;
    bc.body = name;
    bc.body_index = static_cast<int>(a.bodies_.size());
    const JsonCursor b = bodies[name];
    if (!b.json().is_object()) b.fail_type("an object with a \"type\" key");
    const BodyType& type = body_type(b["type"]);
    std::unique_ptr<Body> body =
        type.build(BodyInput{root, b, bc, a.geometry_, materials, comm.rank(), comm.size()});
    cut.push_back(type.cut && comm.size() > 1);
    a.body_names_.push_back(name);
    a.bodies_.push_back(std::move(body));
    a.system_->add(*a.bodies_.back());
    read.push_back(std::move(bc));
  }
  if (comm.size() > 1) a.system_->distribute(comm, owners(a.bodies_, cut, comm.size()));
  a.collect_pairs(root);
  if (root.has("rigid_motions"))  // a motion of a tool no pair touches is a typo
    for (const std::string& tool : root["rigid_motions"].keys())
      if (std::none_of(a.pairs_.begin(), a.pairs_.end(),
                       [&](const PairRef& p) { return p.rigid == tool; }))
        root["rigid_motions"][tool].fail_plain("no contact pair names the rigid surface \"" + tool +
                                               "\"");
  if (root.has("solver"))
    a.settings_ = parse_solver(root["solver"], a.stop_full_slip_after_, a.full_slip_steps_);
  else
    a.settings_.analysis = AnalysisKind::certified;  // "auto", as parse_solver's default
  if (a.has_contact()) newton_for_contact(root, a.settings_);
  if (comm.size() > 1 && a.settings_.linear_method == LinearMethod::suitesparse) {
    // Over several processes the tangent is solved by PETSc: MUMPS unless the model says
    // otherwise; SuiteSparse works on one process only.
    if (root.has("solver") && root["solver"].has("linear_solver"))
      root["solver"]["linear_solver"].fail(
          "SuiteSparse solves on one process; over " + std::to_string(comm.size()) +
          " processes use \"mumps\" (the default there) or \"krylov\"");
    a.settings_.linear_method = LinearMethod::mumps;
  }
  // Every load curve, used or not (steps.csv has a column for each), must stay finite over the
  // run's pseudo-time.
  for (const auto& [name, curve] : a.curves_)
    check_finite_curve(root["load_curves"][name], curve, a.settings_);
  if (root.has("output")) {
    a.output_ = parse_output(root["output"], read);
    // the plots' terms must name columns of steps.csv
    check_plot_columns(root["output"], a.output_, a.csv_columns());
  }
  if (a.system_->num_dofs() == 0)
    root["boundary_conditions"].fail_plain("every degree of freedom is constrained");
  return a;
}

void Analysis::collect_pairs(const JsonCursor& root) {
  // The pairs in the file's order: each body attached its own in that order.
  if (!root.has("contact")) return;
  const JsonCursor list = root["contact"];
  std::vector<int> next(bodies_.size(), 0);
  for (std::size_t k = 0; k < list.size(); ++k) {
    const JsonCursor c = list[k];
    const auto it = std::find(body_names_.begin(), body_names_.end(), c["body"].as_string());
    const int b = static_cast<int>(it - body_names_.begin());
    const std::string name = c.has("name")
                                 ? column_name(c["name"])
                                 : (list.size() > 1 ? "contact_" + std::to_string(k) : "contact");
    // per_face: one pair per face of the tool, named <name>_<face> (face = piece index)
    const bool per_face = c.has("per_face") && c["per_face"].as_bool();
    const std::size_t faces = per_face ? geometry_.surfaces_of(c["rigid"].as_string()).size() : 1;
    for (std::size_t f = 0; f < faces; ++f) {
      PairRef p;
      p.pair = &bodies_[static_cast<std::size_t>(b)]->pair(next[static_cast<std::size_t>(b)]++);
      p.body = b;
      p.rigid = c["rigid"].as_string();
      p.name = per_face ? name + "_" + std::to_string(f) : name;
      if (c.has("moment_about")) {
        p.moment_about = vec3(c["moment_about"]);
      } else if (const RigidMotion* m = p.pair->motion(); m && m->rotates()) {
        p.moment_about = m->point();
      }
      for (const PairRef& q : pairs_)
        if (q.name == p.name)
          (c.has("name") ? c["name"] : c)
              .fail_plain("a second contact pair named \"" + p.name +
                          "\" (pair names are the columns of steps.csv)");
      pairs_.push_back(std::move(p));
    }
  }
}

std::pair<Vector3d, Vector3d> Analysis::tool_load(int k) const {
  const PairRef& p = pairs_.at(static_cast<std::size_t>(k));
  const ContactPair& P = *p.pair;
  return {P.tool_force(), P.tool_moment(P.pose().to_world(p.moment_about))};
}

Analysis Analysis::load(const std::string& path, const Communicator& comm) {
  return from_json(read_json_file(path), path, comm);
}

std::string Analysis::describe() const {
  std::ostringstream s;
  for (int b = 0; b < num_bodies(); ++b) {
    if (b > 0) s << "; ";
    s << (num_bodies() > 1 ? body_name(b) + ": " : "") << body(b).describe();
  }
  s << ", " << system_->num_dofs() << " unknowns";
  for (const PairRef& p : pairs_) {
    s << ", ";
    if (num_pairs() > 1) s << p.name << " (" << body_name(p.body) << " on " << p.rigid << "): ";
    s << p.pair->describe();
  }
  s << ", t in [" << settings_.t0 << ", " << settings_.t1 << "]";
  return s.str();
}

ContactCounts Analysis::contact_counts() const {
  ContactCounts sum;
  for (const PairRef& p : pairs_) {
    const ContactCounts c = p.pair->counts();
    sum.active += c.active;
    sum.stick += c.stick;
    sum.slip += c.slip;
  }
  return sum;
}

double Analysis::contact_time() const {
  double t = 0.0;
  for (const PairRef& p : pairs_) t += p.pair->time();
  return t;
}

Vector3d Analysis::displacement(const AnalysisMonitor& m, const VectorXd& u, double t) const {
  return body(m.body).displacement(m.u, m.v, system_->block(u, m.body), t);
}

double Analysis::model_size() {
  if (model_size_ > 0.0) return model_size_;
  // The bounding box of the bodies at the start (u = 0), over every process's part.
  std::array<double, 6> box{};  // max x, y, z and max -x, -y, -z
  box.fill(-std::numeric_limits<double>::infinity());
  const VectorXd u0 = VectorXd::Zero(system_->num_dofs());
  for (int b = 0; b < num_bodies(); ++b)
    for (const Vector3d& x : body(b).sample(system_->block(u0, b), settings_.t0, 1).points)
      for (int i = 0; i < 3; ++i) {
        box[static_cast<std::size_t>(i)] = std::max(box[static_cast<std::size_t>(i)], x[i]);
        box[static_cast<std::size_t>(i) + 3] =
            std::max(box[static_cast<std::size_t>(i) + 3], -x[i]);
      }
  communicator().max(box);
  double d2 = 0.0;
  for (std::size_t i = 0; i < 3; ++i)
    if (std::isfinite(box[i]) && std::isfinite(box[i + 3])) d2 += std::pow(box[i] + box[i + 3], 2);
  model_size_ = d2 > 0.0 ? std::sqrt(d2) : 1.0;
  return model_size_;
}

std::vector<Vector3d> Analysis::reactions(const VectorXd& u, double t) {
  if (settings_.analysis != AnalysisKind::linear) return body_reactions(u, t);
  // Linear analysis: linear theory's reactions r(u_0) + K_0 d at d = u - u_0 (u_0 = 0, the
  // start), not the bodies' nonlinear r(u), which at a large d neither is linear in the load
  // nor balances it. K_0 d by the fourth-order central difference of r along d,
  // (8 (r(h d) - r(-h d)) - (r(2h d) - r(-2h d))) / (12 h), over a perturbation whose largest
  // displacement is kLinearProbe times the model's size L: r is smooth in u, the error is
  // O(kLinearProbe^4) with a constant set by how soon the body's response turns nonlinear (a
  // thin shell's: L / h), and the round-off ~1e-16 / kLinearProbe of the perturbation's
  // internal forces. Measured on the Scordelis-Lo roof at the full load (L / h = 240), the
  // reactions' imbalance against the load: 8e-11 (1e-3), 1.7e-10 (3e-4), 1.3e-9 (1e-4),
  // 1.3e-8 (1e-5); the second-order difference left 1.8e-5 (1e-4) and at best 4e-8 (1e-6).
  constexpr double kLinearProbe = 3e-4;
  const double d_max = u.lpNorm<Eigen::Infinity>();
  std::vector<Vector3d> r0 = body_reactions(VectorXd::Zero(u.size()), t);
  if (!(d_max > 0.0)) return r0;
  const double h = kLinearProbe * model_size() / d_max;
  const std::vector<Vector3d> r1 = body_reactions(h * u, t), r_1 = body_reactions(-h * u, t);
  const std::vector<Vector3d> r2 = body_reactions(2.0 * h * u, t);
  const std::vector<Vector3d> r_2 = body_reactions(-2.0 * h * u, t);
  std::vector<Vector3d> r(r0.size());
  for (std::size_t k = 0; k < r.size(); ++k)
    r[k] = r0[k] + (8.0 * (r1[k] - r_1[k]) - (r2[k] - r_2[k])) / (12.0 * h);
  return r;
}

std::vector<Vector3d> Analysis::body_reactions(const VectorXd& u, double t) {
  std::vector<std::vector<Vector3d>> all(static_cast<std::size_t>(num_bodies()));
  std::vector<Vector3d> r;
  for (const AnalysisReaction& q : output_.reactions) {
    std::vector<Vector3d>& a = all[static_cast<std::size_t>(q.body)];
    if (a.empty()) a = body(q.body).reactions(system_->block(u, q.body), t);
    r.push_back(a[static_cast<std::size_t>(q.point)]);
  }
  // Each process has its share's part (the constraint forces are linear in the residual).
  std::vector<double> flat;
  for (const Vector3d& v : r) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  communicator().sum(flat);
  for (std::size_t k = 0; k < r.size(); ++k)
    r[k] = Vector3d(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
  return r;
}

bool Analysis::sliding_steadily() const {
  // Every pair in contact slides steadily (a pair without contact, e.g. a face of a per-face
  // tool the body does not touch, holds nothing back), and some pair is in contact.
  bool any = false;
  for (const PairRef& p : pairs_) {
    if (p.pair->counts().active == 0) continue;
    any = true;
    if (!p.pair->sliding_steadily()) return false;
  }
  return any;
}

bool Analysis::plateau_complete(double t, int& sliding_steps) const {
  if (!has_contact() || stop_full_slip_after_ < 0.0 || t <= stop_full_slip_after_ + 1e-12)
    return false;
  if (!sliding_steadily()) {
    sliding_steps = 0;  // the plateau is a run of consecutive sliding steps
    return false;
  }
  return ++sliding_steps >= full_slip_steps_;
}

AnalysisStep Analysis::record_step(const VectorXd& u, double t, int iterations) {
  AnalysisStep st;
  st.t = t;
  st.iterations = iterations;
  st.contact = contact_counts();
  for (int k = 0; k < num_pairs(); ++k) {
    st.pairs.push_back(pair(k).counts());
    st.tool_loads.push_back(tool_load(k));
  }
  if (!output_.reactions.empty()) st.reactions = reactions(u, t);
  for (const AnalysisMonitor& m : output_.monitors)
    st.displacements.push_back(displacement(m, u, t));
  return st;
}

std::vector<std::string> Analysis::csv_columns() const {
  std::vector<std::string> c{"step", "t", "lambda", "iterations", "active", "stick", "slip"};
  if (num_pairs() > 1)  // the counts of each pair
    for (const PairRef& p : pairs_)
      for (const char* q : {"active", "stick", "slip"}) c.push_back(p.name + "_" + q);
  for (const PairRef& p : pairs_)  // the force and moment on each pair's tool
    for (const char* q : {"Fx", "Fy", "Fz", "Mx", "My", "Mz"}) c.push_back(p.name + "_" + q);
  for (const AnalysisReaction& r : output_.reactions)
    for (const char* q : {"x", "y", "z", "norm"})
      c.push_back("R" + (num_bodies() > 1 ? body_name(r.body) + "_" : "") +
                  std::to_string(r.point) + "_" + q);
  for (const AnalysisMonitor& m : output_.monitors)
    for (const char* q : {"ux", "uy", "uz"})  // with several bodies <body>_<name>_u*
      c.push_back((num_bodies() > 1 ? body_name(m.body) + "_" : "") + m.name + "_" + q);
  for (const auto& [name, curve] : curves_) c.push_back(name);
  return c;
}

std::vector<double> Analysis::step_values(int index, const AnalysisStep& st) const {
  std::vector<double> v{static_cast<double>(index),
                        st.t,
                        load_factor(st.t),
                        static_cast<double>(st.iterations),
                        static_cast<double>(st.contact.active),
                        static_cast<double>(st.contact.stick),
                        static_cast<double>(st.contact.slip)};
  if (num_pairs() > 1)
    for (const ContactCounts& c : st.pairs)
      v.insert(v.end(), {static_cast<double>(c.active), static_cast<double>(c.stick),
                         static_cast<double>(c.slip)});
  for (const auto& [F, M] : st.tool_loads)
    v.insert(v.end(), {F.x(), F.y(), F.z(), M.x(), M.y(), M.z()});
  for (const Vector3d& r : st.reactions) v.insert(v.end(), {r.x(), r.y(), r.z(), r.norm()});
  for (const Vector3d& d : st.displacements) v.insert(v.end(), {d.x(), d.y(), d.z()});
  for (const auto& [name, curve] : curves_) v.push_back(curve(st.t));
  return v;
}

Json Analysis::summary(const AnalysisResult& res) const {
  Json s = Json::object();
  s["name"] = name_;
  std::string types;  // "rod", "shell" or, with several bodies, e.g. "rod, shell"
  for (int b = 0; b < num_bodies(); ++b) types += (b > 0 ? ", " : "") + body(b).type();
  s["body"] = types;
  s["status"] = to_string(res.solver.status);
  s["message"] = res.solver.message;
  s["t"] = json_number(res.solver.t);
  s["steps"] = res.solver.steps;
  s["cutbacks"] = res.solver.cutbacks;
  s["newton_iterations"] = res.solver.total_iterations;
  // The path: the analysis asked for, the steps the linear path
  // solved, and the assemblies and factorizations of the run.
  s["analysis"] =
      settings_.analysis == AnalysisKind::certified ? "auto" : to_string(settings_.analysis);
  s["linear_steps"] = res.solver.linear_steps;
  s["assemblies"] = res.solver.assemblies;
  s["residual_assemblies"] = res.solver.residual_assemblies;  // without the tangent
  s["load_rates"] = res.solver.load_rates;  // arc length's dR/dt from the loads alone
  s["factorizations"] = res.solver.cholmod_factorizations + res.solver.ldlt_factorizations +
                        res.solver.umfpack_factorizations + res.solver.petsc_factorizations;
  s["jumps"] = res.solver.jumps;  // load control: steps that likely jumped over a limit point
  s["dofs"] = system_->num_dofs();
  s["full_slip"] = res.full_slip;
  Json pairs = Json::array();  // each pair at the last converged step
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    Json p = Json::object();
    p["name"] = pairs_[k].name;
    p["body"] = body_name(pairs_[k].body);
    p["rigid"] = pairs_[k].rigid;
    const ContactCounts c = res.steps.empty() ? ContactCounts{} : res.steps.back().pairs[k];
    p["active"] = c.active;
    p["stick"] = c.stick;
    p["slip"] = c.slip;
    pairs.push_back(p);
  }
  s["pairs"] = pairs;
  Json limits = Json::array();  // the load's maxima and minima along the path
  for (const LoadLimitPoint& lp : load_limit_points(res.steps)) {
    const AnalysisStep& st = res.steps[lp.index];
    Json l = Json::object();
    l["kind"] = lp.maximum ? "maximum" : "minimum";
    l["step"] = st.step;
    l["t"] = json_number(st.t);
    l["lambda"] = json_number(load_factor(st.t));
    Json m = Json::object();
    for (std::size_t i = 0; i < output_.monitors.size() && i < st.displacements.size(); ++i) {
      const Vector3d& d = st.displacements[i];
      m[output_.monitors[i].name] = {json_number(d.x()), json_number(d.y()), json_number(d.z())};
    }
    l["monitors"] = m;
    limits.push_back(l);
  }
  s["limit_points"] = limits;
  if (!res.restart_file.empty()) s["restart_file"] = res.restart_file;
  s["time_total_s"] = json_number(res.solver.time_total);
  s["time_assembly_s"] = json_number(res.solver.time_assembly);
  s["time_contact_s"] = json_number(res.contact_time);
  s["time_linear_solve_s"] = json_number(res.solver.time_linear_solve);
  return s;
}

void Analysis::archive_run(StateArchive& a, RunState& s,
                           const std::vector<std::unique_ptr<OutputSink>>& sinks) {
  a.section("analysis");
  // What must not change between the run that wrote the file and the one that reads it.
  const auto same = [&](auto value, auto&& name_of) {
    auto stored = value;
    a.io(stored);
    if (a.loading() && stored != value) a.fail(name_of(stored, value));
  };
  same(communicator().size(), [](int f, int m) {
    return "the file was written by a run on " + std::to_string(f) +
           " process(es), this one runs on " + std::to_string(m) +
           ": restart it on as many (each process's file holds its share of the bodies)";
  });
  same(system_->num_dofs(), [](int f, int m) {
    return "the file's model has " + std::to_string(f) + " unknowns, this one " + std::to_string(m);
  });
  same(std::string(to_string(settings_.control)), [](const std::string& f, const std::string& m) {
    return "the file's run uses " + f + " control, this one " + m +
           " (the path control cannot change in a restart)";
  });
  std::string header;  // steps.csv's header line
  for (const std::string& c : csv_columns()) header += (header.empty() ? "" : ",") + c;
  same(header + "\n", [](const std::string& f, const std::string& m) {
    return "the file's steps.csv has other columns (" + f.substr(0, f.size() - 1) +
           "), this model's: " + m.substr(0, m.size() - 1);
  });
  a.io(s.steps);
  a.io(s.sliding_steps);
  for (const std::unique_ptr<OutputSink>& sink : sinks) sink->archive(a);  // rows, series
  a.section("state");
  a.io(s.u);
  if (a.loading() && s.u.size() != system_->num_dofs()) a.fail("the state has another size");
  s.solver.archive(a);
  system_->archive(a);
}

void Analysis::read_restart(const std::string& file, RunState& s,
                            const std::vector<std::unique_ptr<OutputSink>>& sinks) {
  // Each process reads its own file; one that cannot stops them all with its reason.
  const Communicator& comm = communicator();
  std::string why;
  try {
    StateArchive a = StateArchive::reader(restart_file_of(file, comm.rank()));
    archive_run(a, s, sinks);
    a.finish();
  } catch (const std::exception& e) {
    if (comm.size() == 1) throw;
    why = e.what();
  }
  if (comm.size() > 1)
    if (const std::string first = comm.first_message(why); !first.empty())
      throw RestartError(first);
}

// The output side of one run(): the sinks (steps table, field series, summary; iga/output), restart
// files, the error that ends the run.
struct Analysis::RunContext {
  RunContext(Analysis& a, std::ostream* l, std::string dir, AnalysisResult& r)
      : an(a), comm(a.communicator()), log(l), out_dir(std::move(dir)), res(r) {
    // Made whether or not there is an output folder: a restart file holds their state.
    for (const std::string& format :
         {std::string("csv"), an.output_.field_format, std::string("summary")})
      sinks.push_back(make_output_sink(format));
  }
  Analysis& an;
  // The run's processes: all take part in every step's reductions and in the fields' gather;
  // process 0 writes the tables, summary and fields; each writes its own restart file.
  const Communicator& comm;
  std::ostream* log;
  std::string out_dir;
  AnalysisResult& res;
  RunState rs;  // a restart's state
  std::vector<std::unique_ptr<OutputSink>> sinks;
  bool opened = false;  // the run writes into out_dir (process 0's sinks)
  // An error after the start (output of a converged step, the problem's history update, the
  // user's callback, the last ParaView files) ends the run with status `failed` and this
  // message; summary.json and the rows written so far stay.
  std::string error;
  std::string restart_base;  // restart.bin in the output folder (empty: no output folder)
  std::string restart_path;  // this process's restart file (restart_file_of)
  int restart_step = -1;     // the step of the last restart file written
  int sliding_steps = 0;     // consecutive steps of steady sliding (the plateau so far)
  LoadDirection direction;   // of the load factor along the path (its limit points)

  // The number of the step that converged last (the rows before a restart included).
  int step_number() const { return rs.steps + static_cast<int>(res.steps.size()); }

  // The sinks open in out_dir (steps.csv with its header and a restart's rows, the series of a
  // restart); the rigid tools at t0. steps.csv that cannot be written: std::runtime_error.
  void open() {
    if (out_dir.empty()) return;
    restart_base = (fs::path(out_dir) / "restart.bin").string();
    restart_path = restart_file_of(restart_base, comm.rank());
    try {
      fs::create_directories(out_dir);
      opened = true;
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (opened && comm.root()) open_sinks();
    if (opened && !comm.root())
      for (const std::unique_ptr<OutputSink>& sink : sinks) sink->open_part(out_dir);
    // An output folder or a steps.csv that cannot be written ends the run before it starts, on
    // every process; the other sinks' errors end it after the start (status failed,
    // summary.json written).
    if (comm.size() > 1) {
      const double worst = comm.max(!opened ? 2.0 : !error.empty() ? 1.0 : 0.0);
      if (worst > 0.0) error = comm.first_message(error);
      if (worst == 2.0) opened = false;
    }
    if (!opened) throw std::runtime_error(error);
  }

  void open_sinks() {
    const std::vector<std::string> columns = an.csv_columns();
    try {
      sinks.front()->open(out_dir, columns);  // steps.csv
    } catch (const std::exception& e) {
      error = e.what();
      opened = false;
      return;
    }
    try {
      for (std::size_t i = 1; i < sinks.size(); ++i) sinks[i]->open(out_dir, columns);
    } catch (const std::exception& e) {
      error = e.what();
      return;
    }
    if (an.output_.vtk == AnalysisOutput::Vtk::kNone) return;
    try {
      std::vector<MeshOutput> tools = an.tool_meshes("rigid", an.settings_.t0, false);
      for (MeshOutput& m : tools) m.series.clear();  // the tools at rest: no series
      if (!tools.empty()) snapshot(an.settings_.t0, tools);
    } catch (const std::exception& e) {
      error = std::string("writing the rigid surface's ParaView file: ") + e.what();
    }
  }

  // Over several processes, whether the field format writes each process's pieces (else
  // process 0 writes the meshes whole, gathered).
  bool pieces() const {
    return comm.size() > 1 && std::any_of(sinks.begin(), sinks.end(),
                                          [](const auto& sink) { return sink->writes_pieces(); });
  }

  void snapshot(double key, const std::vector<MeshOutput>& meshes) {
    if (!comm.root() && !pieces()) return;
    for (const std::unique_ptr<OutputSink>& sink : sinks) sink->snapshot(key, meshes);
  }

  // The field series' snapshot of (u, t); its key: t, or under arc length (t falls after a
  // limit point and comes back: ParaView orders a series by its times) the step. Every
  // process takes part (each writes its pieces, or the meshes are gathered to process 0).
  void fields(const VectorXd& u, double t, const std::string& stem) {
    const bool by_step = an.settings_.control == PathControl::arc_length;
    snapshot(by_step ? static_cast<double>(step_number()) : t,
             an.output_meshes(stem, u, t, pieces()));
  }

  // Over several processes: whether every process goes on after a step, and the first
  // process's error (every process stops when one does: none is left waiting).
  bool agree(bool go_on) {
    if (comm.size() == 1) return go_on;
    const double worst = comm.max(!error.empty() ? 2.0 : go_on ? 0.0 : 1.0);
    if (worst == 2.0) error = comm.first_message(error);
    return worst == 0.0;
  }

  // The sinks' summary of the run.
  void close() {
    if (!opened || !comm.root()) return;
    const Json summary = an.summary(res);
    for (const std::unique_ptr<OutputSink>& sink : sinks) sink->close(summary);
  }

  // The restart file of the converged state (u, checkpoint): the run's and the bodies' state.
  void write_restart(const VectorXd& u, const SolverCheckpoint& checkpoint) {
    RunState w;
    w.solver = checkpoint;
    w.u = u;
    w.steps = step_number();
    w.sliding_steps = sliding_steps;
    StateArchive a = StateArchive::file_writer(restart_path);  // written as it goes
    an.archive_run(a, w, sinks);
    a.save(restart_path);
    res.restart_file = restart_base;  // the name a restart is given (each process adds its own)
    restart_step = w.steps;
  }

  // After a converged step: its record, row, files, the caller's callback, the plateau test,
  // the restart file every restart_every steps. False: stop.
  bool step(const VectorXd& u, double t, const StepAttempt& at, const SolverCheckpoint& checkpoint,
            const AnalysisStepCallback& user_callback) {
    try {
      AnalysisStep st = an.record_step(u, t, at.iterations);
      st.step = step_number() + 1;
      res.steps.push_back(st);
      const int k = step_number();
      log_limit_point(t);
      const std::vector<double> row = an.step_values(k, st);
      for (const std::unique_ptr<OutputSink>& sink : sinks) sink->row(row);
      if (opened && an.output_.vtk == AnalysisOutput::Vtk::kAll)
        fields(u, t, "step" + std::to_string(k));
      // The caller sees every converged step, the one that completes the plateau too.
      bool go_on = !user_callback || user_callback(u, t, st);
      if (go_on && an.plateau_complete(t, sliding_steps)) {
        res.full_slip = true;
        if (log) *log << "full slip at t = " << t << ": stopping\n";
        go_on = false;
      }
      const int every = an.output_.restart_every;
      if (!restart_path.empty() && every > 0 && k % every == 0) write_restart(u, checkpoint);
      return agree(go_on);
    } catch (const std::exception& e) {
      error = "output of the step at t = " + fmt(t) + ": " + e.what();
      return agree(false);
    }
  }

  // After the step at t: a limit point of the load at the step before, if the load turned.
  void log_limit_point(double t) {
    const int turned = direction.update(t);
    if (turned == 0 || log == nullptr || res.steps.size() < 2) return;
    const AnalysisStep& at = res.steps[res.steps.size() - 2];
    *log << "limit point: load " << (turned > 0 ? "maximum" : "minimum") << " at step " << at.step
         << ", t = " << fmt(at.t) << "\n";
  }

  // A run that stopped before t1 (not at full slip as asked): the restart file of its last
  // converged state (u), unless the last one written is that state's.
  void restart_at_stop(const VectorXd& u, const SolverCheckpoint& checkpoint, bool resumed) {
    const bool early = !res.solver.converged() && !res.full_slip;
    if (!early || restart_path.empty() || (res.steps.empty() && !resumed) ||
        restart_step == step_number())
      return;
    try {
      // After failed attempts the contact points' current state (their last feet, the warm
      // start of the next search) is theirs: one assembly at the converged state makes it that
      // state's again (the history is the committed one), up to the round-off of the feet
      // found from other starts. Without failed attempts (stopped by max_steps or the caller)
      // the state is the converged step's as it is.
      const auto& attempts = res.solver.attempts;
      if (!attempts.empty() && attempts.back().outcome != NewtonOutcome::converged) {
        VectorXd R(an.system_->num_dofs());
        an.system_->assemble(u, checkpoint.t, R, nullptr);
      }
      write_restart(u, checkpoint);
    } catch (const std::exception& e) {
      if (log) *log << "warning: no restart file: " << e.what() << "\n";
    }
  }
};

AnalysisResult Analysis::run(std::ostream* log, const std::string& out_dir,
                             const AnalysisStepCallback& user_callback,
                             const std::string& restart_file) {
  AnalysisResult res;
  const Communicator& comm = communicator();
  if (!comm.root()) log = nullptr;  // process 0 reports
  NonlinearSolver solver(settings_);
  solver.set_log(log);
  RunContext run{*this, log, out_dir, res};
  // A restart: the state of the run that wrote the file (RestartError if it does not fit);
  // each process reads its own file, and a process that cannot stops them all.
  VectorXd u = VectorXd::Zero(system_->num_dofs());
  const bool resumed = !restart_file.empty();
  if (resumed) {
    read_restart(restart_file, run.rs, run.sinks);
    u = run.rs.u;
    run.sliding_steps = run.rs.sliding_steps;
    run.direction.update(run.rs.solver.t);  // the path's limit points from the next step on
    if (log)
      *log << "restart from " << restart_file << ": step " << run.rs.steps
           << ", t = " << run.rs.solver.t << "\n";
  }
  run.open();
  auto on_step = [&](const VectorXd& uc, double t, const StepAttempt& at) {
    return run.step(uc, t, at, solver.checkpoint(), user_callback);
  };
  if (run.error.empty()) {
    try {
      res.solver = solver.solve(*system_, u, on_step, resumed ? &run.rs.solver : nullptr);
    } catch (const std::exception& e) {  // from commit(): u is the last converged state
      // Over several processes, one that fails alone here would leave the others waiting:
      // the run ends on every process, with this message (the rows written so far stay).
      if (comm.size() > 1)
        comm.abort(1, "process " + std::to_string(comm.rank()) + ": " + e.what());
      run.error = e.what();
      res.solver.t = !res.steps.empty() ? res.steps.back().t
                     : resumed          ? run.rs.solver.t
                                        : settings_.t0;
      res.solver.steps = run.step_number();
    }
  }
  res.u = u;
  res.contact_time = contact_time();
  if (!out_dir.empty() && run.error.empty() && output_.vtk == AnalysisOutput::Vtk::kLast &&
      !res.steps.empty()) {
    try {
      run.fields(u, res.solver.t, "last");
    } catch (const std::exception& e) {
      run.error = std::string("writing the ParaView files of the last step: ") + e.what();
    }
    run.agree(true);  // an error of process 0 is every process's
  }
  if (!run.error.empty()) {
    res.solver.status = NonlinearSolverStatus::failed;
    res.solver.message =
        run.error + "; the state is the last converged one, t = " + fmt(res.solver.t);
    if (log) *log << "run failed: " << res.solver.message << "\n";
  }
  run.restart_at_stop(u, res.steps.empty() ? run.rs.solver : solver.checkpoint(), resumed);
  if (log && !res.restart_file.empty())
    *log << "restart file: " << res.restart_file << " (step " << run.step_number() << ")\n";
  try {
    run.close();
  } catch (const std::exception& e) {  // the run's outcome stands; the summary is lost
    if (log) *log << "warning: " << e.what() << "\n";
  }
  return res;
}

}  // namespace iga
