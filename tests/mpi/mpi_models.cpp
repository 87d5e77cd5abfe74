// Run by the suite under mpirun on 2 and 3 ranks (tests/CMakeLists.txt): models of data/
// spread over the ranks (Analysis::from_json with world(): shells cut into blocks of
// elements, rods whole on a rank) against the same models run on one process (rank 0, the
// serial communicator). Issue 36's must-hold, at every common time (both runs take the same
// steps here: the round-off probe is off, and nothing but the order of sums differs):
//  - t, the tool forces and moments, the reactions and the monitored displacements within
//    1e-8 of their scale (the largest magnitude of the quantity over the run; for a moment,
//    plus the largest force times the bodies' size, its round-off's lever);
//  - active, stick and slip counts (of all pairs and of each) within 1 %;
//  - the end time and the number of steps the same, the status converged (or the sliding
//    plateau reached) in both.
// And the output: the same files in both output folders (the spread run's bodies and contact
// points as parallel collections, .pvts / .pvtu, of one piece per rank at most: a shell's blocks,
// a rod from the rank that owns it, contact points from every rank that has some), the fields
// of every VTK XML file (collections joined from their pieces) within 1e-8
// of each array's largest value (of the file's, for an array that is round-off beside it), but for
// the contact state (0, 1, 2), which must match; a restart of the spread run from its own restart
// files (one per rank) ends where the whole run does; the serial analysis refuses those files
// (another process count). Exit 0 on every rank when all hold. Usage: mpi_models <output folder>
// <model.json> [--set /pointer=value]... [--as NAME] ...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/json_reader.hpp"
#include "iga/core/control_point_problem.hpp"
#include "iga/model/analysis.hpp"
#include "iga/parallel/communicator.hpp"
#include "iga/solvers/roundoff_probe.hpp"
#include "tests/support/vtk_xml_read.hpp"

