// Sweeps of the rope models over mu, phi and the pitch H; see rope_sweep.hpp.
#include "apps/rope_sweep.hpp"

#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "apps/common/app_common.hpp"
#include "iga/contact_integrals/rod_contact_problem.hpp"
#include "iga/model/analysis.hpp"
#include "iga/output/output_format.hpp"

namespace iga::app {

namespace {

namespace fs = std::filesystem;

/// The line pressure along the arc of a planar wrap path (issue 12 item 6): per element the
/// weighted mean of -N over its contact points (the field written to the rod's VTK) at the mean
/// angle theta from the arc's start (the tangent point of the loaded end A), against the full
/// slip value T0 e^{mu theta} / rho. The rope object must be a wrap_path construction with
/// center, axis and mid_dir; otherwise (or with a pitch) nothing is written.
void write_pressure_rows(std::ostream& out, const std::string& name, double mu, double phi,
                         double T0, double rho, const Json& rope, const CurveContact& contact,
                         int per_element) {
  if (!rope.is_object() || !rope.contains("mid_dir") || !rope.contains("axis") ||
      !rope.contains("center") || rope.value("pitch", 0.0) != 0.0 || per_element < 1)
    return;
  auto vec = [&](const char* k) {
    const Json& a = rope.at(k);
    return Vector3d(a.at(0).get<double>(), a.at(1).get<double>(), a.at(2).get<double>());
  };
  const Vector3d c = vec("center"), e3 = vec("axis").normalized();
  Vector3d e1 = vec("mid_dir");
  e1 = (e1 - e1.dot(e3) * e3).normalized();
  const Vector3d e2 = e3.cross(e1);
  // The arc runs clockwise about the axis from mid + phi / 2 to mid - phi / 2.
  auto theta_of = [&](const Vector3d& x) {
    const Vector3d d = x - c;
    double t = 0.5 * phi - std::atan2(d.dot(e2), d.dot(e1));
    return t;
  };
  const auto& pts = contact.points();
  const std::size_t per = static_cast<std::size_t>(per_element);
  for (std::size_t e = 0; e + per <= pts.size(); e += per) {
    double w = 0.0, p = 0.0, th = 0.0;
    bool any = false;
    for (std::size_t k = e; k < e + per; ++k) {
      w += pts[k].weight;
      th += pts[k].weight * theta_of(pts[k].x);
      if (!pts[k].law.active) continue;
      any = true;
      p += pts[k].weight * -pts[k].N;
    }
    if (!any || w <= 0.0) continue;
    th /= w;
    if (th < 0.0 || th > phi) continue;
    out << name << "," << csv_number(mu, 10) << "," << csv_number(phi, 10) << ","
        << csv_number(th, 10) << "," << csv_number(p / w, 10) << ","
        << csv_number(T0 * std::exp(mu * th) / rho, 10) << "\n";
  }
}
constexpr double kPi = std::numbers::pi;

struct Case {
  std::string sweep;  ///< the CSV's sweep column: the model's sweep name or "c" (command line)
  std::string name;   ///< the CSV's case column and file stem: sweep + index
  double mu = 0.0, phi_deg = 0.0, pitch = 0.0;
};

/// Where the app finds its quantities in the model (the "app" section's pointers).
struct Pointers {
  JsonPointer T0, mu, phi_deg, pitch, rho;
  Json reaction_point;
  std::optional<JsonPointer> pull;  ///< the pulled end's displacement magnitude (app/pull)
  double max_pull = 0.0;            ///< how far a case may be pulled on (app/max_pull)
};

/// A number of the model named by an app pointer that must be > 0; the error names the value's
/// own path and the app key that points there.
double positive_at(const Json& doc, const std::string& file, const JsonPointer& p, const char* key,
                   const char* why) {
  const double v = doc.at(p).get<double>();
  if (!(v > 0.0))
    JsonCursor(doc.at(p), file, p).fail(std::string("must be > 0 (app/") + key + ": " + why + ")");
  return v;
}

JsonPointer pointer(const JsonCursor& app, const char* key, const Json& doc) {
  const JsonCursor c = app[key];
  JsonPointer p = model_pointer(c, doc);
  if (!doc.at(p).is_number()) c.fail("must name a number of the model");
  return p;
}

std::vector<Case> sweeps_from(const JsonCursor& s, const Json& doc, const Pointers& ptr) {
  std::vector<Case> cases;
  if (!s.json().is_object()) s.fail_type("an object of named sweeps");
  for (const std::string& name : s.keys()) {
    const JsonCursor c = s[name];
    c.expect_object({"mu", "phi_deg", "pitch"});
    auto list = [&](const char* key, const JsonPointer& p) {
      if (!c.has(key)) return std::vector<double>{doc.at(p).get<double>()};
      const JsonCursor l = c[key];
      l.expect_array(1);
      return l.as_numbers();
    };
    int k = 0;
    for (double mu : list("mu", ptr.mu))
      for (double phi : list("phi_deg", ptr.phi_deg))
        for (double H : list("pitch", ptr.pitch))
          cases.push_back({name, name + std::to_string(++k), mu, phi, H});
  }
  return cases;
}

/// --rod torsion: every rod body of the model becomes a rod with torsion, its material gets
/// GJ = 0.8 EI where it has none (a circle of Poisson's ratio 0.25: GJ = EI / (1 + nu)), and the
/// twist is held where a displacement is prescribed (the pulled end). Malformed entries are
/// left for the model's validation.
void make_twisting(Json& doc) {
  if (!doc.is_object() || !doc.contains("bodies") || !doc["bodies"].is_object()) return;
  for (auto& [name, body] : doc["bodies"].items()) {
    if (!body.is_object() || body.value("type", "") != "rod") continue;
    body["torsion"] = true;
    const std::string mat = body.value("material", "");
    if (doc.contains("materials") && doc["materials"].contains(mat)) {
      Json& m = doc["materials"][mat];
      if (m.is_object() && m.value("type", "") == "rod" && !m.contains("GJ") && m.contains("EI") &&
          m["EI"].is_number())
        m["GJ"] = 0.8 * m["EI"].get<double>();
      if (m.is_object() && m.value("type", "") == "rod_circular" && !m.contains("G") &&
          !m.contains("nu"))
        m["nu"] = 0.25;
    }
    if (!doc.contains("boundary_conditions") || !doc["boundary_conditions"].is_array()) continue;
    Json twists = Json::array();
    for (const Json& bc : doc["boundary_conditions"])
      if (bc.is_object() && bc.value("type", "") == "displacement" &&
          bc.value("body", "") == name && bc.contains("point") && bc["point"].is_string())
        twists.push_back({{"type", "twist"}, {"body", name}, {"at", bc["point"]}});
    for (Json& t : twists) doc["boundary_conditions"].push_back(std::move(t));
  }
}

/// The command line of a rope app.
struct RopeOptions {
  std::string model_file, out;
  std::vector<double> mu_list, phi_list, pitch_list;
  std::vector<std::string> sets;
  bool quick = false, profile = false, verbose = false, penalty = false, torsion = false;
  double max_error = -1.0;
};

/// Parses the command line into `o`; a status >= 0 to exit with (--help, a bad option), else -1.
int parse_options(const RopeApp& ra, int argc, char** argv, RopeOptions& o) {
  CLI::App cli{ra.title};
  o.model_file = ra.default_model;
  o.out = std::string("out/").append(ra.name);
  cli.add_option("model", o.model_file, "Model file (JSON, format iga-contact-model)")
      ->capture_default_str();
  cli.add_option("--mu", o.mu_list, "Friction coefficients (a list: 0,0.5,1)")->delimiter(',');
  cli.add_option("--phi-deg", o.phi_list, "Wrap angles in degrees (a list)")->delimiter(',');
  cli.add_option("--pitch", o.pitch_list, "Helix pitches H, rise per turn (a list)")
      ->delimiter(',');
  cli.add_option("--set", o.sets, "Override a model value: /json/pointer=value (repeatable)");
  cli.add_option("--out,-o", o.out, "Output folder")->capture_default_str();
  cli.add_flag("--quick", o.quick, "Run the model's reduced sweep (app/quick)");
  cli.add_flag("--penalty", o.penalty,
               "Enforce contact by the penalty alone (drops the model's augmented Lagrange keys)");
  cli.add_option("--max-error", o.max_error, "Exit with status 3 if some |rel_error| exceeds this");
  cli.add_flag("--profile", o.profile,
               "Report the time shares: assembly (rod, contact), linear solves");
  cli.add_flag("--verbose,-v", o.verbose, "Print the solver's progress line per step");
  std::string rod_kind = "plain";
  cli.add_option("--rod", rod_kind,
                 "The rope: plain (the torsion-free rod) or torsion (the rod with torsion: GJ from "
                 "the material, else 0.8 EI; its twist held at the pulled end; steps.csv gets the "
                 "friction torque)")
      ->check(CLI::IsMember({"plain", "torsion"}))
      ->capture_default_str();
  if (const int status = parse_command_line(cli, argc, argv); status >= 0) return status;
  o.torsion = rod_kind == "torsion";
  return -1;
}

/// The model as the cases share it: read, overridden (--set, --penalty, --rod torsion) and
/// validated once (an error names the file and the JSON path); where the app's quantities are.
struct RopeModel {
  Json doc;
  Pointers ptr;
};

RopeModel read_rope_model(const RopeApp& ra, const RopeOptions& o) {
  RopeModel m;
  Json& doc = m.doc;
  doc = read_model(o.model_file, false, o.sets);  // --quick is the sweep's own (app/quick)
  if (o.penalty && doc.is_object() && doc.contains("contact") && doc["contact"].is_array())
    for (Json& c : doc["contact"]) {
      if (!c.is_object()) continue;  // reported by the validation below
      c["enforcement"] = "penalty";
      c.erase("penetration_tol");
      c.erase("max_augmentations");
      c.erase("slip_tol");
    }
  if (o.torsion) make_twisting(doc);
  const JsonCursor root(doc, o.model_file);
  if (!root.has("app"))
    root.fail_plain("missing required key \"app\" (the sweep of the " + ra.name + " app)");
  const JsonCursor app = root["app"];
  app.expect_object({"T0", "mu", "phi_deg", "pitch", "centre_radius", "reaction_point", "pull",
                     "max_pull", "sweeps", "quick", "description"});
  m.ptr = Pointers{pointer(app, "T0", doc),
                   pointer(app, "mu", doc),
                   pointer(app, "phi_deg", doc),
                   pointer(app, "pitch", doc),
                   pointer(app, "centre_radius", doc),
                   app["reaction_point"].json(),
                   std::nullopt,
                   0.0};
  Pointers& ptr = m.ptr;
  // T / T0 is the result: T0 = 0 would make every ratio infinite.
  positive_at(doc, o.model_file, ptr.T0, "T0", "the result is T / T0");
  positive_at(doc, o.model_file, ptr.rho, "centre_radius", "the centre line's radius in (83)");
  if (app.has("pull")) {  // a case that reaches t_end without full slip is pulled further
    ptr.pull = pointer(app, "pull", doc);
    const double pull =
        positive_at(doc, o.model_file, *ptr.pull, "pull", "the pulled end's displacement");
    const JsonCursor mp = app["max_pull"];
    ptr.max_pull = mp.as_number();
    if (!(ptr.max_pull >= pull)) mp.fail("must be >= the model's pull " + csv_number(pull));
  }
  doc["output"]["reactions"] = Json::array({ptr.reaction_point});
  (void)Analysis::from_json(doc, o.model_file);  // validates the whole model before any case runs
  return m;
}

/// The case's model: the shared one with the case's mu, phi and pitch.
Json case_model(const RopeModel& m, const Case& c) {
  Json d = m.doc;
  d[m.ptr.mu] = c.mu;
  d[m.ptr.phi_deg] = c.phi_deg;
  d[m.ptr.pitch] = c.pitch;
  return d;
}

/// The cases of the command line's lists (their product), else of the model's sweeps; each
/// case's model validated before the first one runs.
std::vector<Case> rope_cases(RopeOptions o, const RopeModel& m) {
  const Json& doc = m.doc;
  std::vector<Case> cases;
  if (!o.mu_list.empty() || !o.phi_list.empty() || !o.pitch_list.empty()) {
    if (o.mu_list.empty()) o.mu_list = {doc.at(m.ptr.mu).get<double>()};
    if (o.phi_list.empty()) o.phi_list = {doc.at(m.ptr.phi_deg).get<double>()};
    if (o.pitch_list.empty()) o.pitch_list = {doc.at(m.ptr.pitch).get<double>()};
    int k = 0;
    for (double mu : o.mu_list)
      for (double phi : o.phi_list)
        for (double H : o.pitch_list)
          cases.push_back({"c", std::string("c").append(std::to_string(++k)), mu, phi, H});
  } else {
    const JsonCursor app = JsonCursor(doc, o.model_file)["app"];
    cases = sweeps_from(o.quick ? app["quick"] : app["sweeps"], doc, m.ptr);
  }
  if (cases.empty()) throw std::invalid_argument("no cases to run");
  for (const Case& c : cases) (void)Analysis::from_json(case_model(m, c), o.model_file);
  return cases;
}

/// The output folder's tables: one row per case, per converged step, per element at full slip.
struct RopeFiles {
  fs::path dir;
  std::ofstream csv, steps, pressure;
};

void open_files(const RopeApp& ra, const RopeOptions& o, const RopeModel& m, RopeFiles& f) {
  f.dir = fs::path(o.out);
  fs::create_directories(f.dir);
  std::ofstream(f.dir / "model_used.json") << format_json(m.doc) << "\n";
  f.csv.open(f.dir / (ra.name + ".csv"));
  f.steps.open(f.dir / (ra.name + "_steps.csv"));
  f.pressure.open(f.dir / (ra.name + "_pressure.csv"));
  if (!f.csv || !f.steps || !f.pressure) throw std::runtime_error("cannot write to " + o.out);
  // One row per case, failed ones included (status other than full_slip, T_ratio and rel_error
  // empty); csv_number never writes nan or inf.
  f.csv << (ra.pitch_column
                ? "case,sweep,mu,phi,pitch,T_ratio,exact,rel_error,pull,plateau_mean,"
                  "plateau_spread,status\n"
                : "case,sweep,mu,phi,T_ratio,exact,rel_error,pull,plateau_mean,plateau_spread,"
                  "status\n");
  f.steps << "case,mu,phi,pitch,t,T_ratio,active,stick,slip,iterations"
          << (o.torsion ? ",friction_torque\n" : "\n");
  f.pressure << "case,mu,phi,theta,pressure,exact\n";
}

/// Sums over the runs of all cases.
struct Totals {
  double worst = 0.0, t_solver = 0.0, t_assembly = 0.0, t_contact = 0.0, t_linear = 0.0;
  int failed = 0, steps = 0, iterations = 0;
};

/// One case run until the whole arc slides: a run that reaches t_end without full slip is run
/// again with twice the pull, up to app/max_pull.
struct CaseRun {
  std::optional<Analysis> a;
  AnalysisResult r;
  double pull = 0.0;
  double T0 = 0.0, rho = 0.0;  ///< the case's pull at the fixed end and drum radius
  /// The line pressure of the last full_slip_steps steps: the plateau's first one is written.
  std::deque<std::string> recent_pressure;
  std::map<double, double> friction_torque;  ///< per step time (--rod torsion)
};

void run_case(const RopeOptions& o, const RopeModel& m, const Case& c, CaseRun& run,
              Totals& totals) {
  Json d = case_model(m, c);
  const double T0 = d.at(m.ptr.T0).get<double>(), rho = d.at(m.ptr.rho).get<double>();
  run.T0 = T0;
  run.rho = rho;
  const double phi = c.phi_deg * kPi / 180.0;
  run.pull = m.ptr.pull ? d.at(*m.ptr.pull).get<double>() : 0.0;
  for (;;) {
    run.a.emplace(Analysis::from_json(d, o.model_file));
    Analysis& a = *run.a;
    run.recent_pressure.clear();
    run.friction_torque.clear();
    const Json& rope = d.at(m.ptr.phi_deg.parent_pointer());
    auto keep_pressure = [&](const VectorXd&, double t, const AnalysisStep&) {
      const CurveContactPair* rc = a.pair_as<CurveContactPair>();
      if (rc && o.torsion) {  // the friction's moment about the rope's axis, integrated
        double torque = 0.0;
        for (const CurveContactPoint& cp : rc->contact().points()) torque += cp.weight * cp.torque;
        run.friction_torque[t] = torque;
      }
      if (!rc || t <= a.stop_at_full_slip_after()) return true;
      std::ostringstream rows;
      write_pressure_rows(rows, c.name, c.mu, phi, T0, rho, rope, rc->contact(),
                          rc->contact().points_per_element());
      run.recent_pressure.push_back(rows.str());
      if (run.recent_pressure.size() > static_cast<std::size_t>(a.full_slip_steps()))
        run.recent_pressure.pop_front();
      return true;
    };
    run.r = a.run(o.verbose ? &std::cout : nullptr, {}, keep_pressure);
    const AnalysisResult& r = run.r;
    totals.steps += r.solver.steps;
    totals.iterations += r.solver.total_iterations;
    totals.t_solver += r.solver.time_total;
    totals.t_assembly += r.solver.time_assembly;
    totals.t_contact += r.contact_time;
    totals.t_linear += r.solver.time_linear_solve;
    if (r.full_slip || !m.ptr.pull || !r.solver.converged() ||
        2.0 * run.pull > m.ptr.max_pull * (1.0 + 1e-12))
      return;
    std::cout << "  " << c.name << ": no full slip at the pull " << run.pull << ": pulling on to "
              << 2.0 * run.pull << "\n";
    run.pull *= 2.0;
    d[*m.ptr.pull] = run.pull;
  }
}

/// T / T0 over the sliding plateau: the run stops after full_slip_steps consecutive steps of
/// steady sliding (steady_sliding); T / T0 is read at its first step (the onset, before the
/// drift of the discrete rope under sliding), its mean and half range over all of them reported.
struct Plateau {
  std::size_t steps = 0;
  double ratio = 0.0, mean = 0.0, spread = 0.0;
};

Plateau plateau(const CaseRun& run, double T0) {
  Plateau p;
  const std::vector<AnalysisStep>& s = run.r.steps;
  if (!run.r.full_slip || s.empty()) return p;
  p.steps = std::min(s.size(), static_cast<std::size_t>(run.a->full_slip_steps()));
  double lo = 0.0, hi = 0.0;
  for (std::size_t k = s.size() - p.steps; k < s.size(); ++k) {
    const double v = s[k].reactions[0].norm() / T0;
    if (k == s.size() - p.steps) p.ratio = lo = hi = v;
    p.mean += v / static_cast<double>(p.steps);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  p.spread = 0.5 * (hi - lo) / p.mean;
  return p;
}

/// A finished case: its steps' rows, its row of the table, its ParaView files and pressure rows
/// (at full slip), and its line on the console.
void report_case(const RopeApp& ra, const RopeOptions& o, const RopeModel& m, const Case& c,
                 CaseRun& run, RopeFiles& f, Totals& totals) {
  const AnalysisResult& r = run.r;
  const double T0 = run.T0, rho = run.rho;
  const double phi = c.phi_deg * kPi / 180.0, cH = c.pitch / (2.0 * kPi);
  const double exact = std::exp(c.mu * phi * rho / std::sqrt(rho * rho + cH * cH));  // (83)
  for (const AnalysisStep& s : r.steps)
    f.steps << c.name << "," << csv_number(c.mu, 10) << "," << csv_number(phi, 10) << ","
            << csv_number(c.pitch, 10) << "," << csv_number(s.t, 10) << ","
            << csv_number(s.reactions[0].norm() / T0, 10) << "," << s.contact.active << ","
            << s.contact.stick << "," << s.contact.slip << "," << s.iterations
            << (o.torsion
                    ? "," + csv_number(
                                run.friction_torque.count(s.t) ? run.friction_torque[s.t] : 0.0, 10)
                    : std::string())
            << "\n";
  f.steps.flush();
  const bool ok = r.full_slip && !r.steps.empty();
  const Plateau p = plateau(run, T0);
  const double rel = p.ratio / exact - 1.0;
  const std::string status = ok                     ? "full_slip"
                             : r.solver.converged() ? "no_full_slip"
                                                    : to_string(r.solver.status);
  f.csv << c.name << "," << c.sweep << "," << csv_number(c.mu, 10) << "," << csv_number(phi, 10)
        << ",";
  if (ra.pitch_column) f.csv << csv_number(c.pitch, 10) << ",";
  f.csv << (ok ? csv_number(p.ratio, 10) : "") << "," << csv_number(exact, 10) << ","
        << (ok ? csv_number(rel, 10) : "") << "," << (m.ptr.pull ? csv_number(run.pull, 10) : "")
        << "," << (ok ? csv_number(p.mean, 10) : "") << "," << (ok ? csv_number(p.spread, 10) : "")
        << "," << status << std::endl;
  if (!ok) {
    ++totals.failed;
    std::cout << "  " << c.name << ": mu " << c.mu << " phi " << c.phi_deg << " deg pitch "
              << c.pitch << ": no full slip reached (" << status << ": " << r.solver.message;
    if (m.ptr.pull && r.solver.converged())
      std::cout << "; pulled up to " << run.pull << ", the limit app/max_pull is "
                << m.ptr.max_pull;
    std::cout << ")\n";
    return;
  }
  totals.worst = std::max(totals.worst, std::abs(rel));
  run.a->write_vtk(f.dir.string(), c.name, r.u, r.solver.t);
  if (p.steps > 0 && run.recent_pressure.size() == p.steps)
    f.pressure << run.recent_pressure.front();
  f.pressure.flush();
  std::cout << "  " << std::left << std::setw(4) << c.name << " mu " << std::setw(5) << c.mu
            << " phi " << std::setw(5) << c.phi_deg << " deg";
  if (ra.pitch_column) std::cout << " pitch " << std::setw(5) << c.pitch;
  std::cout << "   T/T0 " << std::setw(10) << p.ratio << " exact " << std::setw(10) << exact
            << " rel_error " << std::showpos << rel << std::noshowpos << "   plateau spread "
            << p.spread << " over " << p.steps << " steps, steps " << r.solver.steps << ", Newton "
            << r.solver.total_iterations << "\n";
}

/// The plots, the summary line and the profile; the exit status.
int finish(const RopeApp& ra, const RopeOptions& o, const RopeFiles& f, std::size_t cases,
           const Totals& totals, double secs) {
  const std::string table = (f.dir / (ra.name + ".csv")).string();
  if (!run_python(ra.plot_script, {table, (f.dir / (ra.name + ".png")).string()}))
    std::cout << ra.name << ": warning: the plot failed (" << ra.plot_script << " " << table
              << ")\n";
  const std::string pscript =
      (fs::path(ra.plot_script).parent_path() / "plot_pressure.py").string();
  const std::string pcsv = (f.dir / (ra.name + "_pressure.csv")).string();
  if (!run_python(pscript, {pcsv, (f.dir / (ra.name + "_pressure.png")).string()}))
    std::cout << ra.name << ": warning: the pressure plot failed (" << pscript << " " << pcsv
              << ")\n";
  std::cout << ra.name << ": " << cases - static_cast<std::size_t>(totals.failed) << "/" << cases
            << " cases, max |rel_error| " << totals.worst << ", " << totals.steps << " steps, "
            << static_cast<double>(totals.iterations) / std::max(totals.steps, 1)
            << " Newton iterations per step, " << secs << " s; results in " << f.dir.string()
            << "\n";
  if (o.profile && totals.t_solver > 0.0) {
    const double ts = totals.t_solver;
    std::cout << ra.name << ": profile: solver " << ts << " s = assembly "
              << 100 * totals.t_assembly / ts << " % (of which contact "
              << 100 * totals.t_contact / ts << " %, rod and loads "
              << 100 * (totals.t_assembly - totals.t_contact) / ts << " %), linear solves "
              << 100 * totals.t_linear / ts << " %, other "
              << 100 * (ts - totals.t_assembly - totals.t_linear) / ts << " %\n";
  }
  if (totals.failed > 0) return 2;
  if (o.max_error >= 0.0 && totals.worst > o.max_error) {
    std::cout << ra.name << ": max |rel_error| " << totals.worst << " exceeds --max-error "
              << o.max_error << "\n";
    return 3;
  }
  return 0;
}

}  // namespace

int run_rope_app(const RopeApp& ra, int argc, char** argv) {
  RopeOptions o;
  if (const int status = parse_options(ra, argc, argv, o); status >= 0) return status;
  const RopeModel m = read_rope_model(ra, o);
  const std::vector<Case> cases = rope_cases(o, m);
  RopeFiles files;
  open_files(ra, o, m, files);
  // Each case; rows are written as they finish (a failure keeps what is done).
  const auto t_start = std::chrono::steady_clock::now();
  Totals totals;
  std::cout << ra.name << ": " << cases.size() << " cases from " << o.model_file << "\n";
  for (const Case& c : cases) {
    CaseRun run;
    run_case(o, m, c, run, totals);
    report_case(ra, o, m, c, run, files, totals);
  }
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return finish(ra, o, files, cases.size(), totals, secs);
}

}  // namespace iga::app
