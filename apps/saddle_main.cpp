// saddle: covering a saddle, [KS15] Sects. 6.1-6.2 (Figs. 6-8). A square Kirchhoff-Love plate
// hung by four weakening corner springs is loaded downward onto the rigid hyperboloid
// z = a x y (STAS contact, rigid surface as master or slave), without friction and with Coulomb
// friction. With friction the contact zone splits into a sticking centre and a sliding rim: a
// mass point on the saddle sticks while mu > tan(gamma) = a r, i.e. inside the circle of radius
// mu / a (79)-(81); the app fits the radius of the computed sticking zone and compares. The
// plate's membrane forces, which the mass point does not have, can make the whole plate slide;
// so the app also checks the circle itself: a small stiff block (app/block_model,
// data/saddle_block.json) put at radii around mu/a holds inside and slides outside.
//
//   saddle                                   the model's runs (data/saddle.json: mu = 0; mu = 0.125
//                                            with eps_T = eps_N and with eps_T = eps_N / 1000)
//   saddle --quick                           a coarse version (the model's "app"/"quick" overrides)
//   saddle --mu 0,0.1,0.2 --strategy slave   other friction coefficients (eps_T = eps_N), ray
//   saddle MODEL.json --set /materials/plate/E=1e5 --out DIR
//   saddle --blocks-only --mu 0.125,0.25     only the sticking-circle check with the block
//
// Writes to --out (default out/saddle):
//   saddle.csv            one row per converged step: run, mu, t, load q(t), centre deflection,
//                         contact / sticking / sliding points, Newton iterations
//   saddle_summary.json   per run: status, steps, iterations, times (assembly, contact, linear
//                         solves), DOFs, final deflection, the fitted sticking radius vs mu / a
//   contact_<run>.csv     the active contact points at the snapshot times (t, x, y, z, foot
//                         parameters, N, stick)
//   saddle_blocks.csv     the block check: per frictional run and radius r, the contact points
//                         sticking / sliding and the contact force ratio T/N against
//                         min(a r, mu); also in saddle_summary.json ("sticking_circle")
//   saddle_contact_<run>.png, saddle_load_deflection.png, saddle_sticking_circle.png   plots
//                         (scripts/plot_saddle.py)
//   <run>/                steps.csv, summary.json, shell and contact .vts/.vtu + .pvd per snapshot,
//                         rigid.vts (ParaView)
// Exit status: 0 all runs reached t_end, 1 bad input, 2 a bad command line or a run that ended
// early (its rows are kept).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "apps/common/app_common.hpp"
#include "apps/common/resources.hpp"
#include "iga/contact_integrals/shell_contact_problem.hpp"
#include "iga/model/analysis.hpp"
#include "iga/output/vtk_writer.hpp"

