// JSON (de)serialization of geometric entities: NURBS curves and surfaces, analytic surfaces
// and patch groups. The format is documented in docs/model_format.md.
// Errors name the file, the JSON path (RFC 6901 pointer), the bad value and what was expected,
// e.g.  cyl.json: /geometry/roof/knots/u/3: knots must be non-decreasing, got 0.25 after 0.5
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/json_reader.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "geometry/trimmed_surface.hpp"

namespace iga {

/// A named set of surfaces acting as one (multi-patch rigid body). Members are names of
/// surface entities of the same model.
struct PatchGroup {
  std::vector<std::string> patches;
  bool operator==(const PatchGroup&) const = default;
};

using GeometryEntity = std::variant<NurbsCurve, NurbsSurface, Plane, Sphere, Cylinder, Torus, Cone,
                                    Hyperboloid, Revolution, PatchGroup, TrimmedSurface>;

/// The "geometry" section of a model: named entities in file order.
struct GeometryModel {
  std::vector<std::pair<std::string, GeometryEntity>> entities;

  const GeometryEntity* find(const std::string& name) const;
  /// The entity as a surface (NURBS or analytic), or nullptr if it is a curve or group.
  const Surface* surface(const std::string& name) const;
  const NurbsCurve* curve(const std::string& name) const;
  /// All surfaces of a group (or the single surface itself). Throws std::out_of_range.
  std::vector<const Surface*> surfaces_of(const std::string& name) const;
  bool operator==(const GeometryModel&) const = default;
};

/// The JSON type tag of an entity ("nurbs_curve", "cylinder", "patch_group", ...).
std::string entity_type(const GeometryEntity& e);
/// The entity as a Surface, or nullptr.
const Surface* as_surface(const GeometryEntity& e);

/// Reads an entity of a type this layer does not know (the model layer's "cad": faces of a
/// STEP file): given the entity's cursor and name, returns the entities it stands for, in
/// order; they join the model in its place (their names must be new).
using EntityExpander = std::function<std::vector<std::pair<std::string, GeometryEntity>>(
    const JsonCursor& entity, const std::string& name)>;

/// Parses a "geometry" object. `file` and `at` (the JSON pointer of `j`) are used in messages.
/// Entities keep the order of `j` (file order for documents from read_json_file; a plain
/// nlohmann::json converts implicitly, its keys then come alphabetically). An entity whose
/// "type" is a key of `expanders` is read by that expander.
/// Throws ModelError (see json_reader.hpp).
GeometryModel parse_geometry(const Json& j, const std::string& file, const JsonPointer& at,
                             const std::map<std::string, EntityExpander>& expanders = {});
/// Serializes in the model's entity order, placement, domain and normal written explicitly,
/// so that parse_geometry(geometry_to_json(m)) == m exactly (doubles are written with
/// round-trip precision; rational control points are chosen so that w * P reproduces the
/// stored homogeneous coordinates bit for bit).
Json geometry_to_json(const GeometryModel& m);
/// One entity as JSON (what geometry_to_json writes under its name).
Json entity_to_json(const GeometryEntity& e);

}  // namespace iga
