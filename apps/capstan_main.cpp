// capstan: the Euler-Eytelwein belt friction example of [KS15] Sect. 6.3 (Figs. 11-12): a
// Kirchhoff rod (rope) wrapped over a rigid cylinder (exact NURBS patch or analytic), one end
// under a dead load T0, the other pulled until the whole contact arc slides; T / T0 at that
// point against exp(mu phi) (82).
//
//   capstan                                    the sweeps of data/capstan.json
//   capstan --quick                            a reduced sweep (a CTest test)
//   capstan --mu 0,0.5,1 --phi-deg 180         one sweep over the given lists
//   capstan --set /cylinder/representation=\"analytic\" --set /rope/arc_elements=20
//   capstan MODEL.json --out DIR --max-error 0.005
//   capstan --profile                          time shares: assembly, contact, linear solves
//
// Writes to --out (default out/capstan): capstan.csv (case,mu,phi,T_ratio,exact,rel_error),
// capstan_steps.csv (every converged step), model_used.json, capstan.png (plot), and for each
// case rope_<case><k>.vtk (centre line with axial force and curvature) and
// contact_<case><k>.vtk (contact points with N, T, B, slip) for ParaView.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <sstream>

#include <CLI/CLI.hpp>

#include "geometry/json_reader.hpp"
#include "iga/capstan.hpp"
#include "iga/vtk_writer.hpp"

namespace fs = std::filesystem;
using namespace iga;

namespace {

struct Case {
  std::string sweep;  // "a", "b" (the model's sweeps) or "c" (--mu / --phi-deg): the CSV case
  std::string name;   // "a3": sweep a, third case (file names)
  double mu = 0.0, phi = 0.0;
};

// --set /json/pointer=value: the value is JSON (a number, "string", [list]); the pointer must
// name an existing entry so that a typo is an error, not a silently ignored key.
void apply_set(Json& model, const std::string& file, const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || assignment.empty() || assignment[0] != '/')
    throw std::invalid_argument("--set expects /json/pointer=value, got '" + assignment + "'");
  const JsonPointer ptr(assignment.substr(0, eq));
  if (!model.contains(ptr))
    throw ModelError(file, ptr.to_string(), "--set names no existing entry");
  const std::string text = assignment.substr(eq + 1);
  model[ptr] = parse_json_text(text, "--set " + assignment.substr(0, eq));
}

std::vector<double> numbers(const JsonCursor& c) { return c.as_numbers(); }

// A number that must be > 0 (or >= 0 with allow_zero), checked at its JSON path.
double positive(const JsonCursor& c, bool allow_zero = false) {
  const double x = c.as_number();
  if (allow_zero ? x < 0.0 : x <= 0.0) c.fail(allow_zero ? "must be >= 0" : "must be > 0");
  return x;
}
int positive_int(const JsonCursor& c) {
  const int n = c.as_int();
  if (n < 1) c.fail("must be >= 1");
  return n;
}

CapstanParameters parameters_from(const JsonCursor& m) {
  CapstanParameters p;
  const JsonCursor cyl = m["cylinder"];
  cyl.expect_object({"radius", "representation"});
  p.radius = positive(cyl["radius"]);
  const std::string rep = cyl["representation"].as_string();
  if (rep != "nurbs" && rep != "analytic")
    cyl["representation"].fail("expected \"nurbs\" or \"analytic\"");
  p.nurbs_cylinder = rep == "nurbs";
  const JsonCursor rope = m["rope"];
  rope.expect_object({"EA", "EI", "radius", "span_length", "arc_elements", "span_elements"});
  p.EA = positive(rope["EA"]);
  p.EI = positive(rope["EI"]);
  p.rope_radius = positive(rope["radius"], true);
  p.span_length = positive(rope["span_length"]);
  p.arc_elements = positive_int(rope["arc_elements"]);
  p.span_elements = positive_int(rope["span_elements"]);
  const JsonCursor con = m["contact"];
  con.expect_object({"eps_N", "eps_T", "points_per_element"});
  p.eps_N = positive(con["eps_N"]);
  p.eps_T = positive(con["eps_T"], true);
  p.contact_points = positive_int(con["points_per_element"]);
  const JsonCursor load = m["loading"];
  load.expect_object({"T0", "pull"});
  p.T0 = positive(load["T0"]);
  p.pull = positive(load["pull"]);
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    m.fail_plain(e.what());
  }
  return p;
}

