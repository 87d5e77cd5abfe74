// `iga make KIND ... --out FILE`: writes a model with an exact NURBS construction (or the
// interpolated helix), optionally refined, for use as a rigid surface or a rod's centre line.
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>

#include "apps/iga_commands.hpp"
#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"
#include "iga/model/model.hpp"

namespace iga::app {

namespace {

struct MakeOptions {
  std::string kind, out, name;
  double radius = 1.0, height = 2.0, major_radius = 3.0, minor_radius = 1.0;
  double angle_deg = 360.0, alpha_deg = 30.0, s1 = 0.5, s2 = 2.0, size = 10.0, a = 0.025;
  double pitch = 1.0;
  int points = 33, patches = 1, elevate = 0, subdivide = 1;
  bool inward = false;
};

constexpr double kDeg = std::numbers::pi / 180.0;

// Bicubic 8x8 rational free-form patch with non-uniform knots: a smooth bump over a square.
NurbsSurface freeform(double size) {
  const std::vector<double> U = {0, 0, 0, 0, 0.1, 0.3, 0.45, 0.7, 1, 1, 1, 1};
  const std::vector<double> V = {0, 0, 0, 0, 0.2, 0.35, 0.6, 0.85, 1, 1, 1, 1};
  std::vector<Vector3d> P;
  std::vector<double> w;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const double x = size * (i / 7.0 - 0.5), y = size * (j / 7.0 - 0.5);
      const double z = 0.15 * size * std::sin(2.1 * i / 7.0 * std::numbers::pi) *
                       std::cos(1.3 * j / 7.0 * std::numbers::pi);
      P.emplace_back(x + 0.03 * size * std::sin(3.0 * j), y, z);
      w.push_back(1.0 + 0.25 * std::sin(1.7 * i + 0.9 * j));
    }
  return NurbsSurface(3, U, 3, V, P, w);
}

NurbsSurface refine(NurbsSurface s, const MakeOptions& o) {
  if (o.elevate > 0) s = elevate_degree(s, o.elevate, o.elevate);
  if (o.subdivide > 1) s = subdivide(s, o.subdivide, o.subdivide);
  return s;
}

int run_make(const MakeOptions& o) {
  Model m;
  m.name = o.name.empty() ? o.kind : o.name;
  auto add = [&](const std::string& n, GeometryEntity e) {
    m.geometry.entities.emplace_back(n, std::move(e));
  };
  const Vector3d O = Vector3d::Zero(), Z = Vector3d::UnitZ(), X = Vector3d::UnitX();
  const int sign = o.inward ? -1 : 1;
  auto surf = [&](const std::string& n, NurbsSurface s) {
    s = refine(std::move(s), o);
    s.set_normal_sign(sign);
    add(n, std::move(s));
  };
  if (o.kind == "cylinder") {
    m.description = "NURBS cylinder, radius " + std::to_string(o.radius) + ", height " +
                    std::to_string(o.height) + ", axis z";
    const double total = o.angle_deg * kDeg;
    if (o.patches == 1) {
      surf("cylinder", make_cylinder(O, Z, X, o.radius, o.height, 0.0, total));
    } else {
      PatchGroup g;
      for (int k = 0; k < o.patches; ++k) {
        const std::string n = "cylinder_" + std::to_string(k);
        surf(n, make_cylinder(O, Z, X, o.radius, o.height, total * k / o.patches,
                              total * (k + 1) / o.patches));
        g.patches.push_back(n);
      }
      add("cylinder", g);
    }
  } else if (o.kind == "torus") {
    m.description = "NURBS torus about z";
    surf("torus", make_torus(O, Z, o.major_radius, o.minor_radius));
  } else if (o.kind == "sphere") {
    m.description = "NURBS sphere";
    surf("sphere", make_sphere(O, o.radius));
  } else if (o.kind == "cone") {
    m.description = "NURBS cone frustum, apex at the origin, axis z";
    surf("cone", make_cone(O, Z, X, o.alpha_deg * kDeg, o.s1, o.s2));
  } else if (o.kind == "plane") {
    m.description = "bilinear plane patch";
    surf("plane", make_plane_patch(Vector3d(-o.size / 2, -o.size / 2, 0), o.size * X,
                                   o.size * Vector3d::UnitY()));
  } else if (o.kind == "hyperboloid") {
    m.description = "bilinear hyperboloid z = a x y (KS15 eq. 11)";
    surf("hyperboloid",
         make_bilinear_hyperboloid(o.a, -o.size / 2, o.size / 2, -o.size / 2, o.size / 2));
  } else if (o.kind == "freeform") {
    m.description = "bicubic rational free-form patch, 8x8 control points, non-uniform knots";
    surf("freeform", freeform(o.size));
  } else if (o.kind == "helix") {
    const HelixApproximation h = make_helix_cubic(o.radius, o.pitch, o.angle_deg * kDeg, o.points);
    m.description = "cubic B-spline interpolating a helix, radius " + std::to_string(o.radius) +
                    ", pitch " + std::to_string(o.pitch) + ", max deviation " +
                    std::to_string(h.max_deviation);
    std::cerr << "iga make: helix max deviation " << h.max_deviation << "\n";
    add("helix", h.curve);
  } else if (o.kind == "circle") {
    m.description = "rational quadratic full circle";
    add("circle", make_circle(O, Z, o.radius));
  } else {
    throw std::invalid_argument("unknown kind '" + o.kind + "'");
  }
  save_model(m, o.out);
  std::cerr << "iga make: wrote " << o.out << "\n";
  return 0;
}

}  // namespace