namespace {

using namespace iga;
namespace fs = std::filesystem;

struct RunSpec {
  double mu = 0.0, eps_t = 0.0;
  std::string name;  // file stem, "mu0.125"
};

/// Where the app finds its quantities in the model (the "app" section).
struct AppSection {
  JsonPointer mu, eps_t, strategy, a, load;
  std::string load_curve, centre_monitor;
  std::vector<RunSpec> runs;
  std::vector<double> snapshots;
  std::string block_model;  ///< the sticking-circle check's model (a path), empty: none
};

JsonPointer pointer(const JsonCursor& app, const char* key, const Json& doc) {
  return model_pointer(app[key], doc);
}

std::string run_name(double mu) {
  std::ostringstream s;
  s << "mu" << mu;
  return s.str();
}

AppSection read_app(const Json& doc, const std::string& file) {
  const JsonCursor root(doc, file);
  if (!root.has("app"))
    root.fail_plain("missing required key \"app\" (the runs of the saddle app)");
  const JsonCursor app = root["app"];
  app.expect_object({"mu", "eps_T", "strategy", "a", "load", "load_curve", "centre_monitor", "runs",
                     "snapshots", "quick", "block_model", "description"});
  AppSection s;
  s.mu = pointer(app, "mu", doc);
  s.eps_t = pointer(app, "eps_T", doc);
  s.strategy = pointer(app, "strategy", doc);
  s.a = pointer(app, "a", doc);
  s.load = pointer(app, "load", doc);
  s.load_curve = app["load_curve"].as_string();
  s.centre_monitor = app["centre_monitor"].as_string();
  const JsonCursor runs = app["runs"];
  runs.expect_array(1);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const JsonCursor r = runs[k];
    r.expect_object({"mu", "eps_T", "description"});
    RunSpec spec{r["mu"].as_number(), r["eps_T"].as_number(), {}};
    if (spec.mu < 0.0) r["mu"].fail("must be >= 0");
    if (spec.eps_t < 0.0) r["eps_T"].fail("must be >= 0");
    spec.name = run_name(spec.mu);
    // a second run with the same mu (another eps_T) is told apart by its eps_T
    for (const RunSpec& o : s.runs)
      if (o.name == spec.name)
        spec.name += "_epsT" + [&] {
          std::ostringstream e;
          e << spec.eps_t;
          return e.str();
        }();
    for (const RunSpec& o : s.runs)
      if (o.name == spec.name) r.fail_plain("the same run (mu and eps_T) is listed twice");
    s.runs.push_back(spec);
  }
  const JsonCursor snaps = app["snapshots"];
  snaps.expect_array(1);
  s.snapshots = snaps.as_numbers();
  if (app.has("block_model")) {  // relative to the model's folder
    const fs::path p(app["block_model"].as_string());
    s.block_model = (p.is_relative() ? fs::path(file).parent_path() / p : p).string();
  }
  return s;
}

/// The sticking zone of the active points at one state: the radius (about the saddle's axis,
/// from the foot points' x, y) that best separates sticking points (inside) from sliding points
/// (outside), i.e. minimizes the misclassified contact area; the radius of the circle with the
/// sticking area; the centroid of the sticking points.
struct StickZone {
  double radius_fit = 0.0, radius_area = 0.0;
  Vector2d centroid = Vector2d::Zero();
  int stick = 0, active = 0;
  int first_contact = 0;  ///< active points that were not in contact at the previous step
};

StickZone stick_zone(const SurfaceContact& sc) {
  struct P {
    double r, w;
    bool stick;
  };
  std::vector<P> pts;
  StickZone z;
  double area = 0.0;
  for (const SurfaceContactPoint& cp : sc.points()) {
    if (!cp.active) continue;
    const bool st = sc.sticks(cp);
    const Vector2d xy = cp.foot.point.head<2>();
    pts.push_back({xy.norm(), cp.weight, st});
    ++z.active;
    if (cp.first_contact) ++z.first_contact;
    if (st) {
      ++z.stick;
      area += cp.weight;
      z.centroid += cp.weight * xy;
    }
  }
  if (z.stick == 0) return z;
  z.centroid /= area;
  z.radius_area = std::sqrt(area / std::numbers::pi);
  // Misclassified area as the circle grows past each point: sliding inside + sticking outside.
  std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.r < b.r; });
  double outside_stick = area, inside_slip = 0.0, best = area;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    (pts[k].stick ? outside_stick : inside_slip) += pts[k].stick ? -pts[k].w : pts[k].w;
    const double miss = outside_stick + inside_slip;
    if (miss < best) {
      best = miss;
      z.radius_fit = k + 1 < pts.size() ? 0.5 * (pts[k].r + pts[k + 1].r) : pts[k].r;
    }
  }
  return z;
}

Json zone_json(const StickZone& z) {
  Json j = Json::object();
  j["sticking_points"] = z.stick;
  j["contact_points"] = z.active;
  j["first_contact_points"] = z.first_contact;
  j["sticking_radius_fit"] = z.radius_fit;
  j["sticking_radius_area"] = z.radius_area;
  j["sticking_centroid"] = {z.centroid.x(), z.centroid.y()};
  return j;
}

