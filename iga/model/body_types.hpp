// The body types of the model file, keyed by a body's "type" (docs/model_format.md, "bodies"):
// each registers its reader (the body with its conditions, loads and contact pairs, and its
// shape for the shared parsers of monitors and reactions) and its material types. The loader
// (analysis.cpp) names no body type: it looks the type up here. Built in: "rod"
// (rod_body.cpp) and "shell" (shell_body.cpp).
//
// Notation: a reader gets the model's root, the body's entry b, the context of the body being
// read (its name, index, the load curves, tools and motions read before), the geometry and the
// materials section.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "iga/model/sections.hpp"

namespace iga::model_detail {

/// Everything a body type's reader gets.
struct BodyInput {
  const JsonCursor& root;       ///< the model
  const JsonCursor& b;          ///< the body's entry ("bodies"/<name>)
  Context& ctx;                 ///< the reader sets ctx.shape
  const GeometryModel& geometry;
  const JsonCursor& materials;  ///< the "materials" section (possibly empty)
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

/// The built-in body types (their files).
BodyType rod_body_type();
BodyType shell_body_type();

}  // namespace iga::model_detail
