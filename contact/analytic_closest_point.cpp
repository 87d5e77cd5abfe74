// Closest point projections onto the analytic rigid surfaces of [KS15] (closest_point_analytic,
// hyperboloid_closest_point_ks): closed forms where the paper gives them, short 1-D Newton
// iterations elsewhere.
// References: [KS15] (see ../shared/paper/EQUATIONS.md): plane (8); hyperboloid (11), (13),
// (15)-(22); surface of revolution (A.1); sphere (B.4); cylinder (B.10); torus (B.16); cone
// (B.23); Sect. 2.2 for edges and vertices.
//
// Notation and the decisions shared with the ray projections: analytic_detail.hpp.
//
// Decisions (the contract is analytic_projection.hpp):
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
// - Horn and spindle tori (r >= R, analytic_surfaces.hpp): |x - rho(u, v)|^2 =
//   s^2 + z^2 + a^2 + b^2 - 2 s a cos(u - phi) - 2 z b with a = R + r cos v (of either sign),
//   b = r sin v. Where a >= 0 the best u is the domain's angle nearest phi, where a <= 0 the
//   one nearest phi + pi; for that u the distance grows with the angle along the tube circle
//   from the foot of x's meridian image (s cos(u - phi), z), so over the v's of one sign of a
//   (arcs cut by the axis crossings a = 0, v = +-acos(-R/r)) the minimum is that foot or an
//   end of the arcs (a domain bound or an axis crossing). Every such candidate (u, v) is a
//   point of the face; the nearest is the closest point (closest_horn_spindle_torus).
// - The cone is its upper nappe v >= 0 (domain bounds below 0 are treated as 0), a surface of
//   revolution the radii r >= 0 of its u interval.
#include "contact/analytic_projection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "contact/analytic_detail.hpp"
#include "contact/closest_point.hpp"

namespace iga {

using namespace detail;

namespace {

/// Samples of the 1-D search along the meridian profile.
constexpr int kProfileSamples = 32;

/// Clamp to a linear interval, telling whether the bound became active.
double clamp_to(double t, const Interval& I, bool& active) {
  active = t < I.lo || t > I.hi;
  return std::clamp(t, I.lo, I.hi);
}

/// Largest cosine between x - rho and the free tangents rho_i (the scaled projected gradient
/// (16)); tangents that vanish (poles, apex, axis) carry no condition.
double orthogonality_residual(const SurfaceDerivs& d, const Vector3d& diff, bool u_free,
                              bool v_free) {
  const double dn = diff.stableNorm();
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
/// Within round_off of the axis the angle is undefined (analytic_detail.hpp) and s = 0.
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
    // stableNorm: |x - rho| of a far point (|x| ~ 1e154 and beyond) without the overflow of
    // the squared norm.
    const double dist = diff.stableNorm();
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

/// Horn and spindle tori (r >= R): the candidates of the file header, the nearest one.
ProjectionResult closest_horn_spindle_torus(const View& V, const Vector3d& x, const Vector3d& xl,
                                            double round_off) {
  const double s = std::hypot(xl.x(), xl.y()), z = xl.z();
  const double phi = s > round_off ? std::atan2(xl.y(), xl.x()) : undefined_angle(V.dom.u);
  const AngleFit us[2] = {fit_angle(phi, V.dom.u), fit_angle(phi + std::numbers::pi, V.dom.u)};
  // The v candidates: the foot for each u (fitted into the domain), the domain's bounds and
  // the axis crossings inside it.
  struct Candidate {
    double v;
    bool foot;  // the unconstrained foot on the tube circle
  };
  std::vector<Candidate> vs = {{V.dom.v.lo, false}, {V.dom.v.hi, false}};
  for (const AngleFit& u : us) {
    const double seen = s * std::cos(u.value - phi) - V.R;
    if (std::hypot(seen, z) <= round_off) continue;  // x on the tube's centre: every v ties
    const AngleFit f = fit_angle(std::atan2(z, seen), V.dom.v);
    vs.push_back({f.value, f.inside});
  }
  const double vc = std::acos(std::clamp(-V.R / V.r, -1.0, 1.0));
  for (const double a : {vc, -vc}) {
    const AngleFit f = fit_angle(a, V.dom.v);
    if (f.inside) vs.push_back({f.value, false});
  }
  double best = std::numeric_limits<double>::infinity();
  Vector2d uv(0.0, 0.0);
  bool u_active = false, v_active = false, axis = false;
  for (const AngleFit& u : us)
    for (const Candidate& c : vs) {
      const double d = (x - V.s->derivs(u.value, c.v, 0).S).squaredNorm();
      if (!(d < best)) continue;
      best = d;
      uv = {u.value, c.v};
      u_active = !u.inside;
      v_active = !c.foot && (c.v == V.dom.v.lo || c.v == V.dom.v.hi);
      axis = !c.foot && std::abs(V.R + V.r * std::cos(c.v)) <= 1e-12 * V.r;
    }
  // The axis point (R + r cos v = 0) is a vertex: rho_u vanishes there, as at the cone's apex.
  if (axis) u_active = false;
  return closest_result(V, x, uv, u_active, v_active, axis,
                        std::numeric_limits<double>::quiet_NaN());
}

}  // namespace

ProjectionResult hyperboloid_closest_point_ks(double a, const Vector3d& x_local,
                                              const ProjectionOptions& opt) {
  return hyperboloid_newton(a, x_local, Vector2d(x_local.x(), x_local.y()), opt);  // (20)
}

ProjectionResult closest_point_analytic(const AnalyticSurface& s, const Vector3d& x,
                                        const ProjectionOptions& opt) {
  const View V = view_of(s);
  const Vector3d xl = V.E.transpose() * (x - V.c);
  const double z = xl.z();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  // Length below which x - c carries only round-off (of x - c and of the frame): a point that
  // close to the axis (or the torus' centre circle) has an undefined angle.
  const double round_off = 8.0 * kEps * (x.stableNorm() + V.c.stableNorm());
  switch (V.kind) {
    case Kind::plane: {  // foot = in-plane coordinates, p = z (8)
      bool au = false, av = false;
      const Vector2d uv(clamp_to(xl.x(), V.dom.u, au), clamp_to(xl.y(), V.dom.v, av));
      return closest_result(V, x, uv, au, av, false, z);
    }
    case Kind::sphere: {  // (B.4): u = atan2(y, x), v = asin(z / |x - c|) (as atan2(z, s))
      const Meridian m = meridian_of(xl.x(), xl.y(), V.dom.u, round_off);
      AngleFit lat{std::clamp(0.0, V.dom.v.lo, V.dom.v.hi), true};  // x = c: undefined
      if (xl.stableNorm() > round_off) lat = fit_angle(std::atan2(z, m.s), V.dom.v);
      const double p = xl.stableNorm() - V.R;  // (B.4)
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
      if (V.r >= V.R) return closest_horn_spindle_torus(V, x, xl, round_off);
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

}  // namespace iga
