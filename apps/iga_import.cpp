// `iga import FILE.step --out FILE.json`: the faces of a STEP or IGES file (cad/cad_import.hpp)
// written as an ordinary model: one entity per face (NURBS or analytic, exact unless the
// import says otherwise) and a patch group of them under the tool's name, so that a user can
// inspect the faces and run without OpenCASCADE. Entities of the file OpenCASCADE skipped are a
// warning on stderr (an error with --strict).
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/iga_commands.hpp"
#include "cad/cad_import.hpp"
#include "iga/model/model.hpp"

namespace iga::app {

namespace {

struct ImportOptions {
  std::string file, out, name, unit = "mm";
  std::vector<int> faces;
  bool strict = false;
};

int run_import(const ImportOptions& o) {
  const std::string name = o.name.empty() ? std::filesystem::path(o.file).stem().string() : o.name;
  CadOptions opt;
  opt.faces = o.faces;
  opt.unit = o.unit;
  opt.strict = o.strict;
  const CadImport imp = import_cad(o.file, name, opt);
  for (const std::string& w : imp.warnings) std::cerr << "warning: " << w << "\n";
  Model m;
  m.name = name;
  m.description = "faces of " + std::filesystem::path(o.file).filename().string() +
                  " (lengths in " + o.unit + "), imported by iga import";
  PatchGroup group;
  for (const auto& [member, entity] : imp.entities) {
    m.geometry.entities.emplace_back(member, entity);
    group.patches.push_back(member);
  }
  m.geometry.entities.emplace_back(name, group);
  save_model(m, o.out);
  for (const CadFace& f : imp.faces)
    std::cout << "face " << f.index << ": " << f.cad_type << " -> " << f.entity_type
              << (f.exact ? " (exact)"
                          : " (approximated within " + std::to_string(f.tolerance) + ")")
              << "\n";
  std::cout << "wrote " << o.out << ": " << imp.entities.size() << " faces as the patch group \""
            << name << "\" (read in " << imp.seconds << " s)\n";
  return 0;
}

}  // namespace

Action add_import_command(CLI::App& app) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* cmd = app.add_subcommand("import", "Write the faces of a STEP or IGES file as a model");
  cmd->add_option("file", o->file, "CAD file (.step, .stp, .iges, .igs)")->required();
  cmd->add_option("--out,-o", o->out, "Model file to write (JSON)")->required();
  cmd->add_option("--name", o->name, "Name of the patch group (default: the file's stem)");
  cmd->add_option("--faces", o->faces,
                  "Faces to import, 0-based as `iga info` lists them "
                  "(default: all)")
      ->delimiter(',');
  cmd->add_option("--unit", o->unit, "Length unit to convert the file's lengths into")
      ->capture_default_str()
      ->check(CLI::IsMember({"mm", "cm", "m", "in", "ft", "um", "km"}));
  cmd->add_flag("--strict", o->strict,
                "Refuse a file of which OpenCASCADE skipped entities (default: a warning)");
  return [o]() { return run_import(*o); };
}

}  // namespace iga::app
