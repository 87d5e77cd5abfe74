// Static load stepping in pseudo-time t in [t0, t1] with Newton-Raphson on the consistent tangent
// (a consistent tangent gives quadratic convergence, [KS15] as restated in EQUATIONS.md Sect. 3),
// adaptive steps (growth on easy steps, cutback on divergence), residual and energy convergence
// tests, a progress line per step, timings of assembly and linear solves. Non-convergence is a
// status, never an exception.
// Arc length (PathControl::arc_length): [Cri81] M. A. Crisfield, A fast incremental/iterative
// solution procedure that handles "snap-through", Computers & Structures 13 (1981) 55-62: the
// cylindrical constraint |Delta u| = Delta l on the step's increment, the load increment from
// its quadratic equation in each iteration, the root nearest to the previous increment; the
// predictor's sign from the previous step's increment (the angle criterion, as in Feng, Peric &
// Owen, CMAME 137, 1996). dR/dt by a one-sided difference in t (exact for loads and prescribed
// values linear in t, the model's load curves between their points).
// References: [KS15] see ../shared/paper/EQUATIONS.md; [Wri08] P. Wriggers, Nonlinear Finite
// Element Methods, Springer 2008 (Newton-Raphson, load stepping); the energy test as in FEAP
// (R. L. Taylor): |du . R| relative to its value in the first iteration of the step.
//
// Notation (code -> meaning): R_k = R(u_k, t), the residual after k Newton corrections of the
// step; du_k = -K(u_{k-1})^-1 R_{k-1}; E_k = |du_k . R_{k-1}| the energy norm of correction k;
// lambda = (t - t0) / (t1 - t0), the fraction of the pseudo-time span done (the load factor of
// linear load curves). Arc length: Delta u = u - u_n, Delta t = t - t_n the step's increments
// from the converged (u_n, t_n); du_t = -K^-1 dR/dt the tangent solution; du_R = -K^-1 R;
// Delta l the arc length.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "iga/core/nonlinear_problem.hpp"
#include "iga/solvers/linear_solver.hpp"

