// Brute-force references for projection tests and benchmarks: a dense parameter grid over the
// surface, then the local bound-constrained Newton from the best few grid points.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "contact/closest_point.hpp"
#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"

namespace iga::test {

inline ProjectionResult brute_force_closest(const Surface& s, const Vector3d& x, int n = 120,
                                            int polish = 3) {
  const Domain2 d = s.domain();
  std::vector<std::pair<double, Vector2d>> grid;
  grid.reserve(static_cast<std::size_t>(n * n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vector2d uv(d.u.lo + (d.u.hi - d.u.lo) * i / (n - 1),
                        d.v.lo + (d.v.hi - d.v.lo) * j / (n - 1));
      grid.emplace_back((s.point(uv[0], uv[1]) - x).squaredNorm(), uv);
    }
  std::partial_sort(grid.begin(), grid.begin() + polish, grid.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  ProjectionResult best;
  double best2 = 1e300;
  for (int k = 0; k < polish; ++k) {
    const ProjectionResult r = closest_point_local(s, x, grid[static_cast<std::size_t>(k)].second);
    const double d2 = (r.point - x).squaredNorm();
    if (d2 < best2) best2 = d2, best = r;
  }
  return best;
}

/// The first NURBS surface of a model file in data/.
inline NurbsSurface data_surface(const std::string& file) {
  const std::string path = std::string(IGA_SOURCE_DIR) + "/data/" + file;
  const GeometryModel g =
      parse_geometry(read_json_file(path)["geometry"], path, JsonPointer("/geometry"));
  for (const auto& [name, e] : g.entities)
    if (const auto* s = std::get_if<NurbsSurface>(&e)) return *s;
  throw std::runtime_error(path + ": no NURBS surface");
}

}  // namespace iga::test
