// The membrane body type of the model file (body_types.hpp): membranes on NURBS surfaces of the
// geometry section (iga/membrane/membrane.hpp), their materials ("type": "membrane"), edge
// conditions, dead surface loads and follower pressure, and STAS contact pairs shared with the
// shells (attach_surface_pairs). Every error names the file, the JSON path and the value.
#include "geometry/constructions.hpp"
#include "iga/membrane/membrane.hpp"
#include "iga/model/body_types.hpp"

namespace iga::model_detail {

namespace {

/// {"type": "membrane", "law": "saint_venant_kirchhoff" (E, nu) or "neo_hookean" (mu),
/// "thickness", "prestress"}.
MembraneMaterial parse_membrane_material(const JsonCursor& m) {
  m.expect_object({"type", "law", "E", "nu", "mu", "thickness", "prestress", "description"});
  MembraneMaterial mm;
  if (m.has("law") && one_of(m["law"], {"saint_venant_kirchhoff", "neo_hookean"}) == "neo_hookean")
    mm.law = MembraneLaw::kNeoHookean;
  if (mm.law == MembraneLaw::kNeoHookean) {
    if (m.has("E") || m.has("nu"))
      m.fail_plain(
          "a neo-Hookean membrane (incompressible) takes the shear modulus \"mu\", "
          "not \"E\" or \"nu\"");
    mm.mu = positive(m["mu"]);
  } else {
    if (m.has("mu")) m["mu"].fail("belongs to \"law\": \"neo_hookean\"; give \"E\" and \"nu\"");
    mm.E = positive(m["E"]);
    mm.nu = m["nu"].as_number();
    if (!(mm.nu > -1.0 && mm.nu <= 0.5)) m["nu"].fail("must be in (-1, 0.5]");
  }
  mm.thickness = positive(m["thickness"]);
  if (m.has("prestress")) mm.prestress = positive(m["prestress"], true);
  return mm;
}

void parse_membrane_condition(const JsonCursor& o, const Context& ctx, MembraneProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type =
      one_of(o["type"], {"fix", "displacement", "simply_supported", "symmetry"});
  check_body(o, ctx);
  try {
    if (type == "fix") {
      fix_points(o, ctx, p);
    } else if (type == "displacement") {
      o.expect_object({"type", "body", "point", "value", "magnitude", "direction", "curve",
                       "motion", "description"});
      const int i = point_index(o["point"], ctx);
      const Vector3d d = vector_value(o, "value", ctx, -1);
      if (const auto m = motion_of(o, ctx))
        prescribe_following(o, p, i, d, curve_of(o, ctx), m);
      else
        p.prescribe(i, d, curve_of(o, ctx));
    } else if (type == "simply_supported") {  // the edge's control points, chosen components
      o.expect_object({"type", "body", "edge", "components", "description"});
      p.support(parse_edge(o["edge"]), components(o));
    } else {
      o.expect_object({"type", "body", "edge", "normal", "description"});
      const Vector3d n = vec3(o["normal"]);
      if (!(n.norm() > 0.0)) o["normal"].fail("must be a non-zero vector");
      p.symmetry(parse_edge(o["edge"]), n);
    }
  } catch (const MembraneError& e) {
    o.fail_plain(e.what());
  }
}

void parse_membrane_load(const JsonCursor& o, const Context& ctx, MembraneProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type = one_of(o["type"], {"surface_load", "pressure"});
  check_body(o, ctx);
  if (type == "surface_load") {  // dead force per reference area
    o.expect_object({"type", "name", "body", "q", "curve", "description"});
    p.add_surface_load(vec3(o["q"]), curve_of(o, ctx));
  } else {  // follower, per current area, along a_1 x a_2
    o.expect_object({"type", "name", "body", "p", "curve", "description"});
    p.add_pressure(o["p"].as_number(), curve_of(o, ctx));
  }
}

std::unique_ptr<Body> build_membrane(const BodyInput& in) {
  const JsonCursor& b = in.b;
  b.expect_object({"type", "surface", "material", "quadrature_points", "description"});
  const JsonCursor sc = b["surface"];
  const auto* surface = dynamic_cast<const NurbsSurface*>(in.geometry.surface(sc.as_string()));
  if (surface == nullptr) sc.fail("names no NURBS surface of the geometry section");
  const ElementBlock block = surface_block(in, sc, *surface, "membrane");
  const MembraneMaterial material =
      parse_membrane_material(body_material(b, in.materials, {"membrane"}, "membrane"));
  const int qp = int_or(b, "quadrature_points", 0, 0, 20, "0..20 (0: p + 1)");
  std::unique_ptr<MembraneProblem> problem;
  try {
    problem = std::make_unique<MembraneProblem>(*surface, material, qp, block);
  } catch (const MembraneError& e) {
    sc.fail(e.what());
  }
  in.ctx.shape = surface_shape(*surface);
  attach_surface_pairs(in, *problem, *surface, "membrane", material.thickness, block);
  for_each_entry(in.root, "boundary_conditions", in.ctx,
                 [&](const JsonCursor& o) { parse_membrane_condition(o, in.ctx, *problem); });
  for_each_entry(in.root, "loads", in.ctx,
                 [&](const JsonCursor& o) { parse_membrane_load(o, in.ctx, *problem); });
  return problem;
}

}  // namespace

BodyType membrane_body_type() {
  BodyType t;
  t.material_types = {"membrane"};
  t.check_material = [](const JsonCursor& m) { parse_membrane_material(m); };
  t.build = build_membrane;
  t.cut = true;
  return t;
}

}  // namespace iga::model_detail
