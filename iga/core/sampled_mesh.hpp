// Output fields apart from any file format: a body, a contact pair or a tool hands a SampledMesh
// (points, how they connect, named fields per point) to a writer (iga/output: one writer per
// format, e.g. legacy VTK).
//
// Notation: a sample is a point of a body at parameters (u, v) (rods: u only) inside element e;
// fields are values per sample, scalars or 3-vectors, in the order they are added.
#pragma once

#include <algorithm>
#include <array>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "iga/core/partition.hpp"

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
  /// A part of a grid (a process's block of a cut patch): the column and row of its first
  /// point in the whole grid (kGrid).
  int i0 = 0, j0 = 0;
  std::vector<Eigen::Vector3d> points;
  /// The body's parameters (u, v) and element of each point, where the mesh samples a body (for
  /// fields added by others, e.g. a contact pair's contact pressure on the body); else empty.
  std::vector<std::array<double, 2>> params;
  std::vector<int> elements;
  PointFields fields;
};

/// A grid over a patch's element spans, `samples` intervals per span and direction (kGrid;
/// bu, bv: the breaks of the knot vectors in u and v), without points or fields yet: its size,
/// and each sample's parameters and element (u fastest; elements eu + n_u ev, a span's end
/// belonging to that span, the first sample to the first span). Only the spans of `block` are
/// sampled (a process's part of a patch spread over several; by default all); the elements
/// keep their numbers over the whole patch.
inline SampledMesh element_grid(const std::vector<double>& bu, const std::vector<double>& bv,
                                int samples, const ElementBlock& block = {}) {
  const auto along = [samples](const std::vector<double>& br, int lo, int hi) {
    std::vector<std::pair<double, int>> s;  // (parameter, span)
    const int n = static_cast<int>(br.size()) - 1;
    lo = std::max(lo, 0);
    hi = std::min(hi, n);
    for (int k = lo; k < hi; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      for (int i = (k == lo ? 0 : 1); i <= samples; ++i)
        s.emplace_back(br[kk] + (br[kk + 1] - br[kk]) * i / samples, k);
    }
    return s;
  };
  const auto us = along(bu, block.u0, block.u1), vs = along(bv, block.v0, block.v1);
  const int ne_u = static_cast<int>(bu.size()) - 1;
  SampledMesh m;
  m.shape = SampledMesh::Shape::kGrid;
  m.nu = static_cast<int>(us.size());
  m.nv = static_cast<int>(vs.size());
  m.i0 = std::max(block.u0, 0) * samples;
  m.j0 = std::max(block.v0, 0) * samples;
  for (const auto& [v, ev] : vs)
    for (const auto& [u, eu] : us) {
      m.params.push_back({u, v});
      m.elements.push_back(eu + ne_u * ev);
    }
  return m;
}

}  // namespace iga
