// Second-order forward automatic differentiation: a number that carries its gradient and
// Hessian with respect to N independent variables (a truncated Taylor expansion to second
// order), for energy densities whose derivatives are too long to write out by hand (the
// twisting rod's frame, iga/rod/twisting_rod.hpp). Each operation applies the chain rule to
// second order: for z = f(x, y),
//   grad z = f_x grad x + f_y grad y,
//   H z = f_x H x + f_y H y + f_xx gx gx^T + f_yy gy gy^T + f_xy (gx gy^T + gy gx^T).
// Fixed-size Eigen storage (no heap allocation); a product costs O(N^2).
//
// Notation: v value, g gradient (N), H Hessian (N x N, symmetric).
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Core>

namespace iga {

template <int N>
struct Jet {
  using Grad = Eigen::Matrix<double, N, 1>;
  using Hess = Eigen::Matrix<double, N, N>;
  double v = 0.0;
  Grad g = Grad::Zero();
  Hess H = Hess::Zero();

  Jet() = default;
  /// A constant.
  explicit Jet(double value) : v(value) {}
  /// The independent variable i with value `value`.
  static Jet variable(double value, int i) {
    Jet j(value);
    j.g[i] = 1.0;
    return j;
  }
  /// sum_i c_i z_i of the independent variables z (a linear function: zero Hessian).
  static Jet linear(double value, const Grad& c) {
    Jet j(value);
    j.g = c;
    return j;
  }

  Jet& operator+=(const Jet& b) {
    v += b.v;
    g += b.g;
    H += b.H;
    return *this;
  }
  Jet& operator-=(const Jet& b) {
    v -= b.v;
    g -= b.g;
    H -= b.H;
    return *this;
  }
  Jet& operator*=(double s) {
    v *= s;
    g *= s;
    H *= s;
    return *this;
  }
};

/// z = f(x) with f' = d1, f'' = d2 at x.v.
template <int N>
Jet<N> chain(const Jet<N>& x, double value, double d1, double d2) {
  Jet<N> z(value);
  z.g = d1 * x.g;
  z.H = d1 * x.H + d2 * x.g.lazyProduct(x.g.transpose());
  return z;
}

template <int N>
Jet<N> operator+(Jet<N> a, const Jet<N>& b) {
  return a += b;
}
template <int N>
Jet<N> operator-(Jet<N> a, const Jet<N>& b) {
  return a -= b;
}
template <int N>
Jet<N> operator-(Jet<N> a) {
  return a *= -1.0;
}
template <int N>
Jet<N> operator+(Jet<N> a, double s) {
  a.v += s;
  return a;
}
template <int N>
Jet<N> operator+(double s, Jet<N> a) {
  a.v += s;
  return a;
}
template <int N>
Jet<N> operator-(Jet<N> a, double s) {
  a.v -= s;
  return a;
}
template <int N>
Jet<N> operator-(double s, const Jet<N>& a) {
  return s + (-a);
}
template <int N>
Jet<N> operator*(Jet<N> a, double s) {
  return a *= s;
}
template <int N>
Jet<N> operator*(double s, Jet<N> a) {
  return a *= s;
}
template <int N>
Jet<N> operator*(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> z(a.v * b.v);
  z.g = a.v * b.g + b.v * a.g;
  // one pass over H (the outer products evaluated coefficient-wise, without temporaries)
  z.H = a.v * b.H + b.v * a.H + a.g.lazyProduct(b.g.transpose()) + b.g.lazyProduct(a.g.transpose());
  return z;
}
template <int N>
Jet<N> inverse(const Jet<N>& a) {
  const double r = 1.0 / a.v;
  return chain(a, r, -r * r, 2.0 * r * r * r);
}
template <int N>
Jet<N> operator/(const Jet<N>& a, const Jet<N>& b) {
  return a * inverse(b);
}
template <int N>
Jet<N> operator/(Jet<N> a, double s) {
  return a *= 1.0 / s;
}
template <int N>
Jet<N> sqrt(const Jet<N>& a) {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}
template <int N>
Jet<N> sin(const Jet<N>& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, s, c, -s);
}
template <int N>
Jet<N> cos(const Jet<N>& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return chain(a, c, -s, -c);
}
/// atan2(y, x): theta_y = x / r2, theta_x = -y / r2, theta_yy = -2xy / r2^2 = -theta_xx,
/// theta_xy = (y^2 - x^2) / r2^2 (r2 = x^2 + y^2).
template <int N>
Jet<N> atan2(const Jet<N>& y, const Jet<N>& x) {
  const double r2 = x.v * x.v + y.v * y.v;
  const double ty = x.v / r2, tx = -y.v / r2;
  const double tyy = -2.0 * x.v * y.v / (r2 * r2), txy = (y.v * y.v - x.v * x.v) / (r2 * r2);
  Jet<N> z(std::atan2(y.v, x.v));
  z.g = ty * y.g + tx * x.g;
  z.H = ty * y.H + tx * x.H;
  z.H.noalias() += tyy * (y.g * y.g.transpose() - x.g * x.g.transpose());
  z.H.noalias() += txy * (x.g * y.g.transpose() + y.g * x.g.transpose());
  return z;
}