/// The mass-point check of the sticking circle (79)-(81) on a second model (app/block_model,
/// data/saddle_block.json): a small stiff block lying on the saddle at distance r from its
/// axis, loaded downward, held by soft horizontal springs. A mass point there sticks while
/// tan(gamma) = |grad z| = a r <= mu: friction then carries the whole slope component of the load
/// and the contact force ratio T/N is tan(gamma). Outside the circle r = mu/a it slides and
/// T/N = mu (the springs take the rest). The app moves the block to radii around mu/a.
struct BlockModel {
  std::string file;
  Json doc;
  JsonPointer block, a, thickness, mu, eps_t, strategy;
  double half_size = 0.0, gap = 0.0, direction = 0.0;  ///< direction of the radius, radians
  std::vector<double> radii;                           ///< fractions of mu / a
};

BlockModel read_block_model(const std::string& file) {
  BlockModel b;
  b.file = file;
  b.doc = read_json_file(file);
  const JsonCursor root(b.doc, file);
  if (!root.has("app"))
    root.fail_plain("missing required key \"app\" (where the saddle app moves the block)");
  const JsonCursor app = root["app"];
  app.expect_object({"block", "a", "thickness", "mu", "eps_T", "strategy", "half_size", "gap",
                     "direction_deg", "radii", "description"});
  b.block = pointer(app, "block", b.doc);
  b.a = pointer(app, "a", b.doc);
  b.thickness = pointer(app, "thickness", b.doc);
  b.mu = pointer(app, "mu", b.doc);
  b.eps_t = pointer(app, "eps_T", b.doc);
  b.strategy = pointer(app, "strategy", b.doc);
  b.half_size = app["half_size"].as_number();
  if (!(b.half_size > 0.0)) app["half_size"].fail("must be > 0");
  b.gap = app["gap"].as_number();
  if (!(b.gap >= 0.0)) app["gap"].fail("must be >= 0");
  b.direction = app["direction_deg"].as_number() * std::numbers::pi / 180.0;
  const JsonCursor radii = app["radii"];
  radii.expect_array(1);
  b.radii = radii.as_numbers();
  for (std::size_t k = 0; k < b.radii.size(); ++k)
    if (!(b.radii[k] > 0.0)) radii[k].fail("must be > 0 (a fraction of mu/a)");
  (void)Analysis::from_json(b.doc, file);  // validates the model as given
  return b;
}

struct BlockResult {
  double fraction = 0.0, r_start = 0.0, r = 0.0, tan_gamma = 0.0, ratio = 0.0, theory = 0.0;
  int active = 0, stick = 0, slip = 0;
  /// "stick" (all contact points), "slide" (all: the block slides), "partial slip" (the block
  /// holds, the points of least pressure slip: N varies over the block, whose friction acts at
  /// its lower face, h/2 below the load), "no contact"
  std::string state;
  std::string status;  ///< the solver's
  bool converged = false;
};

