// rigid_contact_iga._core: the compiled part of the Python package (docs/python.md). This file:
// the module, its exceptions (a model error carries the file and the JSON path) and the numpy
// helpers of py_common.hpp.
#include <cmath>
#include <sstream>

#include <omp.h>

#include "cad/cad_import.hpp"
#include "geometry/json_reader.hpp"
#include "iga/core/state_archive.hpp"
#include "python/src/py_common.hpp"

namespace iga::py {

namespace {

std::string shape_text(const pb::array& a) {
  std::ostringstream s;
  s << "(";
  for (pb::ssize_t d = 0; d < a.ndim(); ++d) s << (d > 0 ? ", " : "") << a.shape(d);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

/// `obj` as a numpy array of real numbers (integers or floats), TypeError otherwise.
pb::array numeric_array(pb::handle obj, const char* name) {
  pb::array a;
  try {
    a = pb::array::ensure(obj);
  } catch (const pb::error_already_set&) {
  }
  if (!a) throw pb::type_error(std::string(name) + ": expected an array of real numbers");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw pb::type_error(std::string(name) + ": expected an array of real numbers, got dtype " +
                         pb::str(a.dtype()).cast<std::string>());
  return a;
}

void check_finite(const Rows& r, const char* name) {
  const double* p = r.array.data();
  for (pb::ssize_t i = 0; i < r.n * r.k; ++i)
    if (!std::isfinite(p[i])) {
      std::ostringstream s;
      s << name << ": row " << i / (r.k > 0 ? r.k : 1) << " holds " << p[i]
        << " (finite numbers expected)";
      throw pb::value_error(s.str());
    }
}

}  // namespace

Rows rows_of(pb::handle obj, const char* name, int k, bool finite, bool allow_single) {
  const pb::array a = numeric_array(obj, name);
  const bool single = allow_single && a.ndim() == 1 && a.shape(0) == k;
  if (!single && (a.ndim() != 2 || a.shape(1) != k))
    throw pb::value_error(std::string(name) + ": expected shape (N, " + std::to_string(k) +
                          "), got " + shape_text(a));
  Rows r;
  r.array = pb::array_t<double, pb::array::c_style | pb::array::forcecast>::ensure(a);
  r.k = k;
  r.n = single ? 1 : a.shape(0);
  if (finite) check_finite(r, name);
  return r;
}

Rows values_of(pb::handle obj, const char* name, bool finite) {
  const pb::array a = numeric_array(obj, name);
  if (a.ndim() > 1)
    throw pb::value_error(std::string(name) + ": expected shape (N,), got " + shape_text(a));
  Rows r;
  r.array = pb::array_t<double, pb::array::c_style | pb::array::forcecast>::ensure(a);
  r.k = 1;
  r.n = a.ndim() == 0 ? 1 : a.shape(0);
  if (finite) check_finite(r, name);
  return r;
}

pb::array_t<double> new_array(pb::ssize_t n, int k) {
  if (k == 0) return pb::array_t<double>(std::vector<pb::ssize_t>{n});
  return pb::array_t<double>(std::vector<pb::ssize_t>{n, k});
}

pb::array_t<double> to_array(const std::vector<Eigen::Vector3d>& v) {
  pb::array_t<double> a = new_array(static_cast<pb::ssize_t>(v.size()), 3);
  double* p = a.mutable_data();
  for (const Eigen::Vector3d& x : v) p = std::copy(x.data(), x.data() + 3, p);
  return a;
}

pb::array_t<double> to_array(const std::vector<double>& v) {
  pb::array_t<double> a = new_array(static_cast<pb::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

int thread_count(int threads) {
  return threads > 0 ? threads : omp_get_max_threads();
}

}  // namespace iga::py

PYBIND11_MODULE(_core, m) {
  namespace pb = pybind11;
  m.doc() =
      "Isogeometric contact of rods and shells with rigid NURBS and analytic surfaces "
      "(compiled part; use the package rigid_contact_iga).";

  // Errors: ModelError (a ValueError) carries .file, .pointer (the JSON path) and .message;
  // CadError and RestartError are RuntimeErrors. The other C++ errors map as pybind11 maps
  // them (std::invalid_argument: ValueError, std::runtime_error: RuntimeError).
  static pb::exception<iga::ModelError> model_error(m, "ModelError", PyExc_ValueError);
  static pb::exception<iga::CadError> cad_error(m, "CadError", PyExc_RuntimeError);
  static pb::exception<iga::RestartError> restart_error(m, "RestartError", PyExc_RuntimeError);
  model_error.doc() =
      "Bad model input. Attributes: file, pointer (the JSON path, e.g. '/bodies/0/material'), "
      "message (without the file and path).";
  cad_error.doc() = "A CAD file that cannot be read or a face that cannot be imported.";
  restart_error.doc() = "A restart file that does not belong to the model, or is damaged.";
  // NOLINTNEXTLINE(performance-unnecessary-value-param): pybind11's translator signature
  pb::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const iga::ModelError& e) {
      pb::object err = pb::handle(model_error.ptr())(e.what());
      err.attr("file") = e.file();
      err.attr("pointer") = e.pointer();
      err.attr("message") = e.message();
      PyErr_SetObject(model_error.ptr(), err.ptr());
    } catch (const iga::CadError& e) {
      cad_error(e.what());
    } catch (const iga::RestartError& e) {
      restart_error(e.what());
    }
  });

  iga::py::bind_geometry(m);
  iga::py::bind_contact(m);
  iga::py::bind_model(m);
}
