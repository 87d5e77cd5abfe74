// rigid_contact_iga._core, contact: rigid surfaces (pieces of a model, of a CAD file, or given
// surfaces) and their closest point and ray projections, vectorised over (N, 3) arrays: the
// GIL is released and the points are shared among OpenMP threads.
//
// Notation ([KS15] -> here, projection.hpp): alpha -> uv, rho(alpha) -> point, n -> normal,
// p = xi^3 -> distance (signed for a closest point: along n; a ray's parameter for a ray).
#include <cstring>
#include <exception>
#include <memory>

#include <omp.h>
#include <pybind11/stl/filesystem.h>

#include "cad/cad_import.hpp"
#include "contact/rigid_surface.hpp"
#include "iga/model/model.hpp"
#include "python/src/py_common.hpp"

namespace iga::py {

namespace {

/// Statuses as a numpy array of strings (dtype '<U13': "interior", "edge", ...).
pb::array status_array(const std::vector<ProjectionResult>& r) {
  constexpr int kWidth = 13;  // "not_converged"
  pb::array a(pb::dtype("<U13"), std::vector<pb::ssize_t>{static_cast<pb::ssize_t>(r.size())});
  auto* p = static_cast<char32_t*>(a.mutable_data());
  std::memset(static_cast<void*>(p), 0, r.size() * kWidth * sizeof(char32_t));
  for (std::size_t i = 0; i < r.size(); ++i) {
    const char* s = to_string(r[i].status);
    for (int c = 0; c < kWidth && s[c] != '\0'; ++c)
      p[i * kWidth + static_cast<std::size_t>(c)] = static_cast<char32_t>(s[c]);
  }
  return a;
}

/// The results as a dict of arrays.
pb::dict result_dict(const std::vector<ProjectionResult>& r) {
  const auto n = static_cast<pb::ssize_t>(r.size());
  pb::array_t<double> uv = new_array(n, 2), point = new_array(n, 3), normal = new_array(n, 3),
                      distance = new_array(n), residual = new_array(n);
  pb::array_t<bool> certified(std::vector<pb::ssize_t>{n});
  pb::array_t<int> patch(std::vector<pb::ssize_t>{n}), iterations(std::vector<pb::ssize_t>{n});
  double *pu = uv.mutable_data(), *px = point.mutable_data(), *pn = normal.mutable_data(),
         *pd = distance.mutable_data(), *pr = residual.mutable_data();
  bool* pc = certified.mutable_data();
  int *pp = patch.mutable_data(), *pi = iterations.mutable_data();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const bool ok = found(r[i].status);  // without a foot point: NaN, not stale numbers
    for (int k = 0; k < 2; ++k) *pu++ = ok ? r[i].uv[k] : nan;
    for (int k = 0; k < 3; ++k) *px++ = ok ? r[i].point[k] : nan;
    for (int k = 0; k < 3; ++k) *pn++ = ok ? r[i].normal[k] : nan;
    *pd++ = ok ? r[i].distance : nan;
    *pr++ = r[i].residual;
    *pc++ = r[i].certified;
    *pp++ = r[i].patch;
    *pi++ = r[i].iterations;
  }
  pb::dict d;
  d["uv"] = uv;
  d["point"] = point;
  d["normal"] = normal;
  d["distance"] = distance;
  d["status"] = status_array(r);
  d["certified"] = certified;
  d["patch"] = patch;
  d["iterations"] = iterations;
  d["residual"] = residual;
  return d;
}

/// f(i) for every point, on `threads` threads with the GIL released; the first exception is
/// rethrown after the loop.
template <class F>
void parallel_points(pb::ssize_t n, int threads, F&& f) {
  std::exception_ptr error;
  pb::gil_scoped_release release;
#pragma omp parallel for schedule(dynamic, 64) num_threads(thread_count(threads))
  for (pb::ssize_t i = 0; i < n; ++i) {
    try {
      f(i);
    } catch (...) {
#pragma omp critical(iga_python_error)
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

ProjectionOptions options(bool certify) {
  ProjectionOptions o;
  o.certify = certify;
  return o;
}

}  // namespace

void bind_contact(pb::module_& m) {
  pb::class_<RigidSurface, std::shared_ptr<RigidSurface>>(
      m, "RigidSurface",
      "A rigid body's surface: NURBS patches, analytic surfaces and trimmed CAD faces acting as "
      "one surface for projections ([KS15] Sect. 2.2). Its vectorised projections release the "
      "GIL and share the points among threads.")
      .def(pb::init([](const pb::iterable& surfaces) {
             auto rs = std::make_shared<RigidSurface>();
             int k = 0;
             for (pb::handle h : surfaces) {
               const std::string what = "surfaces[" + std::to_string(k++) + "]";
               if (!pb::isinstance<Surface>(h))
                 throw pb::type_error(
                     what + ": expected a Surface (NurbsSurface, Plane, ...), got " +
                     pb::str(pb::type::of(h).attr("__name__")).cast<std::string>());
               rs->add(*h.cast<std::shared_ptr<Surface>>());
             }
             if (k == 0) throw pb::value_error("surfaces: at least one surface expected");
             return rs;
           }),
           pb::arg("surfaces"), "RigidSurface([surface, ...]): NurbsSurface, Plane, Cylinder, ...")
      .def_static(
          "_from_model_json",
          [](const std::string& text, const std::string& file, const std::string& name) {
            const Model model = parse_model(parse_json_text(text, file), file);
            try {
              return std::make_shared<RigidSurface>(
                  RigidSurface::from_geometry(model.geometry, name));
            } catch (const std::invalid_argument& e) {
              throw ModelError(file, "/geometry", e.what());
            }
          },
          pb::arg("text"), pb::arg("file"), pb::arg("name"))
      .def_static(
          "from_cad",
          [](const std::filesystem::path& file, const std::string& unit, const pb::object& faces,
             bool strict) {
            const std::string path = file.string();
            CadOptions o;
            o.unit = unit;
            o.strict = strict;
            if (!faces.is_none())
              for (pb::handle f : faces) o.faces.push_back(f.cast<int>());
            CadImport imp;
            {
              pb::gil_scoped_release release;
              imp = import_cad(path, "cad", o);
            }
            auto rs = std::make_shared<RigidSurface>();
            for (const auto& entity : imp.entities)
              if (const Surface* s = as_surface(entity.second)) rs->add(*s);
            if (rs->num_patches() == 0) throw CadError(path + ": no face to import");
            return rs;
          },
          pb::arg("path"), pb::arg("unit") = "mm", pb::arg("faces") = pb::none(),
          pb::arg("strict") = false,
          "The faces of a STEP or IGES file (all, or the 0-based numbers in `faces`) as one rigid "
          "surface, lengths in `unit` ('mm', 'cm', 'm', 'in', ...). CadError for a file that "
          "cannot be read (the message names it); with strict, also for skipped entities.")
      .def_property_readonly("num_pieces", &RigidSurface::num_patches,
                             "The number of pieces (patches, analytic surfaces, faces).")
      .def_property_readonly(
          "piece_types",
          [](const RigidSurface& rs) {
            pb::list l;
            for (int i = 0; i < rs.num_patches(); ++i) l.append(rs.patch(i).type_name());
            return l;
          },
          "Each piece's type: 'nurbs_surface', 'cylinder', 'trimmed_surface', ...")
      .def_property_readonly(
          "box",
          [](const RigidSurface& rs) {
            return pb::make_tuple(to_array(std::vector<Vector3d>{rs.box().lo}),
                                  to_array(std::vector<Vector3d>{rs.box().hi}));
          },
          "(lo, hi) of the bounding box, each (1, 3) (infinite for unbounded surfaces).")
      .def(
          "closest_points",
          [](const RigidSurface& rs, pb::handle X, bool certify, int threads) {
            const Rows P = rows_of(X, "X", 3);
            std::vector<ProjectionResult> r(static_cast<std::size_t>(P.n));
            const ProjectionOptions o = options(certify);
            parallel_points(P.n, threads, [&](pb::ssize_t i) {
              const double* x = P.row(i);
              r[static_cast<std::size_t>(i)] = rs.closest_point(Vector3d(x[0], x[1], x[2]), o);
            });
            return result_dict(r);
          },
          pb::arg("X"), pb::arg("certify") = true, pb::arg("threads") = 0,
          "Closest points of the points X (N, 3) on the surface ([KS15] eqs. 10-18), the global "
          "minimum over all pieces. Returns a dict of arrays: uv (N, 2), point (N, 3), normal "
          "(N, 3), distance (N,) signed along the normal, status (N,) strings ('interior', "
          "'edge', 'vertex'; 'not_converged'), certified (N,) bool (proven global on a NURBS "
          "piece), patch (N,) the piece, iterations (N,), residual (N,). Rows without a foot "
          "point hold NaN. certify=False: the faster sampled search without a proof. threads: "
          "0 uses OpenMP's default (OMP_NUM_THREADS, else every core).")
      .def(
          "rays",
          [](const RigidSurface& rs, pb::handle X, pb::handle D, int threads) {
            const Rows P = rows_of(X, "X", 3);
            const Rows N = rows_of(D, "D", 3);
            if (N.n != P.n)
              throw pb::value_error("D: expected as many rows as X (" + std::to_string(P.n) +
                                    "), got " + std::to_string(N.n));
            for (pb::ssize_t i = 0; i < N.n; ++i)
              if (N.row(i)[0] == 0 && N.row(i)[1] == 0 && N.row(i)[2] == 0)
                throw pb::value_error("D: row " + std::to_string(i) + " is the zero vector");
            std::vector<ProjectionResult> r(static_cast<std::size_t>(P.n));
            parallel_points(P.n, threads, [&](pb::ssize_t i) {
              const double *x = P.row(i), *d = N.row(i);
              r[static_cast<std::size_t>(i)] =
                  rs.ray(Vector3d(x[0], x[1], x[2]), Vector3d(d[0], d[1], d[2]));
            });
            return result_dict(r);
          },
          pb::arg("X"), pb::arg("D"), pb::arg("threads") = 0,
          "Ray projections ([KS15] eqs. 2-5): the hits of the lines X + xi D/|D| on the surface "
          "with the smallest |xi|, for X and D (N, 3). The same dict as closest_points; distance "
          "is xi, the signed length along D; status 'miss' or 'tangent' where a line does not "
          "cut the surface (its numbers NaN).");
}

}  // namespace iga::py
