// Knot vectors with their invariants: non-decreasing, open (clamped) ends, interior
// multiplicity <= degree, consistent with a number of basis functions.
// References: [PT97] The NURBS Book, Sect. 2.2 and 3.2.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace iga {

/// Thrown for inconsistent geometric input (knots, degrees, weights, control net sizes).
/// `what()` says what is wrong and which value; file / JSON path context is added by the loader.
class GeometryError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A validated, clamped knot vector of degree p: U[0] = ... = U[p] < ... < U[m-p] = ... = U[m],
/// non-decreasing, every interior knot of multiplicity <= p (so the basis is at least C^0).
class KnotVector {
 public:
  KnotVector() = default;
  /// Validates and stores; throws GeometryError naming the offending index and value.
  KnotVector(int degree, std::vector<double> knots);

  /// Uniform open knot vector on [a, b] with n_elements elements and interior multiplicity
  /// `mult` (1 gives maximal continuity C^{p-1}).
  static KnotVector uniform(int degree, int n_elements, double a = 0.0, double b = 1.0,
                            int mult = 1);

  int degree() const { return p_; }
  const std::vector<double>& knots() const { return U_; }
  std::span<const double> span() const { return U_; }
  double operator[](int i) const { return U_[static_cast<std::size_t>(i)]; }
  int size() const { return static_cast<int>(U_.size()); }
  /// Number of basis functions n+1 = m - p.
  int num_basis() const { return size() - p_ - 1; }
  /// Parameter domain [U[p], U[m-p]].
  std::pair<double, double> domain() const;
  /// Distinct knot values, in increasing order (element boundaries).
  std::vector<double> breaks() const;
  /// Number of non-empty knot spans (elements).
  int num_elements() const { return static_cast<int>(breaks().size()) - 1; }
  /// Multiplicity of the knot value u (0 when u is not a knot).
  int multiplicity(double u) const;
  /// A2.1 on this vector.
  int find_span(double u) const;
  /// Greville abscissae (knot averages), one per basis function.
  std::vector<double> greville() const;

  bool operator==(const KnotVector&) const = default;

 private:
  int p_ = 0;
  std::vector<double> U_;
};

/// Validates a knot vector against a degree and a number of control points. Throws
/// GeometryError with a message naming the index/value at fault:
/// degree < 1 or > kMaxDegree, non-finite knots, decreasing knots, count != n_cp + p + 1,
/// ends not clamped (multiplicity p+1), interior multiplicity > p, empty domain.
void validate_knots(int degree, std::span<const double> knots, int n_control_points);

}  // namespace iga
