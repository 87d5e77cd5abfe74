// The "cad" geometry entity of a model (issue 15): a rigid tool read from a STEP or IGES file
// (cad/cad_import.hpp) becomes, under the entity's name, a patch group of the file's faces,
// named <name>.face<k>. docs/model_format.md, section 3.
//   {"type": "cad", "file": "die.step", ["faces": [0, 2]], ["unit": "mm"],
//    ["placement": {"rotation": {"point", "axis", "angle"}, "translation": {"vector"}}],
//    ["strict": false]}   (strict: entities of the file OpenCASCADE skipped are an error, not
//    a warning on stderr)
#pragma once

#include <string>

#include "geometry/geometry_io.hpp"

namespace iga {

/// The expander of "cad" entities for parse_geometry: `model_file` locates relative paths
/// (relative to the model file's folder). Errors name the model file, the JSON path and the
/// CAD file.
EntityExpander cad_entity_expander(const std::string& model_file);

}  // namespace iga
