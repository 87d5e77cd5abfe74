// The shell body type of the model file (body_types.hpp): Kirchhoff-Love shells on NURBS surfaces
// of the geometry section, their materials, boundary conditions, springs, loads and STAS contact
// pairs ([KS15] Sects. 2-3; docs/model_format.md, "Analysis sections"). Every error names the
// file, the JSON path and the value.
#include <optional>

#include "geometry/constructions.hpp"
#include "iga/contact_integrals/shell_contact_problem.hpp"
#include "iga/model/body_types.hpp"

namespace iga::model_detail {

// ---- shared by the readers of bodies on NURBS surfaces (body_types.hpp) ----------------------

SurfaceEdge parse_edge(const JsonCursor& c) {
  const std::string e = one_of(c, {"u_min", "u_max", "v_min", "v_max"});
  return e == "u_min"   ? SurfaceEdge::kUMin
         : e == "u_max" ? SurfaceEdge::kUMax
         : e == "v_min" ? SurfaceEdge::kVMin
                        : SurfaceEdge::kVMax;
}

/// A parameter pair (u, v) inside the surface's domain.
Vector2d surface_parameters(const JsonCursor& c, const NurbsSurface& S) {
  const std::vector<double> uv = c.as_numbers();
  if (uv.size() != 2) c.fail_type("surface parameters [u, v]");
  const Domain2 D = S.domain();
  const Interval I[2] = {D.u, D.v};
  for (int k = 0; k < 2; ++k)
    if (uv[k] < I[k].lo || uv[k] > I[k].hi)
      c[static_cast<std::size_t>(k)].fail("parameter must lie in the surface's domain [" +
                                          std::to_string(I[k].lo) + ", " + std::to_string(I[k].hi) +
                                          "]");
  return {uv[0], uv[1]};
}

/// What the shared parsers need of a body on the surface S: [i, j] names a control point
/// (i along u), [u, v] a point of the surface.
BodyShape surface_shape(const NurbsSurface& S) {
  const int nu = S.num_u(), nv = S.num_v();
  BodyShape s;
  s.n_points = nu * nv;
  s.corners = {0, nu - 1, nu * (nv - 1), nu * nv - 1};
  s.named_point = [nu, nv](const JsonCursor& c) {
    if (!c.json().is_array()) return -1;
    if (c.size() != 2) c.fail_type("a control point [i, j] or an index");
    const int i = c[0].as_int(), j = c[1].as_int();
    if (i < 0 || i >= nu) c[0].fail("i must be in 0.." + std::to_string(nu - 1));
    if (j < 0 || j >= nv) c[1].fail("j must be in 0.." + std::to_string(nv - 1));
    return i + nu * j;
  };
  s.array_is_point = [](const JsonCursor& c) { return c.size() == 2 && c[0].json().is_number(); };
  s.parameters = [&S](const JsonCursor& c) { return surface_parameters(c, S); };
  return s;
}

void attach_surface_pairs(const BodyInput& in, ControlPointProblem& problem,
                          const NurbsSurface& surface, const std::string& body_type,
                          double thickness, const ElementBlock& block) {
  const Context& ctx = in.ctx;
  for_each_entry(in.root, "contact", ctx, [&](const JsonCursor& c) {
    if (one_of(c["type"], {"curve_to_rigid", "surface_to_rigid"}) != "surface_to_rigid")
      c["type"].fail("a " + body_type + "'s contact is \"surface_to_rigid\"");
    c.expect_object({"name", "type", "body", "rigid", "eps_N", "eps_T", "mu", "strategy", "face",
                     "points_per_direction", "search_distance", "enforcement", "penetration_tol",
                     "slip_tol", "max_augmentations", "moment_about", "description"});
    check_body(c, ctx);
    const std::shared_ptr<const RigidSurface> rigid = rigid_surface(c["rigid"], in.geometry, ctx);
    for (const Surface* piece : in.geometry.surfaces_of(c["rigid"].as_string()))
      if (piece == &surface)
        c["rigid"].fail("is (or holds) the " + body_type + "'s own surface \"" +
                        in.b["surface"].as_string() +
                        "\"; the rigid surface must be another surface");
    SurfaceContactParameters cp;
    penalty_and_friction(c, cp.law);
    if (c.has("strategy"))
      cp.strategy = one_of(c["strategy"], {"master", "slave"}) == "master"
                        ? SurfaceContactStrategy::kRigidMaster
                        : SurfaceContactStrategy::kRigidSlave;
    if (c.has("face")) {
      const std::string f = one_of(c["face"], {"lower", "upper", "mid"});
      cp.face = f == "lower"   ? ShellFace::kLower
                : f == "upper" ? ShellFace::kUpper
                               : ShellFace::kMid;
    }
    cp.points_per_direction =
        int_or(c, "points_per_direction", cp.points_per_direction, 1, 20, "1..20");
    if (c.has("search_distance")) cp.search_distance = positive(c["search_distance"]);
    const ContactEnforcement enforcement = parse_enforcement(c);
    cp.thickness = thickness;
    try {
      auto pair = std::make_unique<SurfaceContactPair>(surface, rigid, cp, block);
      pair->contact().set_enforcement(enforcement);  // validated by parse_enforcement
      if (const auto m = ctx.motions.find(c["rigid"].as_string()); m != ctx.motions.end())
        pair->set_motion(m->second);
      problem.attach(std::move(pair));
    } catch (const std::invalid_argument& e) {
      c.fail_plain(e.what());
    }
  });
}

namespace {

void parse_shell_boundary_condition(const JsonCursor& o, const Context& ctx, ShellProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type =
      one_of(o["type"], {"fix", "displacement", "simply_supported", "clamp", "symmetry", "spring"});
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
    } else if (type == "simply_supported") {
      o.expect_object({"type", "body", "edge", "components", "description"});
      const std::vector<int> c = components(o);
      const SurfaceEdge e = parse_edge(o["edge"]);
      for (int k : c) p.simply_support(e, {k});
    } else if (type == "clamp") {
      o.expect_object({"type", "body", "edge", "description"});
      p.clamp(parse_edge(o["edge"]));
    } else if (type == "symmetry") {
      o.expect_object({"type", "body", "edge", "normal", "description"});
      const Vector3d n = vec3(o["normal"]);
      if (!(n.norm() > 0.0)) o["normal"].fail("must be a non-zero vector");
      p.symmetry(parse_edge(o["edge"]), n.normalized());
    } else {
      o.expect_object({"type", "body", "points", "stiffness", "curve", "direction", "description"});
      const double k = positive(o["stiffness"]);
      std::optional<Vector3d> d;
      if (o.has("direction")) {
        const Vector3d v = vec3(o["direction"]);
        if (!(v.norm() > 0.0)) o["direction"].fail("must be a non-zero vector");
        d = v.normalized();
      }
      // A spring's stiffness k curve(t); without a curve it is constant.
      const LoadCurve curve = o.has("curve") ? curve_of(o, ctx) : constant_curve();
      for (int i : point_list(o["points"], ctx)) p.add_spring(i, k, curve, d);
    }
  } catch (const ShellError& e) {
    o.fail_plain(e.what());
  }
}