/// The block at radius fraction * mu / a (along bm.direction), on the saddle z = a x y: the
/// bilinear patch with corners on the saddle is the saddle itself, written with degree 2 and
/// lifted so that its lower face (h/2 along the normal) lies bm.gap above it.
BlockResult run_block(const BlockModel& bm, double a, double mu, double eps_t,
                      const std::string& strategy, double fraction) {
  BlockResult res;
  res.fraction = fraction;
  res.r_start = fraction * mu / a;
  const double xc = res.r_start * std::cos(bm.direction), yc = res.r_start * std::sin(bm.direction);
  const double h = bm.doc.at(bm.thickness).get<double>();
  const double lift = 0.5 * h * std::sqrt(1.0 + a * a * res.r_start * res.r_start) + bm.gap;
  Json d = bm.doc;
  d[bm.a] = a;
  d[bm.mu] = mu;
  d[bm.eps_t] = eps_t;
  d[bm.strategy] = strategy;
  Json pts = Json::array();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const double x = xc + (i - 1) * bm.half_size, y = yc + (j - 1) * bm.half_size;
      pts.push_back({x, y, a * x * y + lift});
    }
  d[bm.block] = {{"type", "nurbs_surface"},
                 {"degree", {2, 2}},
                 {"knots", {{"u", {0, 0, 0, 1, 1, 1}}, {"v", {0, 0, 0, 1, 1, 1}}}},
                 {"control_points", pts}};
  Analysis an = Analysis::from_json(d, bm.file);
  const SurfaceContactPair* contact = an.pair_as<SurfaceContactPair>();
  if (contact == nullptr)
    throw std::invalid_argument(
        bm.file + ": the block check needs a shell body with a surface_to_rigid contact pair");
  const AnalysisResult r = an.run();
  res.converged = r.solver.converged();
  res.status = r.solver.message;
  // Contact forces summed over the active points: normal sum w |N|, tangential |sum w f_T|.
  double fn = 0.0;
  Vector3d ft = Vector3d::Zero();
  Vector2d centre = Vector2d::Zero();
  for (const SurfaceContactPoint& cp : contact->contact().points()) {
    if (!cp.active) continue;
    ++res.active;
    if (contact->contact().sticks(cp)) ++res.stick;
    if (cp.slip) ++res.slip;
    fn -= cp.weight * cp.N;
    ft += cp.weight * cp.T_vector;
    centre -= cp.weight * cp.N * cp.foot.point.head<2>();
  }
  if (res.active == 0) {
    res.state = "no contact";
    return res;
  }
  centre /= fn;
  res.r = centre.norm();
  res.tan_gamma = a * res.r;  // |grad (a x y)| = a r
  res.ratio = ft.norm() / fn;
  res.theory = std::min(res.tan_gamma, mu);
  res.state = res.stick == res.active ? "stick" : res.slip == res.active ? "slide" : "partial slip";
  return res;
}

/// The command line.
struct SaddleOptions {
  std::string model_file = iga::app::resource("data/saddle.json");
  std::vector<double> mu_list;
  std::vector<std::string> sets;
  std::string strategy, out = "out/saddle";
  bool quick = false, verbose = false, blocks_only = false;
};

/// Parses the command line into `o`; a status >= 0 to exit with (--help, a bad option), else -1.
int parse_options(int argc, char** argv, SaddleOptions& o) {
  CLI::App cli{
      "saddle: a plate pressed onto a rigid hyperboloid, STAS contact with friction ([KS15] Sects. "
      "6.1-6.2)"};
  cli.add_option("model", o.model_file, "Model file (JSON, format iga-contact-model)")
      ->capture_default_str();
  cli.add_option("--mu", o.mu_list,
                 "Friction coefficients (a list: 0,0.125); eps_T = eps_N when mu > 0")
      ->delimiter(',');
  cli.add_option("--strategy", o.strategy,
                 "Penetration strategy: the rigid surface as master (closest point) or slave (ray)")
      ->check(CLI::IsMember({"master", "slave"}));
  cli.add_option("--set", o.sets, "Override a model value: /json/pointer=value (repeatable)");
  cli.add_option("--out,-o", o.out, "Output folder")->capture_default_str();
  cli.add_flag("--quick", o.quick, "Coarse version: apply the model's app/quick overrides first");
  cli.add_flag("--blocks-only", o.blocks_only,
               "Only the sticking-circle check (79)-(81): the small block of app/block_model at "
               "radii around mu/a");
  cli.add_flag("--verbose,-v", o.verbose, "Print the solver's progress line per step");
  return iga::app::parse_command_line(cli, argc, argv);
}

/// The model and what every run reads from it, validated before any run.
struct Saddle {
  Json doc;
  AppSection app;
  std::optional<BlockModel> block_model;
  std::string describe;
  double t_end = 1.0, a = 0.0, q_final = 0.0;
  int centre = -1;  ///< the index of the centre's monitor
  LoadCurve lambda;
};

