// The rod body type of the model file (body_types.hpp): Kirchhoff rods on curves of the geometry
// section, with or without torsion ("torsion": true), their materials, boundary conditions,
// loads and CTRS contact pairs ([KS15] Sects. 4-5; docs/model_format.md, "Analysis sections").
// Every error names the file, the JSON path and the value.
#include <cmath>
#include <numbers>
#include <type_traits>

#include "geometry/constructions.hpp"
#include "iga/contact_integrals/rod_contact_problem.hpp"
#include "iga/model/body_types.hpp"
#include "iga/rod/twisting_rod.hpp"

namespace iga::model_detail {

namespace {

const std::vector<std::string> kRodMaterials{"rod", "rod_circular"};

/// Unit tangent pointing out of the curve at one of its ends.
Vector3d outward_tangent(const NurbsCurve& C, bool at_end) {
  const Interval D = C.domain();
  const Vector3d d = C.derivs(at_end ? D.hi : D.lo, 1).d[1].normalized();
  return at_end ? d : Vector3d(-d);
}

/// "start", "end" or a parameter in the curve's domain.
double curve_parameter(const JsonCursor& c, const NurbsCurve& C) {
  const Interval D = C.domain();
  if (c.json().is_string()) return one_of(c, {"start", "end"}) == "start" ? D.lo : D.hi;
  const double xi = c.as_number();
  if (xi < D.lo || xi > D.hi)
    c.fail("parameter must lie in the curve's domain [" + std::to_string(D.lo) + ", " +
           std::to_string(D.hi) + "]");
  return xi;
}

/// The knot of a rod with torsion at c: "start", "end" or a knot index.
int twist_knot(const JsonCursor& c, const TwistingRodProblem& p) {
  if (c.json().is_string())
    return p.end_knot(one_of(c, {"start", "end"}) == "start" ? RodEnd::kStart : RodEnd::kEnd);
  const int k = c.as_int();
  if (k < 0 || k >= p.rod().num_knots())
    c.fail("knot index must be in 0.." + std::to_string(p.rod().num_knots() - 1));
  return k;
}

/// Boundary conditions of rods, with and without torsion (P: RodProblem, TwistingRodProblem).
template <class P>
void parse_rod_boundary_condition(const JsonCursor& o, const Context& ctx, P& p) {
  constexpr bool kTwist = std::is_same_v<P, TwistingRodProblem>;
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type =
      kTwist ? one_of(o["type"], {"fix", "clamp", "symmetry", "displacement", "twist"})
             : one_of(o["type"], {"fix", "clamp", "symmetry", "displacement"});
  check_body(o, ctx);
  try {
    if (type == "fix") {
      fix_points(o, ctx, p);
    } else if (type == "clamp") {
      o.expect_object({"type", "body", "end", "description"});
      const std::string e = one_of(o["end"], {"start", "end"});
      p.clamp(e == "start" ? RodEnd::kStart : RodEnd::kEnd);
    } else if (type == "twist") {  // the twist at a knot, fixed or along a load curve (radians)
      if constexpr (kTwist) {
        o.expect_object({"type", "body", "at", "angle", "curve", "description"});
        const int k = twist_knot(o["at"], p);
        const double angle = o.has("angle") ? o["angle"].as_number() : 0.0;
        if (angle == 0.0 && !o.has("curve"))
          p.fix_twist(k);
        else
          p.prescribe_twist(k, angle, curve_of(o, ctx));
      }
    } else if (type == "symmetry") {  // the end crosses a symmetry plane of normal n
      o.expect_object({"type", "body", "end", "normal", "description"});
      const std::string e = one_of(o["end"], {"start", "end"});
      const Vector3d n = vec3(o["normal"]);
      if (!(n.norm() > 0.0)) o["normal"].fail("must be a non-zero vector");
      p.symmetry(e == "start" ? RodEnd::kStart : RodEnd::kEnd, n);
    } else {
      o.expect_object({"type", "body", "point", "value", "magnitude", "direction", "curve",
                       "motion", "description"});
      const int i = point_index(o["point"], ctx);
      const Vector3d d = vector_value(o, "value", ctx, end_of(o["point"]));
      if (const auto m = motion_of(o, ctx))
        prescribe_following(o, p, i, d, curve_of(o, ctx), m);
      else
        p.prescribe(i, d, curve_of(o, ctx));
    }
  } catch (const RodError& e) {
    o.fail_plain(e.what());
  }
}

/// Loads of rods, with and without torsion (P: RodProblem, TwistingRodProblem).
template <class P>
void parse_rod_load(const JsonCursor& o, const Context& ctx, P& p) {
  constexpr bool kTwist = std::is_same_v<P, TwistingRodProblem>;
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type = kTwist
                               ? one_of(o["type"], {"point_force", "line_load", "moment", "torque"})
                               : one_of(o["type"], {"point_force", "line_load", "moment"});
  check_body(o, ctx);
  auto at = [&](const JsonCursor& c) { return ctx.shape.parameters(c)[0]; };
  if (type == "point_force") {
    o.expect_object({"type", "name", "body", "at", "force", "magnitude", "direction", "curve",
                     "motion", "description"});
    const double xi = at(o["at"]);
    const Vector3d F = vector_value(o, "force", ctx, end_of(o["at"]));
    if (const auto m = motion_of(o, ctx))
      turning_force(F, curve_of(o, ctx), m,
                    [&](const Vector3d& e, LoadCurve c) { p.add_point_load(xi, e, std::move(c)); });
    else
      p.add_point_load(xi, F, curve_of(o, ctx));
  } else if (type == "line_load") {
    o.expect_object({"type", "name", "body", "q", "curve", "description"});
    p.add_line_load(vec3(o["q"]), curve_of(o, ctx));
  } else if constexpr (kTwist) {
    if (type == "torque") {
      o.expect_object({"type", "name", "body", "at", "torque", "curve", "description"});
      p.add_torque_at(at(o["at"]), o["torque"].as_number(), curve_of(o, ctx));
    } else {
      o.expect_object({"type", "name", "body", "at", "moment", "curve", "description"});
      p.add_moment_at(at(o["at"]), vec3(o["moment"]), curve_of(o, ctx));
    }
  } else {
    o.expect_object({"type", "name", "body", "at", "moment", "curve", "description"});
    p.add_moment(at(o["at"]), vec3(o["moment"]), curve_of(o, ctx));
  }
}

/// A rod material ("rod": EA, EI or EI1 and EI2, GJ; "rod_circular": E, radius, G or nu).
RodSection parse_rod_material(const JsonCursor& m) {
  const std::string type = one_of(m["type"], {"rod", "rod_circular"});
  RodSection s;
  if (type == "rod_circular") {
    m.expect_object({"type", "E", "radius", "G", "nu", "description"});
    const double E = positive(m["E"]), r = positive(m["radius"]);
    s = RodSection::circular(E, r);
    if (m.has("G") && m.has("nu")) m.fail_plain("give either \"G\" or \"nu\"");
    double G = 0.0;
    if (m.has("G")) G = positive(m["G"]);
    if (m.has("nu")) {
      const double nu = m["nu"].as_number();
      if (!(nu > -1.0 && nu < 0.5)) m["nu"].fail("must be in (-1, 0.5)");
      G = E / (2.0 * (1.0 + nu));
    }
    s.GJ = G * std::numbers::pi * r * r * r * r / 2.0;  // J: the polar moment of the circle
    return s;
  }
  m.expect_object({"type", "EA", "EI", "EI1", "EI2", "GJ", "ref_direction", "description"});
  if (m.has("GJ")) s.GJ = positive(m["GJ"]);
  s.EA = positive(m["EA"]);
  if (m.has("EI")) {
    if (m.has("EI1") || m.has("EI2")) m.fail_plain("give either \"EI\" or \"EI1\" and \"EI2\"");
    s.EI1 = s.EI2 = positive(m["EI"], true);
  } else {
    s.EI1 = positive(m["EI1"], true);
    s.EI2 = positive(m["EI2"], true);
  }
  if (m.has("ref_direction")) s.ref_direction = vec3(m["ref_direction"]);
  return s;
}

/// A rod's contact pairs, boundary conditions and loads (P: RodProblem, TwistingRodProblem; the
/// contact acts on the centre line's control points alone).
template <class P>
void attach_rod_entries(const JsonCursor& root, Context& ctx, const GeometryModel& geometry,
                        P& problem) {
  for_each_entry(root, "contact", ctx, [&](const JsonCursor& c) {
    // The type first: a shell's contact keys would otherwise be reported as unknown keys.
    if (one_of(c["type"], {"curve_to_rigid", "surface_to_rigid"}) != "curve_to_rigid")
      c["type"].fail("a rod's contact is \"curve_to_rigid\"");
    c.expect_object({"name", "type", "body", "rigid", "eps_N", "eps_T", "mu", "radius",
                     "points_per_element", "enforcement", "penetration_tol", "max_augmentations",
                     "slip_tol", "moment_about", "search_distance", "per_face", "description"});
    check_body(c, ctx);
    const std::shared_ptr<const RigidSurface> rigid = rigid_surface(c["rigid"], geometry, ctx);
    CurveContactParameters cp;
    penalty_and_friction(c, cp.law);
    cp.radius = c.has("radius") ? positive(c["radius"], true) : 0.0;
    const ContactEnforcement enforcement = parse_enforcement(c);
    cp.points_per_element = int_or(c, "points_per_element", 3, 1, 16, "1..16");
    // per_face: a pair per piece (face) of the tool, so that a contact point touches several
    // faces at once, each with its own gap, normal and friction history (issue 15, item 4).
    const bool per_face = c.has("per_face") && c["per_face"].as_bool();
    const int n_tools = per_face ? rigid->num_patches() : 1;
    std::vector<std::shared_ptr<const RigidSurface>> tools;
    tools.reserve(static_cast<std::size_t>(n_tools));
    for (int i = 0; i < n_tools; ++i)
      tools.push_back(per_face ? std::make_shared<const RigidSurface>(rigid->piece(i)) : rigid);
    for (const std::shared_ptr<const RigidSurface>& tool : tools) {
      auto pair = std::make_unique<CurveContactPair>(problem.rod().reference(), tool, cp);
      pair->contact().set_enforcement(enforcement);  // validated by parse_enforcement
      if (c.has("search_distance"))  // default: rope radius + the longest element chord
        pair->contact().set_search_distance(positive(c["search_distance"]));
      if (const auto m = ctx.motions.find(c["rigid"].as_string()); m != ctx.motions.end())
        pair->set_motion(m->second);
      if constexpr (std::is_same_v<P, TwistingRodProblem>)
        pair->contact().set_rolling(true);  // the rod hands its frames at each assembly
      problem.attach(std::move(pair));
    }
  });
  for_each_entry(root, "boundary_conditions", ctx,
                 [&](const JsonCursor& o) { parse_rod_boundary_condition(o, ctx, problem); });
  for_each_entry(root, "loads", ctx, [&](const JsonCursor& o) { parse_rod_load(o, ctx, problem); });
}

/// What the shared parsers need of a rod on `curve` with n control points: "start" and "end"
/// name its end points and parameters, "outward_tangent" a direction at an end.
BodyShape rod_shape(const NurbsCurve& curve, int n) {
  BodyShape s;
  s.n_points = n;
  s.corners = {0, n - 1};
  s.named_point = [n](const JsonCursor& c) {
    if (!c.json().is_string()) return -1;
    return one_of(c, {"start", "end"}) == "start" ? 0 : n - 1;
  };
  s.parameters = [&curve](const JsonCursor& c) { return Vector2d(curve_parameter(c, curve), 0.0); };
  s.named_direction = [&curve](const JsonCursor& d, int where) {
    one_of(d, {"outward_tangent"});
    if (where != 0 && where != 1)
      d.fail("\"outward_tangent\" needs the point \"start\" or \"end\"");
    return outward_tangent(curve, where == 1);
  };
  return s;
}

/// The rod body, its contact pair, boundary conditions and loads.
std::unique_ptr<Body> build_rod(const BodyInput& in) {
  const JsonCursor& b = in.b;
  Context& ctx = in.ctx;
  b.expect_object({"type", "curve", "material", "quadrature_points", "bending", "stress_free",
                   "torsion", "description"});
  const JsonCursor cc = b["curve"];
  const NurbsCurve* curve = in.geometry.curve(cc.as_string());
  if (curve == nullptr) cc.fail("names no curve of the geometry section");
  // The size bound of constructed curves holds for explicit ones too (docs/model_format.md).
  if (const long n = static_cast<long>(curve->knots().breaks().size()) - 1; n > kMaxCurveElements)
    cc.fail("the curve has " + std::to_string(n) + " elements, above the limit of " +
            std::to_string(kMaxCurveElements) + " of a rod body");
  const JsonCursor mc = b["material"];
  const JsonCursor mat = body_material(b, in.materials, kRodMaterials, "rod");
  const RodSection section = parse_rod_material(mat);
  const bool torsion = b.has("torsion") && b["torsion"].as_bool();
  if (torsion && !(section.GJ > 0.0))
    mc.fail(
        "a rod with \"torsion\": true needs a torsional stiffness: \"GJ\" (type \"rod\") or "
        "\"G\" or \"nu\" (type \"rod_circular\")");
  if (torsion && b.has("bending"))
    b["bending"].fail("a rod with torsion has its section frame: no \"bending\" measure to choose");
  RodOptions opt;
  opt.quadrature_points = int_or(b, "quadrature_points", 0, 0, 20, "0..20 (0: p + 1)");
  if (b.has("bending"))
    opt.bending =
        one_of(b["bending"], {"transported_frame", "curvature_magnitude"}) == "transported_frame"
            ? BendingMeasure::kTransportedFrame
            : BendingMeasure::kCurvatureMagnitude;
  if (b.has("stress_free"))
    opt.straight_stress_free = one_of(b["stress_free"], {"reference", "straight"}) == "straight";
  try {
    if (torsion) {
      auto problem = std::make_unique<TwistingRodProblem>(TwistingRod(*curve, section, opt));
      ctx.shape = rod_shape(*curve, problem->rod().num_control_points());
      attach_rod_entries(in.root, ctx, in.geometry, *problem);
      return problem;
    }
    auto problem = std::make_unique<RodProblem>(KirchhoffRod(*curve, section, opt));
    ctx.shape = rod_shape(*curve, problem->rod().num_control_points());
    attach_rod_entries(in.root, ctx, in.geometry, *problem);
    return problem;
  } catch (const RodError& e) {
    b.fail_plain(e.what());
  }
}

}  // namespace

BodyType rod_body_type() {
  BodyType t;
  t.material_types = kRodMaterials;
  t.check_material = [](const JsonCursor& m) { parse_rod_material(m); };
  t.build = build_rod;
  return t;
}

}  // namespace iga::model_detail
