// Where the example programs find their models (data/) and plot scripts (scripts/):
//   1. $IGA_CONTACT_HOME, when set: a folder holding data/ and scripts/;
//   2. <prefix>/share/iga-contact beside an installed program <prefix>/bin/<program>
//      (cmake --install puts them there);
//   3. the source tree the program was built from (IGA_SOURCE_DIR), for a program run from
//      its build folder.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace iga::app {

inline std::filesystem::path resource_root() {
  namespace fs = std::filesystem;
  if (const char* home = std::getenv("IGA_CONTACT_HOME"); home != nullptr && *home != '\0')
    return fs::path(home);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path share = exe.parent_path().parent_path() / "share" / "iga-contact";
    if (fs::is_directory(share / "data", ec)) return share;
  }
  return fs::path(IGA_SOURCE_DIR);
}

/// A file under the resource root, e.g. resource("data/capstan.json").
inline std::string resource(const std::string& relative) {
  return (resource_root() / relative).string();
}

}  // namespace iga::app
