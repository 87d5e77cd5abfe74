// A whole analysis from a model file (docs/model_format.md, "Analysis sections"): the body (a
// Kirchhoff rod on a curve, or a Kirchhoff-Love shell on a surface of the geometry section),
// its material, boundary conditions and springs, loads along load curves, contact with a rigid
// surface of the geometry section (CTRS for rods, [KS15] Sects. 4-5; STAS for shells, Sects.
// 2-3), solver settings and output requests; run() drives the nonlinear solver and writes the
// results (CSV per step, ParaView files, a JSON summary).
// Every input error is a ModelError naming the file, the JSON path and the value.
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"
#include "iga/contact_integrals/rod_contact_problem.hpp"
#include "iga/contact_integrals/shell_contact_problem.hpp"
#include "iga/solvers/nonlinear_solver.hpp"

namespace iga {

enum class BodyKind { kRod, kShell };

/// A point of the body whose displacement is recorded per step ("output": "monitors").
struct AnalysisMonitor {
  std::string name;
  double u = 0.0;  ///< rod: the curve parameter; shell: the surface parameters (u, v)
  double v = 0.0;
};

/// Output requests of the "output" section.
struct AnalysisOutput {
  enum class Vtk { kNone, kLast, kAll };
  Vtk vtk = Vtk::kLast;                   ///< ParaView files: none, the last step, every step
  std::vector<int> reactions;             ///< control points whose reactions go to steps.csv
  std::vector<AnalysisMonitor> monitors;  ///< displacements that go to steps.csv
  /// Points per element (per direction for shells) in the VTK files; 0: 16 for rods, 4 for
  /// shells.
  int samples_per_element = 0;
};

/// Contact point counts of the contact pair at a converged step.
struct ContactCounts {
  int active = 0, stick = 0, slip = 0;
  double drag_ratio = 0.0;  ///< rods: friction across / along the rope (CurveContactCounts)
  int slip_back = 0;        ///< rods: slipping points pulling the other way than the most
};

/// One converged step as recorded by Analysis::run.
struct AnalysisStep {
  double t = 0.0;
  int iterations = 0;
  ContactCounts contact;
  std::vector<Vector3d> reactions;      ///< at AnalysisOutput::reactions, Cartesian
  std::vector<Vector3d> displacements;  ///< at AnalysisOutput::monitors
};

/// Called by Analysis::run after each converged step (after the step's row is written); return
/// false to stop the run.
using AnalysisStepCallback =
    std::function<bool(const VectorXd& u, double t, const AnalysisStep& step)>;

struct AnalysisResult {
  NonlinearSolverResult solver;
  std::vector<AnalysisStep> steps;
  VectorXd u;                 ///< state at the last converged step (time solver.t)
  bool full_slip = false;     ///< the run stopped at the onset of full slip
  double contact_time = 0.0;  ///< seconds in the contact integral (part of the assembly)
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
  BodyKind body_kind() const { return kind_; }
  const std::string& body_name() const { return body_; }
  ControlPointProblem& problem() { return *problem_; }
  /// The rod (shell) problem; std::logic_error if the body is a shell (rod).
  RodProblem& rod_problem();
  ShellProblem& shell_problem();
  /// The rod problem with contact, or nullptr if the body is a shell or has no contact.
  RodContactProblem* contact_problem() { return rod_contact_; }
  /// The shell problem with contact, or nullptr if the body is a rod or has no contact.
  ShellContactProblem* shell_contact_problem() { return shell_contact_; }
  bool has_contact() const { return rod_contact_ != nullptr || shell_contact_ != nullptr; }
  /// Contact point counts of the last assembly (zeros without contact).
  ContactCounts contact_counts() const;
  /// Coulomb coefficient of the contact pair (0 without contact).
  double contact_mu() const;
  /// Seconds spent in the contact integral so far (0 without contact).
  double contact_time() const;
  /// The named load curves of the model, in the file's order (steps.csv has a column for each).
  const std::vector<std::pair<std::string, LoadCurve>>& load_curves() const { return curves_; }
  /// One line: the body (elements, degree, control points), unknowns, contact (pieces, points,
  /// strategy), the pseudo-time span.
  std::string describe() const;
  /// Displacement of the monitored point at the state (u, t).
  Vector3d displacement(const AnalysisMonitor& m, const VectorXd& u, double t) const;
  const NonlinearSolverSettings& solver_settings() const { return settings_; }
  NonlinearSolverSettings& solver_settings() { return settings_; }
  const AnalysisOutput& output() const { return output_; }
  /// Pseudo-time after which the run stops once `full_slip_steps` consecutive steps slide
  /// steadily (steady_sliding, curve_contact.hpp: every active point slips, all pulling one
  /// way, friction along the rope) (< 0: off). "solver": {"stop_at_full_slip_after": t,
  /// "full_slip_steps": n (1)}.
  double stop_at_full_slip_after() const { return stop_full_slip_after_; }
  int full_slip_steps() const { return full_slip_steps_; }