namespace {

namespace fs = std::filesystem;
using iga::AnalysisResult;
using iga::AnalysisStep;
using iga::Vector3d;

struct Checker {
  int errors = 0;
  std::string model;
  void expect(bool ok, const std::string& what) {
    if (ok) return;
    std::fprintf(stderr, "[rank %d] %s: %s\n", iga::world().rank(), model.c_str(), what.c_str());
    ++errors;
  }
};

// The largest |v| over the steps, of the vectors `get` picks from a step.
template <class Get>
double scale_of(const std::vector<AnalysisStep>& steps, std::size_t n, Get get) {
  std::vector<double> s(n, 0.0);
  for (const AnalysisStep& st : steps)
    for (std::size_t k = 0; k < n; ++k) s[k] = std::max(s[k], get(st, k).norm());
  return n == 0 ? 0.0 : *std::max_element(s.begin(), s.end());
}

// The size of the bodies: the diagonal of their reference control points' box.
double model_size(iga::Analysis& a) {
  Eigen::AlignedBox3d box;
  for (int b = 0; b < a.num_bodies(); ++b)
    if (auto* p = dynamic_cast<iga::ControlPointProblem*>(&a.body(b)))
      for (int i = 0; i < p->num_control_points(); ++i) box.extend(p->reference_point(i));
  return box.isEmpty() ? 1.0 : box.diagonal().norm();
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

bool counts_close(int a, int b) {
  return std::abs(a - b) <= 0.01 * std::max(a, b);
}

void compare_steps(Checker& c, const AnalysisResult& whole, const AnalysisResult& spread,
                   double size, double span) {
  const std::vector<AnalysisStep>& s = whole.steps;
  const std::vector<AnalysisStep>& d = spread.steps;
  c.expect(whole.solver.status == spread.solver.status,
           "status " + std::string(to_string(whole.solver.status)) + " on one process, " +
               to_string(spread.solver.status) + " spread");
  c.expect(whole.solver.converged() || whole.full_slip,
           "the run on one process: " + whole.solver.message);
  c.expect(s.size() == d.size() && !s.empty(), "steps: " + std::to_string(s.size()) +
                                                   " on one process, " + std::to_string(d.size()) +
                                                   " spread");
  if (s.empty() || s.size() != d.size()) return;
  const std::size_t np = s.front().tool_loads.size(), nr = s.front().reactions.size(),
                    nm = s.front().displacements.size();
  const double F =
      scale_of(s, np, [](const AnalysisStep& st, std::size_t k) { return st.tool_loads[k].first; });
  const double M =
      scale_of(s, np,
               [](const AnalysisStep& st, std::size_t k) { return st.tool_loads[k].second; }) +
      F * size;
  const double R =
      scale_of(s, nr, [](const AnalysisStep& st, std::size_t k) { return st.reactions[k]; });
  const double U =
      scale_of(s, nm, [](const AnalysisStep& st, std::size_t k) { return st.displacements[k]; });
  constexpr double kTol = 1e-8;
  double worst[4] = {0.0, 0.0, 0.0, 0.0};  // F, M, R, U relative to their scales
  for (std::size_t i = 0; i < s.size(); ++i) {
    const AnalysisStep &a = s[i], &b = d[i];
    const std::string at = "step " + std::to_string(i + 1) + " (t = " + std::to_string(a.t) + ")";
    c.expect(std::abs(a.t - b.t) <= kTol * span, at + ": t " + std::to_string(b.t) + " spread");
    c.expect(counts_close(a.contact.active, b.contact.active) &&
                 counts_close(a.contact.stick, b.contact.stick) &&
                 counts_close(a.contact.slip, b.contact.slip),
             at + ": contact counts " + std::to_string(a.contact.active) + "/" +
                 std::to_string(a.contact.stick) + "/" + std::to_string(a.contact.slip) +
                 " on one process, " + std::to_string(b.contact.active) + "/" +
                 std::to_string(b.contact.stick) + "/" + std::to_string(b.contact.slip) +
                 " spread");
    for (std::size_t k = 0; k < np; ++k) {
      c.expect(counts_close(a.pairs[k].active, b.pairs[k].active) &&
                   counts_close(a.pairs[k].stick, b.pairs[k].stick) &&
                   counts_close(a.pairs[k].slip, b.pairs[k].slip),
               at + ": pair " + std::to_string(k) + "'s counts");
      worst[0] = std::max(worst[0], (a.tool_loads[k].first - b.tool_loads[k].first).norm() / F);
      worst[1] = std::max(worst[1], (a.tool_loads[k].second - b.tool_loads[k].second).norm() / M);
    }
    for (std::size_t k = 0; k < nr; ++k)
      worst[2] = std::max(worst[2], (a.reactions[k] - b.reactions[k]).norm() / R);
    for (std::size_t k = 0; k < nm; ++k)
      worst[3] = std::max(worst[3], (a.displacements[k] - b.displacements[k]).norm() / U);
  }
  const char* what[4] = {"tool forces", "tool moments", "reactions", "monitors"};
  for (int q = 0; q < 4; ++q) {
    c.expect(!(worst[q] > kTol), std::string(what[q]) + " differ by " +
                                     std::to_string(worst[q] / kTol) + "e-8 of their scale");
    std::printf("  %-12s %.1e of their scale\n", what[q], worst[q]);
  }
}

// A set of points (an unstructured grid of vertices only) in the lexicographic order of its
// points' coordinates, rounded to 1e-9 of the largest (the points of a contact set are apart
// by far more; round-off is far less), every point array permuted alike.
void sort_point_set(iga::test::VtkXmlFile& f) {
  const std::vector<double> types = f.field("types");
  const std::vector<double> x = f.points();
  const std::size_t n = x.size() / 3;
  if (types.size() != n || n < 2 ||
      std::any_of(types.begin(), types.end(), [](double t) { return t != 1.0; }))
    return;
  double top = 0.0;
  for (double v : x) top = std::max(top, std::abs(v));
  const auto key = [&](std::size_t i, int k) { return std::round(x[3 * i + k] / (1e-9 * top)); };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    for (int k = 0; k < 3; ++k)
      if (key(a, k) != key(b, k)) return key(a, k) < key(b, k);
    return false;
  });
  for (auto& [name, arr] : f.arrays) {
    if (name == "connectivity" || name == "offsets" || name == "types") continue;
    const auto c = static_cast<std::size_t>(arr.components);
    if (arr.values.size() != n * c) continue;
    std::vector<double> v(arr.values.size());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t q = 0; q < c; ++q) v[c * i + q] = arr.values[c * order[i] + q];
    arr.values = std::move(v);
  }
}

