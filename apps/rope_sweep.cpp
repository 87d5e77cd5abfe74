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
  const JsonPointer p = model_pointer(c, doc);
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

}  // namespace

int run_rope_app(const RopeApp& ra, int argc, char** argv) {
  // 1. Arguments.
  CLI::App cli{ra.title};
  std::string model_file = ra.default_model;
  std::vector<double> mu_list, phi_list, pitch_list;
  std::vector<std::string> sets;
  std::string out = std::string("out/").append(ra.name);
  bool quick = false, profile = false, verbose = false, penalty = false;
  double max_error = -1.0;
  cli.add_option("model", model_file, "Model file (JSON, format iga-contact-model)")
      ->capture_default_str();
  cli.add_option("--mu", mu_list, "Friction coefficients (a list: 0,0.5,1)")->delimiter(',');
  cli.add_option("--phi-deg", phi_list, "Wrap angles in degrees (a list)")->delimiter(',');
  cli.add_option("--pitch", pitch_list, "Helix pitches H, rise per turn (a list)")->delimiter(',');
  cli.add_option("--set", sets, "Override a model value: /json/pointer=value (repeatable)");
  cli.add_option("--out,-o", out, "Output folder")->capture_default_str();
  cli.add_flag("--quick", quick, "Run the model's reduced sweep (app/quick)");
  cli.add_flag("--penalty", penalty,
               "Enforce contact by the penalty alone (drops the model's augmented Lagrange keys)");
  cli.add_option("--max-error", max_error, "Exit with status 3 if some |rel_error| exceeds this");
  cli.add_flag("--profile", profile,
               "Report the time shares: assembly (rod, contact), linear solves");
  cli.add_flag("--verbose,-v", verbose, "Print the solver's progress line per step");
  std::string rod_kind = "plain";
  cli.add_option("--rod", rod_kind,
                 "The rope: plain (the torsion-free rod) or torsion (the rod with torsion: GJ from "
                 "the material, else 0.8 EI; its twist held at the pulled end; steps.csv gets the "
                 "friction torque)")
      ->check(CLI::IsMember({"plain", "torsion"}))
      ->capture_default_str();
  if (const int status = parse_command_line(cli, argc, argv); status >= 0) return status;
  const bool torsion = rod_kind == "torsion";

  // 2. Model: read, override, validate once (an error names the file and the JSON path).
  Json doc = read_model(model_file, false, sets);  // --quick is the sweep's own (app/quick)
  if (penalty && doc.is_object() && doc.contains("contact") && doc["contact"].is_array())
    for (Json& c : doc["contact"]) {
      if (!c.is_object()) continue;  // reported by the validation below
      c["enforcement"] = "penalty";
      c.erase("penetration_tol");
      c.erase("max_augmentations");
      c.erase("slip_tol");
    }
  if (torsion) make_twisting(doc);
  const JsonCursor root(doc, model_file);
  if (!root.has("app"))
    root.fail_plain("missing required key \"app\" (the sweep of the " + ra.name + " app)");
  const JsonCursor app = root["app"];
  app.expect_object({"T0", "mu", "phi_deg", "pitch", "centre_radius", "reaction_point", "pull",
                     "max_pull", "sweeps", "quick", "description"});
  Pointers ptr{pointer(app, "T0", doc),
               pointer(app, "mu", doc),
               pointer(app, "phi_deg", doc),
               pointer(app, "pitch", doc),
               pointer(app, "centre_radius", doc),
               app["reaction_point"].json(),
               std::nullopt,
               0.0};
  // T / T0 is the result: T0 = 0 would make every ratio infinite.
  positive_at(doc, model_file, ptr.T0, "T0", "the result is T / T0");
  positive_at(doc, model_file, ptr.rho, "centre_radius", "the centre line's radius in (83)");
  if (app.has("pull")) {  // a case that reaches t_end without full slip is pulled further
    ptr.pull = pointer(app, "pull", doc);
    const double pull =
        positive_at(doc, model_file, *ptr.pull, "pull", "the pulled end's displacement");
    const JsonCursor m = app["max_pull"];
    ptr.max_pull = m.as_number();
    if (!(ptr.max_pull >= pull)) m.fail("must be >= the model's pull " + csv_number(pull));
  }
  doc["output"]["reactions"] = Json::array({ptr.reaction_point});
  (void)Analysis::from_json(doc, model_file);  // validates the whole model before any case runs

  std::vector<Case> cases;
  if (!mu_list.empty() || !phi_list.empty() || !pitch_list.empty()) {
    if (mu_list.empty()) mu_list = {doc.at(ptr.mu).get<double>()};
    if (phi_list.empty()) phi_list = {doc.at(ptr.phi_deg).get<double>()};
    if (pitch_list.empty()) pitch_list = {doc.at(ptr.pitch).get<double>()};
    int k = 0;
    for (double mu : mu_list)
      for (double phi : phi_list)
        for (double H : pitch_list)
          cases.push_back({"c", std::string("c").append(std::to_string(++k)), mu, phi, H});
  } else {
    cases = sweeps_from(quick ? app["quick"] : app["sweeps"], doc, ptr);
  }
  if (cases.empty()) throw std::invalid_argument("no cases to run");
  for (const Case& c : cases) {  // every case is valid before the first one runs
    Json d = doc;
    d[ptr.mu] = c.mu;
    d[ptr.phi_deg] = c.phi_deg;
    d[ptr.pitch] = c.pitch;
    (void)Analysis::from_json(d, model_file);
  }

  // 3. Output folder and the model used.
  const fs::path dir(out);
  fs::create_directories(dir);
  std::ofstream(dir / "model_used.json") << format_json(doc) << "\n";
  std::ofstream csv(dir / (ra.name + ".csv")), steps(dir / (ra.name + "_steps.csv"));
  if (!csv || !steps) throw std::runtime_error("cannot write to " + out);
  // One row per case, failed ones included (status other than full_slip, T_ratio and rel_error
  // empty); csv_number never writes nan or inf.
  csv << (ra.pitch_column
              ? "case,sweep,mu,phi,pitch,T_ratio,exact,rel_error,pull,plateau_mean,"
                "plateau_spread,status\n"
              : "case,sweep,mu,phi,T_ratio,exact,rel_error,pull,plateau_mean,plateau_spread,"
                "status\n");
  steps << "case,mu,phi,pitch,t,T_ratio,active,stick,slip,iterations"
        << (torsion ? ",friction_torque\n" : "\n");
  std::ofstream pressure(dir / (ra.name + "_pressure.csv"));
  if (!pressure) throw std::runtime_error("cannot write to " + out);
  pressure << "case,mu,phi,theta,pressure,exact\n";

  // 4. Each case; rows are written as they finish (a failure keeps what is done).
  const auto t_start = std::chrono::steady_clock::now();
  double worst = 0.0, t_solver = 0.0, t_assembly = 0.0, t_contact = 0.0, t_linear = 0.0;
  int failed = 0, steps_total = 0, iterations_total = 0;
  std::cout << ra.name << ": " << cases.size() << " cases from " << model_file << "\n";
  for (const Case& c : cases) {
    Json d = doc;
    d[ptr.mu] = c.mu;
    d[ptr.phi_deg] = c.phi_deg;
    d[ptr.pitch] = c.pitch;
    const double T0 = d.at(ptr.T0).get<double>(), rho = d.at(ptr.rho).get<double>();
    const double phi = c.phi_deg * kPi / 180.0, cH = c.pitch / (2.0 * kPi);
    const double exact = std::exp(c.mu * phi * rho / std::sqrt(rho * rho + cH * cH));  // (83)
    // Pull until the whole arc slides: a case that reaches t_end without full slip is run again
    // with twice the pull, up to app/max_pull.
    double pull = ptr.pull ? d.at(*ptr.pull).get<double>() : 0.0;
    std::optional<Analysis> a;
    AnalysisResult r;
    // The line pressure of the last full_slip_steps steps: the plateau's first one is written.
    std::deque<std::string> recent_pressure;
    std::map<double, double> friction_torque;  // per step time (--rod torsion)
    for (;;) {
      a.emplace(Analysis::from_json(d, model_file));
      recent_pressure.clear();
      const Json& rope = d.at(ptr.phi_deg.parent_pointer());
      friction_torque.clear();
      auto keep_pressure = [&](const VectorXd&, double t, const AnalysisStep&) {
        const CurveContactPair* rc = a->rod_contact();
        if (rc && torsion) {  // the friction's moment about the rope's axis, integrated
          double m = 0.0;
          for (const CurveContactPoint& cp : rc->contact().points()) m += cp.weight * cp.torque;
          friction_torque[t] = m;
        }
        if (!rc || t <= a->stop_at_full_slip_after()) return true;
        std::ostringstream rows;
        write_pressure_rows(rows, c.name, c.mu, phi, T0, rho, rope, rc->contact(),
                            rc->contact().points_per_element());
        recent_pressure.push_back(rows.str());
        if (recent_pressure.size() > static_cast<std::size_t>(a->full_slip_steps()))
          recent_pressure.pop_front();
        return true;
      };
      r = a->run(verbose ? &std::cout : nullptr, {}, keep_pressure);
      steps_total += r.solver.steps;
      iterations_total += r.solver.total_iterations;
      t_solver += r.solver.time_total;
      t_assembly += r.solver.time_assembly;
      t_contact += r.contact_time;
      t_linear += r.solver.time_linear_solve;
      if (r.full_slip || !ptr.pull || !r.solver.converged() ||
          2.0 * pull > ptr.max_pull * (1.0 + 1e-12))
        break;
      std::cout << "  " << c.name << ": no full slip at the pull " << pull << ": pulling on to "
                << 2.0 * pull << "\n";
      pull *= 2.0;
      d[*ptr.pull] = pull;
    }
    for (const AnalysisStep& s : r.steps)
      steps << c.name << "," << csv_number(c.mu, 10) << "," << csv_number(phi, 10) << ","
            << csv_number(c.pitch, 10) << "," << csv_number(s.t, 10) << ","
            << csv_number(s.reactions[0].norm() / T0, 10) << "," << s.contact.active << ","
            << s.contact.stick << "," << s.contact.slip << "," << s.iterations
            << (torsion
                    ? "," + csv_number(friction_torque.count(s.t) ? friction_torque[s.t] : 0.0, 10)
                    : std::string())
            << "\n";
    steps.flush();
    const bool ok = r.full_slip && !r.steps.empty();
    // The sliding plateau: the run stops after full_slip_steps consecutive steps of steady
    // sliding (steady_sliding); T / T0 is read at its first step (the onset, before the drift
    // of the discrete rope under sliding), its mean and half range over all of them reported.
    const std::size_t n_plateau =
        ok ? std::min(r.steps.size(), static_cast<std::size_t>(a->full_slip_steps())) : 0;
    double T_ratio = 0.0, plateau_mean = 0.0, plateau_lo = 0.0, plateau_hi = 0.0;
    for (std::size_t k = r.steps.size() - n_plateau; k < r.steps.size(); ++k) {
      const double v = r.steps[k].reactions[0].norm() / T0;
      if (k == r.steps.size() - n_plateau) T_ratio = plateau_lo = plateau_hi = v;
      plateau_mean += v / static_cast<double>(n_plateau);
      plateau_lo = std::min(plateau_lo, v);
      plateau_hi = std::max(plateau_hi, v);
    }
    const double rel = T_ratio / exact - 1.0;
    const double spread = ok ? 0.5 * (plateau_hi - plateau_lo) / plateau_mean : 0.0;
    std::string status = ok                     ? "full_slip"
                         : r.solver.converged() ? "no_full_slip"
                                                : to_string(r.solver.status);
    csv << c.name << "," << c.sweep << "," << csv_number(c.mu, 10) << "," << csv_number(phi, 10)
        << ",";
    if (ra.pitch_column) csv << csv_number(c.pitch, 10) << ",";
    csv << (ok ? csv_number(T_ratio, 10) : "") << "," << csv_number(exact, 10) << ","
        << (ok ? csv_number(rel, 10) : "") << "," << (ptr.pull ? csv_number(pull, 10) : "") << ","
        << (ok ? csv_number(plateau_mean, 10) : "") << "," << (ok ? csv_number(spread, 10) : "")
        << "," << status << std::endl;
    if (!ok) {
      ++failed;
      std::cout << "  " << c.name << ": mu " << c.mu << " phi " << c.phi_deg << " deg pitch "
                << c.pitch << ": no full slip reached (" << status << ": " << r.solver.message;
      if (ptr.pull && r.solver.converged())
        std::cout << "; pulled up to " << pull << ", the limit app/max_pull is " << ptr.max_pull;
      std::cout << ")\n";
      continue;
    }
    worst = std::max(worst, std::abs(rel));
    a->write_vtk(dir.string(), c.name, r.u, r.solver.t);
    if (n_plateau > 0 && recent_pressure.size() == n_plateau) pressure << recent_pressure.front();
    pressure.flush();
    std::cout << "  " << std::left << std::setw(4) << c.name << " mu " << std::setw(5) << c.mu
              << " phi " << std::setw(5) << c.phi_deg << " deg";
    if (ra.pitch_column) std::cout << " pitch " << std::setw(5) << c.pitch;
    std::cout << "   T/T0 " << std::setw(10) << T_ratio << " exact " << std::setw(10) << exact
              << " rel_error " << std::showpos << rel << std::noshowpos << "   plateau spread "
              << spread << " over " << n_plateau << " steps, steps " << r.solver.steps
              << ", Newton " << r.solver.total_iterations << "\n";
  }
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

  // 5. Plot and summary.
  const std::string table = (dir / (ra.name + ".csv")).string();
  if (!run_python(ra.plot_script, {table, (dir / (ra.name + ".png")).string()}))
    std::cout << ra.name << ": warning: the plot failed (" << ra.plot_script << " " << table
              << ")\n";
  const std::string pscript =
      (fs::path(ra.plot_script).parent_path() / "plot_pressure.py").string();
  const std::string pcsv = (dir / (ra.name + "_pressure.csv")).string();
  if (!run_python(pscript, {pcsv, (dir / (ra.name + "_pressure.png")).string()}))
    std::cout << ra.name << ": warning: the pressure plot failed (" << pscript << " " << pcsv
              << ")\n";
  std::cout << ra.name << ": " << cases.size() - failed << "/" << cases.size()
            << " cases, max |rel_error| " << worst << ", " << steps_total << " steps, "
            << static_cast<double>(iterations_total) / std::max(steps_total, 1)
            << " Newton iterations per step, " << secs << " s; results in " << dir.string() << "\n";
  if (profile && t_solver > 0.0)
    std::cout << ra.name << ": profile: solver " << t_solver << " s = assembly "
              << 100 * t_assembly / t_solver << " % (of which contact "
              << 100 * t_contact / t_solver << " %, rod and loads "
              << 100 * (t_assembly - t_contact) / t_solver << " %), linear solves "
              << 100 * t_linear / t_solver << " %, other "
              << 100 * (t_solver - t_assembly - t_linear) / t_solver << " %\n";
  if (failed > 0) return 2;
  if (max_error >= 0.0 && worst > max_error) {
    std::cout << ra.name << ": max |rel_error| " << worst << " exceeds --max-error " << max_error
              << "\n";
    return 3;
  }
  return 0;
}

}  // namespace iga::app
