// Legacy VTK POLYDATA and PVD writers.
#include "iga/vtk_writer.hpp"

#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace iga {

void write_vtk_polydata(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                        bool connect, const VtkPointData& data, const std::string& title) {
  const std::size_t n = points.size();
  for (const auto& [name, v] : data.scalars)
    if (v.size() != n)
      throw std::runtime_error(path + ": field '" + name + "' has " + std::to_string(v.size()) +
                               " values for " + std::to_string(n) + " points");
  for (const auto& [name, v] : data.vectors)
    if (v.size() != n)
      throw std::runtime_error(path + ": field '" + name + "' has " + std::to_string(v.size()) +
                               " values for " + std::to_string(n) + " points");
  std::ofstream os(path);
  if (!os) throw std::runtime_error("cannot write " + path);
  os << std::setprecision(12);
  os << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET POLYDATA\n";
  os << "POINTS " << n << " double\n";
  for (const Eigen::Vector3d& p : points) os << p.x() << " " << p.y() << " " << p.z() << "\n";
  if (connect && n >= 2) {
    os << "LINES 1 " << n + 1 << "\n" << n;
    for (std::size_t i = 0; i < n; ++i) os << " " << i;
    os << "\n";
  } else if (n > 0) {
    os << "VERTICES " << n << " " << 2 * n << "\n";
    for (std::size_t i = 0; i < n; ++i) os << "1 " << i << "\n";
  }
  if (n > 0 && (!data.scalars.empty() || !data.vectors.empty())) {
    os << "POINT_DATA " << n << "\n";
    for (const auto& [name, v] : data.scalars) {
      os << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
      for (double x : v) os << x << "\n";
    }
    for (const auto& [name, v] : data.vectors) {
      os << "VECTORS " << name << " double\n";
      for (const Eigen::Vector3d& x : v) os << x.x() << " " << x.y() << " " << x.z() << "\n";
    }
  }
  if (!os) throw std::runtime_error("error while writing " + path);
}

void VtkCollection::add(double time, const std::string& file) {
  entries_.emplace_back(time, file);
  std::ofstream os(path_);
  if (!os) throw std::runtime_error("cannot write " + path_);
  os << std::setprecision(12);
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  for (const auto& [t, f] : entries_)
    os << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << f << "\"/>\n";
  os << "  </Collection>\n</VTKFile>\n";
}

}  // namespace iga
