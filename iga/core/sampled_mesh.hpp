// Output fields apart from any file format: a body, a contact pair or a tool hands a SampledMesh
// (points, how they connect, named fields per point) to a writer (iga/output: one writer per
// format, e.g. legacy VTK).
//
// Notation: a sample is a point of a body at parameters (u, v) (rods: u only) inside element e;
// fields are values per sample, scalars or 3-vectors, in the order they are added.
#pragma once

#include <array>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace iga {

/// Named fields, one value per point.
struct PointFields {
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> vectors;

  /// Empty fields of these names, in this order (replacing any).
  void name(std::initializer_list<const char*> scalar_names,
            std::initializer_list<const char*> vector_names) {
    scalars.clear();
    vectors.clear();
    for (const char* n : scalar_names) scalars.emplace_back(n, std::vector<double>{});
    for (const char* n : vector_names) vectors.emplace_back(n, std::vector<Eigen::Vector3d>{});
  }
  /// Appends the fields of `more` (the same points) after these.
  void add(PointFields&& more) {
    for (auto& f : more.scalars) scalars.push_back(std::move(f));
    for (auto& f : more.vectors) vectors.push_back(std::move(f));
  }
  /// One point's values, in the order of the fields (as many as there are fields).
  void append(std::initializer_list<double> s, std::initializer_list<Eigen::Vector3d> v) {
    if (s.size() != scalars.size() || v.size() != vectors.size())
      throw std::logic_error("PointFields::append: one value per field expected");
    auto sv = s.begin();
    for (auto& f : scalars) f.second.push_back(*sv++);
    auto vv = v.begin();
    for (auto& f : vectors) f.second.push_back(*vv++);
  }
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

/// Parameters of a grid over element spans (the breaks of a knot vector): `samples` intervals
/// per span, the spans' shared ends once.
inline std::vector<double> span_samples(const std::vector<double>& breaks, int samples) {
  std::vector<double> s;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
    for (int i = (k == 0 ? 0 : 1); i <= samples; ++i)
      s.push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * i / samples);
  return s;
}

/// The element span of grid sample i of span_samples(.., samples): the first sample belongs to
/// span 0, a span's end to that span.
inline int span_of_sample(std::size_t i, int samples) {
  return i == 0 ? 0 : static_cast<int>((i - 1) / static_cast<std::size_t>(samples));
}

}  // namespace iga
