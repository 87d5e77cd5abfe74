// Least-squares B-spline curve fitting ([PT97] Sect. 9.4.1).
#include "geometry/fitting.hpp"

#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

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
  // Interior unknowns P_1..P_{n-2}; ends fixed to Q_0 and Q_{m-1} (clamped knots).
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(m, n);
  BasisValues b;
  for (int k = 0; k < m; ++k) {
    const int span = K.find_span(t[static_cast<std::size_t>(k)]);
    basis_funs(span, t[static_cast<std::size_t>(k)], degree, K.span(), b);
    for (int j = 0; j <= degree; ++j) N(k, span - degree + j) = b[j];
  }
  Eigen::MatrixXd rhs(m, 3);
  for (int k = 0; k < m; ++k)
    rhs.row(k) = (Q[static_cast<std::size_t>(k)] - N(k, 0) * Q.front() - N(k, n - 1) * Q.back()).transpose();
  const Eigen::MatrixXd Ni = N.block(0, 1, m, n - 2);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(Ni.transpose() * Ni);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().array() > 0).all())
    throw GeometryError("fit_curve: the samples do not determine every control point");
  const Eigen::MatrixXd P = ldlt.solve(Ni.transpose() * rhs);
  std::vector<Vector3d> cp(static_cast<std::size_t>(n));
  cp.front() = Q.front();
  cp.back() = Q.back();
  for (int i = 1; i < n - 1; ++i) cp[static_cast<std::size_t>(i)] = P.row(i - 1).transpose();
  CurveFit fit{NurbsCurve(degree, knots, cp), 0.0};
  for (int k = 0; k < m; ++k)
    fit.max_deviation = std::max(fit.max_deviation,
                                 (fit.curve.point(t[static_cast<std::size_t>(k)]) - Q[static_cast<std::size_t>(k)]).norm());
  return fit;
}

}  // namespace iga