namespace iga {

/// How the steps advance along the equilibrium path.
enum class PathControl {
  load,        ///< t advances by dt each step (load control, or displacement control when t
               ///< drives prescribed displacements); stops at a limit point of t
  arc_length,  ///< t is an unknown of each step, the step's length is measured in u: Crisfield's
               ///< cylindrical arc length [Cri81], through limit points and snap-backs
};

/// What each step solves (NonlinearSolverSettings::analysis).
enum class AnalysisKind {
  nonlinear,  ///< Newton-Raphson on every step
  /// Small displacements: u(t) = u_0 - K_0^-1 R(u_0, t), with u_0 the start state and K_0 the
  /// tangent of the first step's assembly at u_0, factorized once for the run. Per step one
  /// assembly and one solve: the first step's assembly gives R and K_0, each later step's
  /// R(u_0, t) alone. No Newton and no residual test: the solution of the linearized
  /// problem (linear theory wherever the bodies' response at u_0 is linear in u).
  linear,
  /// The linear path while it is exact to the residual test: each step's u as for `linear`,
  /// then R(u, t) assembled without the tangent; the step is accepted when it passes the
  /// residual test of a Newton iteration (|R| <= tol_residual_rel |R(u_0, t)| or the absolute
  /// test), so the state is Newton's to its tolerance. The first step that does not pass goes
  /// on with Newton from the linear state (the linear solve was Newton's first correction),
  /// and so does the rest of the run. A nonlinear run pays one residual assembly for the test.
  certified,
};

/// Step control and convergence tests. validate() names the offending field.
struct NonlinearSolverSettings {
  /// Newton on every step (default), the linear path, or the linear path while certified
  /// (AnalysisKind). The linear paths take steps of initial_step (landing on hit_times and t1),
  /// need load control (arc length follows a nonlinear path) and do not resume a restart
  /// (a resumed run is solved by Newton).
  AnalysisKind analysis = AnalysisKind::nonlinear;
  /// Load control (default) or arc length. With arc length the sizes below keep their meaning
  /// in units of t for the first step: the arc length is Delta l_0 = initial_step |du_t| (du_t
  /// the tangent solution K du_t = -dR/dt at the start), and min_step, max_step bound it as
  /// Delta l_0 min_step / initial_step and Delta l_0 max_step / initial_step.
  PathControl control = PathControl::load;
  /// Arc length: after a converged step of N iterations the next arc length is
  /// Delta l sqrt(desired_iterations / N) [Cri81], the factor within [cutback_factor,
  /// growth_factor].
  int desired_iterations = 5;
  /// Arc length: a converged step whose increment turns by more than this angle (degrees) from
  /// its predictor (the tangent) is refused and its arc length cut back, unless the arc is at
  /// its minimum: a large turn means the arc is long against the path's curvature, where the
  /// corrector can land on another branch of the path (and then turn back along it). 180: off.
  /// The default: the 16 x 16 pinched cylinder (data/pinched_cylinder_nonlinear.json) loops
  /// between its folds with 30 or 45 and reaches P_max with 20; 24 x 24 to 40 x 40 follow the
  /// same path with 20 and 45 (24 x 24: 278 steps instead of 208; 40 x 40: 51 either way).
  double max_turn_deg = 20.0;
  /// Arc length: dR/dt from the loads alone where the problem gives it
  /// (NonlinearProblem::load_rate), else by an assembly at t + h; false: always by the
  /// assembly (not a model key: for comparing the two in tests and bench_arc_length).
  bool rate_from_loads = true;
  double t0 = 0.0;  ///< start of the pseudo-time span (u is converged there)
  /// End of the span. With arc length the run ends when the path reaches t1 (the step that
  /// crosses it is repeated under load control to land on t1); t may go down and up before.
  double t1 = 1.0;
  double initial_step = 0.1;  ///< first step size in t
  double min_step = 1e-6;     ///< a failed step of this size ends the run (min_step_reached)
  double max_step = 1.0;      ///< steps never grow beyond this
  int max_steps = 100000;     ///< limit on attempted steps (converged and failed)
  int max_iterations = 20;    ///< Newton iterations per step before a cutback
  /// Residual test: |R_k| <= tol_residual_rel |R_0| or |R_k| <= max(tol_residual_abs,
  /// tol_residual_scaled F), where F is the run's force scale: the largest |R_0| of its steps
  /// so far (the load or reaction increments, in the problem's units). The scaled part makes
  /// the test independent of units (round-off in R grows with the forces); tol_residual_abs is
  /// the floor for unloaded starts (F = 0).
  double tol_residual_rel = 1e-8;
  double tol_residual_abs = 1e-12;
  double tol_residual_scaled = 1e-10;
  /// Energy test: E_k <= tol_energy_rel E_1 or E_k <= tol_energy_abs; both <= 0: the test is
  /// off. E_k measures the correction already applied, one iteration behind |R_k|: with
  /// quadratic convergence E_k / E_1 is of the order of |R_k| / |R_0| (often 10-100 times
  /// larger), so a tight energy tolerance costs an extra iteration per step. The default guards
  /// against a small residual after a large last correction (soft modes) without that cost.
  /// A step has converged when the residual test and the energy test hold; a step whose |R_0|
  /// already meets the absolute residual test is converged with 0 iterations.
  double tol_energy_rel = 1e-6;
  double tol_energy_abs = 0.0;
  int easy_iterations = 4;      ///< a step converged in <= this many iterations grows the next
  double growth_factor = 1.5;   ///< dt <- min(growth_factor dt, max_step) after an easy step
  double cutback_factor = 0.5;  ///< dt <- max(cutback_factor dt, min_step) after a failure
  /// Divergence: |R_k| > divergence_ratio max |R_0| (the largest |R_0| of the run's steps so
  /// far: a step cut back to a small dt keeps the run's force scale), or the residual grew in
  /// max_residual_increases consecutive iterations (0: that check is off).
  double divergence_ratio = 1e4;
  int max_residual_increases = 3;
  /// Times inside (t0, t1) that steps land on exactly (output times of an application, e.g.
  /// the snapshots of a load history): a step that would pass one ends there instead; the
  /// step size itself is kept for the step after. Any order; must be finite.
  std::vector<double> hit_times;
  /// Start of a step's Newton iteration: false, the last converged u (the prescribed values
  /// jump, the rest follows in the first iteration); true, the secant extrapolation of the
  /// last two converged states, u_n + (dt / dt_prev) (u_n - u_prev) (from the second step on):
  /// a body carried by a moving tool or anchor then starts where its motion takes it.
  bool secant_predictor = false;
  /// The library of the linear solves (LinearSolver::set_method): SuiteSparse (default), or
  /// PETSc's MUMPS or Krylov solvers (a build with PETSc).
  LinearMethod linear_method = LinearMethod::suitesparse;

