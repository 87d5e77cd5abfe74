// The analysis model file: one JSON document with the geometry and (in later versions) the
// materials, bodies, loads, contact and solver settings of a run. Format: docs/model_format.md.
// Errors name the file, the JSON path, the bad value and what was expected (json_reader.hpp).
#pragma once

#include <string>

#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"

namespace iga {

/// The value of the top-level "format" key, and the version this program reads and writes.
inline constexpr const char* kModelFormat = "iga-contact-model";
inline constexpr int kModelFormatVersion = 1;

/// The analysis sections (docs/model_format.md), in file order; iga/model/analysis.hpp reads them.
/// "app" is free-form input of the example programs (capstan, helix, saddle): ignored by the
/// generic loader.
inline constexpr const char* kAnalysisSections[] = {
    "materials", "bodies",  "load_curves",   "boundary_conditions",
    "loads",     "contact", "rigid_motions", "solver",
    "output",    "app"};

/// A whole model: the geometry, parsed, and the analysis sections as written (Analysis
/// validates and builds them).
struct Model {
  std::string name;
  std::string description;
  GeometryModel geometry;
  Json sections = Json::object();  ///< the analysis sections present, in file order
  bool has_analysis() const { return sections.contains("bodies"); }
  bool operator==(const Model&) const = default;
};

/// Reads and validates a model file. Throws ModelError.
Model load_model(const std::string& path);
/// Validates a parsed document; `file` is used in messages. Throws ModelError.
Model parse_model(const Json& j, const std::string& file);
/// The document save_model writes: "format", "version", "name", "description", "geometry",
/// then the analysis sections as read.
Json model_to_json(const Model& m);
/// Writes model_to_json(m) readably (format_json). Throws std::runtime_error on I/O failure.
/// load_model(path) == m afterwards, exactly.
void save_model(const Model& m, const std::string& path);

}  // namespace iga
