// libFuzzer target: load + evaluate + project + a few solver steps. The input is a model file;
// if it loads, every curve and surface of its geometry is evaluated at a few parameters, every
// surface (and patch group) is used as a rigid surface for a closest-point and a ray projection
// of points taken from the input's hash, and an analysis model runs a few load steps. Rejections
// must be ModelErrors; projections and runs must report their outcome as a status, never throw,
// never produce a non-finite foot point for a point they call converged.
// Work caps, so that an execution stays in milliseconds under the sanitizers: the integers that
// size the model (elements, refinement, quadrature and contact points, augmentations) are clamped
// before anything is built (fuzz_caps.hpp); an analysis runs only with at most kMaxDofs unknowns,
// at most kMaxSteps attempted steps (converged or cut back) of at most kMaxIterations Newton
// iterations each (its solver settings; the model's own smaller values kept).
// IGA_FUZZ_VERBOSE=1: what happened to each input on stderr (to check seeds: scripts/fuzz.sh).
// Build: scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined; off by default).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <type_traits>
#include <variant>

#include "contact/rigid_surface.hpp"
#include "fuzz/fuzz_caps.hpp"
#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

namespace {

constexpr int kMaxDofs = 400;
constexpr int kMaxSteps = 3;
constexpr int kMaxIterations = 8;

const bool verbose = std::getenv("IGA_FUZZ_VERBOSE") != nullptr;

/// A number in [0, 1) from the hash h and a salt.
double unit(std::size_t h, int salt) {
  return static_cast<double>((h >> (salt * 7 % 50)) % 1009) / 1009.0;
}

void exercise_geometry(const iga::GeometryModel& g, std::size_t h) {
  for (const auto& [name, entity] : g.entities) {
    if (const auto* c = std::get_if<iga::NurbsCurve>(&entity)) {
      const iga::Interval d = c->domain();
      for (int k = 0; k < 3; ++k) (void)c->derivs(d.lo + unit(h, k) * (d.hi - d.lo), 2);
      continue;
    }
    if (std::holds_alternative<iga::PatchGroup>(entity) || iga::as_surface(entity) != nullptr) {
      const iga::RigidSurface rigid = iga::RigidSurface::from_geometry(g, name);
      const iga::Box3& box = rigid.box();
      for (int k = 0; k < 2; ++k) {
        iga::Vector3d x;
        for (int i = 0; i < 3; ++i) {
          const double lo = std::isfinite(box.lo[i]) ? box.lo[i] : -1.0;
          const double hi = std::isfinite(box.hi[i]) ? box.hi[i] : 1.0;
          x[i] = lo + (2.0 * unit(h, 3 * k + i) - 0.5) * (hi - lo);
        }
        const iga::ProjectionResult cp = rigid.closest_point(x);
        if (cp.status == iga::ProjectionStatus::interior && !cp.point.allFinite()) __builtin_trap();
        (void)rigid.ray(x, iga::Vector3d(unit(h, 11) - 0.5, unit(h, 12) - 0.5, 1.0));
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  iga::fuzz::set_process_caps();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t h = std::hash<std::string>{}(text);
  iga::Json doc;
  try {
    doc = iga::parse_json_text(text, "fuzz.json");
  } catch (const iga::ModelError& e) {
    if (verbose) std::cerr << "fuzz_pipeline: " << e.what() << "\n";
    return 0;
  }
  if (!doc.is_object() || !doc.contains("geometry")) return 0;
  iga::fuzz::clamp_work(doc);
  iga::GeometryModel g;
  try {
    g = iga::parse_geometry(doc["geometry"], "fuzz.json", iga::JsonPointer("/geometry"));
  } catch (const iga::ModelError& e) {
    if (verbose) std::cerr << "fuzz_pipeline: " << e.what() << "\n";
    return 0;
  }
  exercise_geometry(g, h);
  if (!doc.contains("bodies")) return 0;
  try {
    iga::Analysis a = iga::Analysis::from_json(doc, "fuzz.json");
    if (a.problem().num_dofs() > kMaxDofs) {
      if (verbose) std::cerr << "fuzz_pipeline: " << a.problem().num_dofs() << " unknowns\n";
      return 0;
    }
    iga::NonlinearSolverSettings& s = a.solver_settings();
    s.max_steps = std::min(s.max_steps, kMaxSteps);
    s.max_iterations = std::min(s.max_iterations, kMaxIterations);
    const iga::AnalysisResult r = a.run();
    if (verbose)
      std::cerr << "fuzz_pipeline: " << r.steps.size() << " steps to t = " << r.solver.t << "\n";
  } catch (const iga::ModelError& e) {
    if (verbose) std::cerr << "fuzz_pipeline: " << e.what() << "\n";
  }
  return 0;
}
