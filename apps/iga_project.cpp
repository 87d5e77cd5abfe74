// `iga project MODEL.json --points pts.csv [--ray normals.csv] [--out result.csv]`: closest
// point (or ray) projection of points onto a rigid surface of the model: a NURBS patch, a patch
// group or an analytic surface ([KS15] eqs. 2-5 and 10-18). Writes one row per point:
// u,v,x,y,z,nx,ny,nz,distance,status,iterations,patch.
#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "apps/iga_commands.hpp"
#include "contact/rigid_surface.hpp"
#include "iga/model/model.hpp"

namespace iga::app {

namespace {

struct ProjectOptions {
  std::string file, entity, points, rays, out;
  bool warm = false, cgal = false;
  double search_distance = 0.0;
};

[[noreturn]] void bad_row(const std::string& path, int lineno, const std::string& what,
                          const std::string& line) {
  throw std::runtime_error(path + ":" + std::to_string(lineno) + ": " + what + ", got '" + line +
                           "'");
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const std::size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

/// The fields of a line: separated by commas, or by blanks when the line has no comma.
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  if (line.find(',') != std::string::npos) {
    std::istringstream ls(line);
    std::string f;
    while (std::getline(ls, f, ',')) out.push_back(trim(f));
    if (!line.empty() && line.back() == ',') out.emplace_back();
  } else {
    std::istringstream ls(line);
    std::string f;
    while (ls >> f) out.push_back(f);
  }
  return out;
}

/// A whole field as a decimal number (optional sign, digits, point, exponent; no hex floats,
/// no inf or nan), or an explanation of why not.
bool parse_number(const std::string& field, double& x, std::string& why) {
  const std::string f = !field.empty() && field[0] == '+' ? field.substr(1) : field;
  if (f.empty()) return why = "an empty field", false;
  if (f.find_first_not_of("0123456789.eE+-") != std::string::npos)
    return why = "'" + field + "' is not a decimal number", false;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
  if (ec == std::errc::result_out_of_range)
    return why = "'" + field + "' is out of the range of a double", false;
  if (ec != std::errc() || end != f.data() + f.size())
    return why = "'" + field + "' is not a decimal number", false;
  if (!std::isfinite(x)) return why = "'" + field + "' is not finite", false;
  return true;
}

/// Whether the fields are one of the header name triples (case-insensitive).
bool is_header(const std::vector<std::string>& f,
               const std::vector<std::array<const char*, 3>>& names) {
  if (f.size() != 3) return false;
  for (const auto& triple : names) {
    bool all = true;
    for (std::size_t i = 0; i < 3 && all; ++i) {
      std::string a = f[i];
      if (a.size() >= 2 && a.front() == '"' && a.back() == '"') a = a.substr(1, a.size() - 2);
      std::transform(a.begin(), a.end(), a.begin(),
                     [](unsigned char ch) { return std::tolower(ch); });
      all = a == triple[i];
    }
    if (all) return true;
  }
  return false;
}

// A CSV of rows of three finite decimal numbers (comma- or blank-separated). The first
// non-blank line is a header only if its fields are one of `header` (x,y,z for points;
// dx,dy,dz, nx,ny,nz or x,y,z for directions); any other line that is not three numbers is an
// error naming the file, the line and the text. The file must be a regular, readable file
// holding at least one row.
std::vector<Vector3d> read_xyz(const std::string& path,
                               const std::vector<std::array<const char*, 3>>& header) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st)) throw std::runtime_error(path + ": no such file");
  if (!std::filesystem::is_regular_file(st))
    throw std::runtime_error(path + ": not a regular file (a CSV of x,y,z rows is expected)");
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::vector<Vector3d> rows;
  std::string line;
  int lineno = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++lineno;
    if (lineno == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
    if (trim(line).empty()) continue;
    const std::vector<std::string> f = fields(line);
    const bool was_first = first;
    first = false;
    if (was_first && is_header(f, header)) continue;
    if (f.size() != 3)
      bad_row(path, lineno,
              "expected 3 values x,y,z, found " + std::to_string(f.size()) + " field" +
                  (f.size() == 1 ? "" : "s"),
              line);
    Vector3d x;
    for (int i = 0; i < 3; ++i) {
      std::string why;
      if (!parse_number(f[static_cast<std::size_t>(i)], x[i], why))
        bad_row(path, lineno, "value " + std::to_string(i + 1) + ": " + why, line);
    }
    rows.push_back(x);
  }
  if (in.bad())
    throw std::runtime_error(path + ": read error after line " + std::to_string(lineno));
  if (rows.empty()) throw std::runtime_error(path + ": holds no rows of x,y,z values");
  return rows;
}

