// Internal header of the analytic projections (analytic_projection.hpp), shared by
// analytic_closest_point.cpp and analytic_ray.cpp only; not part of the public API: the
// surface's dynamic type with its frame (View), angles placed in angular domains, the
// closed-form outward normal and a bracketed 1-D root finder.
// References: [KS15] (see ../shared/paper/EQUATIONS.md): hyperboloid (22); surface of
// revolution (A.1); sphere (B.4); cylinder (B.10); torus (B.16); cone (B.23).
//
// Notation ([KS15] -> code): alpha^1, alpha^2 -> uv; r_s -> x; rho -> point; n -> normal;
// p = xi^3 -> distance (closest point) or the ray parameter t (ray); ray direction n_xi -> N;
// meridian coordinates in the local frame: s = sqrt(x^2 + y^2), z (B.16, B.23), polar angle phi.
//
// Decisions shared by both files:
// - All work is done in the placement's local frame (e_x, e_y, e_z) = Placement::frame().
// - An undefined angle (a point on the axis, on the torus' tube centre circle, the sphere's
//   centre) is 0 if 0 lies in the angular domain, else the domain's lower bound.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/knot_vector.hpp"  // GeometryError

namespace iga::detail {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr double kTiny = 1e-300;
/// Samples of the 1-D searches along a line (the hyperboloid's critical points, the ray of a
/// surface of revolution).
inline constexpr int kLineSamples = 64;

enum class Kind { plane, sphere, cylinder, torus, cone, hyperboloid, revolution };

/// The dynamic type of an analytic surface with its frame and shape parameters.
struct View {
  Kind kind = Kind::plane;
  const AnalyticSurface* s = nullptr;
  const Revolution* rev = nullptr;
  Vector3d c = Vector3d::Zero();      ///< placement origin
  Matrix3d E = Matrix3d::Identity();  ///< columns e_x, e_y, e_z
  double R = 0.0, r = 0.0;            ///< radius (sphere, cylinder), major/minor radius (torus)
  double alpha = 0.0;                 ///< cone angle (B.23)
  double a = 0.0;                     ///< hyperboloid z = a x y (11)
  double L = 1.0;                     ///< length scale of the surface (for relative tests)
  int sign = 1;                       ///< normal_sign
  Domain2 dom;
};

inline View view_of(const AnalyticSurface& s) {
  View v;
  v.s = &s;
  v.c = s.placement().center;
  v.E = s.placement().frame();
  v.sign = s.normal_sign();
  v.dom = s.domain();
  visit_analytic(s, Overloaded{
                        [&](const Plane&) { v.kind = Kind::plane; },
                        [&](const Sphere& sp) {
                          v.kind = Kind::sphere;
                          v.R = v.L = sp.radius();
                        },
                        [&](const Cylinder& cy) {
                          v.kind = Kind::cylinder;
                          v.R = v.L = cy.radius();
                        },
                        [&](const Torus& to) {
                          v.kind = Kind::torus;
                          v.R = to.major_radius();
                          v.r = to.minor_radius();
                          v.L = v.R + v.r;
                        },
                        [&](const Cone& co) {
                          v.kind = Kind::cone;
                          v.alpha = co.alpha();
                        },
                        [&](const Hyperboloid& hy) {
                          v.kind = Kind::hyperboloid;
                          v.a = hy.a();
                        },
                        [&](const Revolution& re) {
                          v.kind = Kind::revolution;
                          v.rev = &re;
                        },
                    });
  return v;
}

// ---- parameters and domains -----------------------------------------------------------------

/// An angle placed in an angular interval: value in [lo, lo + 2 pi) when inside; outside a
/// sector, the bound nearer along the circle (ties: the upper one).
struct AngleFit {
  double value = 0.0;
  bool inside = true;
};

inline AngleFit fit_angle(double a, const Interval& I) {
  double w = std::fmod(a - I.lo, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  w += I.lo;
  if (w <= I.hi) return {w, true};
  const double past_hi = w - I.hi, before_lo = I.lo + kTwoPi - w;
  return {past_hi <= before_lo ? I.hi : I.lo, false};
}

/// The deterministic choice for an undefined angle: 0 if the domain holds it, else lo.
inline double undefined_angle(const Interval& I) {
  const AngleFit f = fit_angle(0.0, I);
  return f.inside ? f.value : I.lo;
}

/// Radial and circumferential unit vectors of the frame at polar angle phi.
inline Vector3d e_r(const View& V, double phi) {
  return std::cos(phi) * V.E.col(0) + std::sin(phi) * V.E.col(1);
}

/// The "outward" unit normal of analytic_surfaces.hpp at (u, v), in closed form (also at the
/// poles, the apex and the axis, where rho_u x rho_v vanishes).
inline Vector3d outward_normal(const View& V, double u, double v) {
  const Vector3d& ez = V.E.col(2);
  switch (V.kind) {
    case Kind::plane:
      return ez;
    case Kind::sphere:  // (B.4)
      return std::cos(v) * e_r(V, u) + std::sin(v) * ez;
    case Kind::torus: {  // (B.16); rho_u x rho_v turns over where R + r cos v < 0 (r > R)
      const Vector3d n = std::cos(v) * e_r(V, u) + std::sin(v) * ez;
      return V.R + V.r * std::cos(v) < 0.0 ? Vector3d(-n) : n;
    }
    case Kind::cylinder:  // (B.10)
      return e_r(V, u);
    case Kind::cone:  // (B.23)
      return std::sin(V.alpha) * e_r(V, u) - std::cos(V.alpha) * ez;
    case Kind::hyperboloid: {  // (22)
      const Vector3d n = -V.a * v * V.E.col(0) - V.a * u * V.E.col(1) + ez;
      return n / std::sqrt(1.0 + V.a * V.a * (u * u + v * v));
    }
    case Kind::revolution: {
      double f = 0.0, df = 0.0, ddf = 0.0;
      V.rev->profile(u, f, df, ddf);
      return (ez - df * e_r(V, v)) / std::sqrt(1.0 + df * df);
    }
  }
  return ez;
}

// ---- 1-D root finding -----------------------------------------------------------------------

/// A root of fn on [a, b], where fn(a), fn(b) differ in sign: Newton steps kept inside the
/// shrinking bracket, bisection otherwise. fn(t) returns (value, derivative); a zero or
/// non-finite derivative forces bisection.
template <class Fn>
double safe_root(Fn&& fn, double a, double b, int& iterations) {
  double lo = a, hi = b;
  const double f_lo = fn(lo).first;
  const bool neg_lo = f_lo < 0.0;
  double t = 0.5 * (lo + hi), last_step = std::abs(hi - lo);
  for (int it = 0; it < 200; ++it) {
    const std::pair<double, double> fd = fn(t);
    ++iterations;
    if (fd.first == 0.0) return t;
    if ((fd.first < 0.0) == neg_lo)
      lo = t;
    else
      hi = t;
    double next = t - fd.first / fd.second;
    const double lo_b = std::min(lo, hi), hi_b = std::max(lo, hi);
    if (!std::isfinite(next) || next <= lo_b || next >= hi_b ||
        std::abs(next - t) > 0.5 * last_step)
      next = 0.5 * (lo + hi);  // bisection
    last_step = std::abs(next - t);
    t = next;
    if (last_step <= 2.0 * kEps * std::abs(t) + kTiny || hi_b - lo_b <= 4.0 * kEps * std::abs(t))
      break;
  }
  return t;
}

}  // namespace iga::detail
