// Subcommands of the `iga` tool; each registers itself on the CLI11 app and runs when chosen.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace iga::app {

/// A registered subcommand: the action to run when it was selected on the command line.
using Action = std::function<int()>;

Action add_info_command(CLI::App& app);
Action add_eval_command(CLI::App& app);
Action add_make_command(CLI::App& app);
Action add_project_command(CLI::App& app);

}  // namespace iga::app