/// The jet `a` over M variables as a jet over N >= M variables, its variable i becoming
/// variable offset + i.
template <int N, int M>
Jet<N> embed(const Jet<M>& a, int offset) {
  static_assert(M <= N);
  Jet<N> z(a.v);
  z.g.template segment<M>(offset) = a.g;
  z.H.template block<M, M>(offset, offset) = a.H;
  return z;
}

/// A 3-vector of jets.
template <int N>
struct JetVec3 {
  std::array<Jet<N>, 3> c;

  /// A constant vector.
  static JetVec3 constant(const Eigen::Vector3d& a) {
    JetVec3 r;
    for (int k = 0; k < 3; ++k) r.c[k] = Jet<N>(a[k]);
    return r;
  }
  Eigen::Vector3d value() const { return {c[0].v, c[1].v, c[2].v}; }
};

template <int N>
JetVec3<N> operator+(const JetVec3<N>& a, const JetVec3<N>& b) {
  JetVec3<N> r;
  for (int k = 0; k < 3; ++k) r.c[k] = a.c[k] + b.c[k];
  return r;
}
template <int N>
JetVec3<N> operator-(const JetVec3<N>& a, const JetVec3<N>& b) {
  JetVec3<N> r;
  for (int k = 0; k < 3; ++k) r.c[k] = a.c[k] - b.c[k];
  return r;
}
template <int N>
JetVec3<N> operator*(const Jet<N>& s, const JetVec3<N>& a) {
  JetVec3<N> r;
  for (int k = 0; k < 3; ++k) r.c[k] = s * a.c[k];
  return r;
}
template <int N>
JetVec3<N> operator*(double s, const JetVec3<N>& a) {
  JetVec3<N> r;
  for (int k = 0; k < 3; ++k) r.c[k] = s * a.c[k];
  return r;
}
template <int N>
Jet<N> dot(const JetVec3<N>& a, const JetVec3<N>& b) {
  return a.c[0] * b.c[0] + a.c[1] * b.c[1] + a.c[2] * b.c[2];
}
/// a . b with a constant b.
template <int N>
Jet<N> dot(const JetVec3<N>& a, const Eigen::Vector3d& b) {
  return a.c[0] * b[0] + a.c[1] * b[1] + a.c[2] * b[2];
}
template <int N>
JetVec3<N> cross(const JetVec3<N>& a, const JetVec3<N>& b) {
  JetVec3<N> r;
  r.c[0] = a.c[1] * b.c[2] - a.c[2] * b.c[1];
  r.c[1] = a.c[2] * b.c[0] - a.c[0] * b.c[2];
  r.c[2] = a.c[0] * b.c[1] - a.c[1] * b.c[0];
  return r;
}

}  // namespace iga
