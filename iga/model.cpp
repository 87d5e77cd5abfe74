// The analysis model file: top-level keys, format/version checks, sections reserved for later
// versions (docs/model_format.md, "Planned sections").
#include "iga/model.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace iga {

namespace {

/// Sections of the planned format that this version does not read yet. Rejecting them (rather
/// than ignoring them) keeps a newer model from being run silently without its loads.
constexpr const char* kReservedSections[] = {"materials", "bodies",      "boundary_conditions",
                                             "loads",     "load_curves", "contact",
                                             "solver",    "output"};

}  // namespace

Model parse_model(const Json& j, const std::string& file) {
  const JsonCursor root(j, file);
  if (!j.is_object()) root.fail_type("an object (the model)");
  for (const char* section : kReservedSections)
    if (root.has(section))
      root[section].fail_plain(std::string("section \"") + section +
                               "\" is not supported yet by this version (format version " +
                               std::to_string(kModelFormatVersion) + " reads \"geometry\" only)");
  root.expect_object({"format", "version", "name", "description", "geometry"});

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
  m.geometry = parse_geometry(g.json(), file, g.path());
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
