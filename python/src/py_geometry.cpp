// rigid_contact_iga._core, geometry: NURBS curves and surfaces from numpy arrays, the analytic
// surfaces, and their evaluation vectorised over (N,) or (N, 2) parameter arrays.
//
// Notation: (u, v) surface parameters; S, Su, Sv, Suu, Suv, Svv the point and its derivatives
// (derivatives.hpp); n the unit normal, oriented by the surface's normal sign; control points
// of a surface as an (n_u, n_v, 3) array P[i, j] (i along u), weights (n_u, n_v).
#include <memory>
#include <optional>
#include <sstream>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/differential_geometry.hpp"
#include "geometry/geometry_io.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "python/src/py_common.hpp"

namespace iga::py {

namespace {

std::vector<double> vector_of(pb::handle obj, const char* name) {
  const Rows r = values_of(obj, name);
  return {r.array.data(), r.array.data() + r.n};
}

Vector3d vec3_of(pb::handle obj, const char* name) {
  const Rows r = rows_of(obj, name, 3, true, true);
  if (r.n != 1) throw pb::value_error(std::string(name) + ": expected 3 numbers");
  return {r.row(0)[0], r.row(0)[1], r.row(0)[2]};
}

void check_in(double x, const Interval& I, pb::ssize_t row, const char* what) {
  if (x < I.lo || x > I.hi) {
    std::ostringstream s;
    s.precision(17);
    s << what << ": row " << row << ": " << x << " is outside the domain [" << I.lo << ", " << I.hi
      << "]";
    throw pb::value_error(s.str());
  }
}

/// Derivatives of order `order` at every row of uv, checked against the domain.
std::vector<SurfaceDerivs> surface_derivs(const Surface& s, pb::handle uv, int order) {
  const Rows r = rows_of(uv, "uv", 2);
  const Domain2 d = s.domain();
  for (pb::ssize_t i = 0; i < r.n; ++i) {
    check_in(r.row(i)[0], d.u, i, "uv[:, 0]");
    check_in(r.row(i)[1], d.v, i, "uv[:, 1]");
  }
  std::vector<SurfaceDerivs> out(static_cast<std::size_t>(r.n));
  {
    pb::gil_scoped_release release;
    for (pb::ssize_t i = 0; i < r.n; ++i)
      out[static_cast<std::size_t>(i)] = s.derivs(r.row(i)[0], r.row(i)[1], order);
  }
  return out;
}

pb::array_t<double> field(const std::vector<SurfaceDerivs>& D, Vector3d SurfaceDerivs::*f) {
  std::vector<Vector3d> v;
  v.reserve(D.size());
  for (const SurfaceDerivs& d : D) v.push_back(d.*f);
  return to_array(v);
}

pb::tuple domain_of(const Surface& s) {
  const Domain2 d = s.domain();
  return pb::make_tuple(pb::make_tuple(d.u.lo, d.u.hi), pb::make_tuple(d.v.lo, d.v.hi));
}

Domain2 domain_arg(const pb::object& d, const Domain2& fallback) {
  if (d.is_none()) return fallback;
  const Rows r = rows_of(d, "domain", 2, false, false);
  if (r.n != 2) throw pb::value_error("domain: expected ((u0, u1), (v0, v1))");
  return {{r.row(0)[0], r.row(0)[1]}, {r.row(1)[0], r.row(1)[1]}};
}

Placement placement_of(pb::handle center, pb::handle axis, pb::handle ref_dir) {
  Placement p;
  p.center = vec3_of(center, "center");
  p.axis = vec3_of(axis, "axis");
  p.ref_dir = vec3_of(ref_dir, "ref_dir");
  return p;
}

/// NURBS surface from the (n_u, n_v, 3) net and (n_u, n_v) weights (None: all 1).
std::shared_ptr<NurbsSurface> make_surface(int pu, int pv, pb::handle ku, pb::handle kv,
                                           pb::handle points, const pb::object& weights) {
  const pb::array a = pb::array::ensure(points);
  if (!a || a.ndim() != 3 || a.shape(2) != 3)
    throw pb::value_error("control_points: expected shape (n_u, n_v, 3)");
  const pb::ssize_t nu = a.shape(0), nv = a.shape(1);
  const Rows P = rows_of(a.attr("reshape")(nu * nv, 3), "control_points", 3, true, false);
  std::vector<Vector3d> pts(static_cast<std::size_t>(nu * nv));
  std::vector<double> w;
  for (pb::ssize_t i = 0; i < nu; ++i)
    for (pb::ssize_t j = 0; j < nv; ++j) {  // u fastest in the flat storage
      const double* x = P.row(i * nv + j);
      pts[static_cast<std::size_t>(i + nu * j)] = {x[0], x[1], x[2]};
    }
  if (!weights.is_none()) {
    const pb::array wa = pb::array::ensure(weights);
    if (!wa || wa.ndim() != 2 || wa.shape(0) != nu || wa.shape(1) != nv)
      throw pb::value_error("weights: expected shape (n_u, n_v) = (" + std::to_string(nu) + ", " +
                            std::to_string(nv) + ")");
    const Rows W = values_of(wa.attr("reshape")(nu * nv), "weights");
    w.resize(pts.size());
    for (pb::ssize_t i = 0; i < nu; ++i)
      for (pb::ssize_t j = 0; j < nv; ++j)
        w[static_cast<std::size_t>(i + nu * j)] = W.row(i * nv + j)[0];
  }
  return std::make_shared<NurbsSurface>(pu, vector_of(ku, "knots_u"), pv, vector_of(kv, "knots_v"),
                                        pts, w);
}

void bind_curves(pb::module_& m) {
  pb::class_<NurbsCurve, std::shared_ptr<NurbsCurve>>(
      m, "NurbsCurve",
      "A NURBS curve C(u) = sum_i N_i,p(u) w_i P_i / sum_i N_i,p(u) w_i (The NURBS Book).")
      .def(pb::init([](int degree, pb::handle knots, pb::handle points, const pb::object& weights) {
             const Rows P = rows_of(points, "control_points", 3, true, false);
             std::vector<Vector3d> pts;
             for (pb::ssize_t i = 0; i < P.n; ++i)
               pts.emplace_back(P.row(i)[0], P.row(i)[1], P.row(i)[2]);
             return std::make_shared<NurbsCurve>(
                 degree, vector_of(knots, "knots"), pts,
                 weights.is_none() ? std::vector<double>{} : vector_of(weights, "weights"));
           }),
           pb::arg("degree"), pb::arg("knots"), pb::arg("control_points"),
           pb::arg("weights") = pb::none(),
           "NurbsCurve(degree, knots, control_points (n, 3), weights (n,) or None: all 1).\n"
           "ValueError for inconsistent data (knots not clamped or decreasing, wrong counts, "
           "weights not positive).")
      .def_property_readonly("degree", &NurbsCurve::degree, "The polynomial degree p.")
      .def_property_readonly(
          "knots", [](const NurbsCurve& c) { return to_array(c.knots().knots()); },
          "The knot vector, (n + p + 1,).")
      .def_property_readonly(
          "control_points", [](const NurbsCurve& c) { return to_array(c.control_points()); },
          "The control points, (n, 3).")
      .def_property_readonly(
          "weights", [](const NurbsCurve& c) { return to_array(c.weights()); },
          "The weights, (n,).")
      .def_property_readonly(
          "domain",
          [](const NurbsCurve& c) { return pb::make_tuple(c.domain().lo, c.domain().hi); },
          "The parameter interval (u0, u1).")
      .def(
          "evaluate",
          [](const NurbsCurve& c, pb::handle u) {
            const Rows r = values_of(u, "u");
            const Interval I = c.domain();
            for (pb::ssize_t i = 0; i < r.n; ++i) check_in(r.row(i)[0], I, i, "u");
            std::vector<Vector3d> x(static_cast<std::size_t>(r.n));
            {
              pb::gil_scoped_release release;
              for (pb::ssize_t i = 0; i < r.n; ++i)
                x[static_cast<std::size_t>(i)] = c.point(r.row(i)[0]);
            }
            return to_array(x);
          },
          pb::arg("u"), "The points C(u), (N, 3), at the parameters u (N,) inside the domain.")
      .def(
          "derivatives",
          [](const NurbsCurve& c, pb::handle u, int order) {
            const Rows r = values_of(u, "u");
            if (order < 0 || order > kMaxDerivOrder)
              throw pb::value_error("order: expected 0 .. " + std::to_string(kMaxDerivOrder) +
                                    ", got " + std::to_string(order));
            const Interval I = c.domain();
            for (pb::ssize_t i = 0; i < r.n; ++i) check_in(r.row(i)[0], I, i, "u");
            std::vector<std::vector<Vector3d>> d(static_cast<std::size_t>(order) + 1);
            {
              pb::gil_scoped_release release;
              for (pb::ssize_t i = 0; i < r.n; ++i) {
                const CurveDerivs cd = c.derivs(r.row(i)[0], order);
                for (int k = 0; k <= order; ++k)
                  d[static_cast<std::size_t>(k)].push_back(cd.d[static_cast<std::size_t>(k)]);
              }
            }
            pb::list out;
            for (const auto& v : d) out.append(to_array(v));
            return out;
          },
          pb::arg("u"), pb::arg("order") = 2,
          "[C, C', C'', ...] up to `order`, each (N, 3), at the parameters u (N,).");
}

void bind_surfaces(pb::module_& m) {
  pb::class_<Surface, std::shared_ptr<Surface>>(
      m, "Surface",
      "A parametric surface rho(u, v): a NURBS patch or an analytic surface. The evaluation "
      "methods take (N, 2) parameter arrays (or one (u, v) pair) inside the domain.")
      .def_property_readonly("type", &Surface::type_name, "'nurbs_surface', 'cylinder', ...")
      .def_property_readonly("domain", &domain_of, "((u0, u1), (v0, v1)); bounds may be infinite.")
      .def_property_readonly("closed_u", &Surface::closed_u,
                             "Whether rho(u0, v) == rho(u1, v) (a full circle in u).")
      .def_property_readonly("closed_v", &Surface::closed_v, "As closed_u, in v.")
      .def_property(
          "normal_sign", &Surface::normal_sign, &Surface::set_normal_sign,
          "+1: the normal is rho_u x rho_v / |.|; -1: its opposite (an inward tool surface).")
      .def(
          "evaluate",
          [](const Surface& s, pb::handle uv) {
            return field(surface_derivs(s, uv, 0), &SurfaceDerivs::S);
          },
          pb::arg("uv"), "The points rho(u, v), (N, 3), at the parameters uv (N, 2).")
      .def(
          "derivatives",
          [](const Surface& s, pb::handle uv) {
            const std::vector<SurfaceDerivs> D = surface_derivs(s, uv, 2);
            pb::dict out;
            out["S"] = field(D, &SurfaceDerivs::S);
            out["Su"] = field(D, &SurfaceDerivs::Su);
            out["Sv"] = field(D, &SurfaceDerivs::Sv);
            out["Suu"] = field(D, &SurfaceDerivs::Suu);
            out["Suv"] = field(D, &SurfaceDerivs::Suv);
            out["Svv"] = field(D, &SurfaceDerivs::Svv);
            return out;
          },
          pb::arg("uv"),
          "A dict of (N, 3) arrays: S, Su, Sv, Suu, Suv, Svv (the point and its first and second "
          "derivatives) at the parameters uv (N, 2).")
      .def(
          "normals",
          [](const Surface& s, pb::handle uv) {
            const std::vector<SurfaceDerivs> D = surface_derivs(s, uv, 1);
            std::vector<Vector3d> n;
            n.reserve(D.size());
            for (const SurfaceDerivs& d : D) n.push_back(surface_frame(d, s.normal_sign()).n);
            return to_array(n);
          },
          pb::arg("uv"),
          "The unit normals, oriented by normal_sign, (N, 3), at the parameters uv (N, 2) "
          "(zero where the surface is singular).");

  pb::class_<NurbsSurface, Surface, std::shared_ptr<NurbsSurface>>(
      m, "NurbsSurface",
      "A tensor-product NURBS patch. Control points P[i, j] as an (n_u, n_v, 3) array, i along "
      "u.")
      .def(pb::init(&make_surface), pb::arg("degree_u"), pb::arg("degree_v"), pb::arg("knots_u"),
           pb::arg("knots_v"), pb::arg("control_points"), pb::arg("weights") = pb::none(),
           "NurbsSurface(degree_u, degree_v, knots_u, knots_v, control_points (n_u, n_v, 3), "
           "weights (n_u, n_v) or None: all 1). ValueError for inconsistent data.")
      .def_property_readonly("degree_u", &NurbsSurface::degree_u, "The degree in u.")
      .def_property_readonly("degree_v", &NurbsSurface::degree_v, "The degree in v.")
      .def_property_readonly(
          "knots_u", [](const NurbsSurface& s) { return to_array(s.knots_u().knots()); },
          "The knot vector in u.")
      .def_property_readonly(
          "knots_v", [](const NurbsSurface& s) { return to_array(s.knots_v().knots()); },
          "The knot vector in v.")
      .def_property_readonly(
          "control_points",
          [](const NurbsSurface& s) {
            pb::array_t<double> a(std::vector<pb::ssize_t>{s.num_u(), s.num_v(), 3});
            double* p = a.mutable_data();
            for (int i = 0; i < s.num_u(); ++i)
              for (int j = 0; j < s.num_v(); ++j) {
                const Vector3d x = s.control_point(i, j);
                p = std::copy(x.data(), x.data() + 3, p);
              }
            return a;
          },
          "The control net, (n_u, n_v, 3).")
      .def_property_readonly(
          "weights",
          [](const NurbsSurface& s) {
            pb::array_t<double> a(std::vector<pb::ssize_t>{s.num_u(), s.num_v()});
            double* p = a.mutable_data();
            for (int i = 0; i < s.num_u(); ++i)
              for (int j = 0; j < s.num_v(); ++j) *p++ = s.weight(i, j);
            return a;
          },
          "The weights, (n_u, n_v).");
}

/// The analytic surfaces (analytic_surfaces.hpp: parameters and domains).
void bind_analytic(pb::module_& m) {
  pb::class_<Plane, Surface, std::shared_ptr<Plane>>(
      m, "Plane",
      "The plane through center with normal axis; (u, v) along ref_dir and axis x ref_dir.")
      .def(pb::init([](pb::handle c, pb::handle a, pb::handle r, const pb::object& d) {
             return std::make_shared<Plane>(placement_of(c, a, r),
                                            domain_arg(d, Plane::default_domain()));
           }),
           pb::arg("center") = std::vector<double>{0, 0, 0},
           pb::arg("axis") = std::vector<double>{0, 0, 1},
           pb::arg("ref_dir") = std::vector<double>{1, 0, 0}, pb::arg("domain") = pb::none());
  pb::class_<Sphere, Surface, std::shared_ptr<Sphere>>(
      m, "Sphere", "A sphere of the given radius; u longitude, v latitude; normal outward.")
      .def(pb::init([](double R, pb::handle c, pb::handle a, pb::handle r, const pb::object& d) {
             return std::make_shared<Sphere>(placement_of(c, a, r), R,
                                             domain_arg(d, Sphere::default_domain()));
           }),
           pb::arg("radius"), pb::arg("center") = std::vector<double>{0, 0, 0},
           pb::arg("axis") = std::vector<double>{0, 0, 1},
           pb::arg("ref_dir") = std::vector<double>{1, 0, 0}, pb::arg("domain") = pb::none())
      .def_property_readonly("radius", &Sphere::radius, "The radius.");
  pb::class_<Cylinder, Surface, std::shared_ptr<Cylinder>>(
      m, "Cylinder", "A circular cylinder about axis; u the angle, v the height; normal outward.")
      .def(pb::init([](double R, pb::handle c, pb::handle a, pb::handle r, const pb::object& d) {
             return std::make_shared<Cylinder>(placement_of(c, a, r), R,
                                               domain_arg(d, Cylinder::default_domain()));
           }),
           pb::arg("radius"), pb::arg("center") = std::vector<double>{0, 0, 0},
           pb::arg("axis") = std::vector<double>{0, 0, 1},
           pb::arg("ref_dir") = std::vector<double>{1, 0, 0}, pb::arg("domain") = pb::none())
      .def_property_readonly("radius", &Cylinder::radius, "The radius.");
  pb::class_<Torus, Surface, std::shared_ptr<Torus>>(
      m, "Torus", "A torus about axis: major radius R, minor radius r; normal outward.")
      .def(pb::init([](double R, double r0, pb::handle c, pb::handle a, pb::handle r,
                       const pb::object& d) {
             return std::make_shared<Torus>(placement_of(c, a, r), R, r0,
                                            domain_arg(d, Torus::default_domain()));
           }),
           pb::arg("major_radius"), pb::arg("minor_radius"),
           pb::arg("center") = std::vector<double>{0, 0, 0},
           pb::arg("axis") = std::vector<double>{0, 0, 1},
           pb::arg("ref_dir") = std::vector<double>{1, 0, 0}, pb::arg("domain") = pb::none())
      .def_property_readonly("major_radius", &Torus::major_radius,
                             "R, the radius of the centre circle.")
      .def_property_readonly("minor_radius", &Torus::minor_radius, "r, the radius of the tube.");
  pb::class_<Cone, Surface, std::shared_ptr<Cone>>(
      m, "Cone",
      "A circular cone with apex at center about axis; alpha in (0, pi/2) the angle between a "
      "generator and the plane normal to the axis.")
      .def(
          pb::init([](double alpha, pb::handle c, pb::handle a, pb::handle r, const pb::object& d) {
            return std::make_shared<Cone>(placement_of(c, a, r), alpha,
                                          domain_arg(d, Cone::default_domain()));
          }),
          pb::arg("alpha"), pb::arg("center") = std::vector<double>{0, 0, 0},
          pb::arg("axis") = std::vector<double>{0, 0, 1},
          pb::arg("ref_dir") = std::vector<double>{1, 0, 0}, pb::arg("domain") = pb::none())
      .def_property_readonly("alpha", &Cone::alpha,
                             "The angle between a generator and the plane normal to the axis.");
  pb::class_<Hyperboloid, Surface, std::shared_ptr<Hyperboloid>>(
      m, "Hyperboloid", "The hyperbolic paraboloid z = a x y in its frame (the paper's saddle).")
      .def(pb::init([](double a0, pb::handle c, pb::handle a, pb::handle r, const pb::object& d) {
             return std::make_shared<Hyperboloid>(placement_of(c, a, r), a0,
                                                  domain_arg(d, Hyperboloid::default_domain()));
           }),
           pb::arg("a"), pb::arg("center") = std::vector<double>{0, 0, 0},
           pb::arg("axis") = std::vector<double>{0, 0, 1},
           pb::arg("ref_dir") = std::vector<double>{1, 0, 0}, pb::arg("domain") = pb::none())
      .def_property_readonly("a", &Hyperboloid::a, "The coefficient a of z = a x y.");
}

}  // namespace

void bind_geometry(pb::module_& m) {
  bind_curves(m);
  bind_surfaces(m);
  bind_analytic(m);

  m.def(
      "_entity_json",
      [](const pb::handle& obj) -> std::string {
        if (pb::isinstance<NurbsCurve>(obj))
          return entity_to_json(GeometryEntity(obj.cast<NurbsCurve>())).dump();
        const auto s = obj.cast<std::shared_ptr<Surface>>();
        const auto as = [&](auto* p) -> std::optional<std::string> {
          using T = std::remove_pointer_t<decltype(p)>;
          if (const auto* q = dynamic_cast<const T*>(s.get()))
            return entity_to_json(GeometryEntity(*q)).dump();
          return std::nullopt;
        };
        for (const auto& j :
             {as(static_cast<NurbsSurface*>(nullptr)), as(static_cast<Plane*>(nullptr)),
              as(static_cast<Sphere*>(nullptr)), as(static_cast<Cylinder*>(nullptr)),
              as(static_cast<Torus*>(nullptr)), as(static_cast<Cone*>(nullptr)),
              as(static_cast<Hyperboloid*>(nullptr))})
          if (j) return *j;
        throw pb::type_error("not a geometry entity of a model: " + s->type_name());
      },
      pb::arg("entity"), "The entity as the model file's JSON (geometry_io.hpp).");
}

}  // namespace iga::py