  /// Throws std::invalid_argument naming the field, e.g. "NonlinearSolverSettings.min_step:
  /// must be > 0, got 0".
  void validate() const;
};

/// How one Newton iteration sequence (one attempted step) ended.
enum class NewtonOutcome {
  converged,
  diverged,             ///< residual growth (ratio to |R_0| or consecutive increases)
  not_finite,           ///< NaN or Inf in the residual or the correction
  max_iterations,       ///< no convergence within max_iterations
  linear_solve_failed,  ///< singular tangent or non-finite entries in it
  assembly_failed,      ///< the problem threw while assembling (e.g. a non-finite state met by
                        ///< the contact search); the step is cut back like any other failure
  augmentation_failed,  ///< Newton converged but NonlinearProblem::augment found the constraints
                        ///< still violated after its allowed multiplier updates; cut back
  landing_failed,       ///< arc length: the step crossed t1 or a hit time and the solve at that t
                        ///< failed; cut back (at the minimum arc length the arc state is kept)
  passed_through,       ///< Newton converged but a contact point went through a rigid surface in
                        ///< the step (NonlinearProblem::augment, penalty or exact); cut back
  probe_refused,        ///< tests only: converged, refused by the round-off probe
                        ///< (IGA_ROUNDOFF_PROBE, roundoff_probe.hpp) as round-off on another
                        ///< processor may refuse a step at the edge of convergence; cut back
};

/// How the whole run ended.
enum class NonlinearSolverStatus {
  converged,          ///< t1 reached
  min_step_reached,   ///< a step of size min_step failed; u is the state at result.t
  max_steps_reached,  ///< settings.max_steps attempts; u is the state at result.t
  stopped,            ///< the step callback asked to stop; u is the state at result.t
  failed,             ///< an error ended the run (set by callers such as Analysis::run when
                      ///< writing a converged step's output fails); u is the state at result.t
};

const char* to_string(NewtonOutcome o);
const char* to_string(NonlinearSolverStatus s);
const char* to_string(PathControl c);
const char* to_string(AnalysisKind k);

/// Load control: a converged step whose increment exceeds this many times the tangent's
/// prediction is reported as a probable jump over a limit point (StepAttempt::jump_ratio).
inline constexpr double kJumpRatio = 10.0;

/// One attempted step, converged or not, with the history of its Newton iterations.
struct StepAttempt {
  int step = 0;          ///< number of the step it tries to complete (1 + converged steps before)
  double t_start = 0.0;  ///< last converged time
  double t = 0.0;        ///< target time of the step
  double dt = 0.0;       ///< t - t_start
  NewtonOutcome outcome = NewtonOutcome::max_iterations;
  int iterations = 0;       ///< Newton corrections computed (linear solves), the
                            ///< re-solves after multiplier updates included
  int augmentations = 0;    ///< multiplier updates (re-solves) of the step
  double arc_length = 0.0;  ///< arc length Delta l of the step (0 under load control)
  bool linear = false;      ///< solved by the linear path (AnalysisKind), accepted
  bool landed = false;      ///< arc length: the step was repeated under load control to land
                            ///< on t1 or a hit time it crossed
  /// Arc length: the angle (degrees) between the converged increment Delta u and the step's
  /// predictor, the tangent (0 under load control).
  double turn_deg = 0.0;
  std::vector<double> residual_norms;  ///< |R_0|, |R_1|, ..., |R_iterations| (2-norms); after
                                       ///< an augmentation the re-solve's |R_0|, |R_1|, ...
  std::vector<double> energy_norms;    ///< E_1, ..., E_iterations
  int cholmod_factorizations = 0;      ///< factorizations that succeeded with CHOLMOD LL^T
  int ldlt_factorizations = 0;         ///< ... with CHOLMOD LDL^T (symmetric indefinite)
  int umfpack_factorizations = 0;      ///< ... with UMFPACK (incl. fallbacks)
  int petsc_factorizations = 0;        ///< ... with PETSc (MUMPS or a Krylov preconditioner)
  int cholesky_fallbacks = 0;          ///< LL^T attempts that failed (then LDL^T or UMFPACK)
  /// Load control: |du_1|, the first Newton correction of the step (the tangent's prediction
  /// of its increment, after the secant predictor if any: then the larger of the two).
  double predicted = 0.0;
  /// Load control: |u - u_start| of the converged step over `predicted`. A step that lands far
  /// beyond the tangent's prediction (more than kJumpRatio times) has likely jumped over a
  /// limit point to another branch of the path (snap-through); it is logged as a warning.
  double jump_ratio = 0.0;
  std::string message;  ///< why it failed (empty if converged)
};

/// The outcome of NonlinearSolver::solve.
struct NonlinearSolverResult {
  NonlinearSolverStatus status = NonlinearSolverStatus::converged;
  std::string message;                ///< one line: what ended the run, where, why
  double t = 0.0;                     ///< last converged time; u holds the state there
  int steps = 0;                      ///< converged steps
  int cutbacks = 0;                   ///< failed attempts
  int total_iterations = 0;           ///< Newton iterations over all attempts, failed ones included
  int augmentations = 0;              ///< multiplier updates over all attempts (augment)
  std::vector<int> step_iterations;   ///< Newton iterations of each converged step
  std::vector<StepAttempt> attempts;  ///< every attempt, in order
  int assemblies = 0;                 ///< calls of NonlinearProblem::assemble
  int residual_assemblies = 0;        ///< ... of them without the tangent (the linear paths; dR/dt)
  /// Arc length's dR/dt taken from the loads alone (NonlinearProblem::load_rate), each in place
  /// of a residual assembly.
  int load_rates = 0;
  /// Steps solved by the linear path (AnalysisKind::linear, or certified: accepted by the
  /// residual test); their solves count as one iteration each.
  int linear_steps = 0;
  /// Certified linear path: the first step it could not certify, where Newton took over (0:
  /// none), and why.
  int linear_until = 0;
  std::string linear_message;
  int cholmod_factorizations = 0;
  int ldlt_factorizations = 0;
  int umfpack_factorizations = 0;
  int petsc_factorizations = 0;
  int cholesky_fallbacks = 0;
  int jumps = 0;            ///< load control: converged steps that jumped (StepAttempt::jump_ratio)
  double time_total = 0.0;  ///< wall time of solve() (seconds)
  double time_assembly = 0.0;      ///< in NonlinearProblem::assemble
  double time_linear_solve = 0.0;  ///< in factorizations and solves
  double time_callback = 0.0;      ///< in commit() and the step callback (output)