/// Snapshot times inside (0, t_end) become step ends (the last one is t_end itself).
void snapshot_hit_times(Json& doc, const AppSection& app, const std::string& file) {
  const JsonPointer t_end_ptr("/solver/t_end");
  const double t_end = doc.contains(t_end_ptr) && doc.at(t_end_ptr).is_number()
                           ? doc.at(t_end_ptr).get<double>()
                           : 1.0;
  const JsonCursor snaps = JsonCursor(doc, file)["app"]["snapshots"];
  Json hits = Json::array();
  for (std::size_t k = 0; k < app.snapshots.size(); ++k) {
    const double t = app.snapshots[k];
    if (!(t > 0.0 && t <= t_end))
      snaps[k].fail("must lie in (0, t_end] = (0, " + std::to_string(t_end) + "]");
    if (t < t_end) hits.push_back(t);
  }
  doc["solver"]["hit_times"] = hits;
}

/// The model: read, quick overrides, --set, the command line's runs and strategy; validated once
/// before any run, with the block model of the sticking-circle check.
Saddle read_saddle(const SaddleOptions& o) {
  Saddle sd;
  Json& doc = sd.doc;
  const std::string& file = o.model_file;
  doc = iga::app::read_model(file, o.quick, o.sets);
  sd.app = read_app(doc, file);
  AppSection& app = sd.app;
  if (!o.strategy.empty()) doc[app.strategy] = o.strategy;
  if (!o.mu_list.empty()) {
    const double eps_n = doc.at(JsonPointer("/contact/0/eps_N")).get<double>();
    app.runs.clear();
    for (double mu : o.mu_list) {
      if (!(mu >= 0.0))
        throw std::invalid_argument("--mu: must be >= 0, got " + std::to_string(mu));
      app.runs.push_back({mu, mu > 0.0 ? eps_n : 0.0, run_name(mu)});
    }
  }
  snapshot_hit_times(doc, app, file);
  const Analysis probe = Analysis::from_json(doc, file);  // validates the whole model
  sd.describe = probe.describe();
  // The sticking-circle check's model is read and validated now, before any run.
  if (!app.block_model.empty()) sd.block_model = read_block_model(app.block_model);
  sd.t_end = probe.solver_settings().t1;
  sd.a = doc.at(app.a).get<double>();
  const std::vector<double> load_vec = doc.at(app.load).get<std::vector<double>>();
  sd.q_final =
      std::sqrt(std::inner_product(load_vec.begin(), load_vec.end(), load_vec.begin(), 0.0));
  for (std::size_t k = 0; k < probe.output().monitors.size(); ++k)
    if (probe.output().monitors[k].name == app.centre_monitor) sd.centre = static_cast<int>(k);
  if (sd.centre < 0)
    throw std::invalid_argument(file + ": app/centre_monitor: no output monitor named '" +
                                app.centre_monitor + "'");
  for (const auto& [name, curve] : probe.load_curves())
    if (name == app.load_curve) sd.lambda = curve;
  if (!sd.lambda)
    throw std::invalid_argument(file + ": app/load_curve: no load curve named '" + app.load_curve +
                                "'");
  return sd;
}

