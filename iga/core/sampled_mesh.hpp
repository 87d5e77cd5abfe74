// Output fields apart from any file format: a body, a contact pair or a tool hands a SampledMesh
// (points, how they connect, named fields per point) to a writer (iga/output: one writer per
// format, e.g. legacy VTK).
//
// Notation: a sample is a point of a body at parameters (u, v) (rods: u only) inside element e;
// fields are values per sample, scalars or 3-vectors, in the order they are added.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace iga {

/// Named fields, one value per point.
struct PointFields {
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> vectors;
};

/// Points with fields and their connectivity.
struct SampledMesh {
  enum class Shape {
    kPoints,    ///< independent points (contact points, feet)
    kPolyline,  ///< one line through the points in order (a rod's centre line)
    kGrid,      ///< nu x nv structured grid, u fastest: point i + nu j (a sampled surface)
  };
  Shape shape = Shape::kPoints;
  int nu = 0, nv = 0;  ///< grid size (kGrid)
  std::vector<Eigen::Vector3d> points;
  /// The body's parameters (u, v) and element of each point, where the mesh samples a body (for
  /// fields added by others, e.g. a contact pair's contact pressure on the body); else empty.
  std::vector<std::array<double, 2>> params;
  std::vector<int> elements;
  PointFields fields;
};

}  // namespace iga
