// Shared helpers of the tests: a fresh output folder, a whole file as a string, the cells of a
// CSV text.
#pragma once

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace iga::test {

/// A fresh (emptied) output folder <build>/test_out/<group>/<name> for a test's files.
inline std::string fresh_out_dir(const std::string& group, const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(IGA_BINARY_DIR) / "test_out" / group / name;
  std::filesystem::remove_all(d);
  return d.string();
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The rows of a CSV text split at commas (no quoting); a line ending in ',' has an empty last
/// cell, so every row has one cell more than it has commas.
inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

/// The numbers of a legacy-VTK file from the line after `at` up to the next keyword line.
inline std::vector<double> vtk_numbers_after(const std::string& text, std::size_t at) {
  std::vector<double> v;
  std::istringstream in(text.substr(at + 1));
  std::string line;
  while (std::getline(in, line) && !line.empty() &&
         !std::isalpha(static_cast<unsigned char>(line[0]))) {
    std::istringstream ls(line);
    double x = 0.0;
    while (ls >> x) v.push_back(x);
  }
  return v;
}

/// The values of a legacy-VTK point array ("SCALARS <name> ..." or "VECTORS <name> ..."); empty
/// if there is no such array.
inline std::vector<double> vtk_array(const std::string& text, const std::string& kind,
                                     const std::string& name) {
  auto at = text.find("\n" + kind + " " + name + " ");
  if (at == std::string::npos) return {};
  at = text.find('\n', at + 1);                         // past the header
  if (kind == "SCALARS") at = text.find('\n', at + 1);  // past LOOKUP_TABLE
  return vtk_numbers_after(text, at);
}

/// The points of a legacy-VTK file, 3 numbers each.
inline std::vector<double> vtk_points(const std::string& text) {
  const auto at = text.find("\nPOINTS ");
  if (at == std::string::npos) return {};
  return vtk_numbers_after(text, text.find('\n', at + 1));
}

}  // namespace iga::test