/// The run's summary in saddle_summary.json.
Json run_summary(const RunSpec& run, const Saddle& sd, int dofs, const SurfaceContactPair& contact,
                 const AnalysisResult& r, const Json& snaps) {
  const NonlinearSolverResult& s = r.solver;
  Json j = zone_json(stick_zone(contact.contact()));
  j["name"] = run.name;
  j["mu"] = run.mu;
  j["eps_T"] = run.eps_t;
  j["expected_radius_mu_over_a"] = run.mu / sd.a;
  j["status"] = to_string(s.status);
  j["message"] = s.message;
  j["t_reached"] = s.t;
  j["steps"] = s.steps;
  j["cutbacks"] = s.cutbacks;
  j["newton_iterations"] = s.total_iterations;
  j["iterations_per_step"] = static_cast<double>(s.total_iterations) / std::max(s.steps, 1);
  j["dofs"] = dofs;
  j["contact_quadrature_points"] = contact.contact().points().size();
  j["time_total_s"] = s.time_total;
  j["time_assembly_s"] = s.time_assembly;
  j["time_contact_s"] = r.contact_time;
  j["time_linear_solve_s"] = s.time_linear_solve;
  j["time_per_iteration_s"] = s.time_total / std::max(s.total_iterations, 1);
  j["centre_deflection"] =
      r.steps.empty() ? 0.0
                      : -r.steps.back().displacements[static_cast<std::size_t>(sd.centre)].z();
  j["snapshots"] = snaps;
  return j;
}

/// One run of the plate: its rows of saddle.csv, its contact points and ParaView files at the
/// snapshots, its summary appended to `summary`. Returns whether it reached t_end.
bool run_plate(const SaddleOptions& o, const Saddle& sd, const RunSpec& run, const fs::path& dir,
               std::ostream& csv, Json& summary) {
  Json d = sd.doc;
  d[sd.app.mu] = run.mu;
  d[sd.app.eps_t] = run.eps_t;
  Analysis an = Analysis::from_json(d, o.model_file);
  SurfaceContactPair* contact = an.pair_as<SurfaceContactPair>();
  if (contact == nullptr)
    throw std::invalid_argument(
        o.model_file + ": the saddle app needs a shell body with a surface_to_rigid contact pair");
  const fs::path run_dir = dir / run.name;
  fs::create_directories(run_dir);
  std::ofstream points(dir / ("contact_" + run.name + ".csv"));
  points << "t,x,y,z,foot_u,foot_v,N,stick\n" << std::setprecision(10);
  VtkCollection pvd_shell((run_dir / "snapshots_shell.pvd").string());
  VtkCollection pvd_contact((run_dir / "snapshots_contact.pvd").string());
  Json snaps = Json::array();
  std::cout << "saddle: run " << run.name << " (mu = " << run.mu << ", eps_T = " << run.eps_t
            << ")\n";
  const auto snapshot = [&](const VectorXd& u, double t, const AnalysisStep& st, double w) {
    for (const SurfaceContactPoint& cp : contact->contact().points())
      if (cp.active)
        points << t << "," << cp.x.x() << "," << cp.x.y() << "," << cp.x.z() << ","
               << cp.foot.uv.x() << "," << cp.foot.uv.y() << "," << cp.N << ","
               << (contact->contact().sticks(cp) ? 1 : 0) << "\n";
    points.flush();
    std::ostringstream stem;
    stem << "t" << t;
    const std::vector<std::string> f = an.write_vtk(run_dir.string(), stem.str(), u, t);
    pvd_shell.add(t, f[0]);
    pvd_contact.add(t, f[1]);
    Json z = zone_json(stick_zone(contact->contact()));
    z["t"] = t;
    z["centre_deflection"] = w;
    snaps.push_back(z);
    std::cout << "  t = " << std::setw(6) << t << "  q = " << std::setw(8)
              << sd.q_final * sd.lambda(t) << "  centre deflection " << std::setw(9) << w
              << "  contact " << st.contact.active << " (stick " << st.contact.stick << ", slide "
              << st.contact.slip << ")\n";
  };
  auto on_step = [&](const VectorXd& u, double t, const AnalysisStep& st) {
    const double w = -st.displacements[static_cast<std::size_t>(sd.centre)].z();
    csv << run.name << "," << run.mu << "," << t << "," << sd.q_final * sd.lambda(t) << "," << w
        << "," << st.contact.active << "," << st.contact.stick << "," << st.contact.slip << ","
        << st.iterations << std::endl;
    for (double ts : sd.app.snapshots)
      if (std::abs(t - ts) <= 1e-9 * sd.t_end) snapshot(u, t, st, w);
    return true;
  };
  const AnalysisResult r = an.run(o.verbose ? &std::cout : nullptr, run_dir.string(), on_step);
  const NonlinearSolverResult& s = r.solver;
  summary["runs"].push_back(run_summary(run, sd, an.problem().num_dofs(), *contact, r, snaps));
  std::ofstream(dir / "saddle_summary.json") << format_json(summary) << "\n";  // after each run
  std::cout << "  " << run.name << ": " << to_string(s.status) << " at t = " << s.t << ", "
            << s.steps << " steps, " << s.total_iterations << " Newton iterations ("
            << static_cast<double>(s.total_iterations) / std::max(s.steps, 1) << " per step), "
            << s.time_total << " s: assembly " << 100 * s.time_assembly / s.time_total
            << " % (contact " << 100 * r.contact_time / s.time_total << " %), linear solves "
            << 100 * s.time_linear_solve / s.time_total << " %\n";
  if (run.mu > 0.0) {
    const StickZone zone = stick_zone(contact->contact());
    std::cout << "  sticking zone: " << zone.stick << " of " << zone.active << " contact points ("
              << zone.first_contact << " in their first step of contact), radius "
              << zone.radius_fit << " (fit), " << zone.radius_area
              << " (area), mu/a = " << run.mu / sd.a << ", centroid (" << zone.centroid.x() << ", "
              << zone.centroid.y() << ")\n";
  }
  if (!s.converged())
    std::cout << "saddle: run " << run.name << " ended early: " << s.message << "\n";
  return s.converged();
}

