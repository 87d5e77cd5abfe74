// ParaView output: legacy VTK POLYDATA files (polylines and point clouds with point data) and
// a .pvd collection tying the files of a run to their pseudo-times.
// Reference: VTK User's Guide, "VTK File Formats" (legacy format, POLYDATA; ParaView's PVD).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "iga/core/sampled_mesh.hpp"

namespace iga {

/// Point data of one VTK file: named scalar or 3-vector fields, one value per point.
using VtkPointData = PointFields;

/// No file holds a non-finite number: a non-finite coordinate or field value is written as 0
/// and its point gets the scalar field non_finite = 1 (present only when some point needs it).
///
/// Writes points as a polyline (`connect` = true: a curve such as a rope's centre line) or as
/// independent vertices (contact points). Throws std::runtime_error if the file cannot be
/// written or a field's length differs from the number of points.
void write_vtk_polydata(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                        bool connect, const VtkPointData& data = {},
                        const std::string& title = "iga");

/// Writes a structured grid of points (nu x nv, u fastest: point i + nu j) as quadrilaterals
/// (a sampled surface). Throws std::runtime_error as write_vtk_polydata, and if the number of
/// points is not nu nv or nu, nv < 2.
void write_vtk_grid(const std::string& path, const std::vector<Eigen::Vector3d>& points, int nu,
                    int nv, const VtkPointData& data = {}, const std::string& title = "iga");

/// Writes a sampled mesh (a body, contact points, a tool's grid) with its fields: points and
/// polylines as write_vtk_polydata, grids as write_vtk_grid.
void write_vtk(const std::string& path, const SampledMesh& mesh, const std::string& title = "iga");

/// A ParaView collection (.pvd): (time, file) pairs, files relative to the .pvd's folder.
class VtkCollection {
 public:
  using Entries = std::vector<std::pair<double, std::string>>;
  /// A collection at `path` with the given entries (a restarted run's series), not yet written.
  explicit VtkCollection(std::string path, Entries entries = {})
      : path_(std::move(path)), entries_(std::move(entries)) {}
  /// Adds an entry and rewrites the .pvd at once, so that a run that stops midway leaves a
  /// valid collection of what it wrote.
  void add(double time, const std::string& file);
  /// Writes the .pvd of the entries so far (std::runtime_error if it cannot).
  void write() const;
  const Entries& entries() const { return entries_; }

 private:
  std::string path_;
  Entries entries_;
};

}  // namespace iga
