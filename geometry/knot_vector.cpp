// Knot vector validation and queries ([PT97] Sect. 2.2, 3.2).
#include "geometry/knot_vector.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "geometry/bspline_basis.hpp"

namespace iga {

namespace {
// Shortest decimal text that reads back to the same double (0.7, not 0.69999999999999996).
std::string num(double x) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}
}  // namespace

void validate_knots(int degree, std::span<const double> U, int n_control_points) {
  if (degree < 1 || degree > kMaxDegree)
    throw GeometryError("degree must be in 1.." + std::to_string(kMaxDegree) + ", got " +
                        std::to_string(degree));
  const int m = static_cast<int>(U.size());
  if (n_control_points >= 0 && m != n_control_points + degree + 1)
    throw GeometryError("knot count must be control points + degree + 1 = " +
                        std::to_string(n_control_points + degree + 1) + ", got " +
                        std::to_string(m) + " knots");
  if (m < 2 * (degree + 1))
    throw GeometryError("a degree-" + std::to_string(degree) + " knot vector needs at least " +
                        std::to_string(2 * (degree + 1)) + " knots, got " + std::to_string(m));
  for (int i = 0; i < m; ++i) {
    if (!std::isfinite(U[i]))
      throw GeometryError("knot " + std::to_string(i) + " is not finite: " + num(U[i]));
    if (i > 0 && U[i] < U[i - 1])
      throw GeometryError("knots must be non-decreasing: knot " + std::to_string(i) + " = " +
                          num(U[i]) + " < knot " + std::to_string(i - 1) + " = " + num(U[i - 1]));
  }
  for (int i = 1; i <= degree; ++i) {
    if (U[i] != U[0])
      throw GeometryError("knot vector must be clamped: the first " + std::to_string(degree + 1) +
                          " knots must be equal, knot " + std::to_string(i) + " = " + num(U[i]) +
                          " != " + num(U[0]));
    if (U[m - 1 - i] != U[m - 1])
      throw GeometryError("knot vector must be clamped: the last " + std::to_string(degree + 1) +
                          " knots must be equal, knot " + std::to_string(m - 1 - i) + " = " +
                          num(U[m - 1 - i]) + " != " + num(U[m - 1]));
  }
  if (!(U[degree] < U[m - 1 - degree]))
    throw GeometryError("empty parameter domain [" + num(U[degree]) + ", " +
                        num(U[m - 1 - degree]) + "]");
  // Interior multiplicities.
  for (int i = degree + 1; i < m - degree - 1;) {
    int j = i;
    while (j + 1 < m - degree - 1 && U[j + 1] == U[i]) ++j;
    const int mult = j - i + 1;
    if (mult > degree)
      throw GeometryError("interior knot " + num(U[i]) + " (index " + std::to_string(i) +
                          ") has multiplicity " + std::to_string(mult) + " > degree " +
                          std::to_string(degree));
    i = j + 1;
  }
}

KnotVector::KnotVector(int degree, std::vector<double> knots) : p_(degree), U_(std::move(knots)) {
  validate_knots(p_, U_, -1);
}

KnotVector KnotVector::uniform(int degree, int n_elements, double a, double b, int mult) {
  if (n_elements < 1) throw GeometryError("uniform knot vector needs >= 1 element");
  std::vector<double> U(static_cast<std::size_t>(degree + 1), a);
  for (int e = 1; e < n_elements; ++e)
    for (int k = 0; k < mult; ++k) U.push_back(a + (b - a) * e / n_elements);
  U.insert(U.end(), static_cast<std::size_t>(degree + 1), b);
  return KnotVector(degree, std::move(U));
}

std::pair<double, double> KnotVector::domain() const {
  return {U_[p_], U_[U_.size() - 1 - p_]};
}

std::vector<double> KnotVector::breaks() const {
  std::vector<double> b;
  const auto [lo, hi] = domain();
  for (double u : U_)
    if (u >= lo && u <= hi && (b.empty() || u != b.back())) b.push_back(u);
  return b;
}

int KnotVector::multiplicity(double u) const {
  // The knots are sorted: a binary search, O(log n) (callers loop over every knot).
  const auto [lo, hi] = std::equal_range(U_.begin(), U_.end(), u);
  return static_cast<int>(hi - lo);
}

int KnotVector::find_span(double u) const {
  return iga::find_span(num_basis(), p_, u, U_);
}

std::vector<double> KnotVector::greville() const {
  std::vector<double> g(static_cast<std::size_t>(num_basis()));
  for (int i = 0; i < num_basis(); ++i) {
    double s = 0.0;
    for (int k = 1; k <= p_; ++k) s += U_[i + k];
    g[i] = s / p_;
  }
  return g;
}

}  // namespace iga