/// One friction coefficient's check of the circle: the block at each radius (rows of
/// saddle_blocks.csv, an entry of summary["sticking_circle"]). Returns the blocks that failed.
int circle_check(const Saddle& sd, const RunSpec& run, const std::string& strategy,
                 std::ostream& bcsv, Json& summary) {
  const BlockModel& bm = *sd.block_model;
  const double a = sd.a;
  Json c = Json::object();
  c["mu"] = run.mu;
  c["eps_T"] = run.eps_t;
  c["expected_radius_mu_over_a"] = run.mu / a;
  double hold_max = 0.0, slide_min = std::numeric_limits<double>::infinity(), err = 0.0;
  bool consistent = true;
  int failed = 0;
  Json blocks = Json::array();
  for (double f : bm.radii) {
    const BlockResult b = run_block(bm, a, run.mu, run.eps_t, strategy, f);
    bcsv << run.mu << "," << run.eps_t << "," << f << "," << b.r_start << "," << b.r << ","
         << b.tan_gamma << "," << b.active << "," << b.stick << "," << b.slip << "," << b.state
         << "," << b.ratio << "," << b.theory << "," << (b.converged ? 1 : 0) << std::endl;
    if (!b.converged) ++failed;
    const bool holds = b.active > 0 && b.state != "slide";
    if (holds) hold_max = std::max(hold_max, b.r);
    if (b.state == "slide") slide_min = std::min(slide_min, b.r);
    // a mass point sticks inside the circle, slides outside (radii exactly on it are not judged)
    if ((f < 1.0 && !holds) || (f > 1.0 && b.state != "slide") || !b.converged) consistent = false;
    if (b.active > 0 && b.theory > 0.0)
      err = std::max(err, std::abs(b.ratio - b.theory) / b.theory);
    blocks.push_back({{"radius_fraction", f},
                      {"r_start", b.r_start},
                      {"r", b.r},
                      {"tan_gamma", b.tan_gamma},
                      {"contact_points", b.active},
                      {"sticking_points", b.stick},
                      {"sliding_points", b.slip},
                      {"state", b.state},
                      {"T_over_N", b.ratio},
                      {"theory_min_tan_gamma_mu", b.theory},
                      {"converged", b.converged},
                      {"message", b.status}});
  }
  c["holds_up_to_r"] = hold_max;
  c["slides_from_r"] = std::isfinite(slide_min) ? Json(slide_min) : Json(nullptr);
  c["consistent_with_circle"] = consistent;
  c["max_relative_error_T_over_N"] = err;
  c["blocks"] = blocks;
  summary["sticking_circle"].push_back(c);
  std::cout << "saddle: sticking circle, mu = " << run.mu << " (mu/a = " << run.mu / a
            << "): the block holds up to r = " << hold_max << ", slides from r = " << slide_min
            << (consistent ? " (as (79)-(81))" : " (NOT as (79)-(81))")
            << "; T/N vs min(a r, mu) within " << 100.0 * err << " %\n";
  return failed;
}

