// A whole analysis from a model file (docs/model_format.md, "Analysis sections"): the body (a
// Kirchhoff rod on a curve of the geometry section), its material, boundary conditions, loads
// along load curves, contact with a rigid surface of the geometry section (CTRS, [KS15]
// Sects. 4-5), solver settings and output requests; run() drives the nonlinear solver and
// writes the results (CSV per step, ParaView files, a JSON summary).
// Every input error is a ModelError naming the file, the JSON path and the value.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"
#include "iga/nonlinear_solver.hpp"
#include "iga/rod_contact_problem.hpp"

namespace iga {

/// Output requests of the "output" section.
struct AnalysisOutput {
  enum class Vtk { kNone, kLast, kAll };
  Vtk vtk = Vtk::kLast;          ///< ParaView files: none, the last step, every step
  std::vector<int> reactions;    ///< control points whose reactions go to steps.csv
  int samples_per_element = 16;  ///< centre line points per element in the VTK files
};

/// One converged step as recorded by Analysis::run.
struct AnalysisStep {
  double t = 0.0;
  int iterations = 0;
  CurveContactCounts contact;
  std::vector<Vector3d> reactions;  ///< at AnalysisOutput::reactions, Cartesian
};

struct AnalysisResult {
  NonlinearSolverResult solver;
  std::vector<AnalysisStep> steps;
  VectorXd u;                ///< state at the last converged step (time solver.t)
  bool full_slip = false;    ///< the run stopped at the onset of full slip
  double contact_time = 0.0; ///< seconds in the contact integral (part of the assembly)
};

class Analysis {
 public:
  /// Builds the analysis of a parsed model document (the whole file, "format"
  /// "iga-contact-model"); `file` names it in messages. Throws ModelError.
  static Analysis from_json(const Json& doc, const std::string& file);
  /// read_json_file + from_json.
  static Analysis load(const std::string& path);

  const std::string& name() const { return name_; }
  const GeometryModel& geometry() const { return geometry_; }
  RodProblem& rod_problem() { return *problem_; }
  /// The problem with contact, or nullptr if the model has no "contact" section.
  RodContactProblem* contact_problem() { return contact_; }
  const NonlinearSolverSettings& solver_settings() const { return settings_; }
  NonlinearSolverSettings& solver_settings() { return settings_; }
  const AnalysisOutput& output() const { return output_; }
  /// Pseudo-time after which the run stops at the first step where every active contact point
  /// slides (< 0: off). "solver": {"stop_at_full_slip_after": t}.
  double stop_at_full_slip_after() const { return stop_full_slip_after_; }

  /// Runs from the reference state over [settings.t0, settings.t1]. Progress lines go to `log`
  /// (may be null). With a non-empty `out_dir`: steps.csv (one row per converged step, written
  /// as it converges), rod/contact VTK files (+ .pvd collections) as requested, summary.json
  /// at the end, whatever the outcome. Non-convergence is reported in result.solver.status.
  AnalysisResult run(std::ostream* log = nullptr, const std::string& out_dir = {});

  /// ParaView files of the state (u, t): <dir>/<stem>_rod.vtk (centre line with axial force
  /// and curvature) and, with contact, <dir>/<stem>_contact.vtk (active points with N, T, B
  /// (68)-(70), slip). Returns the file names written (relative to dir).
  std::vector<std::string> write_vtk(const std::string& dir, const std::string& stem,
                                     const VectorXd& u, double t);

  /// Reactions (f_int - f_ext + contact, Cartesian) at the output's reaction points.
  std::vector<Vector3d> reactions(const VectorXd& u, double t);

 private:
  Analysis() = default;
  std::string name_;
  GeometryModel geometry_;
  std::unique_ptr<RodProblem> problem_;
  RodContactProblem* contact_ = nullptr;
  NonlinearSolverSettings settings_;
  AnalysisOutput output_;
  double stop_full_slip_after_ = -1.0;
};

/// --set /json/pointer=value for the apps: the value is JSON text (a number, "string", [list]);
/// the pointer must name an existing entry, so that a typo is an error rather than a silently
/// ignored key. Throws ModelError / std::invalid_argument.
void apply_override(Json& doc, const std::string& file, const std::string& assignment);

}  // namespace iga
