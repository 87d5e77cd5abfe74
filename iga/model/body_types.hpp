// The body types of the model file, keyed by a body's "type" (docs/model_format.md, "bodies"):
// each registers its reader (the body with its conditions, loads and contact pairs, and its
// shape for the shared parsers of monitors and reactions) and its material types. The loader
// (analysis.cpp) names no body type: it looks the type up here. Built in (body_types.cpp): "rod"
// (rod_body.cpp), "shell" (shell_body.cpp) and "membrane" (membrane_body.cpp).
//
// Notation: a reader gets the model's root, the body's entry b, the context of the body being
// read (its name, index, the load curves, tools and motions read before), the geometry and the
// materials section.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry/nurbs_surface.hpp"
#include "iga/model/sections.hpp"

namespace iga::model_detail {

/// Everything a body type's reader gets.
struct BodyInput {
  const JsonCursor& root;  ///< the model
  const JsonCursor& b;     ///< the body's entry ("bodies"/<name>)
  Context& ctx;            ///< the reader sets ctx.shape
  const GeometryModel& geometry;
  const JsonCursor& materials;  ///< the "materials" section (possibly empty)
  /// The processes of the run and this one's rank: a body type that cuts its bodies
  /// (BodyType::cut) builds the part of process `rank` only (iga/core/partition.hpp).
  int rank = 0, processes = 1;
};

/// A body type of the model file.
struct BodyType {
  /// The "type"s of the material entries this body reads (e.g. "rod", "rod_circular").
  std::vector<std::string> material_types;
  /// Checks a material entry of one of those types (ModelError at its key).
  std::function<void(const JsonCursor& m)> check_material;
  /// Builds the body with the boundary conditions, loads and contact pairs that name it (in
  /// the file's order) and sets in.ctx.shape; ModelError at the entry at fault.
  std::function<std::unique_ptr<Body>(const BodyInput& in)> build;
  /// Whether a body of this type is cut into parts over the processes of a run (each process
  /// builds and assembles its part: a shell's block of elements); otherwise it goes whole to
  /// one process (Analysis::from_json balances them).
  bool cut = false;
};

/// Registers a body type under its "type" name (replacing one of the name).
void register_body_type(const std::string& type, BodyType t);
/// The body type named at c (a body's "type"); ModelError at c listing the known types.
const BodyType& body_type(const JsonCursor& c);
/// The registered type names, sorted.
std::vector<std::string> body_type_names();
/// The material types of every registered body type, sorted.
std::vector<std::string> material_type_names();
/// Checks a material entry by the body type that reads its "type" (ModelError at m["type"]
/// listing the known material types, or at the key at fault).
void check_material(const JsonCursor& m);

// ---- shared by the readers of bodies on NURBS surfaces (defined in shell_body.cpp) ---------
/// "u_min", "u_max", "v_min" or "v_max".
SurfaceEdge parse_edge(const JsonCursor& c);
/// A parameter pair (u, v) inside the surface's domain.
Vector2d surface_parameters(const JsonCursor& c, const NurbsSurface& S);
/// What the shared parsers need of a body on the surface S: [i, j] names a control point (i
/// along u), [u, v] a point of the surface.
BodyShape surface_shape(const NurbsSurface& S);
/// The STAS contact pairs ("surface_to_rigid", [KS15] Sects. 2-3) of the body being read
/// (in.ctx.body), on the surface of its control points, attached to `problem` in the file's
/// order; `thickness` places the contact faces ("face": lower, upper, mid), `body_type` names
/// the body in messages; contact points in the elements of `block` (a process's part).
void attach_surface_pairs(const BodyInput& in, ControlPointProblem& problem,
                          const NurbsSurface& surface, const std::string& body_type,
                          double thickness, const ElementBlock& block = {});
/// This process's block of the surface's elements (in.rank of in.processes; the whole patch
/// on one process), and the bound of the control points it touches (kMaxSurfaceControlPoints a
/// process); a patch that cannot be cut so, or a block above the bound, fails at `sc` (the
/// body's "surface"), naming `body_type`.
ElementBlock surface_block(const BodyInput& in, const JsonCursor& sc, const NurbsSurface& S,
                           const std::string& body_type);

}  // namespace iga::model_detail
