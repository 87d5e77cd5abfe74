// Closest point and ray projections onto the analytic rigid surfaces of [KS15]: closed forms
// where the paper gives them, short 1-D / 3-D Newton iterations elsewhere.
// References: [KS15] (see ../shared/paper/EQUATIONS.md): plane (8)-(9); ray projection (2)-(5);
// hyperboloid (11), (13), (15)-(22); surface of revolution (A.1)-(A.2); sphere (B.4); cylinder
// (B.10); torus (B.16); cone (B.23)-(B.25); Sect. 2.2 for edges and vertices.
//
// Notation ([KS15] -> code): alpha^1, alpha^2 -> uv; r_s -> x; rho -> point; n -> normal;
// p = xi^3 -> distance (closest point) or the ray parameter t (ray); ray direction n_xi -> N;
// meridian coordinates in the local frame: s = sqrt(x^2 + y^2), z (B.16, B.23), polar angle phi.
//
// Decisions (the contract is analytic_projection.hpp):
// - All work is done in the placement's local frame (e_x, e_y, e_z) = Placement::frame().
// - An undefined angle (a point on the axis, on the torus' tube centre circle, the sphere's
//   centre) is 0 if 0 lies in the angular domain, else the domain's lower bound.
// - Bounded domains of the surfaces of revolution (sphere, cylinder, torus, cone, revolution)
//   are handled exactly, without iterating: the distance from x to the meridian at angle u
//   grows with the angle |u - phi| (|x - rho|^2 = s^2 + r^2 - 2 s r cos(u - phi) + (z - z_rho)^2
//   for every point (r, z_rho) of the meridian), so outside an angular sector the minimum lies
//   on the meridian of the nearer sector bound, where x is seen at radius s cos(u - phi)
//   (possibly negative); there the nearest point of the meridian line / circle / profile,
//   clamped to the other parameter's interval, is the constrained minimum. The plane's
//   rectangle is a clamp.
// - Hyperboloid: the paper's Newton (16)-(22) from (20), accepted when it converges within the
//   reach 1/|a| of the surface (then it is the global minimum); otherwise every critical point
//   from a scalar equation in the foot's height and, on a bounded domain, the straight edges
//   (closest_hyperboloid). closest_point_local is only a last resort there.
// - Statuses: interior when no bound is active; edge with one active bound; vertex with two, or
//   when the active bound is an edge collapsed to a point (the cone's apex v = 0; the tip r = 0
//   of a surface of revolution with f'(0) != 0). At the apex the normal is the cone's normal on
//   the meridian through x (chosen angle), at a tip the profile's normal there.
// - The cone is its upper nappe v >= 0 (domain bounds below 0 are treated as 0), a surface of
//   revolution the radii r >= 0 of its u interval.
// - Rays: N is normalized first, so xi3 is a length: x + xi3 N/|N| = rho. Ray hits outside the
//   domain are skipped; a double root of the line-surface equation (discriminant within
//   round-off of zero, or |n.N| < 1e-10 predicted from it) is reported as `tangent` (9).
#include "contact/analytic_projection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include <Eigen/LU>

#include "contact/closest_point.hpp"
#include "geometry/knot_vector.hpp"  // GeometryError

