// The shallow von Mises truss as a NonlinearProblem with its closed-form load-deflection curve
// (limit points at w = h (1 -+ 1/sqrt 3)): the test problem of the load-stepping and the
// arc-length solvers.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "iga/core/nonlinear_problem.hpp"

namespace iga::test {

/// Shallow von Mises truss: two St. Venant-Kirchhoff bars from the supports (-a, 0) and (a, 0)
/// to the apex (0, h), which carries the dead load (0, -t P). Unknowns: apex displacement
/// (u_x, u_y). Bar b: d = X_apex + u - X_b, Green strain E = (d.d - L0^2) / (2 L0^2), energy
/// EA L0 E^2 / 2, so R = sum_b EA E d / L0 - f and K = sum_b EA / L0 (d d^T / L0^2 + E I).
/// Closed form with the deflection w = -u_y: P = EA / L0^3 w (2h - w)(h - w), u_x = 0; the limit
/// point is at w = h (1 - 1/sqrt 3), P_max = 2 EA h^3 / (3 sqrt(3) L0^3).
class VonMisesTruss : public NonlinearProblem {
 public:
  VonMisesTruss(double a, double h, double EA, double P) : a_(a), h_(h), EA_(EA), P_(P) {}
  int num_dofs() const override { return 2; }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    const double L0sq = a_ * a_ + h_ * h_;
    const double L0 = std::sqrt(L0sq);
    Eigen::Vector2d r = Eigen::Vector2d(0.0, t * P_);  // -f_ext
    Eigen::Matrix2d k = Eigen::Matrix2d::Zero();
    for (const double xb : {-a_, a_}) {
      const Eigen::Vector2d d(-xb + u(0), h_ + u(1));
      const double E = (d.squaredNorm() - L0sq) / (2.0 * L0sq);
      r.noalias() += EA_ * E / L0 * d;
      k.noalias() += EA_ / L0 * (d * d.transpose() / L0sq + E * Eigen::Matrix2d::Identity());
    }
    R = r;
    if (K) {
      K->resize(2, 2);
      std::vector<Eigen::Triplet<double>> tr;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) tr.emplace_back(i, j, k(i, j));
      K->setFromTriplets(tr.begin(), tr.end());
    }
  }
  std::string status() const override { return "truss"; }
  /// The bars' force on the apex (R without the load) and its tangent.
  void bars(const Eigen::Vector2d& u, Eigen::Vector2d& r, Eigen::Matrix2d& k) const {
    const double L0sq = a_ * a_ + h_ * h_;
    const double L0 = std::sqrt(L0sq);
    r.setZero();
    k.setZero();
    for (const double xb : {-a_, a_}) {
      const Eigen::Vector2d d(-xb + u(0), h_ + u(1));
      const double E = (d.squaredNorm() - L0sq) / (2.0 * L0sq);
      r.noalias() += EA_ * E / L0 * d;
      k.noalias() += EA_ / L0 * (d * d.transpose() / L0sq + E * Eigen::Matrix2d::Identity());
    }
  }

  double L0() const { return std::sqrt(a_ * a_ + h_ * h_); }
  /// The closed form P(w).
  double load(double w) const { return EA_ / std::pow(L0(), 3) * w * (2.0 * h_ - w) * (h_ - w); }
  double w_limit() const { return h_ * (1.0 - 1.0 / std::sqrt(3.0)); }
  double P_max() const { return load(w_limit()); }
  /// The deflection w in [0, w_limit] under the load P (bisection on the closed form).
  double deflection(double P) const {
    double lo = 0.0, hi = w_limit();
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (load(mid) < P ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

 private:
  double a_, h_, EA_, P_;
};

/// The truss loaded through a linear spring of stiffness k_s above the apex: unknowns (u_x, u_y,
/// v), v the vertical displacement of the loaded point, which carries (0, -t P). The spring
/// carries t P, so P(w) = t P as for the truss and the loaded point's deflection is
/// W = w + t P / k_s: where the truss softens faster than k_s (dP/dw < -k_s, around w = h) W
/// goes back while the load falls, a snap-back in the load-deflection curve of the loaded point.
class TrussWithSpring : public NonlinearProblem {
 public:
  TrussWithSpring(double a, double h, double EA, double P, double k_s)
      : truss_(a, h, EA, P), P_(P), k_s_(k_s) {}
  int num_dofs() const override { return 3; }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override {
    Eigen::Vector2d r;
    Eigen::Matrix2d k;
    truss_.bars(u.head<2>(), r, k);
    const double s = k_s_ * (u(2) - u(1));  // spring force (tension positive upwards)
    R.resize(3);
    R << r(0), r(1) - s, s + t * P_;
    if (K) {
      Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
      m.topLeftCorner<2, 2>() = k;
      m(1, 1) += k_s_;
      m(1, 2) -= k_s_;
      m(2, 1) -= k_s_;
      m(2, 2) += k_s_;
      K->resize(3, 3);
      std::vector<Eigen::Triplet<double>> tr;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) tr.emplace_back(i, j, m(i, j));
      K->setFromTriplets(tr.begin(), tr.end());
    }
  }
  const VonMisesTruss& truss() const { return truss_; }
  double k_s() const { return k_s_; }

 private:
  VonMisesTruss truss_;
  double P_, k_s_;
};

}  // namespace iga::test