std::vector<Case> sweeps_from(const JsonCursor& s) {
  std::vector<Case> cases;
  for (const std::string& name : {std::string("a"), std::string("b")}) {
    if (!s.has(name)) continue;
    const JsonCursor c = s[name];
    c.expect_object({"mu", "phi_deg"});
    int k = 0;
    for (double mu : numbers(c["mu"]))
      for (double phi : numbers(c["phi_deg"]))
        cases.push_back({name, name + std::to_string(++k), mu, phi * std::numbers::pi / 180.0});
  }
  return cases;
}

void write_vtk(const fs::path& dir, const Case& c, CapstanModel& model, const CapstanResult& r) {
  const KirchhoffRod& rod = model.problem.rod();
  std::vector<Vector3d> x = model.problem.current_points(r.u, r.solver.t);
  std::vector<Vector3d> line;
  VtkPointData d;
  std::vector<double> force, curvature;
  const Interval I = rod.reference().domain();
  for (int k = 0; k <= 400; ++k) {
    const double xi = I.lo + (I.hi - I.lo) * k / 400.0;
    line.push_back(rod.point(xi, x));
    const RodStrains s = rod.strains(xi, x);
    force.push_back(s.axial_force);
    curvature.push_back(s.curvature);
  }
  d.scalars = {{"axial_force", force}, {"curvature", curvature}};
  write_vtk_polydata((dir / ("rope_" + c.name + ".vtk")).string(), line, true, d, "capstan rope " + c.name);
  std::vector<Vector3d> pts;
  std::vector<double> N, T, B, slip;
  for (const CurveContactPoint& cp : model.problem.contact().points()) {
    if (!cp.law.active) continue;
    pts.push_back(cp.x);
    N.push_back(cp.N);
    T.push_back(cp.T);
    B.push_back(cp.B);
    slip.push_back(cp.law.slip ? 1.0 : 0.0);
  }
  VtkPointData cd;
  cd.scalars = {{"N", N}, {"T", T}, {"B", B}, {"slip", slip}};
  write_vtk_polydata((dir / ("contact_" + c.name + ".vtk")).string(), pts, false, cd, "capstan contact " + c.name);
}

