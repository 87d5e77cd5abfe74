// The Python module's shared helpers: numpy arrays in (checked: dtype, shape, finite values,
// with the argument's name in every message) and out (copies owned by numpy), and the parts of
// the module each file defines.
//
// Notation: N the number of points of a vectorised call; (N, k) a C-contiguous float64 array.
#pragma once

#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>

namespace iga::py {

namespace pb = pybind11;

/// A read-only view of a checked (N, k) float64 array (a copy when the input was not one).
struct Rows {
  pb::array_t<double, pb::array::c_style> array;
  pb::ssize_t n = 0;
  int k = 0;
  const double* row(pb::ssize_t i) const { return array.data() + i * k; }
};

/// `obj` as an (N, k) float64 array: a list, tuple or numpy array of real numbers (integers are
/// converted). A single point of shape (k,) is taken as (1, k) only with `allow_single`.
/// TypeError for a non-numeric dtype (strings, objects, complex, booleans); ValueError for
/// another shape or, with `finite`, a NaN or infinite entry (naming the first such row).
Rows rows_of(pb::handle obj, const char* name, int k, bool finite = true, bool allow_single = true);
/// A 1-D float64 array of N values, checked as rows_of (shape (N,), or a scalar with
/// allow_single).
Rows values_of(pb::handle obj, const char* name, bool finite = true);

/// A new (N, k) float64 array (k = 0: shape (N,)).
pb::array_t<double> new_array(pb::ssize_t n, int k = 0);
/// Eigen vectors as an (N, 3) array.
pb::array_t<double> to_array(const std::vector<Eigen::Vector3d>& v);
pb::array_t<double> to_array(const std::vector<double>& v);

/// The number of threads a vectorised call uses: `threads` if positive, else OpenMP's default.
int thread_count(int threads);

void bind_geometry(pb::module_& m);
void bind_contact(pb::module_& m);
void bind_model(pb::module_& m);

}  // namespace iga::py