namespace iga {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTiny = 1e-300;
/// |n.N| below which a ray hit counts as tangent: (8) needs n.N != 0 (9).
constexpr double kTangentTol = 1e-10;
/// Samples of the 1-D searches (meridian profile, ray line of a surface of revolution).
constexpr int kProfileSamples = 32;
constexpr int kLineSamples = 64;

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

View view_of(const AnalyticSurface& s, const char* caller) {
  View v;
  v.s = &s;
  v.c = s.placement().center;
  v.E = s.placement().frame();
  v.sign = s.normal_sign();
  v.dom = s.domain();
  if (dynamic_cast<const Plane*>(&s) != nullptr) {
    v.kind = Kind::plane;
  } else if (const Sphere* sp = dynamic_cast<const Sphere*>(&s)) {
    v.kind = Kind::sphere;
    v.R = v.L = sp->radius();
  } else if (const Cylinder* cy = dynamic_cast<const Cylinder*>(&s)) {
    v.kind = Kind::cylinder;
    v.R = v.L = cy->radius();
  } else if (const Torus* to = dynamic_cast<const Torus*>(&s)) {
    v.kind = Kind::torus;
    v.R = to->major_radius();
    v.r = to->minor_radius();
    v.L = v.R + v.r;
  } else if (const Cone* co = dynamic_cast<const Cone*>(&s)) {
    v.kind = Kind::cone;
    v.alpha = co->alpha();
  } else if (const Hyperboloid* hy = dynamic_cast<const Hyperboloid*>(&s)) {
    v.kind = Kind::hyperboloid;
    v.a = hy->a();
  } else if (const Revolution* re = dynamic_cast<const Revolution*>(&s)) {
    v.kind = Kind::revolution;
    v.rev = re;
  } else {
    throw GeometryError(std::string(caller) + ": unsupported analytic surface type '" +
                        s.type_name() + "'");
  }
  return v;
}

// ---- parameters and domains -----------------------------------------------------------------

/// An angle placed in an angular interval: value in [lo, lo + 2 pi) when inside; outside a
/// sector, the bound nearer along the circle (ties: the upper one).
struct AngleFit {
  double value = 0.0;
  bool inside = true;
};

AngleFit fit_angle(double a, const Interval& I) {
  double w = std::fmod(a - I.lo, kTwoPi);
  if (w < 0.0) w += kTwoPi;
  w += I.lo;
  if (w <= I.hi) return {w, true};
  const double past_hi = w - I.hi, before_lo = I.lo + kTwoPi - w;
  return {past_hi <= before_lo ? I.hi : I.lo, false};
}

/// The deterministic choice for an undefined angle: 0 if the domain holds it, else lo.
double undefined_angle(const Interval& I) {
  const AngleFit f = fit_angle(0.0, I);
  return f.inside ? f.value : I.lo;
}

/// Clamp to a linear interval, telling whether the bound became active.
double clamp_to(double t, const Interval& I, bool& active) {
  active = t < I.lo || t > I.hi;
  return std::clamp(t, I.lo, I.hi);
}

bool angle_u(Kind k) {
  return k == Kind::sphere || k == Kind::cylinder || k == Kind::torus || k == Kind::cone;
}
bool angle_v(Kind k) {
  return k == Kind::torus || k == Kind::revolution;
}

/// Radial and circumferential unit vectors of the frame at polar angle phi.
Vector3d e_r(const View& V, double phi) {
  return std::cos(phi) * V.E.col(0) + std::sin(phi) * V.E.col(1);
}

/// The "outward" unit normal of analytic_surfaces.hpp at (u, v), in closed form (also at the
/// poles, the apex and the axis, where rho_u x rho_v vanishes).
Vector3d outward_normal(const View& V, double u, double v) {
  const Vector3d& ez = V.E.col(2);
  switch (V.kind) {
    case Kind::plane:
      return ez;
    case Kind::sphere:  // (B.4)
    case Kind::torus:   // (B.16)
      return std::cos(v) * e_r(V, u) + std::sin(v) * ez;
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

/// Largest cosine between x - rho and the free tangents rho_i (the scaled projected gradient
/// (16)); tangents that vanish (poles, apex, axis) carry no condition.
double orthogonality_residual(const SurfaceDerivs& d, const Vector3d& diff, bool u_free,
                              bool v_free) {
  const double dn = diff.norm();
  double res = 0.0;
  if (u_free) {
    const double tn = d.Su.norm();
    if (tn > 0.0) res = std::max(res, std::abs(d.Su.dot(diff)) / (tn * dn + kTiny));
  }
  if (v_free) {
    const double tn = d.Sv.norm();
    if (tn > 0.0) res = std::max(res, std::abs(d.Sv.dot(diff)) / (tn * dn + kTiny));
  }
  return res;
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

// ---- surface of revolution: the meridian problem (A.1) ---------------------------------------

struct MeridianFoot {
  double r = 0.0;
  int iterations = 0;
  bool at_bound = false;  ///< r rests on a bound of [a, b] with g' pointing out
};

/// Global minimizer over r in [a, b] (0 <= a < b <= inf) of the squared meridian distance
/// g(r) = 1/2 [(r - sp)^2 + (f(r) - z)^2] from (sp, z) to the profile z = f(r) of (A.1).
/// Its stationarity g'(r) = (r - sp) + f'(r)(f(r) - z) = 0 is the gradient (16) of the CPP in
/// the meridian plane, g''(r) = 1 + f'^2 + f''(f - z) its Hessian (17). Any minimizer lies
/// within |r - sp| <= D0, D0 the distance to the profile point at clamp(sp, a, b); that
/// interval is sampled, and every local minimum of the samples is refined by a bracketed Newton.
MeridianFoot revolution_meridian_foot(const Revolution& rev, double sp, double z, double a,
                                      double b) {
  auto g = [&](double r) {
    double f = 0.0, df = 0.0, ddf = 0.0;
    rev.profile(r, f, df, ddf);
    return 0.5 * ((r - sp) * (r - sp) + (f - z) * (f - z));
  };
  auto dg = [&](double r) {
    double f = 0.0, df = 0.0, ddf = 0.0;
    rev.profile(r, f, df, ddf);
    return std::make_pair((r - sp) + df * (f - z), 1.0 + df * df + ddf * (f - z));
  };
  MeridianFoot out;
  const double r_ref = std::clamp(sp, a, b);
  double best_r = r_ref, best_g = g(r_ref);
  const double d0 = std::sqrt(2.0 * best_g);
  const double lo = std::max(a, sp - d0), hi = std::min(b, sp + d0);
  if (hi > lo) {
    double gs[kProfileSamples + 1];
    auto r_at = [&](int k) { return lo + (hi - lo) * k / kProfileSamples; };
    for (int k = 0; k <= kProfileSamples; ++k) gs[k] = g(r_at(k));
    for (int k = 0; k <= kProfileSamples; ++k) {
      if ((k > 0 && gs[k] > gs[k - 1]) || (k < kProfileSamples && gs[k] > gs[k + 1])) continue;
      // A local minimum of the samples: refine within its neighbours.
      const double p = r_at(std::max(k - 1, 0)), q = r_at(std::min(k + 1, kProfileSamples));
      double cand[3] = {p, q, r_at(k)};
      if (dg(p).first < 0.0 && dg(q).first > 0.0) cand[2] = safe_root(dg, p, q, out.iterations);
      for (const double rc : cand) {
        const double gc = g(rc);
        if (gc < best_g) best_g = gc, best_r = rc;
      }
    }
  }
  out.r = best_r;
  const double slope = dg(best_r).first;
  out.at_bound = (best_r <= a && slope > 0.0) || (best_r >= b && slope < 0.0);
  return out;
}

// ---- closest point --------------------------------------------------------------------------

/// Meridian half-plane holding the closest point: its polar angle and the radius at which x is
/// seen in it (s, or s cos(u - phi) on the nearer bound of a sector; see the file header).
/// Within round_off of the axis the angle is undefined (file header) and s = 0.
struct Meridian {
  double angle = 0.0;
  double s = 0.0;
  bool at_bound = false;
};

Meridian meridian_of(double x, double y, const Interval& I, double round_off) {
  const double s = std::hypot(x, y);
  if (s <= round_off) return {undefined_angle(I), 0.0, false};  // on the axis
  const double phi = std::atan2(y, x);
  const AngleFit f = fit_angle(phi, I);
  if (f.inside) return {f.value, s, false};
  return {f.value, s * std::cos(phi - f.value), true};
}

/// Result at the foot parameters uv: point, oriented normal, signed distance, status from the
/// active bounds (file header). p_closed: the paper's closed-form penetration along the outward
/// normal, used for interior feet (non-finite: use |x - rho|).
ProjectionResult closest_result(const View& V, const Vector3d& x, const Vector2d& uv, bool u_active,
                                bool v_active, bool degenerate, double p_closed,
                                int iterations = 0) {
  ProjectionResult res;
  res.uv = uv;
  const SurfaceDerivs d = V.s->derivs(uv[0], uv[1], 1);
  res.point = d.S;
  res.normal = V.sign * outward_normal(V, uv[0], uv[1]);
  const Vector3d diff = x - d.S;
  const int active = (u_active ? 1 : 0) + (v_active ? 1 : 0);
  if (active == 0 && std::isfinite(p_closed)) {
    res.distance = V.sign * p_closed;
  } else {
    const double dist = diff.norm();
    res.distance = diff.dot(res.normal) < 0.0 ? -dist : dist;  // (10): p along n
  }
  res.status = (degenerate || active == 2) ? ProjectionStatus::vertex
               : active == 1               ? ProjectionStatus::edge
                                           : ProjectionStatus::interior;
  res.iterations = iterations;
  res.residual = orthogonality_residual(d, diff, !u_active, !v_active);
  return res;
}

/// [KS15] (16)-(22): Newton for the closest point on z = a x y (local frame) from `start`.
ProjectionResult hyperboloid_newton(double a, const Vector3d& x_local, const Vector2d& start,
                                    const ProjectionOptions& opt) {
  const double x = x_local.x(), y = x_local.y(), z = x_local.z();
  Vector2d al = start;
  ProjectionResult res;
  bool converged = false;
  for (int it = 0; it <= opt.max_iterations; ++it) {
    const double a1 = al[0], a2 = al[1];
    const Vector3d rho(a1, a2, a * a1 * a2);                          // (11)
    const Vector3d rho_1(1.0, 0.0, a * a2), rho_2(0.0, 1.0, a * a1);  // (13)
    const Vector3d diff = x_local - rho;
    const Vector2d Fp(-rho_1.dot(diff), -rho_2.dot(diff));  // (16)
    const double dn = diff.norm();
    res.residual = std::max(std::abs(Fp[0]) / (rho_1.norm() * dn + kTiny),
                            std::abs(Fp[1]) / (rho_2.norm() * dn + kTiny));
    if (res.residual <= opt.tol_residual || converged) {
      converged = true;
      break;
    }
    if (it == opt.max_iterations) break;
    // (17) with rho_11 = rho_22 = 0, rho_12 = (0, 0, a) (15).
    const double h11 = 1.0 + (a * a2) * (a * a2), h22 = 1.0 + (a * a1) * (a * a1);
    const double h12 = 2.0 * a * a * a1 * a2 - a * z;
    const double det = h11 * h22 - h12 * h12;  // (19)
    if (det == 0.0 || !std::isfinite(det)) break;
    const Vector2d step(-(h22 * Fp[0] - h12 * Fp[1]) / det,  // (18): -F''^-1 F'
                        -(-h12 * Fp[0] + h11 * Fp[1]) / det);
    al += step;
    res.iterations = it + 1;
    if (!al.allFinite()) break;
    // A step at round-off level ends the iteration after re-evaluating the residual (near the
    // surface the scaled residual cannot reach tol_residual: |x - rho| -> 0).
    if (step.norm() <= opt.tol_step * (1.0 + al.norm())) converged = true;
  }
  const double a1 = al[0], a2 = al[1];
  res.uv = al;
  res.point = Vector3d(a1, a2, a * a1 * a2);
  const double root = std::sqrt((a * a1) * (a * a1) + (a * a2) * (a * a2) + 1.0);
  res.normal = Vector3d(-a * a2, -a * a1, 1.0) / root;                              // (22)
  res.distance = (a * a2 * (a1 - x) + a * a1 * (a2 - y) + z - a * a1 * a2) / root;  // (21)
  res.status =
      converged && al.allFinite() ? ProjectionStatus::interior : ProjectionStatus::not_converged;
  return res;
}

/// Every critical point of (12) on z = a x y whose height offset |w| <= w_max, w = a a1 a2 - z.
/// With w fixed, the stationarity (16) is linear: a1 + a w a2 = x, a w a1 + a2 = y, so
/// alpha(w) = (x - a w y, y - a w x) / (1 - a^2 w^2), and w solves the scalar equation
/// h(w) = a a1(w) a2(w) - z - w = 0. Its roots are bracketed by sampling [-w_max, w_max] between
/// the poles w = +-1/|a| and refined by a bracketed Newton.
template <class Visit>
void hyperboloid_critical_points(double a, const Vector3d& xl, double w_max, Visit&& visit,
                                 int& iterations) {
  const double x = xl.x(), y = xl.y(), z = xl.z();
  if (a == 0.0) {
    visit(Vector2d(x, y));
    return;
  }
  auto alpha_of = [&](double w) {
    const double det = 1.0 - a * a * w * w;
    return Vector2d((x - a * w * y) / det, (y - a * w * x) / det);
  };
  auto h = [&](double w) {
    const double det = 1.0 - a * a * w * w;
    const Vector2d al = alpha_of(w);
    const double d1 = (-a * y + 2.0 * a * a * w * al[0]) / det;  // d alpha / dw
    const double d2 = (-a * x + 2.0 * a * a * w * al[1]) / det;
    return std::make_pair(a * al[0] * al[1] - z - w, a * (d1 * al[1] + al[0] * d2) - 1.0);
  };
  const double pole = 1.0 / std::abs(a), gap = 1e-12 * pole;
  double cuts[4];
  int nc = 0;
  cuts[nc++] = -w_max;
  if (pole < w_max) cuts[nc++] = -pole, cuts[nc++] = pole;
  cuts[nc++] = w_max;
  for (int piece = 0; piece + 1 < nc; ++piece) {
    // Keep off the poles, where alpha(w) is infinite.
    const double lo = cuts[piece] + (std::abs(cuts[piece]) == pole ? gap : 0.0);
    const double hi = cuts[piece + 1] - (std::abs(cuts[piece + 1]) == pole ? gap : 0.0);
    if (!(hi > lo)) continue;
    double w_prev = lo, h_prev = h(lo).first;
    if (h_prev == 0.0) visit(alpha_of(lo));
    for (int k = 1; k <= kLineSamples; ++k) {
      const double w = lo + (hi - lo) * k / kLineSamples;
      const double hw = h(w).first;
      if (hw == 0.0)
        visit(alpha_of(w));
      else if (h_prev != 0.0 && (hw < 0.0) != (h_prev < 0.0))
        visit(alpha_of(safe_root(h, w_prev, w, iterations)));
      w_prev = w;
      h_prev = hw;
    }
  }
}

/// Closest point on the hyperboloid (11). (1) The paper's Newton from (20): a converged
/// critical point at distance |p| < 1/|a| is the global minimum, 1/|a| being the reach of
/// z = a x y (its largest principal curvature |a| is at the origin), since a point within the
/// reach along a normal projects onto that normal's foot; inside the domain it is the answer.
/// (2) Otherwise the minimum over all interior critical points (hyperboloid_critical_points,
/// with |w| bounded by the distance to rho(clamp(x, y))) and, for a bounded domain, the
/// boundary: each edge is a straight line (a1 or a2 fixed in (11)), projected in closed form.
ProjectionResult closest_hyperboloid(const View& V, const Vector3d& x, const Vector3d& xl,
                                     const ProjectionOptions& opt) {
  const double a = V.a;
  auto inside = [&V](const Vector2d& al) {
    return al[0] >= V.dom.u.lo && al[0] <= V.dom.u.hi && al[1] >= V.dom.v.lo && al[1] <= V.dom.v.hi;
  };
  const ProjectionResult ks = hyperboloid_closest_point_ks(a, xl, opt);
  int iterations = ks.iterations;
  if (ks.status == ProjectionStatus::interior && std::abs(a * ks.distance) < 1.0 && inside(ks.uv)) {
    ProjectionResult res = closest_result(V, x, ks.uv, false, false, false, ks.distance);
    res.iterations = iterations;
    return res;
  }
  struct Candidate {
    Vector2d uv = Vector2d::Zero();
    bool u_active = false, v_active = false;
    double d2 = kInf;
  } best;
  auto consider = [&](const Vector2d& uv, bool u_active, bool v_active) {
    const Vector3d rho(uv[0], uv[1], a * uv[0] * uv[1]);
    const double d2 = (xl - rho).squaredNorm();
    if (uv.allFinite() && d2 < best.d2) best = {uv, u_active, v_active, d2};
  };
  const Vector2d near(std::clamp(xl.x(), V.dom.u.lo, V.dom.u.hi),
                      std::clamp(xl.y(), V.dom.v.lo, V.dom.v.hi));
  const double w_max =
      (xl - Vector3d(near[0], near[1], a * near[0] * near[1])).norm() * (1.0 + 1e-12);
  hyperboloid_critical_points(
      a, xl, w_max,
      [&](const Vector2d& al) {
        // Polish the critical point by (16)-(18); keep the better of the two.
        const ProjectionResult p = hyperboloid_newton(a, xl, al, opt);
        iterations += p.iterations;
        if (inside(al)) consider(al, false, false);
        if (p.status == ProjectionStatus::interior && inside(p.uv)) consider(p.uv, false, false);
      },
      iterations);
  // Edges a1 = const: the line (a1, t, a a1 t); a2 = const: (t, a2, a a2 t).
  for (int dir = 0; dir < 2; ++dir) {
    const Interval& fixed = dir == 0 ? V.dom.u : V.dom.v;
    const Interval& free = dir == 0 ? V.dom.v : V.dom.u;
    for (const double c : {fixed.lo, fixed.hi}) {
      if (!std::isfinite(c)) continue;
      const Vector3d origin = dir == 0 ? Vector3d(c, 0.0, 0.0) : Vector3d(0.0, c, 0.0);
      const Vector3d along = dir == 0 ? Vector3d(0.0, 1.0, a * c) : Vector3d(1.0, 0.0, a * c);
      bool clamped = false;
      const double t = clamp_to((xl - origin).dot(along) / along.squaredNorm(), free, clamped);
      consider(dir == 0 ? Vector2d(c, t) : Vector2d(t, c), dir == 0 || clamped,
               dir == 1 || clamped);
    }
  }
  if (best.d2 == kInf) {
    // No critical point found (degenerate configurations): the safeguarded Newton from (20).
    ProjectionResult res = closest_point_local(*V.s, x, near, opt);
    res.iterations += iterations;
    return res;
  }
  ProjectionResult res = closest_result(V, x, best.uv, best.u_active, best.v_active, false, kInf);
  res.iterations = iterations;
  return res;
}

}  // namespace

ProjectionResult hyperboloid_closest_point_ks(double a, const Vector3d& x_local,
                                              const ProjectionOptions& opt) {
  return hyperboloid_newton(a, x_local, Vector2d(x_local.x(), x_local.y()), opt);  // (20)
}

ProjectionResult closest_point_analytic(const AnalyticSurface& s, const Vector3d& x,
                                        const ProjectionOptions& opt) {
  const View V = view_of(s, "closest_point_analytic");
  const Vector3d xl = V.E.transpose() * (x - V.c);
  const double z = xl.z();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  // Length below which x - c carries only round-off (of x - c and of the frame): a point that
  // close to the axis (or the torus' centre circle) has an undefined angle.
  const double round_off = 8.0 * kEps * (x.norm() + V.c.norm());
  switch (V.kind) {
    case Kind::plane: {  // foot = in-plane coordinates, p = z (8)
      bool au = false, av = false;
      const Vector2d uv(clamp_to(xl.x(), V.dom.u, au), clamp_to(xl.y(), V.dom.v, av));
      return closest_result(V, x, uv, au, av, false, z);
    }
    case Kind::sphere: {  // (B.4): u = atan2(y, x), v = asin(z / |x - c|) (as atan2(z, s))
      const Meridian m = meridian_of(xl.x(), xl.y(), V.dom.u, round_off);
      AngleFit lat{std::clamp(0.0, V.dom.v.lo, V.dom.v.hi), true};  // x = c: undefined
      if (xl.norm() > round_off) lat = fit_angle(std::atan2(z, m.s), V.dom.v);
      const double p = xl.norm() - V.R;  // (B.4)
      return closest_result(V, x, Vector2d(m.angle, lat.value), m.at_bound, !lat.inside, false, p);
    }
    case Kind::cylinder: {  // (B.10): u = polar angle, v = axial coordinate
      const Meridian m = meridian_of(xl.x(), xl.y(), V.dom.u, round_off);
      bool av = false;
      const double v = clamp_to(z, V.dom.v, av);
      const double p = std::hypot(xl.x(), xl.y()) - V.R;  // (B.10): |d| - R
      return closest_result(V, x, Vector2d(m.angle, v), m.at_bound, av, false, p);
    }
    case Kind::torus: {  // (B.16): nearest point of the tube circle in the meridian plane
      const Meridian m = meridian_of(xl.x(), xl.y(), V.dom.u, round_off);
      const double ds = m.s - V.R;
      AngleFit tube{undefined_angle(V.dom.v), true};  // x on the tube's centre circle
      if (std::hypot(ds, z) > round_off) tube = fit_angle(std::atan2(z, ds), V.dom.v);
      // (B.16) p = sqrt(x^2 + y^2 + z^2 + R^2 - 2 R s) - r, written as |(s - R, z)| - r to
      // avoid the cancellation near the centre circle.
      const double p = std::hypot(std::hypot(xl.x(), xl.y()) - V.R, z) - V.r;
      return closest_result(V, x, Vector2d(m.angle, tube.value), m.at_bound, !tube.inside, false,
                            p);
    }
    case Kind::cone: {  // (B.23): project onto the generator ray in the meridian plane
      const Meridian m = meridian_of(xl.x(), xl.y(), V.dom.u, round_off);
      const double ca = std::cos(V.alpha), sa = std::sin(V.alpha);
      const double along = m.s * ca + z * sa;  // coordinate along the generator (cos a, sin a)
      Interval radii = V.dom.v;
      radii.lo = std::max(radii.lo, 0.0);
      bool av = false;
      // Behind the apex (along < 0) the nearest point of the ray is the apex itself.
      const double v = clamp_to(along * ca, radii, av);
      const double p = std::hypot(xl.x(), xl.y()) * sa - z * ca;  // (B.23)
      return closest_result(V, x, Vector2d(m.angle, v), m.at_bound, av, av && v == 0.0, p);
    }
    case Kind::hyperboloid:
      return closest_hyperboloid(V, x, xl, opt);
    case Kind::revolution: {  // (A.1): 1-D Newton for r in the meridian plane
      const Meridian m = meridian_of(xl.x(), xl.y(), V.dom.v, round_off);
      const double a = std::max(V.dom.u.lo, 0.0), b = V.dom.u.hi;
      const MeridianFoot f = revolution_meridian_foot(*V.rev, m.s, z, a, b);
      const bool tip = f.at_bound && f.r == 0.0;
      return closest_result(V, x, Vector2d(f.r, m.angle), f.at_bound, m.at_bound, tip, kNaN,
                            f.iterations);
    }
  }
  return {};
}

// ---- ray projection -------------------------------------------------------------------------

namespace {

/// Parameters (u, v) of a point w (local coordinates) on, or next to, the surface; angles as
/// atan2 (unmapped), undefined ones (within round_off of the axis) as in the file header.
Vector2d params_of(const View& V, const Vector3d& w, double round_off) {
  double s = std::hypot(w.x(), w.y());
  double phi = 0.0;
  if (s > round_off)
    phi = std::atan2(w.y(), w.x());
  else
    s = 0.0, phi = undefined_angle(angle_u(V.kind) ? V.dom.u : V.dom.v);
  switch (V.kind) {
    case Kind::plane:
    case Kind::hyperboloid:
      return Vector2d(w.x(), w.y());
    case Kind::sphere:
      return Vector2d(phi, w.norm() > round_off ? std::atan2(w.z(), s) : 0.0);
    case Kind::cylinder:
      return Vector2d(phi, w.z());
    case Kind::torus: {
      const double ds = s - V.R;
      return Vector2d(phi, std::hypot(ds, w.z()) > round_off ? std::atan2(w.z(), ds)
                                                             : undefined_angle(V.dom.v));
    }
    case Kind::cone:
      return Vector2d(phi, s);
    case Kind::revolution:
      return Vector2d(s, phi);
  }
  return Vector2d::Zero();
}

/// Round-off length of the local coordinates of x + t N (see closest_point_analytic).
double round_off_of(const View& V, const Vector3d& x, double t) {
  return 8.0 * kEps * (x.norm() + V.c.norm() + std::abs(t));
}

/// Maps uv into the domain (angles wrapped); false if it lies outside (beyond round-off).
bool into_domain(const View& V, Vector2d& uv) {
  const Interval* I[2] = {&V.dom.u, &V.dom.v};
  const bool ang[2] = {angle_u(V.kind), angle_v(V.kind)};
  for (int i = 0; i < 2; ++i) {
    if (ang[i]) {
      const AngleFit f = fit_angle(uv[i], *I[i]);
      if (!f.inside) {
        // Accept an angle a round-off beyond the sector bound.
        const double gap = std::abs(std::remainder(uv[i] - f.value, kTwoPi));
        if (gap > 1e-12 * kTwoPi) return false;
      }
      uv[i] = f.value;
    } else {
      const double tol = 1e-12 * (1.0 + std::abs(uv[i]));
      if (uv[i] < I[i]->lo - tol || uv[i] > I[i]->hi + tol) return false;
      uv[i] = std::clamp(uv[i], I[i]->lo, I[i]->hi);
    }
  }
  if (V.kind == Kind::cone && uv[1] < 0.0) return false;
  return true;
}

struct RayBest {
  bool have = false;
  ProjectionResult r;
  int iterations = 0;
};

/// Offers the hit at parameters uv with ray parameter t: polishes it by Newton on the ray
/// residual (3)-(5) unless it is a double root, checks the domain, and keeps it if its |t| is
/// the smallest so far. Status tangent when |n.N| < kTangentTol (9) or forced (double root).
void offer_hit(const View& V, const Vector3d& x, const Vector3d& N, Vector2d uv, double t,
               bool force_tangent, RayBest& best) {
  if (!std::isfinite(t) || !uv.allFinite()) return;
  if (!into_domain(V, uv)) return;
  SurfaceDerivs d = V.s->derivs(uv[0], uv[1], 1);
  Vector3d F = d.S - x - t * N;  // (3)
  if (!force_tangent) {
    for (int k = 0; k < 4; ++k) {
      const double fn = F.norm();
      if (fn <= 4.0 * kEps * (x.norm() + std::abs(t) + V.L)) break;
      Matrix3d J;  // (4)
      J.col(0) = d.Su;
      J.col(1) = d.Sv;
      J.col(2) = -N;
      if (std::abs(J.determinant()) <= 1e-12 * d.Su.norm() * d.Sv.norm()) break;
      const Vector3d step = -J.partialPivLu().solve(F);  // (5)
      Vector2d uv_new(uv[0] + step[0], uv[1] + step[1]);
      if (!into_domain(V, uv_new)) break;
      const double t_new = t + step[2];
      const SurfaceDerivs d_new = V.s->derivs(uv_new[0], uv_new[1], 1);
      const Vector3d F_new = d_new.S - x - t_new * N;
      ++best.iterations;
      if (!(F_new.norm() < fn)) break;
      uv = uv_new;
      t = t_new;
      d = d_new;
      F = F_new;
    }
  }
  if (best.have && std::abs(t) >= std::abs(best.r.distance)) return;
  ProjectionResult& r = best.r;
  best.have = true;
  r.uv = uv;
  r.point = d.S;
  r.normal = V.sign * outward_normal(V, uv[0], uv[1]);
  r.distance = t;
  r.residual = F.norm() / ((x - V.c).norm() + std::abs(t) + V.L);
  const bool apex = V.kind == Kind::cone && uv[1] <= round_off_of(V, x, t);
  r.status = apex ? ProjectionStatus::vertex
             : (force_tangent || std::abs(r.normal.dot(N)) < kTangentTol)
                 ? ProjectionStatus::tangent
                 : ProjectionStatus::interior;
}

/// Offers the points of the local line w(t) = xl + t Nl at the roots of the quadratic
/// q(t) = A t^2 + 2 B t + C = Q(w(t)) of an implicit surface Q = 0. grad_half(w) = |grad Q|/2,
/// so that |n.N| = sqrt(B^2 - A C) / grad_half at a root: a discriminant within round-off of
/// zero, or one predicting |n.N| < kTangentTol, is a double root (tangent, (9)). accept(w)
/// filters the points (the cone's lower nappe).
template <class GradHalf, class Accept>
void offer_quadratic_roots(const View& V, const Vector3d& x, const Vector3d& N, const Vector3d& xl,
                           const Vector3d& Nl, double A, double B, double C, GradHalf&& grad_half,
                           RayBest& best, Accept&& accept) {
  auto offer_t = [&](double t, bool tangent) {
    const Vector3d w = xl + t * Nl;
    if (accept(w)) offer_hit(V, x, N, params_of(V, w, round_off_of(V, x, t)), t, tangent, best);
  };
  const double disc = B * B - A * C;
  const double noise = 8.0 * kEps * (B * B + std::abs(A * C));
  if (A != 0.0) {
    const double tc = -B / A;
    const double g = grad_half(xl + tc * Nl);
    const double tangent_level = (kTangentTol * g) * (kTangentTol * g);
    if (std::abs(disc) <= std::max(noise, tangent_level)) {
      offer_t(tc, true);
      return;
    }
  }
  if (disc < 0.0) return;
  if (A == 0.0 && B == 0.0) {
    if (C == 0.0) offer_t(0.0, true);  // the line lies in the surface
    return;
  }
  // Roots without cancellation: q = -(B + sign(B) sqrt(disc)), t = q/A and C/q.
  const double q = -(B + std::copysign(std::sqrt(disc), B));
  if (A != 0.0) offer_t(q / A, false);
  if (q != 0.0) offer_t(C / q, false);
}

/// Torus (B.16) along the line: (|w|^2 + R^2 - r^2)^2 - 4 R^2 (w_x^2 + w_y^2) = 0, a quartic in
/// tau = t - t0, t0 the parameter of the line point nearest the centre (this removes the cubic
/// term and bounds the roots by |tau| <= sqrt((R + r)^2 - |d'|^2)). Roots are isolated between
/// the critical points (roots of the cubic q', isolated between the roots of q''), each refined
/// by a bracketed Newton; a critical point where q is within round-off of zero is a double root.
void torus_ray(const View& V, const Vector3d& x, const Vector3d& N, const Vector3d& xl,
               const Vector3d& Nl, RayBest& best) {
  const double R = V.R, r = V.r;
  const double t0 = -xl.dot(Nl);
  const Vector3d dp = xl + t0 * Nl;  // d', orthogonal to Nl
  const double reach2 = (R + r) * (R + r) - dp.squaredNorm();
  if (reach2 < -1e-12 * (R + r) * (R + r)) return;  // the line misses the enclosing sphere
  const double T = std::sqrt(std::max(reach2, 0.0)) * (1.0 + 1e-10) + 1e-12 * (R + r);
  // S = tau^2 + c0, P = w_x^2 + w_y^2 = A2 tau^2 + 2 B2 tau + C2.
  const double c0 = dp.squaredNorm() + R * R - r * r;
  const double A2 = Nl.x() * Nl.x() + Nl.y() * Nl.y();
  const double B2 = dp.x() * Nl.x() + dp.y() * Nl.y();
  const double C2 = dp.x() * dp.x() + dp.y() * dp.y();
  const double p2 = 2.0 * c0 - 4.0 * R * R * A2;  // q = tau^4 + p2 tau^2 + p1 tau + p0
  const double p1 = -8.0 * R * R * B2;
  const double p0 = c0 * c0 - 4.0 * R * R * C2;
  auto q = [&](double u) { return ((u * u + p2) * u + p1) * u + p0; };
  auto dq = [&](double u) { return std::make_pair(q(u), (4.0 * u * u + 2.0 * p2) * u + p1); };
  auto d2q = [&](double u) {
    return std::make_pair((4.0 * u * u + 2.0 * p2) * u + p1, 12.0 * u * u + 2.0 * p2);
  };
  auto q_noise = [&](double u) {
    const double u2 = u * u;
    return 16.0 * kEps * (u2 * u2 + std::abs(p2) * u2 + std::abs(p1 * u) + std::abs(p0));
  };
  int iters = 0;
  // Monotone pieces of q' on [-T, T]: split at the roots of q'' = 12 tau^2 + 2 p2.
  double knots[4];
  int nk = 0;
  knots[nk++] = -T;
  if (p2 < 0.0) {
    const double m = std::sqrt(-p2 / 6.0);
    if (m < T) knots[nk++] = -m, knots[nk++] = m;
  }
  knots[nk++] = T;
  // Critical points of q (roots of q') within [-T, T].
  double crit[3];
  int nc = 0;
  for (int i = 0; i + 1 < nk; ++i) {
    const double fa = d2q(knots[i]).first, fb = d2q(knots[i + 1]).first;
    if (fa == 0.0) {
      if (nc == 0 || crit[nc - 1] != knots[i]) crit[nc++] = knots[i];
    } else if ((fa < 0.0) != (fb < 0.0) && fb != 0.0) {
      crit[nc++] = safe_root(d2q, knots[i], knots[i + 1], iters);
    }
  }
  // Double roots at critical points; then sign changes between consecutive critical points.
  bool dbl[3] = {false, false, false};
  double dbl_width[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < nc; ++i) {
    const double u = crit[i];
    const double qv = q(u), q2 = std::abs(d2q(u).second);
    const Vector3d w = dp + u * Nl;
    const double S = w.squaredNorm() + R * R - r * r;
    const Vector3d grad = 4.0 * S * w - 8.0 * R * R * Vector3d(w.x(), w.y(), 0.0);
    // Near a double root |n.N| = sqrt(2 |q| |q''|) / |grad|.
    const double tangent_level =
        kTangentTol * kTangentTol * grad.squaredNorm() / (2.0 * q2 + kTiny);
    if (std::abs(qv) <= std::max(q_noise(u), tangent_level)) {
      dbl[i] = true;
      dbl_width[i] = 4.0 * std::sqrt(2.0 * std::max(std::abs(qv), q_noise(u)) / (q2 + kTiny));
      offer_hit(V, x, N, params_of(V, w, round_off_of(V, x, t0 + u)), t0 + u, true, best);
    }
  }
  for (int i = 0; i <= nc; ++i) {
    const double a = i == 0 ? -T : crit[i - 1], b = i == nc ? T : crit[i];
    const double fa = q(a), fb = q(b);
    if ((fa < 0.0) == (fb < 0.0) || fa == 0.0 || fb == 0.0) continue;
    const double u = safe_root(dq, a, b, iters);
    // A root split off a double root by round-off stays represented by the double root.
    if ((i > 0 && dbl[i - 1] && u - a <= dbl_width[i - 1]) ||
        (i < nc && dbl[i] && b - u <= dbl_width[i]))
      continue;
    offer_hit(V, x, N, params_of(V, dp + u * Nl, round_off_of(V, x, t0 + u)), t0 + u, false, best);
  }
  best.iterations += iters;
}

/// Newton (A.2a-e) on (r, phi, xi3) for r_s(r, phi) = (r cos phi, r sin phi, f(r)) (A.1) and
/// the line xl + xi3 Nl (local frame): residual F = r_s - xl - xi3 Nl (3), Jacobian
/// [dr_s/dr | dr_s/dphi | -Nl] (4) with determinant r D, D = -n3 + f'(r)(n1 cos phi +
/// n2 sin phi) as in (A.2), increments in closed form by Cramer's rule (A.2a-e). Returns false
/// if D or r vanish or it does not converge. r < 0 is folded back (r, phi) -> (-r, phi + pi).
bool revolution_ray_newton(const Revolution& rev, const Vector3d& xl, const Vector3d& Nl, double& r,
                           double& phi, double& xi3, int max_iterations, int& iterations) {
  const double scale = xl.norm() + 1.0;
  for (int it = 0; it < max_iterations; ++it) {
    double f = 0.0, df = 0.0, ddf = 0.0;
    rev.profile(r, f, df, ddf);
    const double c = std::cos(phi), s = std::sin(phi);
    const Vector3d F = Vector3d(r * c, r * s, f) - xl - xi3 * Nl;  // (3)
    if (F.norm() <= 4.0 * kEps * (scale + std::abs(xi3))) return true;
    const Vector3d a(c, s, df), b(-r * s, r * c, 0.0);
    const Vector3d cc = -Nl;
    const double D = -Nl.z() + df * (Nl.x() * c + Nl.y() * s);  // (A.2): D
    const double det = r * D;
    if (std::abs(det) <= 1e-14 * (std::abs(r) + 1.0)) return false;
    const double dr = -b.cross(cc).dot(F) / det;  // (A.2a-e): -J^-1 F by Cramer's rule
    const double dphi = -cc.cross(a).dot(F) / det;
    const double dxi = -a.cross(b).dot(F) / det;
    r += dr;
    phi += dphi;
    xi3 += dxi;
    ++iterations;
    if (!std::isfinite(r) || !std::isfinite(phi) || !std::isfinite(xi3)) return false;
    if (r < 0.0) r = -r, phi += kPi;
    if (std::abs(dr) + std::abs(dxi) <= 4.0 * kEps * (scale + std::abs(xi3)) &&
        std::abs(dphi) <= 4.0 * kEps)
      return true;
  }
  return false;
}

void revolution_ray(const View& V, const Vector3d& x, const Vector3d& N, const Vector3d& xl,
                    const Vector3d& Nl, const ProjectionOptions& opt, RayBest& best) {
  const Revolution& rev = *V.rev;
  const double b = V.dom.u.hi;
  int iters = 0;
  auto offer_newton = [&](double r, double phi, double xi3) {
    if (revolution_ray_newton(rev, xl, Nl, r, phi, xi3, opt.max_iterations, iters))
      offer_hit(V, x, N, Vector2d(r, phi), xi3, false, best);
  };
  const double np2 = Nl.x() * Nl.x() + Nl.y() * Nl.y();
  if (np2 <= 1e-30) {
    // A line along the axis: s is constant, one hit at z = f(s).
    const double s = std::hypot(xl.x(), xl.y());
    double f = 0.0, df = 0.0, ddf = 0.0;
    rev.profile(s, f, df, ddf);
    const double t = (f - xl.z()) / Nl.z();
    offer_hit(V, x, N, params_of(V, xl + t * Nl, round_off_of(V, x, t)), t, false, best);
    best.iterations += iters;
    return;
  }
  // Seeds along the line: the sign changes of G(t) = w_z - f(|w_perp|), each refined by a
  // bracketed Newton on G, then by (A.2).
  auto G = [&](double t) {
    const Vector3d w = xl + t * Nl;
    const double s = std::hypot(w.x(), w.y());
    double f = 0.0, df = 0.0, ddf = 0.0;
    rev.profile(s, f, df, ddf);
    const double ds = s > 0.0 ? (w.x() * Nl.x() + w.y() * Nl.y()) / s : 0.0;
    return std::make_pair(w.z() - f, s > 0.0 ? Nl.z() - df * ds : 0.0);
  };
  auto offer_root = [&](double t) {
    const Vector3d w = xl + t * Nl;
    offer_newton(std::hypot(w.x(), w.y()), std::atan2(w.y(), w.x()), t);
  };
  auto scan = [&](double t_a, double t_b, int n) {
    double t_prev = t_a, g_prev = G(t_a).first;
    if (g_prev == 0.0) offer_root(t_a);
    for (int k = 1; k <= n; ++k) {
      const double t = t_a + (t_b - t_a) * k / n;
      const double g = G(t).first;
      if (g == 0.0)
        offer_root(t);
      else if (g_prev != 0.0 && (g < 0.0) != (g_prev < 0.0))
        offer_root(safe_root(G, t_prev, t, iters));
      t_prev = t;
      g_prev = g;
    }
  };
  // Seed from the closest point of x: the hit nearest x is often close to it.
  const ProjectionResult cp = closest_point_analytic(*V.s, x, opt);
  if (found(cp.status)) offer_newton(cp.uv[0], cp.uv[1], (cp.point - x).dot(N));
  if (std::isfinite(b)) {
    // The part of the line within the cylinder r <= b holds every hit.
    const double B = xl.x() * Nl.x() + xl.y() * Nl.y();
    const double C = xl.x() * xl.x() + xl.y() * xl.y() - b * b;
    const double disc = B * B - np2 * C;
    if (disc >= 0.0) {
      const double sq = std::sqrt(disc);
      scan((-B - sq) / np2, (-B + sq) / np2, kLineSamples);
    }
  } else {
    // Unbounded radii: |t| <= T = 2 (|x - c| + |f(0)| + 1), then rings T < |t| <= 2T, ...
    // (at most 2^8 T) until a hit is nearer than the rings still unscanned.
    double f0 = 0.0, df0 = 0.0, ddf0 = 0.0;
    rev.profile(0.0, f0, df0, ddf0);
    double T = 2.0 * (xl.norm() + std::abs(f0) + 1.0);
    scan(-T, T, kLineSamples);
    for (int ring = 0; ring < 8 && !(best.have && std::abs(best.r.distance) <= T); ++ring) {
      scan(-T, -2.0 * T, kLineSamples / 2);
      scan(T, 2.0 * T, kLineSamples / 2);
      T *= 2.0;
    }
  }
  best.iterations += iters;
}

}  // namespace

ProjectionResult ray_project_analytic(const AnalyticSurface& s, const Vector3d& x,
                                      const Vector3d& N_in, const ProjectionOptions& opt) {
  const View V = view_of(s, "ray_project_analytic");
  const double nlen = N_in.norm();
  if (!(nlen > 0.0) || !std::isfinite(nlen))
    throw GeometryError("ray_project_analytic: the ray direction N must be finite and non-zero");
  const Vector3d N = N_in / nlen;  // unit: xi3 is a length
  const Vector3d xl = V.E.transpose() * (x - V.c);
  const Vector3d Nl = V.E.transpose() * N;
  RayBest best;
  auto any_point = [](const Vector3d&) { return true; };
  switch (V.kind) {
    case Kind::plane: {
      const double nN = Nl.z();
      if (std::abs(nN) < kTangentTol) {
        // (9) violated: the ray runs along the plane. Report the foot of x, xi3 from (8) when
        // finite.
        ProjectionResult res = closest_point_analytic(s, x, opt);
        res.distance = nN != 0.0 ? -xl.z() / nN : kInf;
        res.status = ProjectionStatus::tangent;
        res.iterations = 0;
        return res;
      }
      const double t = -xl.z() / nN;  // (8): xi3 = -(x - r0).N_plane / (n.N_plane)
      offer_hit(V, x, N, params_of(V, xl + t * Nl, round_off_of(V, x, t)), t, false, best);
      break;
    }
    case Kind::sphere: {  // |w|^2 - R^2 = 0
      offer_quadratic_roots(
          V, x, N, xl, Nl, 1.0, xl.dot(Nl), xl.squaredNorm() - V.R * V.R,
          [](const Vector3d& w) { return w.norm(); }, best, any_point);
      break;
    }
    case Kind::cylinder: {  // w_x^2 + w_y^2 - R^2 = 0
      const double A = Nl.x() * Nl.x() + Nl.y() * Nl.y();
      const double B = xl.x() * Nl.x() + xl.y() * Nl.y();
      const double C = xl.x() * xl.x() + xl.y() * xl.y() - V.R * V.R;
      offer_quadratic_roots(
          V, x, N, xl, Nl, A, B, C, [](const Vector3d& w) { return std::hypot(w.x(), w.y()); },
          best, any_point);
      break;
    }
    case Kind::cone: {
      // w_z^2 cos^2 a - (w_x^2 + w_y^2) sin^2 a = 0 (B.23), both nappes. The tangent test
      // n.N -> 0 is (B.24)-(B.25): D = (n_xi . n_cone) / cos a -> 0.
      const double c2 = std::cos(V.alpha) * std::cos(V.alpha);
      const double s2 = std::sin(V.alpha) * std::sin(V.alpha);
      const double A = Nl.z() * Nl.z() * c2 - (Nl.x() * Nl.x() + Nl.y() * Nl.y()) * s2;
      const double B = xl.z() * Nl.z() * c2 - (xl.x() * Nl.x() + xl.y() * Nl.y()) * s2;
      const double C = xl.z() * xl.z() * c2 - (xl.x() * xl.x() + xl.y() * xl.y()) * s2;
      const double tol_z = 1e-12 * (xl.norm() + 1.0);
      offer_quadratic_roots(
          V, x, N, xl, Nl, A, B, C,
          [s2, c2](const Vector3d& w) {
            return Vector3d(s2 * w.x(), s2 * w.y(), c2 * w.z()).norm();
          },
          best, [tol_z](const Vector3d& w) { return w.z() >= -tol_z; });  // upper nappe only
      break;
    }
    case Kind::hyperboloid: {  // a w_x w_y - w_z = 0 (11)
      const double A = V.a * Nl.x() * Nl.y();
      const double B = 0.5 * (V.a * (xl.x() * Nl.y() + xl.y() * Nl.x()) - Nl.z());
      const double C = V.a * xl.x() * xl.y() - xl.z();
      const double a = V.a;
      offer_quadratic_roots(
          V, x, N, xl, Nl, A, B, C,
          [a](const Vector3d& w) { return 0.5 * Vector3d(a * w.y(), a * w.x(), -1.0).norm(); },
          best, any_point);
      break;
    }
    case Kind::torus:
      torus_ray(V, x, N, xl, Nl, best);
      break;
    case Kind::revolution:
      revolution_ray(V, x, N, xl, Nl, opt, best);
      break;
  }
  if (!best.have) {
    ProjectionResult miss;
    miss.status = ProjectionStatus::miss;
    miss.distance = kInf;
    miss.iterations = best.iterations;
    return miss;
  }
  best.r.iterations = best.iterations;
  return best.r;
}

}  // namespace iga
