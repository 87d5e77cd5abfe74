// `iga info MODEL.json`: what a model holds; `iga info FILE.step`: the faces of a CAD file,
// with their type, what each imports as (or why it cannot be), size and trimming, the file's
// length unit and the factor applied; what OpenCASCADE skipped is a warning on stderr.
#include <iostream>
#include <memory>
#include <sstream>

#include "apps/iga_commands.hpp"
#include "cad/cad_import.hpp"
#include "iga/model/analysis.hpp"
#include "iga/model/model.hpp"

namespace iga::app {

namespace {
std::string interval(const Interval& i) {
  std::ostringstream os;
  os << "[" << i.lo << ", " << i.hi << "]";
  return os.str();
}

void describe(const std::string& name, const GeometryEntity& e) {
  std::cout << "  " << name << ": " << entity_type(e);
  if (const auto* c = std::get_if<NurbsCurve>(&e)) {
    std::cout << ", degree " << c->degree() << ", " << c->num_control_points()
              << " control points, " << c->knots().num_elements() << " elements"
              << (c->is_rational() ? ", rational" : "") << ", u in " << interval(c->domain());
  } else if (const auto* s = std::get_if<NurbsSurface>(&e)) {
    std::cout << ", degree " << s->degree_u() << "x" << s->degree_v() << ", " << s->num_u() << "x"
              << s->num_v() << " control points, " << s->knots_u().num_elements() << "x"
              << s->knots_v().num_elements() << " elements"
              << (s->is_rational() ? ", rational" : "");
  } else if (const auto* g = std::get_if<PatchGroup>(&e)) {
    std::cout << " of " << g->patches.size() << ":";
    for (const std::string& p : g->patches) std::cout << " " << p;
  }
  if (const Surface* s = as_surface(e)) {
    std::cout << ", u in " << interval(s->domain().u) << ", v in " << interval(s->domain().v)
              << (s->normal_sign() < 0 ? ", normal inward" : "")
              << (s->closed_u() ? ", closed in u" : "") << (s->closed_v() ? ", closed in v" : "");
  }
  std::cout << "\n";
}

bool is_cad_file(const std::string& path) {
  try {
    (void)cad_format(path);
    return true;
  } catch (const CadError&) {
    return false;
  }
}

int cad_info(const std::string& file, const std::string& unit) {
  const CadListing l = list_cad(file, unit);
  std::size_t failing = 0;
  for (const CadFace& f : l.faces) failing += !f.message.empty();
  std::cout << file << ": " << l.format << " file, " << l.faces.size() << " faces";
  if (failing > 0) std::cout << " (" << failing << " cannot be imported)";
  std::cout << "; length unit of the file: ";
  if (l.units.names.empty())
    std::cout << "not declared";
  else
    for (std::size_t i = 0; i < l.units.names.size(); ++i)
      std::cout << (i ? ", " : "") << l.units.names[i];
  std::cout << " (" << l.units.file_unit_mm << " mm), converted to " << l.units.unit
            << " by the factor " << l.units.factor << "; read in " << l.seconds << " s\n";
  for (const CadFace& f : l.faces) {
    const Eigen::Vector3d size = f.box_hi - f.box_lo;
    std::cout << "  face " << f.index << ": " << f.cad_type << " -> ";
    if (!f.message.empty()) {
      const std::string prefix = "cannot be imported: ";  // (said once)
      const bool said = f.message.rfind(prefix, 0) == 0;
      std::cout << prefix << f.message.substr(said ? prefix.size() : 0);
    } else {
      std::cout << f.entity_type
                << (f.exact ? " (exact)"
                            : " (approximated within " + std::to_string(f.tolerance) + ")");
    }
    if (!f.described) {
      std::cout << "\n";
      continue;
    }
    std::cout << ", area " << f.area << ", box " << size.x() << " x " << size.y() << " x "
              << size.z() << " from (" << f.box_lo.x() << ", " << f.box_lo.y() << ", "
              << f.box_lo.z() << "), " << (f.trimmed ? "trimmed" : "untrimmed") << ", " << f.wires
              << (f.wires == 1 ? " boundary loop" : " boundary loops") << "\n";
  }
  for (const std::string& w : l.warnings) std::cerr << "warning: " << w << "\n";
  return 0;
}
}  // namespace

Action add_info_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto unit = std::make_shared<std::string>("mm");
  CLI::App* cmd = app.add_subcommand(
      "info", "List the entities of a model file, or the faces of a STEP or IGES file");
  cmd->add_option("model", *file, "Model file (JSON), or a CAD file (.step, .stp, .iges, .igs)")
      ->required();
  cmd->add_option("--unit", *unit, "CAD files: the length unit to report in")
      ->capture_default_str()
      ->check(CLI::IsMember({"mm", "cm", "m", "in", "ft", "um", "km"}));
  return [file, unit]() {
    if (is_cad_file(*file)) return cad_info(*file, *unit);
    const Model m = load_model(*file);
    std::cout << *file << ": model \"" << m.name << "\"";
    if (!m.description.empty()) std::cout << " -- " << m.description;
    std::cout << "\n" << m.geometry.entities.size() << " geometric entities:\n";
    for (const auto& [name, e] : m.geometry.entities) describe(name, e);
    if (m.has_analysis()) {  // validate the analysis sections too, and summarize them
      const Analysis a = Analysis::load(*file);
      std::cout << "analysis: " << a.describe() << "\n";
    }
    return 0;
  };
}

}  // namespace iga::app
