// Shared helpers of the tests: a fresh output folder, a whole file as a string, the cells of a
// CSV text.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
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

/// Two steps.csv tables (csv_rows; header first) of runs of one model compared at the times both
/// reached (equal cells of the column "t"), whatever steps each took between them. Columns that
/// count (step, iterations, augmentations, active, stick, slip points) are not compared: another
/// step path may change them. `worst` is the largest difference of a compared column relative to
/// its scale (its largest |value| in table a), `where` names it.
struct CommonTimes {
  int common = 0;       ///< rows at common times
  double last_t = 0.0;  ///< the latest common time
  double worst = 0.0;
  std::string where;
};

inline CommonTimes compare_at_common_times(const std::vector<std::vector<std::string>>& a,
                                           const std::vector<std::vector<std::string>>& b) {
  CommonTimes c;
  if (a.empty() || b.empty() || a.front() != b.front()) return c;
  const std::vector<std::string>& head = a.front();
  const auto t_col =
      static_cast<std::size_t>(std::find(head.begin(), head.end(), "t") - head.begin());
  if (t_col == head.size()) return c;
  auto counts = [](const std::string& name) {
    auto ends = [&](const std::string& e) {
      return name.size() >= e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0;
    };
    return name == "step" || ends("iterations") || ends("augmentations") || ends("active") ||
           ends("stick") || ends("slip");
  };
  std::vector<double> scale(head.size(), 0.0);
  for (std::size_t i = 1; i < a.size(); ++i)
    for (std::size_t j = 0; j < head.size() && j < a[i].size(); ++j)
      if (!a[i][j].empty()) scale[j] = std::max(scale[j], std::abs(std::stod(a[i][j])));
  for (std::size_t i = 1; i < a.size(); ++i)
    for (std::size_t k = 1; k < b.size(); ++k) {
      if (a[i].size() != head.size() || b[k].size() != head.size() || a[i][t_col] != b[k][t_col])
        continue;
      ++c.common;
      c.last_t = std::max(c.last_t, std::stod(a[i][t_col]));
      for (std::size_t j = 0; j < head.size(); ++j) {
        if (counts(head[j]) || a[i][j].empty() || b[k][j].empty()) continue;
        const double d = std::abs(std::stod(a[i][j]) - std::stod(b[k][j]));
        const double rel = scale[j] > 0.0 ? d / scale[j] : d;
        if (rel > c.worst) {
          c.worst = rel;
          c.where =
              "t = " + a[i][t_col] + ", column " + head[j] + ": " + a[i][j] + " vs " + b[k][j];
        }
      }
    }
  return c;
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
