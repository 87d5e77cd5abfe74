// A whole analysis from a model file (docs/model_format.md, "Analysis sections"): the bodies
// (Kirchhoff rods on curves, Kirchhoff-Love shells on surfaces of the geometry section; Body),
// their materials, boundary conditions and springs, loads along load curves, contact pairs of a
// body with a rigid surface of the geometry section (CTRS for rods, [KS15] Sects. 4-5; STAS for
// shells, Sects. 2-3; ContactPair), solver settings and output requests; run() drives the
// nonlinear solver over all bodies (BodySystem) and writes the results (CSV per step, ParaView
// files, a JSON summary). The driver sees bodies and pairs only through their interfaces; a
// model holds any number of bodies and pairs (pairs naming one rigid surface share it).
//
// Notation: u the unknowns of all bodies, u_b the block of body b (BodySystem); t pseudo-time.
// Every input error is a ModelError naming the file, the JSON path and the value.
#pragma once

#include <array>
#include <functional>
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"
#include "iga/core/body_system.hpp"
#include "iga/core/state_archive.hpp"
#include "iga/output/output_sink.hpp"
#include "iga/solvers/nonlinear_solver.hpp"

namespace iga {

/// A point of the body whose displacement is recorded per step ("output": "monitors").
struct AnalysisMonitor {
  std::string name;
  double u = 0.0;  ///< rod: the curve parameter; shell: the surface parameters (u, v)
  double v = 0.0;
  int body = 0;  ///< index of the body in the model
};

/// A control point whose reaction is recorded per step ("output": "reactions").
struct AnalysisReaction {
  int point = 0;
  int body = 0;  ///< index of the body in the model
};

/// Output requests of the "output" section.
struct AnalysisOutput {
  enum class Vtk { kNone, kLast, kAll };
  Vtk vtk = Vtk::kLast;  ///< ParaView files: none, the last step, every step
  /// The format of the field series (a registered output format, iga/output/output_sink.hpp):
  /// "vtk_xml" (.vts/.vtu, the default) or "vtk" (legacy .vtk).
  std::string field_format = "vtk_xml";
  std::vector<AnalysisReaction> reactions;  ///< control points whose reactions go to steps.csv
  std::vector<AnalysisMonitor> monitors;    ///< displacements that go to steps.csv
  /// Points per element (per direction for shells) in the VTK files; 0: each body's default
  /// (16 for rods, 4 for shells).
  int samples_per_element = 0;
  /// Figures of steps.csv columns that `iga run` draws after the run (scripts/plot_steps.py):
  /// x and y are terms "[factor*]column" (y: several separated by ';'), file a PNG name;
  /// reference: published points drawn as markers beside the curves (in the plot's units).
  struct Reference {
    std::string label;
    std::vector<std::array<double, 2>> points;
  };
  struct Plot {
    std::string x, y, file, title;
    std::vector<Reference> reference;
  };
  std::vector<Plot> plots;
  /// A restart file (restart.bin in the output folder) every this many converged steps
  /// (0: none on the way); one is always written when the run stops before t1 (the state of
  /// its last converged step). Analysis::run with `restart_file` continues from one.
  int restart_every = 0;
};

/// One converged step as recorded by Analysis::run.
struct AnalysisStep {
  int step = 0;  ///< its number in steps.csv (a restart's earlier steps counted)
  double t = 0.0;
  int iterations = 0;
  ContactCounts contact;             ///< summed over the pairs
  std::vector<ContactCounts> pairs;  ///< each pair's, in the model's order
  /// Each pair's force on its tool and the moment about the pair's moment point (world frame).
  std::vector<std::pair<Vector3d, Vector3d>> tool_loads;
  std::vector<Vector3d> reactions;      ///< at AnalysisOutput::reactions, Cartesian
  std::vector<Vector3d> displacements;  ///< at AnalysisOutput::monitors
};

/// A limit point of the load along the path (arc length): a converged step at which the load
/// factor t stops rising (a maximum) or falling (a minimum). It is the extreme of the sampled
/// states; the path's own limit lies between the neighbouring steps.
struct LoadLimitPoint {
  std::size_t index = 0;  ///< into the steps
  bool maximum = true;
};

/// The limit points of the load among `steps`, in path order (steps at the same t as the one
/// before are passed over). Analysis::run logs each when the step after it converges and
/// summary.json lists them with the monitors' displacements.
std::vector<LoadLimitPoint> load_limit_points(const std::vector<AnalysisStep>& steps);

/// The restart file of process `rank` of a run whose restart file is `path` (a run over several
/// processes writes one file per process): `path` for process 0, `path`.<rank> for the others.
std::string restart_file_of(const std::string& path, int rank);

/// Called by Analysis::run after each converged step (after the step's row is written); return
/// false to stop the run.
using AnalysisStepCallback =
    std::function<bool(const VectorXd& u, double t, const AnalysisStep& step)>;

struct AnalysisResult {
  NonlinearSolverResult solver;
  std::vector<AnalysisStep> steps;
  VectorXd u;                 ///< state at the last converged step (time solver.t)
  bool full_slip = false;     ///< the run stopped at the onset of full slip
  double contact_time = 0.0;  ///< seconds in the contact integrals (part of the assembly)
  /// The last restart file written (empty: none); over several processes the name of process
  /// 0's, which a restart is given (restart_file_of names the others').
  std::string restart_file;
};

class Analysis {
 public:
  /// Builds the analysis of a parsed model document (the whole file, "format"
  /// "iga-contact-model"); `file` names it in messages. Throws ModelError. Spread over the
  /// processes of `comm` (world(), under mpirun; it must outlive the analysis): every process
  /// reads the whole model and builds every body and tool, shells cut into blocks of elements
  /// (one per process) and the other bodies whole on one process each, balanced by control
  /// points (iga/core/partition.hpp, docs/parallel.md). A shell that cannot be cut into as
  /// many blocks, or exact enforcement on a cut shell, is a ModelError. Over several processes
  /// every process throws the same error (the first failing process's) or none does.
  static Analysis from_json(const Json& doc, const std::string& file,
                            const Communicator& comm = serial_communicator());
  /// read_json_file + from_json.
  static Analysis load(const std::string& path, const Communicator& comm = serial_communicator());
  /// The processes the analysis is spread over.
  const Communicator& communicator() const { return system_->communicator(); }