  bool converged() const { return status == NonlinearSolverStatus::converged; }
};

/// The solver's state after a converged step: what a resumed run needs, besides u and the
/// problem's own state (NonlinearProblem::archive), to go on as the uninterrupted run would
/// (NonlinearSolver::checkpoint, NonlinearSolver::solve with `resume`).
struct SolverCheckpoint {
  double t = 0.0;            ///< the converged time
  int steps = 0;             ///< converged steps so far
  int attempted = 0;         ///< attempted steps so far (settings.max_steps counts them)
  double force_scale = 0.0;  ///< the largest |R_0| so far (residual and divergence tests)
  // Load control
  double dt = 0.0;         ///< the next step's size
  Eigen::VectorXd u_prev;  ///< the converged state before (secant predictor; empty: none)
  double t_prev = 0.0;     ///< and its time
  // Arc length
  Eigen::VectorXd du_prev;  ///< the step's increment (the next predictor's side; empty: none)
  double dl = 0.0, dl_min = 0.0, dl_max = 0.0;  ///< the next arc length and its bounds
  bool flat = false;                            ///< load steps while dR/dt = 0
  double dt_flat = 0.0;                         ///< their size
  /// Writes it to or reads it from a restart archive (iga/core/state_archive.hpp).
  void archive(StateArchive& a);
};

/// Called after each converged step (after NonlinearProblem::commit) with the converged state,
/// its time and the attempt that reached it; return false to stop the run (status stopped).
using StepCallback = std::function<bool(const VectorXd& u, double t, const StepAttempt& step)>;

/// Load stepping with Newton-Raphson. One instance keeps its LinearSolver (and thus the
/// symbolic analysis) across steps and runs.
///
/// Each step tries t = t_start + dt from the converged u (or its secant extrapolation,
/// NonlinearSolverSettings::secant_predictor): R_0 = R(u, t);
/// Newton corrections K du = -R until the residual and energy tests hold. Then
/// NonlinearProblem::augment: while it updates multipliers, Newton runs again at the same t
/// from the converged u (its iterations count for the step; a failure of such a re-solve, or
/// augment's `failed`, fails the step, which is cut back with NonlinearProblem::restore). The
/// step size grows after a step whose every solve took <= easy_iterations iterations. A step that
/// diverges, produces NaN, fails the linear solve or needs more than max_iterations is undone (u
/// restored) and retried with dt * cutback_factor; a failed step of size min_step ends the run with
/// status min_step_reached and u at the last converged step. Prescribed values depend on t
/// inside NonlinearProblem::assemble. An exception thrown by NonlinearProblem::assemble (a
/// std::exception, e.g. the contact search meeting a non-finite state) fails the attempt
/// (outcome assembly_failed, its message kept) and the step is cut back; exceptions of
/// commit() and of the step callback propagate, with u restored to the last converged state.
///
/// Arc length (settings.control == arc_length): t is an unknown of each step. From the
/// converged (u_n, t_n) the predictor goes along the tangent du_t = -K^-1 dR/dt by Delta l,
/// forward (towards t1) at the first step and then on the side of the previous increment;
/// each correction solves K du_R = -R and K du_t = -dR/dt with one factorization and takes
/// the load increment dt from |Delta u + du_R + dt du_t| = Delta l, the root whose increment
/// is nearest the one before (no real root: the step fails and is cut back). The residual and
/// energy tests are those of load control, the relative one against the larger of |R_0| and
/// |Delta t dR/dt| (the predictor's residual is small by construction). Contact whose active
/// set changes within a step is handled as under load control: the contact search and the
/// stick/slip states are part of every assembly, so Newton's iterate changes its active set
/// as it goes; a step whose set does not settle fails (divergence, max_iterations) and is cut
/// back; multiplier updates (augment) re-solve at the step's t. A step that crosses t1 or a
/// hit time is repeated under load control from the state interpolated at that time (when that
/// fails, the arc state is kept). Where dR/dt = 0 (nothing depends on t, e.g. a tool still away
/// from the body) the step is a load step of initial_step (grown and cut back as under load
/// control). NonlinearProblem::commit and the step callback see every converged state, with t
/// going down after a limit point.
class NonlinearSolver {
 public:
  /// Throws std::invalid_argument for invalid settings.
  explicit NonlinearSolver(const NonlinearSolverSettings& settings = {});

