// The analysis model file: top-level keys, format/version checks, the geometry section, the
// analysis sections kept as written (docs/model_format.md).
#include "iga/model/model.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "iga/model/cad_entity.hpp"

namespace iga {

Model parse_model(const Json& j, const std::string& file) {
  const JsonCursor root(j, file);
  if (!j.is_object()) root.fail_type("an object (the model)");
  root.expect_object({"format", "version", "name", "description", "geometry", "materials", "bodies",
                      "load_curves", "boundary_conditions", "loads", "contact", "rigid_motions",
                      "solver", "output", "app"});

  if (root.has("format")) {
    const JsonCursor c = root["format"];
    if (c.as_string() != kModelFormat)
      c.fail(std::string("expected \"") + kModelFormat + "\" (the model file format)");
  }
  if (root.has("version")) {
    const JsonCursor c = root["version"];
    if (c.as_int() != kModelFormatVersion)
      c.fail("unsupported format version (this program reads version " +
             std::to_string(kModelFormatVersion) + ")");
  }
  Model m;
  if (root.has("name")) m.name = root["name"].as_string();
  if (root.has("description")) m.description = root["description"].as_string();
  const JsonCursor g = root["geometry"];
  m.geometry = parse_geometry(g.json(), file, g.path(), {{"cad", cad_entity_expander(file)}});
  for (const std::string& k : root.keys())
    for (const char* section : kAnalysisSections)
      if (k == section) {
        const JsonCursor c = root[k];
        const bool list = k == "boundary_conditions" || k == "loads" || k == "contact";
        if (list ? !c.json().is_array() : !c.json().is_object())
          c.fail_type(list ? "an array" : "an object");
        m.sections[k] = c.json();
      }
  return m;
}

Model load_model(const std::string& path) {
  return parse_model(read_json_file(path), path);
}

Json model_to_json(const Model& m) {
  Json j = Json::object();
  j["format"] = kModelFormat;
  j["version"] = kModelFormatVersion;
  j["name"] = m.name;
  j["description"] = m.description;
  j["geometry"] = geometry_to_json(m.geometry);
  for (const auto& [k, v] : m.sections.items()) j[k] = v;
  return j;
}

void save_model(const Model& m, const std::string& path) {
  const std::string text = format_json(model_to_json(m)) + "\n";
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(path + ": cannot write file: " + std::strerror(errno));
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path + ": error while writing the model file");
}

}  // namespace iga
