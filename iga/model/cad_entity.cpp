// "cad" entities: STEP and IGES faces as a patch group (see cad_entity.hpp).
#include "iga/model/cad_entity.hpp"

#include <filesystem>
#include <iostream>

#include "cad/cad_import.hpp"
#include "iga/model/sections.hpp"

namespace iga {

namespace {

using model_detail::one_of;
using model_detail::vec3;

CadPlacement parse_placement(const JsonCursor& c) {
  c.expect_object({"rotation", "translation"});
  CadPlacement p;
  if (c.has("rotation")) {
    const JsonCursor r = c["rotation"];
    r.expect_object({"point", "axis", "angle"});
    p.point = vec3(r["point"]);
    p.axis = vec3(r["axis"]);
    if (!(p.axis.norm() > 0.0)) r["axis"].fail("must not be zero");
    p.angle = r["angle"].as_number();
  }
  if (c.has("translation")) {
    const JsonCursor t = c["translation"];
    t.expect_object({"vector"});
    p.vector = vec3(t["vector"]);
  }
  return p;
}

}  // namespace

EntityExpander cad_entity_expander(const std::string& model_file) {
  return [model_file](const JsonCursor& e, const std::string& name) {
    e.expect_object({"type", "file", "faces", "unit", "placement", "strict"});
    const JsonCursor fc = e["file"];
    std::filesystem::path path = fc.as_string();
    if (path.is_relative()) path = std::filesystem::path(model_file).parent_path() / path;
    CadOptions opt;
    if (e.has("faces")) {
      const JsonCursor c = e["faces"];
      c.expect_array(1);
      for (std::size_t i = 0; i < c.size(); ++i) {
        const int k = c[i].as_int();
        if (k < 0) c[i].fail("face numbers start at 0");
        opt.faces.push_back(k);
      }
    }
    if (e.has("unit")) opt.unit = one_of(e["unit"], {"mm", "cm", "m", "in", "ft", "um", "km"});
    if (e.has("placement")) opt.placement = parse_placement(e["placement"]);
    if (e.has("strict")) opt.strict = e["strict"].as_bool();
    try {
      CadImport imported = import_cad(path.string(), name, opt);
      std::vector<std::pair<std::string, GeometryEntity>> out = std::move(imported.entities);
      PatchGroup group;
      for (const auto& [member, entity] : out) group.patches.push_back(member);
      out.emplace_back(name, std::move(group));
      // What OpenCASCADE skipped (an error with "strict"): said where the model is read.
      for (const std::string& w : imported.warnings)
        std::cerr << "warning: " << fc.file() << ": " << fc.path().to_string() << ": " << w << "\n";
      return out;
    } catch (const CadError& err) {
      if (err.face_option >= 0)
        e["faces"][static_cast<std::size_t>(err.face_option)].fail_plain(err.what());
      fc.fail_plain(err.what());
    }
  };
}

}  // namespace iga
