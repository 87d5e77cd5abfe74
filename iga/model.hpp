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

/// A whole model. Version 1 carries the geometry only.
struct Model {
  std::string name;
  std::string description;
  GeometryModel geometry;
  bool operator==(const Model&) const = default;
};

/// Reads and validates a model file. Throws ModelError.
Model load_model(const std::string& path);
/// Validates a parsed document; `file` is used in messages. Throws ModelError.
Model parse_model(const Json& j, const std::string& file);
/// The document save_model writes: "format", "version", "name", "description", "geometry".
Json model_to_json(const Model& m);
/// Writes model_to_json(m) readably (format_json). Throws std::runtime_error on I/O failure.
/// load_model(path) == m afterwards, exactly.
void save_model(const Model& m, const std::string& path);

}  // namespace iga