  const std::string& name() const { return name_; }
  const GeometryModel& geometry() const { return geometry_; }
  // ---- bodies and pairs -------------------------------------------------------------------------
  int num_bodies() const { return system_->num_bodies(); }
  Body& body(int b) { return system_->body(b); }
  const Body& body(int b) const { return system_->body(b); }
  const std::string& body_name(int b = 0) const {
    return body_names_.at(static_cast<std::size_t>(b));
  }
  int num_pairs() const { return static_cast<int>(pairs_.size()); }
  const ContactPair& pair(int k) const { return *pairs_.at(static_cast<std::size_t>(k)).pair; }
  /// The body of pair k.
  int pair_body(int k) const { return pairs_.at(static_cast<std::size_t>(k)).body; }
  /// The force pair k exerts on its tool and its moment about the pair's moment point, at the
  /// last assembly (world frame; steps.csv: <name>_Fx .. _Mz).
  std::pair<Vector3d, Vector3d> tool_load(int k) const;
  /// The name of pair k ("name" in the model; default "contact", or "contact_<k>" with several):
  /// its columns in steps.csv are <name>_active, _stick, _slip (with several pairs).
  const std::string& pair_name(int k) const { return pairs_.at(static_cast<std::size_t>(k)).name; }
  /// All bodies as one problem (the solver's).
  BodySystem& problem() { return *system_; }

  // ---- bodies and pairs as their types (for programs and tests that know their model) --------
  /// Body b as the type T the model built (e.g. RodProblem, ShellProblem; the caller includes
  /// its header); std::logic_error naming the body if it is not a T.
  template <class T>
  T& body_as(int b = 0) {
    auto* p = dynamic_cast<T*>(&body(b));
    if (p == nullptr)
      throw std::logic_error("Analysis::body_as: body \"" + body_name(b) + "\" (type \"" +
                             body(b).type() + "\") is not of the type asked for");
    return *p;
  }
  /// Pair k as the type T (e.g. CurveContactPair, SurfaceContactPair), or nullptr if there is no
  /// pair k or it is not a T.
  template <class T>
  T* pair_as(int k = 0) {
    if (k < 0 || k >= num_pairs()) return nullptr;
    return dynamic_cast<T*>(pairs_[static_cast<std::size_t>(k)].pair);
  }