  /// Runs from the reference state over [settings.t0, settings.t1]. Progress lines go to `log`
  /// (may be null). With a non-empty `out_dir`: steps.csv (one row per converged step, written
  /// as it converges), rod/contact VTK files (+ .pvd collections) as requested, summary.json
  /// at the end, whatever the outcome. Non-convergence is reported in result.solver.status;
  /// an error during the run (writing a step's output or the last ParaView files, the problem's
  /// history update, `on_step` throwing) ends it with status `failed` and the error in
  /// result.solver.message, the state and rows of the converged steps kept. Numbers that are
  /// not finite never reach the files (empty CSV cells, JSON null, VTK flag non_finite).
  /// `on_step` (optional) is called after each converged step.
  AnalysisResult run(std::ostream* log = nullptr, const std::string& out_dir = {},
                     const AnalysisStepCallback& on_step = {});

  /// ParaView files of the state (u, t): for a rod <dir>/<stem>_rod.vtk (centre line with
  /// axial force and curvature), for a shell <dir>/<stem>_shell.vtk (the sampled surface with
  /// displacement, normal, membrane forces and moments in a local Cartesian frame) and, with
  /// contact, <dir>/<stem>_contact.vtk (active points: rods N, T, B (68)-(70), slip; shells
  /// N (34), gap, tangential force, slip). Returns the file names written (relative to dir).
  std::vector<std::string> write_vtk(const std::string& dir, const std::string& stem,
                                     const VectorXd& u, double t);

  /// The rigid surface of the contact pair sampled as quadrilaterals (<dir>/<stem>.vtk, pieces
  /// with an unbounded domain are left out); false (nothing written) without contact.
  bool write_rigid_vtk(const std::string& dir, const std::string& stem) const;

  /// Reactions (f_int - f_ext + contact, Cartesian) at the output's reaction points.
  std::vector<Vector3d> reactions(const VectorXd& u, double t);

 private:
  Analysis() = default;
  std::string name_;
  GeometryModel geometry_;
  BodyKind kind_ = BodyKind::kRod;
  std::string body_;
  std::unique_ptr<ControlPointProblem> problem_;
  RodProblem* rod_ = nullptr;
  ShellProblem* shell_ = nullptr;
  RodContactProblem* rod_contact_ = nullptr;
  ShellContactProblem* shell_contact_ = nullptr;
  std::shared_ptr<const RigidSurface> rigid_;
  std::vector<std::pair<std::string, LoadCurve>> curves_;
  NonlinearSolverSettings settings_;
  AnalysisOutput output_;
  double stop_full_slip_after_ = -1.0;
  int full_slip_steps_ = 1;
};

/// --set /json/pointer=value for the apps: the value is JSON text (a number, "string", [list]).
/// The pointer names an existing entry (replaced) or a new key of an existing object (added);
/// a typo in a key is then rejected by the loader's own validation ("unknown key"), with the
/// allowed keys. Throws ModelError naming the pointer for a malformed assignment or pointer
/// (RFC 6901: "/a/b", "~0" for '~', "~1" for '/') and for a pointer whose parent is missing or
/// is not an object.
void apply_override(Json& doc, const std::string& file, const std::string& assignment);

/// A JSON pointer given as a string at `c` (e.g. an app section's "/contact/0/mu") that names an
/// existing entry of `doc`; ModelError at c otherwise.
JsonPointer model_pointer(const JsonCursor& c, const Json& doc);

}  // namespace iga