int run(int argc, char** argv) {
  // 1. Arguments.
  CLI::App app{"capstan: rope on a rigid cylinder, T/T0 against exp(mu phi) ([KS15] Sect. 6.3)"};
  std::string model_file = std::string(IGA_SOURCE_DIR) + "/data/capstan.json";
  std::vector<double> mu_list, phi_list;
  std::vector<std::string> sets;
  std::string out = "out/capstan";
  bool quick = false, profile = false;
  double max_error = -1.0;
  app.add_option("model", model_file, "Model file (JSON)")->capture_default_str();
  app.add_option("--mu", mu_list, "Friction coefficients (a list: 0,0.5,1)")->delimiter(',');
  app.add_option("--phi-deg", phi_list, "Wrap angles in degrees (a list)")->delimiter(',');
  app.add_option("--set", sets, "Override a model value: /json/pointer=value (repeatable)");
  app.add_option("--out,-o", out, "Output folder")->capture_default_str();
  app.add_flag("--quick", quick, "Run the model's reduced sweep (\"quick\")");
  app.add_option("--max-error", max_error, "Exit with status 3 if some |rel_error| exceeds this");
  app.add_flag("--profile", profile, "Report the time shares: assembly (rod, contact), linear solves");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  // 2. Model: read, override, validate.
  Json j = read_json_file(model_file);
  for (const std::string& s : sets) apply_set(j, model_file, s);
  const JsonCursor m(j, model_file);
  m.expect_object({"format", "version", "description", "cylinder", "rope", "contact", "loading", "sweeps", "quick"});
  if (m["format"].as_string() != "iga-capstan") m["format"].fail("expected \"iga-capstan\"");
  const CapstanParameters base = parameters_from(m);
  std::vector<Case> cases;
  if (!mu_list.empty() || !phi_list.empty()) {
    if (mu_list.empty()) mu_list = {base.mu};
    if (phi_list.empty()) phi_list = {180.0};
    int k = 0;
    for (double mu : mu_list)
      for (double phi : phi_list)
        cases.push_back({"c", "c" + std::to_string(++k), mu, phi * std::numbers::pi / 180.0});
  } else {
    cases = sweeps_from(quick ? m["quick"] : m["sweeps"]);
  }
  if (cases.empty()) throw std::invalid_argument("no cases to run");

  // 3. Output folder and the model used.
  const fs::path dir(out);
  fs::create_directories(dir);
  std::ofstream(dir / "model_used.json") << format_json(j) << "\n";
  std::ofstream csv(dir / "capstan.csv"), steps(dir / "capstan_steps.csv");
  if (!csv || !steps) throw std::runtime_error("cannot write to " + out);
  csv << "case,mu,phi,T_ratio,exact,rel_error\n" << std::setprecision(10);
  steps << "case,mu,phi,t,T_ratio,active,stick,slip,iterations\n" << std::setprecision(10);

  // 4. Solve each case; rows are written as they finish (a failure keeps what is done).
  const auto t0 = std::chrono::steady_clock::now();
  double worst = 0.0, max_strain = 0.0;
  double t_solver = 0.0, t_assembly = 0.0, t_contact = 0.0, t_linear = 0.0;
  int failed = 0, steps_total = 0, iterations_total = 0;
  std::cout << "capstan: " << cases.size() << " cases from " << model_file << "\n";
  for (const Case& c : cases) {
    CapstanParameters p = base;
    p.mu = c.mu;
    p.phi = c.phi;
    CapstanModel model = make_capstan(p);
    const CapstanResult r = run_capstan(model);
    steps_total += r.solver.steps;
    iterations_total += r.solver.total_iterations;
    t_solver += r.solver.time_total;
    t_assembly += r.solver.time_assembly;
    t_contact += model.problem.contact_time();
    t_linear += r.solver.time_linear_solve;
    for (const CapstanStep& s : r.steps)
      steps << c.name << "," << c.mu << "," << c.phi << "," << s.t << "," << s.T_ratio << ","
            << s.active << "," << s.stick << "," << s.slip << "," << s.iterations << "\n";
    if (!r.full_slip) {
      ++failed;
      std::cout << "  " << c.name << ": mu " << c.mu << " phi " << c.phi * 180 / std::numbers::pi
                << " deg: no full slip reached (" << to_string(r.solver.status) << ": "
                << r.solver.message << ")\n";
      continue;
    }
    csv << c.sweep << "," << c.mu << "," << c.phi << "," << r.T_ratio << "," << r.exact << ","
        << r.rel_error() << std::endl;
    worst = std::max(worst, std::abs(r.rel_error()));
    max_strain = std::max(max_strain, r.max_axial_strain);
    write_vtk(dir, c, model, r);
    std::cout << "  " << std::left << std::setw(4) << c.name << " mu " << std::setw(5) << c.mu
              << " phi " << std::setw(5) << std::lround(c.phi * 180 / std::numbers::pi)
              << " deg   T/T0 " << std::setw(10) << r.T_ratio << " exact " << std::setw(10)
              << r.exact << " rel_error " << std::showpos << r.rel_error() << std::noshowpos
              << "   steps " << r.solver.steps << ", Newton " << r.solver.total_iterations << "\n";
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // 5. Plot and summary.
  const std::string script = std::string(IGA_SOURCE_DIR) + "/scripts/plot_capstan.py";
  const std::string cmd = "/usr/bin/python3 \"" + script + "\" \"" + (dir / "capstan.csv").string() +
                          "\" \"" + (dir / "capstan.png").string() + "\" 2>&1";
  if (std::system(cmd.c_str()) != 0) std::cout << "capstan: warning: the plot failed (" << cmd << ")\n";
  std::cout << "capstan: " << cases.size() - failed << "/" << cases.size() << " cases, max |rel_error| "
            << worst << ", largest axial strain " << max_strain << ", " << steps_total << " steps, "
            << static_cast<double>(iterations_total) / std::max(steps_total, 1) << " Newton iterations per step, "
            << secs << " s; results in " << dir.string() << "\n";
  if (profile && t_solver > 0.0)
    std::cout << "capstan: profile: solver " << t_solver << " s = assembly " << 100 * t_assembly / t_solver
              << " % (of which contact " << 100 * t_contact / t_solver << " %, rod and loads "
              << 100 * (t_assembly - t_contact) / t_solver << " %), linear solves "
              << 100 * t_linear / t_solver << " %, other " << 100 * (t_solver - t_assembly - t_linear) / t_solver
              << " %\n";
  if (failed > 0) return 2;
  if (max_error >= 0.0 && worst > max_error) {
    std::cout << "capstan: max |rel_error| " << worst << " exceeds --max-error " << max_error << "\n";
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "capstan: error: " << e.what() << "\n";
    return 1;
  }
}
