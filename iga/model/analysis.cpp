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
#include "iga/model/sections.hpp"
#include "iga/output/output_format.hpp"
#include "iga/output/vtk_writer.hpp"

namespace iga {

namespace fs = std::filesystem;
using namespace model_detail;

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

}  // namespace iga
