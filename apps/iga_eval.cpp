// `iga eval`: evaluate the curves and surfaces of a model at a parameter, at the centre of
// their domains, or on a grid (CSV): point, derivatives, normal, metric, curvatures; for
// curves the Serret-Frenet frame, curvature and torsion.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "apps/iga_commands.hpp"
#include "geometry/differential_geometry.hpp"
#include "iga/model/model.hpp"

namespace iga::app {

namespace {

struct EvalOptions {
  std::string file;
  std::string entity;
  std::vector<double> uv;
  double u = NAN;
  bool has_u = false;
  bool center = false;
  int grid = 0;
  std::string out;
};

// x + 0.0 turns -0 into 0 for display.
std::string vec(const Vector3d& x) {
  std::ostringstream os;
  os << std::setprecision(10) << "[" << x.x() + 0.0 << ", " << x.y() + 0.0 << ", " << x.z() + 0.0
     << "]";
  return os.str();
}
std::string mat(const Matrix2d& a) {
  std::ostringstream os;
  os << std::setprecision(10) << "[[" << a(0, 0) + 0.0 << ", " << a(0, 1) + 0.0 << "], ["
     << a(1, 0) + 0.0 << ", " << a(1, 1) + 0.0 << "]]";
  return os.str();
}

// A finite sampling range for an interval that may be unbounded.
Interval finite(const Interval& i, bool& clipped) {
  Interval r = i;
  if (!std::isfinite(r.lo)) r.lo = std::isfinite(r.hi) ? r.hi - 2.0 : -1.0, clipped = true;
  if (!std::isfinite(r.hi)) r.hi = r.lo + 2.0, clipped = true;
  return r;
}
double mid(const Interval& i) {
  bool c = false;
  const Interval f = finite(i, c);
  return 0.5 * (f.lo + f.hi);
}

void check_in(const Interval& i, double x, const char* what) {
  if (!(x >= i.lo && x <= i.hi)) {
    std::ostringstream os;
    os << what << " = " << x << " is outside the domain [" << i.lo << ", " << i.hi << "]";
    throw std::invalid_argument(os.str());
  }
}

// The frame at (u, v) for sampling. At a singular point of the parametrization (a pole, an
// apex, the axis of a surface of revolution: rho_1 x rho_2 = 0) surface_frame throws; then the
// point is still written, with the limit of the normal and of the curvatures where it exists:
// when one of rho_1, rho_2 vanishes, a whole parameter line collapses to the point, and the
// normals (curvatures) at points a small step off that line, taken along its whole length,
// must agree (a sphere's pole, the smooth tip of a paraboloid: the axis direction, curvatures
// of the cap). Where they do not (a cone's apex: the normals circle the axis) the normal and
// the curvatures are absent.
struct SampledFrame {
  bool singular = false, has_normal = true, has_curvature = true;
  SurfaceFrame f;
};

bool frame_finite(const SurfaceFrame& f) {
  return f.n.allFinite() && std::isfinite(f.k1) && std::isfinite(f.k2) &&
         std::isfinite(f.mean_curvature) && std::isfinite(f.gauss_curvature) &&
         f.a_inv.allFinite() && f.h.allFinite() && f.dir1.allFinite() && f.dir2.allFinite();
}

SampledFrame sampled_frame(const Surface& s, double u, double v) {
  SampledFrame out;
  const SurfaceDerivs d = s.derivs(u, v, 2);
  try {
    out.f = surface_frame(d, s.normal_sign());
    if (frame_finite(out.f)) return out;
  } catch (const GeometryError&) {
  }
  out.singular = true;
  out.has_normal = out.has_curvature = false;
  out.f = SurfaceFrame{};
  out.f.a1 = d.Su;
  out.f.a2 = d.Sv;
  // Which parameter line collapses: the one whose tangent vanishes against the other.
  const double lu = d.Su.norm(), lv = d.Sv.norm();
  if (!(std::max(lu, lv) > 0.0) || !std::isfinite(lu) || !std::isfinite(lv)) return out;
  const bool along_u = lu < lv;  // rho_1 ~ 0: the u-line through the point collapses
  bool clipped = false;
  const Interval line = finite(along_u ? s.domain().u : s.domain().v, clipped);
  const Interval off = finite(along_u ? s.domain().v : s.domain().u, clipped);
  const double at = along_u ? v : u;
  const double h = 1e-6 * (off.hi - off.lo);
  std::vector<SurfaceFrame> near;
  constexpr int kAlong = 16;
  for (double step : {h, -h}) {
    const double o = at + step;
    if (!(o >= off.lo && o <= off.hi)) continue;
    for (int k = 0; k < kAlong; ++k) {
      const double t = line.lo + (line.hi - line.lo) * (k + 0.5) / kAlong;
      try {
        const SurfaceFrame g = along_u ? surface_frame(s.derivs(t, o, 2), s.normal_sign())
                                       : surface_frame(s.derivs(o, t, 2), s.normal_sign());
        if (frame_finite(g)) near.push_back(g);
      } catch (const GeometryError&) {
      }
    }
  }
  if (near.size() < 2) return out;
  Vector3d sum = Vector3d::Zero();
  for (const SurfaceFrame& g : near) sum += g.n;
  const Vector3d n = sum.normalized();
  bool agree = sum.norm() > 0.0;
  for (const SurfaceFrame& g : near) agree = agree && g.n.dot(n) > 1.0 - 1e-8;  // ~1e-4 rad
  if (!agree) return out;
  out.has_normal = true;
  out.f.n = n;
  double k1 = 0.0, k2 = 0.0, scale = 0.0;
  for (const SurfaceFrame& g : near) {
    k1 += g.k1 / near.size();
    k2 += g.k2 / near.size();
    scale = std::max({scale, std::abs(g.k1), std::abs(g.k2)});
  }
  bool same = true;
  for (const SurfaceFrame& g : near)
    same = same && std::abs(g.k1 - k1) <= 1e-4 * scale + 1e-12 &&
           std::abs(g.k2 - k2) <= 1e-4 * scale + 1e-12;
  if (same) {
    out.has_curvature = true;
    out.f.k1 = k1;
    out.f.k2 = k2;
    out.f.mean_curvature = 0.5 * (k1 + k2);
    out.f.gauss_curvature = k1 * k2;
  }
  return out;
}

void print_surface(const std::string& name, const Surface& s, double u, double v) {
  const SurfaceDerivs d = s.derivs(u, v, 2);
  const SampledFrame sf = sampled_frame(s, u, v);
  const SurfaceFrame& f = sf.f;
  std::cout << std::setprecision(10) << name << " (" << s.type_name() << ") at (u, v) = (" << u
            << ", " << v << ")\n"
            << "  point      " << vec(d.S) << "\n"
            << "  S_u        " << vec(d.Su) << "\n"
            << "  S_v        " << vec(d.Sv) << "\n"
            << "  S_uu       " << vec(d.Suu) << "\n"
            << "  S_uv       " << vec(d.Suv) << "\n"
            << "  S_vv       " << vec(d.Svv) << "\n";
  if (sf.singular) {
    std::cout << "  singular point of the parametrization (|S_u x S_v| = 0): no metric; "
              << (sf.has_normal ? "normal and curvatures are limits from nearby points"
                                : "the normal has no limit here")
              << "\n";
    if (sf.has_normal) std::cout << "  normal     " << vec(f.n) << " (limit)\n";
    if (sf.has_curvature)
      std::cout << "  principal k1, k2   " << f.k1 << ", " << f.k2 << " (limit)\n"
                << "  mean H, Gauss K    " << f.mean_curvature << ", " << f.gauss_curvature
                << " (limit)\n";
    return;
  }
  std::cout << "  normal     " << vec(f.n) << "\n"
            << "  metric a_ij        " << mat(f.a) << "\n"
            << "  inverse a^ij       " << mat(f.a_inv) << "\n"
            << "  curvature h_ij     " << mat(f.h) << "\n"
            << "  principal k1, k2   " << f.k1 << ", " << f.k2 << "\n"
            << "  directions d1, d2  " << vec(f.dir1) << ", " << vec(f.dir2) << "\n"
            << "  mean H, Gauss K    " << f.mean_curvature << ", " << f.gauss_curvature << "\n";
}

void print_curve(const std::string& name, const NurbsCurve& c, double u) {
  const CurveDerivs d = c.derivs(u, 3);
  const CurveFrame f = curve_frame(d);
  std::cout << std::setprecision(10) << name << " (nurbs_curve) at u = " << u << "\n"
            << "  point      " << vec(d.d[0]) << "\n"
            << "  C'         " << vec(d.d[1]) << "\n"
            << "  C''        " << vec(d.d[2]) << "\n"
            << "  C'''       " << vec(d.d[3]) << "\n"
            << "  tangent    " << vec(f.tangent) << "\n"
            << "  normal     " << vec(f.normal) << "\n"
            << "  binormal   " << vec(f.binormal) << "\n"
            << "  curvature  " << f.curvature << "\n"
            << "  torsion    " << f.torsion << "\n";
}

void grid_surface(std::ostream& os, const std::string& name, const Surface& s, int n) {
  bool clipped = false;
  const Interval iu = finite(s.domain().u, clipped), iv = finite(s.domain().v, clipped);
  if (clipped)
    std::cerr << "iga eval: " << name << " has an unbounded domain; sampling [" << iu.lo << ", "
              << iu.hi << "] x [" << iv.lo << ", " << iv.hi << "]\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = iu.lo + (iu.hi - iu.lo) * i / (n - 1);
      const double v = iv.lo + (iv.hi - iv.lo) * j / (n - 1);
      const SurfaceDerivs d = s.derivs(u, v, 2);
      const SampledFrame sf = sampled_frame(s, u, v);
      const SurfaceFrame& f = sf.f;
      os << name << "," << u << "," << v << "," << d.S.x() << "," << d.S.y() << "," << d.S.z();
      if (sf.has_normal)
        os << "," << f.n.x() << "," << f.n.y() << "," << f.n.z();
      else
        os << ",,,";
      if (sf.has_curvature)
        os << "," << f.k1 << "," << f.k2 << "," << f.mean_curvature << "," << f.gauss_curvature;
      else
        os << ",,,,";
      os << "," << (sf.singular ? 1 : 0) << "\n";
    }
}

void grid_curve(std::ostream& os, const std::string& name, const NurbsCurve& c, int n) {
  const Interval I = c.domain();
  for (int i = 0; i < n; ++i) {
    const double u = I.lo + (I.hi - I.lo) * i / (n - 1);
    const CurveDerivs d = c.derivs(u, 3);
    os << name << "," << u << "," << d.d[0].x() << "," << d.d[0].y() << "," << d.d[0].z() << ",";
    // A point where C' = 0 has no frame: written with empty cells and the singular flag.
    try {
      const CurveFrame f = curve_frame(d);
      if (!f.tangent.allFinite() || !std::isfinite(f.curvature) || !std::isfinite(f.torsion))
        throw GeometryError("non-finite frame");
      os << f.tangent.x() << "," << f.tangent.y() << "," << f.tangent.z() << "," << f.curvature
         << "," << f.torsion << ",0\n";
    } catch (const GeometryError&) {
      os << ",,,,,1\n";
    }
  }
}

/// One surface: its grid's rows (the header before the first), or its point at --uv / --center.
void eval_surface(const EvalOptions& o, const std::string& name, const Surface& s,
                  std::ostream& csv, bool& header) {
  if (o.has_u) throw std::invalid_argument(name + " is a surface: use --uv U,V");
  if (o.grid > 0) {
    if (!header) csv << "entity,u,v,x,y,z,nx,ny,nz,k1,k2,H,K,singular\n";
    header = true;
    grid_surface(csv, name, s, o.grid);
    return;
  }
  const double u = o.center ? mid(s.domain().u) : o.uv[0];
  const double v = o.center ? mid(s.domain().v) : o.uv[1];
  check_in(s.domain().u, u, "u");
  check_in(s.domain().v, v, "v");
  print_surface(name, s, u, v);
}

/// One curve: its grid's rows (the header before the first), or its point at --u / --center.
void eval_curve(const EvalOptions& o, const std::string& name, const NurbsCurve& c,
                std::ostream& csv, bool& header) {
  if (!o.uv.empty()) throw std::invalid_argument(name + " is a curve: use --u U");
  if (o.grid > 0) {
    if (!header) csv << "entity,u,x,y,z,tx,ty,tz,curvature,torsion,singular\n";
    header = true;
    grid_curve(csv, name, c, o.grid);
    return;
  }
  const double u = o.center ? mid(c.domain()) : o.u;
  check_in(c.domain(), u, "u");
  print_curve(name, c, u);
}

int run_eval(const EvalOptions& o) {
  const Model m = load_model(o.file);
  const int modes = (!o.uv.empty()) + o.has_u + o.center + (o.grid > 0);
  if (modes != 1)
    throw std::invalid_argument(
        "give exactly one of --uv U,V (surfaces), --u U (curves), --center, --grid N");
  // Entities to evaluate: the one named, or every curve and surface (groups are skipped,
  // their members are entities of their own).
  std::vector<std::pair<std::string, const GeometryEntity*>> todo;
  for (const auto& [name, e] : m.geometry.entities)
    if ((o.entity.empty() && !std::holds_alternative<PatchGroup>(e)) || name == o.entity)
      todo.emplace_back(name, &e);
  if (todo.empty())
    throw std::invalid_argument(o.entity.empty() ? o.file + ": no curve or surface to evaluate"
                                                 : o.file + ": no entity named '" + o.entity + "'");

  std::ofstream file_out;
  std::ostream* csv = &std::cout;
  if (o.grid > 0) {
    if (o.grid < 2) throw std::invalid_argument("--grid needs N >= 2");
    csv = &output_stream(o.out, file_out);
    *csv << std::setprecision(15);
  }
  bool surface_header = false, curve_header = false;
  for (const auto& [name, e] : todo) {
    if (const Surface* s = as_surface(*e))
      eval_surface(o, name, *s, *csv, surface_header);
    else if (const NurbsCurve* c = std::get_if<NurbsCurve>(e))
      eval_curve(o, name, *c, *csv, curve_header);
    else
      throw std::invalid_argument(name + " is a patch group: evaluate one of its patches");
  }
  if (o.grid > 0 && !o.out.empty()) std::cerr << "iga eval: wrote " << o.out << "\n";
  return 0;
}

}  // namespace

Action add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Evaluate curves and surfaces: point, derivatives, normal, metric a_ij, curvature h_ij, "
      "principal curvatures (curves: tangent, curvature, torsion, Serret-Frenet frame)");
  cmd->add_option("model", o->file, "Model file (JSON)")->required();
  cmd->add_option("--entity,-e", o->entity, "Evaluate only this entity (default: all)");
  cmd->add_option("--uv", o->uv, "Surface parameters U,V")->delimiter(',')->expected(2);
  cmd->add_option_function<double>(
      "--u", [o](double u) { o->u = u, o->has_u = true; }, "Curve parameter U");
  cmd->add_flag("--center", o->center, "Evaluate at the centre of each domain");
  cmd->add_option("--grid", o->grid, "Sample an N x N grid (N points on curves) as CSV")
      ->check(CLI::Range(2, 100000));
  cmd->add_option("--out,-o", o->out, "CSV file for --grid (default: standard output)");
  return [o]() { return run_eval(*o); };
}

}  // namespace iga::app
