// `iga eval`: evaluate the curves and surfaces of a model at a parameter, at the centre of
// their domains, or on a grid (CSV): point, derivatives, normal, metric, curvatures; for
// curves the Serret-Frenet frame, curvature and torsion.
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "apps/iga_commands.hpp"
#include "geometry/differential_geometry.hpp"
#include "iga/model.hpp"

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

void print_surface(const std::string& name, const Surface& s, double u, double v) {
  const SurfaceDerivs d = s.derivs(u, v, 2);
  const SurfaceFrame f = surface_frame(d, s.normal_sign());
  std::cout << std::setprecision(10) << name << " (" << s.type_name() << ") at (u, v) = (" << u
            << ", " << v << ")\n"
            << "  point      " << vec(d.S) << "\n"
            << "  S_u        " << vec(d.Su) << "\n"
            << "  S_v        " << vec(d.Sv) << "\n"
            << "  S_uu       " << vec(d.Suu) << "\n"
            << "  S_uv       " << vec(d.Suv) << "\n"
            << "  S_vv       " << vec(d.Svv) << "\n"
            << "  normal     " << vec(f.n) << "\n"
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
    std::cerr << "iga eval: " << name << " has an unbounded domain; sampling ["
              << iu.lo << ", " << iu.hi << "] x [" << iv.lo << ", " << iv.hi << "]\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = iu.lo + (iu.hi - iu.lo) * i / (n - 1);
      const double v = iv.lo + (iv.hi - iv.lo) * j / (n - 1);
      const SurfaceDerivs d = s.derivs(u, v, 2);
      const SurfaceFrame f = surface_frame(d, s.normal_sign());
      os << name << "," << u << "," << v << "," << d.S.x() << "," << d.S.y() << "," << d.S.z()
         << "," << f.n.x() << "," << f.n.y() << "," << f.n.z() << "," << f.k1 << "," << f.k2
         << "," << f.mean_curvature << "," << f.gauss_curvature << "\n";
    }
}

void grid_curve(std::ostream& os, const std::string& name, const NurbsCurve& c, int n) {
  const Interval I = c.domain();
  for (int i = 0; i < n; ++i) {
    const double u = I.lo + (I.hi - I.lo) * i / (n - 1);
    const CurveDerivs d = c.derivs(u, 3);
    const CurveFrame f = curve_frame(d);
    os << name << "," << u << "," << d.d[0].x() << "," << d.d[0].y() << "," << d.d[0].z() << ","
       << f.tangent.x() << "," << f.tangent.y() << "," << f.tangent.z() << "," << f.curvature
       << "," << f.torsion << "\n";
  }
}

int run_eval(const EvalOptions& o) {
  const Model m = load_model(o.file);
  const int modes = (!o.uv.empty()) + o.has_u + o.center + (o.grid > 0);
  if (modes != 1)
    throw std::invalid_argument("give exactly one of --uv U,V (surfaces), --u U (curves), --center, --grid N");
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
    const Surface* s = as_surface(*e);
    const NurbsCurve* c = std::get_if<NurbsCurve>(e);
    if (s) {
      if (o.has_u) throw std::invalid_argument(name + " is a surface: use --uv U,V");
      if (o.grid > 0) {
        if (!surface_header) *csv << "entity,u,v,x,y,z,nx,ny,nz,k1,k2,H,K\n";
        surface_header = true;
        grid_surface(*csv, name, *s, o.grid);
        continue;
      }
      const double u = o.center ? mid(s->domain().u) : o.uv[0];
      const double v = o.center ? mid(s->domain().v) : o.uv[1];
      check_in(s->domain().u, u, "u");
      check_in(s->domain().v, v, "v");
      print_surface(name, *s, u, v);
    } else if (c) {
      if (!o.uv.empty()) throw std::invalid_argument(name + " is a curve: use --u U");
      if (o.grid > 0) {
        if (!curve_header) *csv << "entity,u,x,y,z,tx,ty,tz,curvature,torsion\n";
        curve_header = true;
        grid_curve(*csv, name, *c, o.grid);
        continue;
      }
      const double u = o.center ? mid(c->domain()) : o.u;
      check_in(c->domain(), u, "u");
      print_curve(name, *c, u);
    } else {
      throw std::invalid_argument(name + " is a patch group: evaluate one of its patches");
    }
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
