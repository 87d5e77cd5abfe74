// `iga run MODEL.json [--out DIR] [--set /ptr=value]... [--threads N] [--restart FILE]`: runs any
// analysis model (rod or shell, with or without contact) (docs/model_format.md, analysis
// sections): progress line per step, the solver's summary, and in DIR steps.csv, summary.json,
// ParaView files, model_used.json, restart.bin (output.restart_every, or a run that stops early);
// --restart continues the run of a restart file. Exit status: 0 converged (or stopped at full
// slip as asked), 1 bad input (a restart file of another model too), 2 the solver stopped early
// (or a bad command line, from iga_main.cpp).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include <omp.h>

#include "apps/common/app_common.hpp"
#include "apps/common/resources.hpp"
#include "apps/iga_commands.hpp"
#include "iga/model/analysis.hpp"
#include "iga/parallel/communicator.hpp"

namespace iga::app {

namespace {

struct RunOptions {
  std::string file, out, restart;
  std::vector<std::string> sets;
  bool quiet = false;
  int threads = 0;  // 0: OpenMP's default (OMP_NUM_THREADS, else every core)
};

int run_model(const RunOptions& o) {
  // Under mpirun the model is spread over the processes (docs/parallel.md); process 0 reports
  // and writes the tables and fields, every process its restart file.
  const Communicator& comm = world();
  std::ostream null_stream(nullptr);  // the other processes' reports go nowhere
  std::ostream& out_log = comm.root() ? std::cout : null_stream;
  Json doc = read_model(o.file, false, o.sets);
  Analysis a = Analysis::from_json(doc, o.file, comm);
  const std::string out =
      o.out.empty() ? "out/" + (a.name().empty() ? std::string("run") : a.name()) : o.out;
  if (comm.root()) {
    std::filesystem::create_directories(out);
    std::ofstream(std::filesystem::path(out) / "model_used.json") << format_json(doc) << "\n";
  }
  if (o.threads > 0) omp_set_num_threads(o.threads);
  out_log << "iga run: " << o.file << ": " << a.describe() << " (" << omp_get_max_threads()
          << " threads"
          << (comm.size() > 1 ? " on each of " + std::to_string(comm.size()) + " processes"
                              : std::string())
          << ")\n";
  const AnalysisResult r = a.run(o.quiet ? nullptr : &std::cout, out, {}, o.restart);
  const bool ok =
      r.solver.converged() || (r.full_slip && r.solver.status == NonlinearSolverStatus::stopped);
  if (!comm.root()) return ok ? 0 : 2;
  std::cout << "iga run: results in " << out << " (steps.csv, summary.json";
  if (a.output().vtk != AnalysisOutput::Vtk::kNone)  // one series per body (write_output)
    for (int b = 0; b < a.num_bodies(); ++b)
      std::cout << ", " << (a.num_bodies() == 1 ? a.body(b).type() : a.body_name(b)) << ".pvd";
  std::cout << ")\n";
  for (const AnalysisOutput::Plot& p : a.output().plots) {  // figures of steps.csv columns
    const std::string png = (std::filesystem::path(out) / p.file).string();
    std::vector<std::string> args{(std::filesystem::path(out) / "steps.csv").string(), p.x, p.y,
                                  png, p.title};
    if (!p.reference.empty()) {  // the published points, beside the PNG: <stem>_reference.json
      Json ref = Json::array();
      for (const AnalysisOutput::Reference& set : p.reference) {
        Json points = Json::array();
        for (const auto& [x, y] : set.points) points.push_back({x, y});
        ref.push_back({{"label", set.label}, {"points", points}});
      }
      const std::string file = png.substr(0, png.size() - 4) + "_reference.json";
      std::ofstream(file) << format_json(ref) << "\n";
      args.push_back(file);
    }
    if (run_python(resource("scripts/plot_steps.py"), args))
      std::cout << "iga run: plot " << png << "\n";
    else
      std::cout << "iga run: warning: the plot " << png << " failed (python3 with matplotlib?)\n";
  }
  if (!ok) std::cout << "iga run: the run ended early: " << r.solver.message << "\n";
  return ok ? 0 : 2;
}

}  // namespace

Action add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd =
      app.add_subcommand("run", "Run an analysis model (rod or shell, with or without contact)");
  // No CLI::ExistingFile check: a missing or unreadable model is bad input (exit 1, reported by
  // the reader like every other model error), not a bad command line.
  cmd->add_option("model", o->file, "Model file (JSON)")->required();
  cmd->add_option("--out,-o", o->out, "Output folder (default out/<model name>)");
  cmd->add_option("--set", o->sets, "Override a model value: /json/pointer=value (repeatable)");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress lines");
  cmd->add_option(
      "--restart", o->restart,
      "Continue the run of a restart file (restart.bin of an earlier run of this model)");
  cmd->add_option("--threads,-j", o->threads,
                  "Threads of the element loops (default: OMP_NUM_THREADS, else every core)")
      ->check(CLI::Range(1, 1024));
  return [o]() { return run_model(*o); };
}

}  // namespace iga::app