  const NonlinearSolverSettings& settings() const { return settings_; }
  /// Throws std::invalid_argument for invalid settings.
  void set_settings(const NonlinearSolverSettings& settings);
  /// Where progress lines and the summary go; nullptr (default): silent.
  void set_log(std::ostream* log) { log_ = log; }
  LinearSolver& linear_solver() { return linear_; }

  /// Solves from t0 to t1. u: on entry the converged state at t0 (size problem.num_dofs(), else
  /// std::invalid_argument), on return the state at result.t.
  /// `resume`: a restart; u is the converged state at resume->t (the problem's state read back
  /// with it) and the run goes on from there as the run that wrote the checkpoint would have
  /// (bit for bit with the same settings; step sizes are clamped to new min_step and max_step).
  /// The result's steps count from the start of the whole run, its other counts and times from
  /// the resume.
  [[nodiscard]] NonlinearSolverResult solve(NonlinearProblem& problem, VectorXd& u,
                                            const StepCallback& on_step = {},
                                            const SolverCheckpoint* resume = nullptr);
  /// Inside the step callback: the state after the step it reports, with the size of the next
  /// step (what a restart file written there needs). After solve(): that of the last converged
  /// step.
  const SolverCheckpoint& checkpoint() const { return checkpoint_; }

 private:
  struct Workspace;
  /// Newton iterations at time t from u (updated in place). `break_cycles` (the re-solves after
  /// a multiplier update): a correction that brings |R| back to its value two iterations
  /// before (a 2-cycle, e.g. points flipping between stick and slip) is followed by a half step.
  /// `r0_step`: |R_0| of the step's first solve; a re-solve's relative residual test is taken
  /// against the larger of it and its own |R_0| (which is only the multipliers' jump).
  /// `e1_step`: E_1 of the step's first correction where it was made before (the linear path);
  /// the energy test is taken against the larger of it and its own E_1.
  void newton(NonlinearProblem& problem, VectorXd& u, double t, Workspace& w, StepAttempt& a,
              NonlinearSolverResult& r, bool break_cycles = false, double r0_step = 0.0,
              double e1_step = 0.0);
  /// One step of the linear path (AnalysisKind) to time t from the start state u_ref into u:
  /// assembles R(u_ref, t) (with the tangent K_0 and its factorization when `factorized` is
  /// false, then set), solves, and for `certify` assembles R(u, t) and tests it. Returns true
  /// when the step is done (a's outcome converged, or a failure of the linear path); false
  /// when certification failed (u is the linear state, a holds its norms).
  bool linear_step(NonlinearProblem& problem, VectorXd& u, const VectorXd& u_ref, double t,
                   Workspace& w, StepAttempt& a, NonlinearSolverResult& r, bool& factorized,
                   bool certify);
  /// One attempt of a load-control step to t: the linear path while `linear_path` (cleared
  /// when it hands over to Newton), else Newton and exact enforcement. Returns the most
  /// iterations of one solve.
  int attempt_step(NonlinearProblem& problem, VectorXd& u, const VectorXd& u_ref, double t,
                   Workspace& w, StepAttempt& a, NonlinearSolverResult& r, bool& linear_path,
                   bool& factorized);
  /// The arc-length run (settings.control == arc_length).
  NonlinearSolverResult solve_arc_length(NonlinearProblem& problem, VectorXd& u,
                                         const StepCallback& on_step,
                                         const SolverCheckpoint* resume);
  SolverCheckpoint checkpoint_;
  struct ArcState;
  /// One arc-length step from the converged (u_last, t) of the ArcState: the tangent
  /// predictor, then corrections on the cylindrical constraint |Delta u| = Delta l. On return
  /// u and a.t hold the state reached (converged or not).
  void arc_newton(NonlinearProblem& problem, VectorXd& u, ArcState& arc, Workspace& w,
                  StepAttempt& a, NonlinearSolverResult& r);
  /// The tangent predictor of arc_newton: Delta t = +-Delta l / |du_t| into Dt, arc.du; false
  /// (a's outcome set) when it fails.
  bool arc_predictor(NonlinearProblem& problem, VectorXd& u, ArcState& arc, Workspace& w,
                     StepAttempt& a, NonlinearSolverResult& r, double& Dt);
  /// Newton at a fixed t from u, then the multiplier updates (augment); returns the most
  /// iterations of one solve.
  int solve_fixed(NonlinearProblem& problem, VectorXd& u, double t, Workspace& w, StepAttempt& a,
                  NonlinearSolverResult& r);
  /// After a converged arc-length step in a: when it crossed t1 or a hit time, the step again
  /// under load control, landing on it (a.landed). If that solve fails the step fails
  /// (landing_failed: cut back, a shorter arc then reaches the time from closer by), or at the
  /// minimum arc length the arc state is kept. `hardest`: the most iterations of one solve.
  void land(NonlinearProblem& problem, VectorXd& u, const ArcState& arc, Workspace& w,
            StepAttempt& a, NonlinearSolverResult& r, int& hardest);

  NonlinearSolverSettings settings_;
  std::ostream* log_ = nullptr;
  LinearSolver linear_;
};

/// The end-of-run summary: status and message, steps, cutbacks, iterations per step, wall time
/// and the shares of assembly and linear solves, factorizations per backend.
void write_summary(std::ostream& os, const NonlinearSolverResult& r);

}  // namespace iga
