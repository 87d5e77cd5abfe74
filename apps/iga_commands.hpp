// Subcommands of the `iga` tool; each registers itself on the CLI11 app and runs when chosen.
#pragma once

#include <fstream>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace iga::app {

/// A registered subcommand: the action to run when it was selected on the command line.
using Action = std::function<int()>;

/// The stream to write a table to: `file` opened at `path`, or standard output if path is
/// empty. Throws std::runtime_error if the file cannot be opened.
inline std::ostream& output_stream(const std::string& path, std::ofstream& file) {
  if (path.empty()) return std::cout;
  file.open(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  return file;
}

Action add_info_command(CLI::App& app);
Action add_eval_command(CLI::App& app);
Action add_import_command(CLI::App& app);
Action add_make_command(CLI::App& app);
Action add_project_command(CLI::App& app);
Action add_run_command(CLI::App& app);

}  // namespace iga::app