void parse_shell_load(const JsonCursor& o, const Context& ctx, ShellProblem& p) {
  if (!o.json().is_object()) o.fail_type("an object with a \"type\" key");
  const std::string type =
      one_of(o["type"], {"surface_load", "pressure", "edge_load", "point_force"});
  check_body(o, ctx);
  if (type == "surface_load") {  // dead force per reference area
    o.expect_object({"type", "name", "body", "q", "curve", "description"});
    p.add_surface_load(vec3(o["q"]), curve_of(o, ctx));
  } else if (type == "pressure") {  // follower, per current area, along +a_3
    o.expect_object({"type", "name", "body", "p", "curve", "description"});
    p.add_pressure(o["p"].as_number(), curve_of(o, ctx));
  } else if (type == "edge_load") {  // dead force per reference length
    o.expect_object({"type", "name", "body", "edge", "q", "curve", "description"});
    p.add_edge_load(parse_edge(o["edge"]), vec3(o["q"]), curve_of(o, ctx));
  } else {
    o.expect_object({"type", "name", "body", "at", "force", "magnitude", "direction", "curve",
                     "motion", "description"});
    const Vector2d uv = ctx.shape.parameters(o["at"]);
    const Vector3d F = vector_value(o, "force", ctx, -1);
    if (const auto m = motion_of(o, ctx))
      turning_force(F, curve_of(o, ctx), m, [&](const Vector3d& e, LoadCurve c) {
        p.add_point_load(uv[0], uv[1], e, std::move(c));
      });
    else
      p.add_point_load(uv[0], uv[1], F, curve_of(o, ctx));
  }
}

/// A shell material: E, nu, thickness, the law and the points through the thickness.
ShellMaterial parse_shell_material(const JsonCursor& m) {
  m.expect_object({"type", "E", "nu", "thickness", "law", "thickness_points", "description"});
  ShellMaterial s;
  s.E = positive(m["E"]);
  const JsonCursor n = m["nu"];
  s.nu = n.as_number();
  if (!(s.nu > -1.0 && s.nu < 0.5)) n.fail("must be in (-1, 0.5)");
  s.thickness = positive(m["thickness"]);
  if (m.has("law") && one_of(m["law"], {"saint_venant_kirchhoff", "neo_hookean"}) == "neo_hookean")
    s.law = ShellLaw::kNeoHookean;
  if (m.has("thickness_points")) {
    const JsonCursor t = m["thickness_points"];
    s.thickness_points = t.as_int();
    if (s.thickness_points < 2 || s.thickness_points > kMaxGaussPoints)
      t.fail("must be in [2, 20]");
  }
  return s;
}