Action add_make_command(CLI::App& app) {
  auto o = std::make_shared<MakeOptions>();
  CLI::App* cmd = app.add_subcommand("make", "Write a model with an exact NURBS construction");
  cmd->add_option("kind", o->kind, "What to make")
      ->required()
      ->check(CLI::IsMember({"cylinder", "torus", "sphere", "cone", "plane", "hyperboloid",
                             "freeform", "helix", "circle"}));
  cmd->add_option("--out,-o", o->out, "Model file to write")->required();
  cmd->add_option("--name", o->name, "Model name (default: the kind)");
  cmd->add_option("--radius", o->radius, "Radius (cylinder, sphere, helix, circle)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--height", o->height, "Cylinder height")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--major-radius", o->major_radius, "Torus centre-circle radius")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--minor-radius", o->minor_radius, "Torus tube radius")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--angle-deg", o->angle_deg, "Cylinder sector / helix polar angle, degrees")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 3600.0));
  cmd->add_option("--alpha-deg", o->alpha_deg, "Cone generator angle to the base plane, degrees")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 89.999));
  cmd->add_option("--s1", o->s1, "Cone: inner radial distance")->capture_default_str();
  cmd->add_option("--s2", o->s2, "Cone: outer radial distance")->capture_default_str();
  cmd->add_option("--size", o->size, "Edge length (plane, hyperboloid, freeform)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--a", o->a, "Hyperboloid coefficient in z = a x y")->capture_default_str();
  cmd->add_option("--pitch", o->pitch, "Helix pitch (rise per turn)")->capture_default_str();
  cmd->add_option("--points", o->points, "Helix interpolation points")
      ->capture_default_str()
      ->check(CLI::Range(4, 100000));
  cmd->add_option("--patches", o->patches, "Cylinder: split into this many patches (a patch group)")
      ->capture_default_str()
      ->check(CLI::Range(1, 360));
  cmd->add_option("--elevate", o->elevate, "Raise the surface degree by this much")
      ->capture_default_str()
      ->check(CLI::Range(0, 5));
  cmd->add_option("--subdivide", o->subdivide, "Split every surface element into N x N")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--inward", o->inward, "Flip the surface normal (inward)");
  return [o]() { return run_make(*o); };
}

}  // namespace iga::app