// A file of the spread run's output folder under the name the run on one process gives it: a
// collection (.pvts, .pvtu) as the file it joins (.vts, .vtu); a piece (<stem>_p<r>.vts) as
// none (empty).
std::string whole_name(const std::string& f) {
  const fs::path p(f);
  const std::string ext = p.extension().string(), stem = p.stem().string();
  if (ext == ".pvts" || ext == ".pvtu") return stem + "." + ext.substr(2);
  const std::size_t at = stem.rfind("_p");
  const bool piece = (ext == ".vts" || ext == ".vtu") && at != std::string::npos &&
                     at + 2 < stem.size() &&
                     stem.find_first_not_of("0123456789", at + 2) == std::string::npos;
  return piece ? std::string() : f;
}

// The output folders: the same files (the spread run's fields as collections of pieces, one
// per process at most, or whole from process 0), the last step's fields alike.
void compare_files(Checker& c, const fs::path& whole, const fs::path& spread, int ranks) {
  std::set<std::string> a, b;
  std::map<std::string, std::string> spread_file;  // by the name on one process
  for (const auto& e : fs::directory_iterator(whole))
    if (e.path().filename().string().rfind("restart", 0) != 0) a.insert(e.path().filename());
  for (const auto& e : fs::directory_iterator(spread)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("restart", 0) == 0) continue;
    if (const std::string w = whole_name(f); !w.empty()) {
      b.insert(w);
      spread_file[w] = f;
    }
  }
  c.expect(a == b, "the output folders hold other files");
  int compared = 0, collections = 0;
  for (const std::string& f : a) {
    const std::string ext = fs::path(f).extension().string();
    if ((ext != ".vts" && ext != ".vtu") || !b.count(f)) continue;
    const std::string g = spread_file[f];
    iga::test::VtkXmlFile x = iga::test::read_vtk_xml(whole / f);
    int pieces = 0;
    const bool collection = g != f;
    iga::test::VtkXmlFile y = collection ? iga::test::read_vtk_xml_collection(spread / g, &pieces)
                                         : iga::test::read_vtk_xml(spread / g);
    // Points in pieces come in rank order, which is the serial order of the elements only
    // where the blocks are stacked along v: a set of points is compared in the order of its
    // points' coordinates.
    sort_point_set(x);
    sort_point_set(y);
    if (collection) {
      ++collections;
      c.expect(pieces >= 1 && pieces <= ranks, g + ": " + std::to_string(pieces) + " pieces");
    }
    c.expect(y.all_finite(), f + ": a value that is not finite");
    // An array that is round-off next to the file's largest (a straight rope's binormal
    // traction, zero in theory) is compared at the file's scale, any other at its own.
    double file_top = 0.0;
    for (const auto& [name, arr] : x.arrays)
      if (arr.type.rfind("Float", 0) == 0)
        for (double v : arr.values) file_top = std::max(file_top, std::abs(v));
    for (const auto& [name, arr] : x.arrays) {
      const std::vector<double> v = y.field(name);
      if (v.size() != arr.values.size()) {
        c.expect(false, f + ": " + name + " has " + std::to_string(v.size()) + " values, not " +
                            std::to_string(arr.values.size()));
        continue;
      }
      double top = 0.0, diff = 0.0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        top = std::max(top, std::abs(arr.values[i]));
        diff = std::max(diff, std::abs(arr.values[i] - v[i]));
      }
      const bool exact = name == "contact_state" || arr.type.rfind("Float", 0) != 0;
      const double scale = top > 1e-6 * file_top ? top : file_top;
      c.expect(exact ? diff == 0.0 : diff <= 1e-8 * scale,
               f + ": " + name + " differs by " + num(diff) + " (largest value " + num(top) + ")");
    }
    ++compared;
  }
  c.expect(compared > 0, "no VTK XML file to compare");
  c.expect(collections > 0, "no collection of pieces");
}

// A model of the command line: its file, the overrides that follow it ("--set /p=v", as iga
// run's), and its name in the output ("--as NAME"; by default the file's stem).
struct ModelArg {
  std::string file, name;
  std::vector<std::string> sets;
};

std::vector<ModelArg> model_args(int argc, char** argv) {
  std::vector<ModelArg> models;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--set" && i + 1 < argc && !models.empty()) {
      models.back().sets.emplace_back(argv[++i]);
    } else if (a == "--as" && i + 1 < argc && !models.empty()) {
      models.back().name = argv[++i];
    } else {
      models.push_back({a, fs::path(a).stem().string(), {}});
    }
  }
  return models;
}

}  // namespace

