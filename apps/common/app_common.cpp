// Shared parts of the programs; see app_common.hpp.
#include "apps/common/app_common.hpp"

#include <cstdlib>

#include "iga/model/analysis.hpp"

namespace iga::app {

int parse_command_line(CLI::App& cli, int argc, char** argv) {
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e) == 0 ? 0 : 2;  // --help: 0; a bad command line: 2 (not CLI11's 105...)
  }
  return -1;
}

Json read_model(const std::string& file, bool quick, const std::vector<std::string>& sets) {
  Json doc = read_json_file(file);
  if (quick) {
    const JsonCursor root(doc, file);
    if (!root.has("app") || !root["app"].has("quick"))
      root.fail_plain("--quick: the model has no \"app\"/\"quick\" overrides");
    const JsonCursor q = root["app"]["quick"];
    if (!q.json().is_object()) q.fail_type("an object {\"/json/pointer\": value}");
    for (const std::string& k : q.keys()) apply_override(doc, file, k + "=" + q[k].json().dump());
  }
  for (const std::string& s : sets) apply_override(doc, file, s);
  return doc;
}

bool run_python(const std::string& script, const std::vector<std::string>& args) {
  std::string cmd = "/usr/bin/python3 \"" + script + "\"";
  for (const std::string& a : args) cmd += " \"" + a + "\"";
  cmd += " 2>&1";
  return std::system(cmd.c_str()) == 0;
}

}  // namespace iga::app