/// The sticking-circle check (79)-(81): per frictional run, the block at radii around mu/a.
/// Returns the blocks that failed.
int sticking_circle(const Saddle& sd, const fs::path& dir, Json& summary) {
  const std::string strategy = sd.doc.at(sd.app.strategy).get<std::string>();
  std::ofstream bcsv(dir / "saddle_blocks.csv");
  bcsv << "mu,eps_T,radius_fraction,r_start,r,tan_gamma,contact_points,sticking_points,sliding_"
          "points,state,"
          "T_over_N,theory,converged\n"
       << std::setprecision(10);
  summary["block_model"] = sd.app.block_model;
  summary["sticking_circle"] = Json::array();
  // Once per friction coefficient, with the stiffest tangential penalty of its runs: the block
  // measures T/N = tan(gamma) only while eps_T * (its area) is far above its springs' stiffness.
  std::vector<RunSpec> checks;
  for (const RunSpec& run : sd.app.runs) {
    if (!(run.mu > 0.0 && run.eps_t > 0.0)) continue;
    auto same = std::find_if(checks.begin(), checks.end(),
                             [&](const RunSpec& c) { return c.mu == run.mu; });
    if (same == checks.end())
      checks.push_back(run);
    else
      same->eps_t = std::max(same->eps_t, run.eps_t);
  }
  int failed = 0;
  for (const RunSpec& run : checks) failed += circle_check(sd, run, strategy, bcsv, summary);
  std::ofstream(dir / "saddle_summary.json") << format_json(summary) << "\n";
  return failed;
}

int run_saddle(int argc, char** argv) {
  SaddleOptions o;
  if (const int status = parse_options(argc, argv, o); status >= 0) return status;
  const Saddle sd = read_saddle(o);
  const std::string strategy = sd.doc.at(sd.app.strategy).get<std::string>();

  const fs::path dir(o.out);
  fs::create_directories(dir);
  std::ofstream(dir / "model_used.json") << format_json(sd.doc) << "\n";
  std::ofstream csv(dir / "saddle.csv");
  if (!csv) throw std::runtime_error("cannot write " + (dir / "saddle.csv").string());
  csv << "run,mu,t,load,centre_deflection,contact_points,sticking_points,sliding_points,"
         "iterations\n"
      << std::setprecision(10);
  std::cout << "saddle: " << sd.describe << "\n";
  std::cout << "saddle: " << sd.app.runs.size() << " run(s), strategy " << strategy
            << ", results in " << dir.string() << "\n";

  Json summary = Json::object();
  summary["model"] = o.model_file;
  summary["strategy"] = strategy;
  summary["a"] = sd.a;
  summary["runs"] = Json::array();
  int failed = 0;
  if (!o.blocks_only)
    for (const RunSpec& run : sd.app.runs)
      failed += run_plate(o, sd, run, dir, csv, summary) ? 0 : 1;
  if (sd.block_model) failed += sticking_circle(sd, dir, summary);

  const std::string script = iga::app::resource("scripts/plot_saddle.py");
  if (!iga::app::run_python(script, {dir.string()}))
    std::cout << "saddle: warning: the plots failed (" << script << " " << dir.string() << ")\n";
  return failed > 0 ? 2 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_saddle(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "saddle: error: " << e.what() << "\n";
    return 1;
  }
}