/// A foot point whose numbers are all finite, with a unit normal (one lost to overflow in the
/// derivatives of a point far out comes back as zero).
bool finite_foot(const ProjectionResult& r) {
  return r.uv.allFinite() && r.point.allFinite() && r.normal.allFinite() &&
         std::isfinite(r.distance) && std::abs(r.normal.norm() - 1.0) < 1e-6;
}

// One row u,v,x,y,z,nx,ny,nz,distance,status,iterations,patch. Only a foot point (interior,
// edge, vertex) has numbers; the other statuses (miss, tangent, far, not_converged) leave the
// nine numeric cells empty. No cell holds a non-finite number: a foot point whose numbers
// overflowed (a point too far out for double arithmetic) is status out_of_range, cells empty.
void write_row(std::ostream& out, const ProjectionResult& r) {
  const bool foot = found(r.status) && finite_foot(r);
  const bool overflow = found(r.status) && !foot;
  if (foot)
    out << r.uv[0] << "," << r.uv[1] << "," << r.point.x() << "," << r.point.y() << ","
        << r.point.z() << "," << r.normal.x() << "," << r.normal.y() << "," << r.normal.z() << ","
        << r.distance << ",";
  else
    out << ",,,,,,,,,";
  out << (overflow ? "out_of_range" : to_string(r.status)) << "," << r.iterations << "," << r.patch
      << "\n";
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
  const std::vector<Vector3d> pts = read_xyz(o.points, {{"x", "y", "z"}});
  std::vector<Vector3d> dirs;
  if (!o.rays.empty()) {
    dirs = read_xyz(o.rays, {{"dx", "dy", "dz"}, {"nx", "ny", "nz"}, {"x", "y", "z"}});
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
    throw std::invalid_argument(
        "--search-distance applies to closest points, not to --ray or --warm");
  std::vector<ProjectionResult> batch;
  if (o.search_distance > 0.0) batch = rs.closest_points(pts, o.search_distance, o.cgal);
  ProjectionResult prev;
  prev.patch = -1;
  std::size_t ok = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    // A ray needs a direction: zero has none (one too large for |N|^2 is rescaled).
    if (!dirs.empty() && !(dirs[i].cwiseAbs().maxCoeff() > 0.0)) {
      *out << ",,,,,,,,,bad_direction,0,\n";
      continue;
    }
    const ProjectionResult r = !batch.empty() ? batch[i]
                               : !dirs.empty()
                                   ? rs.ray(pts[i], dirs[i] / dirs[i].cwiseAbs().maxCoeff())
                               : o.warm && i > 0 ? rs.closest_point(pts[i], prev)
                                                 : rs.closest_point(pts[i]);
    prev = r;
    write_row(*out, r);
    ok += found(r.status) && finite_foot(r);
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cerr << "iga project: " << pts.size() << " points onto '" << name << "' ("
            << rs.num_patches() << " patch" << (rs.num_patches() == 1 ? "" : "es") << "), " << ok
            << " found, " << pts.size() - ok << " without a foot point, " << secs << " s";
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
  cmd->add_option("--entity,-e", o->entity,
                  "Surface or patch group (default: the first group, else the first surface)");
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
