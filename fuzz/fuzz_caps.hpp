// Caps on the work of one input of the model fuzz targets (fuzz_loader.cpp, fuzz_pipeline.cpp;
// scripts/fuzz.sh). The loader accepts models that take seconds to set up (a rod of 100,000
// elements, a shell of 40,000 control points: docs/model_format.md, "Limits"), ten times that
// under the sanitizers; libFuzzer finds such values at once (one changed digit) and then spends
// its time on them. Before a document is loaded, clamp_work lowers the integers that size the
// work (element counts, refinement, quadrature and contact points, augmentations) to small caps
// wherever they appear. A value above the library's own limit is left as it is: the loader
// rejects it before building anything, and that check stays fuzzed. The library's defaults and
// limits are not changed; the file size is capped by -max_len (scripts/fuzz.sh), the solver's
// steps and Newton iterations by the pipeline target (its solver settings).
// The rigid surfaces' projectors (every NURBS rigid surface of a contact pair, every surface the
// pipeline projects onto) precompute a subdivision tree of up to 6144 nodes per patch, which
// costs seconds per patch under the sanitizers and coverage: set_process_caps (called from
// LLVMFuzzerInitialize) lowers its budget to kTreeBudget nodes (a one-element patch two levels
// deep, four elements one level, more elements none), which keeps the tree's code fuzzed and
// gives the same feet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "contact/closest_point.hpp"
#include "geometry/json_reader.hpp"

namespace iga::fuzz {

/// A key whose non-negative integer values (or arrays of them: [n_u, n_v]) are clamped.
struct WorkCap {
  std::string_view key;
  std::uint64_t cap;    ///< values in (cap, limit] become cap
  std::uint64_t limit;  ///< the library's limit: values above it are left for the loader
};

inline constexpr WorkCap kWorkCaps[] = {
    {"elements", 8, 100000},           // constructed curves (and surfaces), kMaxCurveElements
    {"arc_elements", 8, 100000},       // wrap_path
    {"span_elements", 2, 100000},      // wrap_path
    {"subdivide", 4, 1024},            // "refine" of a constructed surface
    {"elevate", 2, 5},                 // "refine"
    {"quadrature_points", 6, 20},      // rod and shell bodies (0: p + 1)
    {"thickness_points", 5, 20},       // neo-Hookean shell material
    {"points_per_element", 4, 16},     // rod contact
    {"points_per_direction", 4, 20},   // shell contact
    {"max_augmentations", 3, 1000},    // augmented Lagrange contact
    {"samples_per_element", 4, 1000},  // output (not written by the targets)
};

/// Node budget of the projectors' trees in the fuzz targets (PatchProjector::set_tree_budget).
inline constexpr std::size_t kTreeBudget = 64;

/// The process-wide caps, once before the first input (LLVMFuzzerInitialize).
inline void set_process_caps() {
  PatchProjector::set_tree_budget(kTreeBudget);
}

namespace detail {

inline void clamp_number(Json& v, const WorkCap& c) {
  if (!v.is_number_unsigned()) return;  // negative, fractional, other types: the loader's to judge
  const auto x = v.get<std::uint64_t>();
  if (x > c.cap && x <= c.limit) v = c.cap;
}

}  // namespace detail

/// Clamps the values of kWorkCaps's keys anywhere in doc (the document is at most kMaxJsonDepth
/// deep: parse_json_text checked it).
inline void clamp_work(Json& doc) {
  if (doc.is_array()) {
    for (Json& e : doc) clamp_work(e);
    return;
  }
  if (!doc.is_object()) return;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    Json& value = it.value();
    for (const WorkCap& c : kWorkCaps) {
      if (it.key() != c.key) continue;
      if (value.is_array())
        for (Json& e : value) detail::clamp_number(e, c);
      else
        detail::clamp_number(value, c);
    }
    clamp_work(value);
  }
}

}  // namespace iga::fuzz