  bool has_contact() const { return !pairs_.empty(); }
  /// Contact point counts of the last assembly, summed over the pairs (zeros without contact).
  ContactCounts contact_counts() const;
  /// Seconds spent in the contact integrals so far (0 without contact).
  double contact_time() const;
  /// The named load curves of the model, in the file's order (steps.csv has a column for each).
  const std::vector<std::pair<std::string, LoadCurve>>& load_curves() const { return curves_; }
  /// One line: the body (elements, degree, control points), unknowns, contact (pieces, points,
  /// strategy), the pseudo-time span.
  std::string describe() const;
  /// Displacement of the monitored point at the state (u, t) of all bodies.
  Vector3d displacement(const AnalysisMonitor& m, const VectorXd& u, double t) const;
  const NonlinearSolverSettings& solver_settings() const { return settings_; }
  NonlinearSolverSettings& solver_settings() { return settings_; }
  const AnalysisOutput& output() const { return output_; }
  /// The columns of steps.csv, in order.
  std::vector<std::string> csv_columns() const;
  /// The values of steps.csv's row for step `st` with 1-based number `index`, in the order of
  /// csv_columns() (counts as whole numbers; the CSV prints them with 12 digits).
  std::vector<double> step_values(int index, const AnalysisStep& st) const;
  /// The stop criterion of a sliding plateau, selected by the model: the pseudo-time after which
  /// the run stops once `full_slip_steps` consecutive steps slide steadily (every pair in
  /// contact by its own rule, ContactPair::sliding_steadily: a rope's every active point slips,
  /// all pulling one way, friction along the rope; elsewhere every active point slips)
  /// (< 0: off). "solver": {"stop_at_full_slip_after": t, "full_slip_steps": n (1)}.
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
  /// Restart: with output.restart_every = N the run writes <out_dir>/restart.bin every N
  /// converged steps, and always when it stops before t1 (min_step, max_steps, an error: the
  /// state of its last converged step): the solver's state (time, step size, arc-length
  /// state), u, every body's history (a rod's triads and twists, the contact points' history,
  /// multipliers, active sets and last feet), the rows of steps.csv and the ParaView series
  /// so far. `restart_file` (non-empty) continues such a run: steps.csv starts with the rows
  /// written before, step numbers and series go on, and with the same settings every later
  /// step is that of the uninterrupted run. Solver settings may change between the runs (e.g.
  /// min_step, max_steps, t1); the model itself must not (a restart file of another model,
  /// other unknowns, pairs or contact points, another path control or other steps.csv
  /// columns, is refused: RestartError naming the file and what differs).
  AnalysisResult run(std::ostream* log = nullptr, const std::string& out_dir = {},
                     const AnalysisStepCallback& on_step = {},
                     const std::string& restart_file = {});

  /// A file written by write_output and the ParaView series (.pvd) it belongs to (empty: none).
  struct OutputFile {
    std::string series, file;
  };
  /// The meshes of the state (u, t) that the field series take, in this order: each body
  /// sampled with its fields and its pairs' (Body::sample; <stem>_<type> for one body,
  /// <stem>_<name> for several: a rod's centre line with axial force and curvature, a shell's
  /// surface with displacement, normal, membrane forces and moments in a local Cartesian
  /// frame); then per contact pair (suffix _<k> with several) its active points
  /// (<stem>_contact: rods N, T, B (68)-(70), slip; shells N (34), gap, tangential force, slip),
  /// the same seen from the tool (<stem>_tool_contact) and the contact fields on a grid of each
  /// bounded piece of the tool (<stem>_tool, or _tool_<i> per piece); then each moving tool
  /// where it is at t (<stem>_rigid...).
  /// Over several processes every process takes part: with `pieces`, each returns its pieces
  /// of the bodies' and contact meshes (MeshOutput::pieces; process 0 also the tool grids,
  /// whose fields are combined over the processes, and the moving tools); without, process 0
  /// gathers the parts and returns the whole meshes, the others none.
  std::vector<MeshOutput> output_meshes(const std::string& stem, const VectorXd& u, double t,
                                        bool pieces = false);
  /// output_meshes written into dir in the field format of the output section
  /// (output().field_format: .vts/.vtu by default, .vtk for "vtk"). File names are relative to
  /// dir.
  std::vector<OutputFile> write_output(const std::string& dir, const std::string& stem,
                                       const VectorXd& u, double t);
  /// The file names of write_output.
  std::vector<std::string> write_vtk(const std::string& dir, const std::string& stem,
                                     const VectorXd& u, double t);

