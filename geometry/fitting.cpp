// Least-squares B-spline curve fitting ([PT97] Sect. 9.4.1).
#include "geometry/fitting.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace iga {

CurveFit fit_curve(const std::vector<Vector3d>& Q, const std::vector<double>& t, int degree,
                   const std::vector<double>& knots) {
  const KnotVector K(degree, knots);
  const int n = K.num_basis();
  const int m = static_cast<int>(Q.size());
  if (static_cast<int>(t.size()) != m)
    throw GeometryError("fit_curve: " + std::to_string(m) + " points but " +
                        std::to_string(t.size()) + " parameters");
  if (m <= n || n < 2)
    throw GeometryError("fit_curve: need more samples (" + std::to_string(m) +
                        ") than control points (" + std::to_string(n) + ")");
  // Normal equations (9.66) N^T N P = N^T R for the interior unknowns P_1..P_{n-2}, the ends
  // fixed to Q_0 and Q_{m-1} (clamped knots). Row k of N holds the p + 1 basis functions
  // N_{span-p..span}(t_k), so N^T N is banded (half-bandwidth p): summed sample by sample into
  // band storage and factored by a sparse LDL^T, O(m p^2) work and O(n p) memory instead of
  // the dense m x n collocation matrix.
  const int ni = n - 2;  // interior unknowns; column j of N is unknown j - 1
  // band(i, d) = (N^T N)_{i, i-d}, d = 0..p: the lower band, summed sample by sample.
  Eigen::MatrixXd band = Eigen::MatrixXd::Zero(std::max(ni, 0), degree + 1);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(std::max(ni, 0), 3);
  BasisValues b;
  for (int k = 0; k < m; ++k) {
    const double tk = t[static_cast<std::size_t>(k)];
    const int span = K.find_span(tk);
    basis_funs(span, tk, degree, K.span(), b);
    const int first = span - degree;
    // R_k = Q_k - N_0(t_k) Q_0 - N_{n-1}(t_k) Q_{m-1}.
    Vector3d r = Q[static_cast<std::size_t>(k)];
    for (int a = 0; a <= degree; ++a) {
      const int col = first + a;
      if (col == 0) r -= b[static_cast<std::size_t>(a)] * Q.front();
      if (col == n - 1) r -= b[static_cast<std::size_t>(a)] * Q.back();
    }
    for (int a = 0; a <= degree; ++a) {
      const int i = first + a - 1;
      if (i < 0 || i >= ni) continue;
      const double ba = b[static_cast<std::size_t>(a)];
      rhs.row(i) += ba * r.transpose();
      for (int c = 0; c <= a; ++c) {
        const int j = first + c - 1;
        if (j < 0) continue;
        band(i, i - j) += ba * b[static_cast<std::size_t>(c)];
      }
    }
  }
  std::vector<Vector3d> cp(static_cast<std::size_t>(n));
  cp.front() = Q.front();
  cp.back() = Q.back();
  if (ni > 0) {
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(static_cast<std::size_t>(ni) * static_cast<std::size_t>(degree + 1));
    for (int i = 0; i < ni; ++i)
      for (int d = 0; d <= degree && d <= i; ++d) trip.emplace_back(i, i - d, band(i, d));
    Eigen::SparseMatrix<double> A(ni, ni);  // lower triangle, as the Lower LDL^T reads it
    A.setFromTriplets(trip.begin(), trip.end());
    // A band needs no fill-reducing ordering: the natural order keeps L within the band.
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower,
                                Eigen::NaturalOrdering<int>>
        ldlt(A);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0).all())
      throw GeometryError("fit_curve: the samples do not determine every control point");
    const Eigen::MatrixXd P = ldlt.solve(rhs);
    for (int i = 1; i < n - 1; ++i) cp[static_cast<std::size_t>(i)] = P.row(i - 1).transpose();
  }
  CurveFit fit{NurbsCurve(degree, knots, cp), 0.0};
  for (int k = 0; k < m; ++k)
    fit.max_deviation = std::max(
        fit.max_deviation,
        (fit.curve.point(t[static_cast<std::size_t>(k)]) - Q[static_cast<std::size_t>(k)]).norm());
  return fit;
}

}  // namespace iga
