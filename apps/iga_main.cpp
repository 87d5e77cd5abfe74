// iga: the generic command-line tool of the framework.
//
//   iga info MODEL.json                      list the model's entities
//   iga eval MODEL.json --uv 0.5,0.5         point, derivatives, normal, metric, curvatures
//   iga eval MODEL.json --u 0.3              curve: point, tangent, curvature, torsion, frame
//   iga eval MODEL.json --grid 20 --out t.csv  a sample table as CSV
//   iga make torus --major-radius 3 --minor-radius 1 --out torus.json   exact NURBS models
//   iga project MODEL.json --points pts.csv [--ray dirs.csv] --out feet.csv  projections
//   iga info die.step                        the faces of a STEP or IGES file
//   iga import die.step --faces 0,3 --out die.json   the faces as an ordinary model
//   iga run MODEL.json [--petsc -pc_type hypre ...]  PETSc's options after --petsc
//
// Errors go to stderr with exit status 1 (bad input) or 2 (bad command line).
#include <iostream>
#include <optional>

#include "apps/common/app_common.hpp"
#include "apps/iga_commands.hpp"
#include "iga/core/state_archive.hpp"
#include "iga/parallel/communicator.hpp"

namespace {

int run_iga(int argc, char** argv) {
  // 1. Command line: one subcommand is required.
  CLI::App app{
      "iga: isogeometric contact of rods and shells with rigid NURBS and analytic surfaces.\n"
      "Models are JSON files (docs/model_format.md)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "iga 0.1.0");
  const iga::app::Action info = iga::app::add_info_command(app);
  const iga::app::Action eval = iga::app::add_eval_command(app);
  const iga::app::Action make = iga::app::add_make_command(app);
  const iga::app::Action import = iga::app::add_import_command(app);
  const iga::app::Action project = iga::app::add_project_command(app);
  const iga::app::Action run = iga::app::add_run_command(app);
  // --help, --version: 0; a bad command line: 2
  if (const int status = iga::app::parse_command_line(app, argc, argv); status >= 0) return status;

  // 2. Run the chosen subcommand.
  const std::string name = app.get_subcommands().front()->get_name();
  if (name == "info") return info();
  if (name == "eval") return eval();
  if (name == "make") return make();
  if (name == "import") return import();
  if (name == "project") return project();
  if (name == "run") return run();
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::optional<iga::ParallelSession> session;
  try {
    // MPI and PETSc under mpirun; PETSc's options after --petsc, taken off the command line.
    session.emplace(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "iga: error: " << e.what() << "\n";
    return 1;
  }
  const iga::Communicator& world = iga::world();
  try {  // every library error ends here with a message
    return run_iga(argc, argv);
  } catch (const iga::ModelError& e) {
    // Bad input, the same on every process (Analysis::from_json agrees on it): said once.
    if (world.root()) std::cerr << "iga: error: " << e.what() << "\n";
    return 1;
  } catch (const iga::RestartError& e) {  // agreed too (Analysis::run)
    if (world.root()) std::cerr << "iga: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    // Over several processes an error may be this process's alone, the others waiting for it
    // in a collective: it ends them all, with its message.
    if (world.size() > 1) world.abort(1, std::string("iga: error: ") + e.what());
    std::cerr << "iga: error: " << e.what() << "\n";
    return 1;
  }
}