int main(int argc, char** argv) {
  const iga::ParallelSession session(argc, argv);
  // Both runs must take the same steps: the probe's refusals are drawn from each run's own bits.
  const iga::RoundoffProbeOff probe_off;
  const iga::Communicator& w = iga::world();
  if (argc < 3) {
    if (w.root())
      std::fprintf(
          stderr,
          "usage: mpi_models <output folder> <model.json> [--set /p=v]... [--as NAME] ...\n");
    return 2;
  }
  const fs::path out = argv[1];
  int errors = 0;
  {
    // A model error of one process alone (here: rank 1 reads a broken copy) is every
    // process's: each throws the same ModelError, none goes on into the run alone.
    Checker c;
    c.model = "an error of rank 1 alone";
    iga::Json doc = iga::read_json_file(argv[2]);
    if (w.rank() == 1) doc["bodies"]["no_such_body_type"] = {{"type", "brick"}};
    std::string message;
    try {
      (void)iga::Analysis::from_json(doc, argv[2], w);
    } catch (const iga::ModelError& e) {
      message = e.what();
    }
    c.expect(message.find("/bodies/no_such_body_type/type") != std::string::npos,
             "the error reached this rank as: \"" + message + "\"");
    errors += c.errors;
  }
  for (const ModelArg& m : model_args(argc, argv)) {
    Checker c;
    const std::string& file = m.file;
    c.model = m.name;
    iga::Json doc = iga::read_json_file(file);
    for (const std::string& set : m.sets) iga::apply_override(doc, file, set);
    const std::string tag = c.model + "_" + std::to_string(w.size()) + "_ranks";
    const fs::path spread_dir = out / tag, whole_dir = out / (tag + "_whole");
    if (w.root()) {
      fs::remove_all(spread_dir);
      fs::remove_all(whole_dir);
    }
    w.barrier();
    iga::Analysis spread = iga::Analysis::from_json(doc, file, w);
    const AnalysisResult d = spread.run(nullptr, spread_dir.string());
    if (w.root())
      std::printf("%s on %d ranks: %zu steps\n", c.model.c_str(), w.size(), d.steps.size());
    // A restart of the spread run from its files (one per rank) at its middle step ends where
    // it does. The files: a run stopped by max_steps writes them.
    {
      iga::Analysis first = iga::Analysis::from_json(doc, file, w);
      first.solver_settings().max_steps = std::max<int>(1, static_cast<int>(d.steps.size()) / 2);
      const fs::path dir = out / (tag + "_restart");
      if (w.root()) fs::remove_all(dir);
      w.barrier();
      const AnalysisResult r1 = first.run(nullptr, dir.string());
      c.expect(!r1.restart_file.empty(), "the stopped run wrote no restart file");
      c.expect(fs::exists(iga::restart_file_of(r1.restart_file, w.rank())),
               "no restart file of this rank");
      iga::Analysis second = iga::Analysis::from_json(doc, file, w);
      const AnalysisResult r2 = second.run(nullptr, dir.string(), {}, r1.restart_file);
      // (Not bit for bit: MUMPS's factorization over several processes sums in the order its
      // messages arrive.)
      const double gap = r2.u.size() == d.u.size() ? (r2.u - d.u).norm() / d.u.norm() : 1.0;
      c.expect(r2.solver.status == d.solver.status && gap <= 1e-8,
               "the restarted run ends elsewhere: |u - u_whole| / |u_whole| = " + num(gap));
      if (w.root()) {  // one process refuses the files of several
        iga::Analysis alone = iga::Analysis::from_json(doc, file);
        bool refused = false;
        try {
          (void)alone.run(nullptr, {}, {}, r1.restart_file);
        } catch (const iga::RestartError& e) {
          refused = std::string(e.what()).find("process") != std::string::npos;
        }
        c.expect(refused, "one process took the restart file of " + std::to_string(w.size()));
      }
    }
    if (w.root()) {
      iga::Analysis whole = iga::Analysis::from_json(doc, file);
      const AnalysisResult s = whole.run(nullptr, whole_dir.string());
      const iga::NonlinearSolverSettings& set = whole.solver_settings();
      compare_steps(c, s, d, model_size(whole), std::abs(set.t1 - set.t0));
      compare_files(c, whole_dir, spread_dir, w.size());
      std::printf("%s: %s\n", c.model.c_str(), c.errors == 0 ? "the same" : "DIFFERENT");
    }
    errors += c.errors;
    w.barrier();
  }
  const long long failed = w.sum(static_cast<long long>(errors));
  if (w.root()) std::printf("mpi_models: %d ranks, %lld failures\n", w.size(), failed);
  return failed == 0 ? 0 : 1;
}