/// The bound of a process's part of a surface body (kMaxSurfaceControlPoints): the control
/// points its block of elements touches (the whole surface on one process).
void check_surface_size(const JsonCursor& sc, const NurbsSurface& S, const ElementBlock& block,
                        int rank, int processes, const std::string& body_type) {
  const long n = static_cast<long>(S.num_u()) * S.num_v();
  if (processes == 1) {
    if (n > kMaxSurfaceControlPoints)
      sc.fail("the surface has " + std::to_string(n) + " control points, above the limit of " +
              std::to_string(kMaxSurfaceControlPoints) + " of a " + body_type +
              " body (a process's; run it on several: docs/parallel.md)");
    return;
  }
  const long nu = S.knots_u().breaks().size() - 1, nv = S.knots_v().breaks().size() - 1;
  const long part = (std::min<long>(block.u1, nu) - block.u0 + S.degree_u()) *
                    (std::min<long>(block.v1, nv) - block.v0 + S.degree_v());
  if (part > kMaxSurfaceControlPoints)
    sc.fail("the surface has " + std::to_string(n) + " control points; the part of process " +
            std::to_string(rank) + " of " + std::to_string(processes) + " (" + block.describe() +
            ", " + std::to_string(part) + " control points) is above the limit of " +
            std::to_string(kMaxSurfaceControlPoints) +
            " a process sets up: run it on more processes");
}

}  // namespace

ElementBlock surface_block(const BodyInput& in, const JsonCursor& sc, const NurbsSurface& S,
                           const std::string& body_type) {
  ElementBlock block;
  if (in.processes > 1) {  // this process's block of the patch's elements
    const int nu = static_cast<int>(S.knots_u().breaks().size()) - 1;
    const int nv = static_cast<int>(S.knots_v().breaks().size()) - 1;
    try {
      block = element_block(in.rank, in.processes, nu, nv);
    } catch (const std::invalid_argument& e) {
      sc.fail(e.what());
    }
  }
  check_surface_size(sc, S, block, in.rank, in.processes, body_type);
  return block;
}

namespace {

/// The shell body, its contact pair, boundary conditions, springs and loads.
std::unique_ptr<Body> build_shell(const BodyInput& in) {
  const JsonCursor& b = in.b;
  Context& ctx = in.ctx;
  const JsonCursor& root = in.root;
  const GeometryModel& geometry = in.geometry;
  b.expect_object({"type", "surface", "material", "quadrature_points", "description"});
  const JsonCursor sc = b["surface"];
  const auto* surface = dynamic_cast<const NurbsSurface*>(geometry.surface(sc.as_string()));
  if (surface == nullptr) sc.fail("names no NURBS surface of the geometry section");
  const JsonCursor mat = body_material(b, in.materials, {"shell"}, "shell");
  ShellOptions opt;
  opt.quadrature_points = int_or(b, "quadrature_points", 0, 0, 20, "0..20 (0: p + 1)");
  // A shell with its contact points costs about 26 KB per control point set up and 48 KB with
  // its tangent assembled: a process sets up at most kMaxSurfaceControlPoints of them
  // (docs/model_format.md).
  opt.block = surface_block(in, sc, *surface, "shell");
  std::optional<KirchhoffLoveShell> shell;
  try {
    shell.emplace(*surface, parse_shell_material(mat), opt);
  } catch (const std::invalid_argument& e) {
    sc.fail(e.what());
  }
  ctx.shape = surface_shape(*surface);

  auto problem = std::make_unique<ShellProblem>(std::move(*shell));
  attach_surface_pairs(in, *problem, *surface, "shell", problem->shell().material().thickness,
                       opt.block);
  for_each_entry(root, "boundary_conditions", ctx,
                 [&](const JsonCursor& o) { parse_shell_boundary_condition(o, ctx, *problem); });
  for_each_entry(root, "loads", ctx,
                 [&](const JsonCursor& o) { parse_shell_load(o, ctx, *problem); });
  return problem;
}

}  // namespace

BodyType shell_body_type() {
  BodyType t;
  t.material_types = {"shell"};
  t.check_material = [](const JsonCursor& m) { parse_shell_material(m); };
  t.build = build_shell;
  t.cut = true;
  return t;
}

}  // namespace iga::model_detail