  /// Each rigid tool (a rigid surface some pair names; pairs naming one tool share it) sampled
  /// as quadrilaterals in the field format (<dir>/<stem>.vts, or <stem>_<i> per piece,
  /// <stem>_<j>... per tool with several, in the order the pairs name them; pieces with an
  /// unbounded domain are left out); false (nothing written) without contact.
  bool write_rigid_vtk(const std::string& dir, const std::string& stem) const;

  /// A rigid tool: a rigid surface named by pairs (the first of them given).
  struct Tool {
    std::string name;
    const ContactPair* pair;
  };
  /// The distinct tools of the pairs, in the order the pairs name them.
  std::vector<Tool> tools() const;

  /// Reactions (f_int - f_ext + contact, Cartesian) at the output's reaction points; in a
  /// linear analysis (solver "analysis": "linear") those of linear theory, r(0) + K_0 u.
  std::vector<Vector3d> reactions(const VectorXd& u, double t);
  /// The diagonal of the bodies' bounding box at the start (the scale of the linear
  /// analysis's reactions; 1 for a point-like model).
  double model_size();

 private:
  Analysis() = default;
  /// from_json's work on this process (from_json agrees on errors over the processes).
  static Analysis build(const Json& doc, const std::string& file, const Communicator& comm);
  /// Whether every pair in contact slides steadily (ContactPair::sliding_steadily) and some pair
  /// is in contact.
  bool sliding_steadily() const;
  /// After a converged step at t: counts the consecutive steps of steady sliding past
  /// stop_at_full_slip_after (sliding_steps) and tells whether they complete the plateau.
  bool plateau_complete(double t, int& sliding_steps) const;
  /// What a restart of run() needs besides the bodies' state and the sinks' (their rows and
  /// series so far).
  struct RunState {
    SolverCheckpoint solver;
    VectorXd u;             ///< the converged state
    int steps = 0;          ///< converged steps (rows of steps.csv)
    int sliding_steps = 0;  ///< consecutive steps of steady sliding (plateau_complete)
  };
  /// The output side of one run (analysis.cpp).
  struct RunContext;
  /// Writes the run's state, the sinks' and the bodies' to a restart archive, or reads them
  /// back (StateArchive; checks that the file is of this model).
  void archive_run(StateArchive& a, RunState& s,
                   const std::vector<std::unique_ptr<OutputSink>>& sinks);
  /// The run's state from the restart file `file` (this process's: restart_file_of), through
  /// archive_run; RestartError on every process when one cannot read its own.
  void read_restart(const std::string& file, RunState& s,
                    const std::vector<std::unique_ptr<OutputSink>>& sinks);
  /// The record of a converged step at (u, t): counts, reactions, monitored displacements.
  AnalysisStep record_step(const VectorXd& u, double t, int iterations);
  /// The bodies' reactions r(u, t) at the output's reaction points, summed over the processes.
  std::vector<Vector3d> body_reactions(const VectorXd& u, double t);
  /// The load factor lambda of time t: (t - t0) / (t1 - t0) (steps.csv, summary.json).
  double load_factor(double t) const { return (t - settings_.t0) / (settings_.t1 - settings_.t0); }
  /// The summary of a run (summary.json).
  Json summary(const AnalysisResult& res) const;
  /// Each tool (moving_only: each moving tool) at its pose at t, as write_rigid_vtk: the meshes
  /// and their series "rigid[_j][_i]".
  std::vector<MeshOutput> tool_meshes(const std::string& stem, double t, bool moving_only) const;
  /// The pairs of the "contact" section in the file's order, with their names (after the bodies
  /// are built, each holding its own pairs).
  void collect_pairs(const JsonCursor& root);
  struct PairRef {
    ContactPair* pair = nullptr;  ///< owned by its body
    int body = 0;
    std::string name, rigid;  ///< the pair's and its rigid surface's name in the model
    /// The point of the tool (in its own frame) about which the moment on it is reported
    /// ("moment_about"; default the rotation point of a rotating tool, else the origin).
    Vector3d moment_about = Vector3d::Zero();
  };
  std::string name_;
  GeometryModel geometry_;
  std::vector<std::unique_ptr<Body>> bodies_;
  std::vector<std::string> body_names_;
  std::vector<PairRef> pairs_;
  std::unique_ptr<BodySystem> system_;  ///< on the heap: it points to the bodies
  std::vector<std::pair<std::string, LoadCurve>> curves_;
  NonlinearSolverSettings settings_;
  double model_size_ = 0.0;  ///< model_size() once computed
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
