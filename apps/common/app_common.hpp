// What the programs share (apps/): reading a model with the command line's overrides, parsing a
// command line with the exit codes of the house (0 --help, 2 a bad command line), and running a
// plot script. Data and scripts are found through resources.hpp.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/json_reader.hpp"

namespace iga::app {

/// Parses the command line: -1 to go on, else the exit status (0 after --help, 2 for a bad
/// command line; CLI11's own codes are above 100).
int parse_command_line(CLI::App& cli, int argc, char** argv);

/// The model file with its overrides applied in order: with `quick` the model's "app"/"quick"
/// object of {"/json/pointer": value} (ModelError if it has none), then each --set assignment
/// (apply_override). Throws ModelError naming the file and the JSON path.
Json read_model(const std::string& file, bool quick, const std::vector<std::string>& sets);

/// Runs `python3 script args...` (output to stdout); false if it failed. The caller warns: a
/// failed plot never fails a run.
bool run_python(const std::string& script, const std::vector<std::string>& args);

}  // namespace iga::app
