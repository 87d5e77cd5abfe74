// Ray projections onto the analytic rigid surfaces of [KS15] (ray_project_analytic): plane
// (8)-(9), sphere, cylinder, cone and hyperboloid (quadratics), torus (quartic), surface of
// revolution by Newton (A.2a-e).
// References: [KS15] (see ../shared/paper/EQUATIONS.md): plane (8)-(9); ray projection (2)-(5);
// hyperboloid (11), (22); surface of revolution (A.1)-(A.2); torus (B.16); cone (B.23)-(B.25).
//
// Notation and the decisions shared with the closest point projections: analytic_detail.hpp.
//
// Decisions (the contract is analytic_projection.hpp):
// - Rays: N is normalized first, so xi3 is a length: x + xi3 N/|N| = rho. Ray hits outside the
//   domain are skipped; a double root of the line-surface equation (discriminant within
//   round-off of zero, or |n.N| < 1e-10 predicted from it) is reported as `tangent` (9).
#include "contact/analytic_projection.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/LU>

#include "contact/analytic_detail.hpp"
#include "geometry/knot_vector.hpp"  // GeometryError

namespace iga {

using namespace detail;

namespace {

/// |n.N| below which a ray hit counts as tangent: (8) needs n.N != 0 (9).
constexpr double kTangentTol = 1e-10;

bool angle_u(Kind k) {
  return k == Kind::sphere || k == Kind::cylinder || k == Kind::torus || k == Kind::cone;
}
bool angle_v(Kind k) {
  return k == Kind::torus || k == Kind::revolution;
}

/// Parameters (u, v) of a point w (local coordinates) on, or next to, the surface; angles as
/// atan2 (unmapped), undefined ones (within round_off of the axis) as in analytic_detail.hpp.
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
      // A horn or spindle torus (r >= R): a point nearer the circle of centre -R in its
      // meridian plane (the tube seen from the half-plane phi + pi) is on the part where
      // R + r cos v < 0, at u = phi + pi.
      if (V.r >= V.R &&
          std::abs(std::hypot(s + V.R, w.z()) - V.r) < std::abs(std::hypot(s - V.R, w.z()) - V.r))
        return Vector2d(phi + std::numbers::pi, std::atan2(w.z(), -s - V.R));
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

/// Round-off length of the local coordinates of x + t N (as in closest_point_analytic,
/// analytic_closest_point.cpp).
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
  const View V = view_of(s);
  // A zero or non-finite direction defines no ray: a miss, as for NURBS patches (a batch of
  // rays goes on). Scaled by its largest component first, so that a huge finite direction
  // (|N|^2 overflowing) is still a direction.
  const double nmax = N_in.cwiseAbs().maxCoeff();
  if (!(nmax > 0.0) || !std::isfinite(nmax)) {
    ProjectionResult none;
    none.status = ProjectionStatus::miss;
    none.distance = kInf;
    return none;
  }
  const Vector3d N = (N_in / nmax).normalized();  // unit: xi3 is a length
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
