// `iga project MODEL.json --points pts.csv [--ray normals.csv] [--out result.csv]`: closest
// point (or ray) projection of points onto a rigid surface of the model: a NURBS patch, a patch
// group or an analytic surface ([KS15] eqs. 2-5 and 10-18). Writes one row per point:
// u,v,x,y,z,nx,ny,nz,distance,status,iterations,patch.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "apps/iga_commands.hpp"
#include "contact/rigid_surface.hpp"
#include "iga/model.hpp"

namespace iga::app {

namespace {

struct ProjectOptions {
  std::string file, entity, points, rays, out;
  bool warm = false, cgal = false;
  double search_distance = 0.0;
};

// Rows of three finite numbers; a first line that is not numeric is a header and skipped.
// Errors name the file, the line and the text.
std::vector<Vector3d> read_xyz(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<Vector3d> rows;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ls(line);
    Vector3d x;
    std::string extra;
    if (!(ls >> x[0] >> x[1] >> x[2])) {
      if (rows.empty() && lineno == 1) continue;  // header
      throw std::runtime_error(path + ":" + std::to_string(lineno) + ": expected x,y,z, got '" + line + "'");
    }
    if (ls >> extra)
      throw std::runtime_error(path + ":" + std::to_string(lineno) + ": expected 3 values, got more: '" + line + "'");
    if (!x.allFinite())
      throw std::runtime_error(path + ":" + std::to_string(lineno) + ": non-finite value in '" + line + "'");
    rows.push_back(x);
  }
  return rows;
}

std::string pick_surface(const Model& m, const std::string& wanted) {
  if (!wanted.empty()) return wanted;
  // A group first (it is the body), else the first surface.
  for (const auto& [name, e] : m.geometry.entities)
    if (std::holds_alternative<PatchGroup>(e)) return name;
  for (const auto& [name, e] : m.geometry.entities)
    if (as_surface(e)) return name;
  throw std::invalid_argument("the model has no surface to project onto");
}

int run_project(const ProjectOptions& o) {
  // 1. Model and rigid surface.
  const Model m = load_model(o.file);
  const std::string name = pick_surface(m, o.entity);
  const RigidSurface rs = RigidSurface::from_geometry(m.geometry, name);
  // 2. Points (and ray directions).
  const std::vector<Vector3d> pts = read_xyz(o.points);
  std::vector<Vector3d> dirs;
  if (!o.rays.empty()) {
    dirs = read_xyz(o.rays);
    if (dirs.size() != pts.size())
      throw std::invalid_argument(o.rays + ": " + std::to_string(dirs.size()) + " directions for " +
                                  std::to_string(pts.size()) + " points in " + o.points);
  }
  // 3. Project and write.
  std::ofstream file_out;
  std::ostream* out = &output_stream(o.out, file_out);
  *out << "u,v,x,y,z,nx,ny,nz,distance,status,iterations,patch\n" << std::setprecision(15);
  const auto t0 = std::chrono::steady_clock::now();
  if (o.search_distance > 0.0 && (!dirs.empty() || o.warm))
    throw std::invalid_argument("--search-distance applies to closest points, not to --ray or --warm");
  std::vector<ProjectionResult> batch;
  if (o.search_distance > 0.0) batch = rs.closest_points(pts, o.search_distance, o.cgal);
  ProjectionResult prev;
  prev.patch = -1;
  std::size_t ok = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const ProjectionResult r = !batch.empty() ? batch[i]
                               : !dirs.empty() ? rs.ray(pts[i], dirs[i])
                               : o.warm && i > 0 ? rs.closest_point(pts[i], prev)
                                                 : rs.closest_point(pts[i]);
    prev = r;
    ok += found(r.status);
    *out << r.uv[0] << "," << r.uv[1] << "," << r.point.x() << "," << r.point.y() << ","
         << r.point.z() << "," << r.normal.x() << "," << r.normal.y() << "," << r.normal.z()
         << "," << r.distance << "," << to_string(r.status) << "," << r.iterations << ","
         << r.patch << "\n";
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cerr << "iga project: " << pts.size() << " points onto '" << name << "' ("
            << rs.num_patches() << " patch" << (rs.num_patches() == 1 ? "" : "es") << "), "
            << ok << " found, " << pts.size() - ok << " without a foot point, " << secs << " s";
  if (!o.out.empty()) std::cerr << ", wrote " << o.out;
  std::cerr << "\n";
  return 0;
}

}  // namespace

Action add_project_command(CLI::App& app) {
  auto o = std::make_shared<ProjectOptions>();
  CLI::App* cmd = app.add_subcommand(
      "project",
      "Project points onto a rigid surface: closest point (default) or along rays (--ray)");
  cmd->add_option("model", o->file, "Model file (JSON)")->required();
  cmd->add_option("--points,-p", o->points, "CSV of points x,y,z (one per row)")->required();
  cmd->add_option("--ray", o->rays, "CSV of ray directions, one per point: project along them");
  cmd->add_option("--entity,-e", o->entity, "Surface or patch group (default: the first group, else the first surface)");
  cmd->add_option("--out,-o", o->out, "Result CSV (default: standard output)");
  cmd->add_flag("--warm", o->warm, "Warm-start each point from the previous one's foot point");
  cmd->add_option("--search-distance", o->search_distance,
                  "Only feet within this distance (others: status far), found through a broad "
                  "phase over the Bezier elements")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--cgal", o->cgal, "Broad phase with CGAL box_intersection_d instead of the grid");
  return [o]() { return run_project(*o); };
}

}  // namespace iga::app
