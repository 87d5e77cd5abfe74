// Legacy VTK POLYDATA and PVD writers.
#include "iga/output/vtk_writer.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace iga {

namespace {

enum class Cells { kVertices, kPolyline, kQuads };

/// Every field has one value per point; std::runtime_error naming the file otherwise.
void check_lengths(const std::string& path, std::size_t n, const VtkPointData& data) {
  const auto check = [&](const std::string& name, std::size_t size) {
    if (size != n)
      throw std::runtime_error(path + ": field '" + name + "' has " + std::to_string(size) +
                               " values for " + std::to_string(n) + " points");
  };
  for (const auto& [name, v] : data.scalars) check(name, v.size());
  for (const auto& [name, v] : data.vectors) check(name, v.size());
}

/// 1 at the points with a non-finite coordinate or field value, else 0.
std::vector<double> non_finite_flags(const std::vector<Eigen::Vector3d>& points,
                                     const VtkPointData& data) {
  std::vector<double> flag(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    bool ok = points[i].allFinite();
    for (const auto& f : data.scalars) ok = ok && std::isfinite(f.second[i]);
    for (const auto& f : data.vectors) ok = ok && f.second[i].allFinite();
    if (!ok) flag[i] = 1.0;
  }
  return flag;
}

double finite(double x) {
  return std::isfinite(x) ? x : 0.0;
}

void write_cells(std::ostream& os, std::size_t n, Cells cells, int nu, int nv) {
  if (cells == Cells::kQuads) {
    const int quads = (nu - 1) * (nv - 1);
    os << "POLYGONS " << quads << " " << 5 * quads << "\n";
    for (int j = 0; j + 1 < nv; ++j)
      for (int i = 0; i + 1 < nu; ++i) {
        const int a = i + nu * j;
        os << "4 " << a << " " << a + 1 << " " << a + 1 + nu << " " << a + nu << "\n";
      }
  } else if (cells == Cells::kPolyline && n >= 2) {
    os << "LINES 1 " << n + 1 << "\n" << n;
    for (std::size_t i = 0; i < n; ++i) os << " " << i;
    os << "\n";
  } else if (n > 0) {
    os << "VERTICES " << n << " " << 2 * n << "\n";
    for (std::size_t i = 0; i < n; ++i) os << "1 " << i << "\n";
  }
}

void write_point_data(std::ostream& os, std::size_t n, const VtkPointData& data,
                      const std::vector<double>& flag, bool flagged) {
  if (n == 0 || (data.scalars.empty() && data.vectors.empty() && !flagged)) return;
  os << "POINT_DATA " << n << "\n";
  for (const auto& [name, v] : data.scalars) {
    os << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
    for (double x : v) os << finite(x) << "\n";
  }
  if (flagged) {
    os << "SCALARS non_finite double 1\nLOOKUP_TABLE default\n";
    for (double x : flag) os << x << "\n";
  }
  for (const auto& [name, v] : data.vectors) {
    os << "VECTORS " << name << " double\n";
    for (const Eigen::Vector3d& x : v)
      os << finite(x.x()) << " " << finite(x.y()) << " " << finite(x.z()) << "\n";
  }
}

void write(const std::string& path, const std::vector<Eigen::Vector3d>& points, Cells cells, int nu,
           int nv, const VtkPointData& data, const std::string& title) {
  const std::size_t n = points.size();
  check_lengths(path, n, data);
  // No output file holds a non-finite number: such a value is written as 0 and its point gets
  // the flag non_finite = 1 (a field added only when some point needs it).
  const std::vector<double> flag = non_finite_flags(points, data);
  const bool flagged = std::find(flag.begin(), flag.end(), 1.0) != flag.end();
  std::ofstream os(path);
  if (!os) throw std::runtime_error("cannot write " + path);
  os << std::setprecision(12);
  os << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET POLYDATA\n";
  os << "POINTS " << n << " double\n";
  for (const Eigen::Vector3d& p : points)
    os << finite(p.x()) << " " << finite(p.y()) << " " << finite(p.z()) << "\n";
  write_cells(os, n, cells, nu, nv);
  write_point_data(os, n, data, flag, flagged);
  if (!os) throw std::runtime_error("error while writing " + path);
}

}  // namespace

void write_vtk_polydata(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                        bool connect, const VtkPointData& data, const std::string& title) {
  write(path, points, connect ? Cells::kPolyline : Cells::kVertices, 0, 0, data, title);
}

void write_vtk_grid(const std::string& path, const std::vector<Eigen::Vector3d>& points, int nu,
                    int nv, const VtkPointData& data, const std::string& title) {
  if (nu < 2 || nv < 2 ||
      points.size() != static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv))
    throw std::runtime_error(path + ": a grid of " + std::to_string(nu) + " x " +
                             std::to_string(nv) + " needs that many points, got " +
                             std::to_string(points.size()));
  write(path, points, Cells::kQuads, nu, nv, data, title);
}

void VtkCollection::add(double time, const std::string& file) {
  entries_.emplace_back(time, file);
  write();
}

void VtkCollection::write() const {
  std::ofstream os(path_);
  if (!os) throw std::runtime_error("cannot write " + path_);
  os << std::setprecision(12);
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const auto& [t, f] : entries_)
    os << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << f << "\"/>\n";
  os << "  </Collection>\n</VTKFile>\n";
}

void write_vtk(const std::string& path, const SampledMesh& mesh, const std::string& title) {
  switch (mesh.shape) {
    case SampledMesh::Shape::kPoints:
      write_vtk_polydata(path, mesh.points, false, mesh.fields, title);
      return;
    case SampledMesh::Shape::kPolyline:
      write_vtk_polydata(path, mesh.points, true, mesh.fields, title);
      return;
    case SampledMesh::Shape::kGrid:
      write_vtk_grid(path, mesh.points, mesh.nu, mesh.nv, mesh.fields, title);
      return;
  }
}

}  // namespace iga
