// Ray projection onto surfaces ([KS15] Sect. 2.1, eqs. 2-5, 9).
#include "contact/ray_projection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace iga {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct RayBox {
  Domain2 bounds;
  bool wrap_u = false, wrap_v = false;
};

double wrap_into(double t, const Interval& I) {
  const double period = I.hi - I.lo;
  double r = std::fmod(t - I.lo, period);
  if (r < 0) r += period;
  return I.lo + r;
}

// Newton (5) on (alpha1, alpha2, xi3) within the box. Statuses: interior/edge/vertex at a hit,
// tangent where n.N -> 0 (9), miss where the iterate leaves the box or does not converge.
ProjectionResult ray_newton(const Surface& s, const Vector3d& x, const Vector3d& N, Vector2d uv,
                            double xi, const RayBox& box, const ProjectionOptions& opt) {
  const Domain2& B = box.bounds;
  auto place = [&](Vector2d& t) {
    t[0] = box.wrap_u ? wrap_into(t[0], B.u) : std::clamp(t[0], B.u.lo, B.u.hi);
    t[1] = box.wrap_v ? wrap_into(t[1], B.v) : std::clamp(t[1], B.v.lo, B.v.hi);
  };
  place(uv);
  ProjectionResult r;
  r.status = ProjectionStatus::miss;
  int pushed_out = 0;
  bool converged_step = false;  // the last Newton step was at round-off
  for (int it = 0; it <= opt.max_iterations; ++it) {
    const SurfaceDerivs d = s.derivs(uv[0], uv[1], 1);
    const Vector3d F = d.S - x - xi * N;  // (3)
    const double scale = std::max({d.Su.norm(), d.Sv.norm(), 1e-300});
    Matrix3d J;
    J.col(0) = d.Su;  // (4)
    J.col(1) = d.Sv;
    J.col(2) = -N;
    const Vector3d nrm = d.Su.cross(d.Sv);
    const double cos_nN = std::abs(nrm.dot(N)) / std::max(nrm.norm(), 1e-300);
    // Converged when the residual is at round-off relative to the local size of the patch.
    const double res = F.norm() / (scale * (1.0 + std::abs(uv[0]) + std::abs(uv[1])));
    r.iterations = it;
    r.residual = res;
    if (res <= opt.tol_residual || converged_step) {
      r.uv = uv;
      r.point = d.S;
      r.normal = s.normal_sign() * nrm / std::max(nrm.norm(), 1e-300);
      r.distance = xi;
      if (cos_nN < 1e-10) {
        r.status = ProjectionStatus::tangent;  // (9): n.N -> 0
      } else {
        r.status = boundary_status(s, uv);
      }
      return r;
    }
    if (cos_nN < 1e-12) {
      r.status = ProjectionStatus::tangent;
      return r;
    }
    const Vector3d delta = -J.partialPivLu().solve(F);  // (5)
    if (!delta.allFinite()) {
      r.status = ProjectionStatus::tangent;
      return r;
    }
    Vector2d next = uv + delta.head<2>();
    const Vector2d unclamped = next;
    place(next);
    // The hit lies outside the box when Newton keeps pushing across a (non-wrapping) bound.
    const bool out =
        (!box.wrap_u && unclamped[0] != next[0]) || (!box.wrap_v && unclamped[1] != next[1]);
    pushed_out = out ? pushed_out + 1 : 0;
    if (pushed_out >= 3) return r;  // miss
    converged_step = !out && std::abs(delta[0]) <= opt.tol_step * (1.0 + std::abs(uv[0])) &&
                     std::abs(delta[1]) <= opt.tol_step * (1.0 + std::abs(uv[1]));
    uv = next;
    xi += delta[2];
  }
  return r;  // miss: no convergence within the iteration limit
}

RayBox full_box(const Surface& s) {
  return {s.domain(), s.closed_u(), s.closed_v()};
}

// Slab test of the line x + t N against a box: the interval [t0, t1] inside it (empty if t0 > t1).
bool line_box(const Box3& b, const Vector3d& x, const Vector3d& N, double pad, double& t0,
              double& t1) {
  t0 = -kInf;
  t1 = kInf;
  for (int k = 0; k < 3; ++k) {
    const double lo = b.lo[k] - pad, hi = b.hi[k] + pad;
    if (std::abs(N[k]) < 1e-300) {
      if (x[k] < lo || x[k] > hi) return false;
      continue;
    }
    double a = (lo - x[k]) / N[k], c = (hi - x[k]) / N[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

ProjectionResult ray_project_local(const Surface& s, const Vector3d& x, const Vector3d& N,
                                   const Vector2d& start, double xi3_start,
                                   const ProjectionOptions& opt) {
  const double len = N.norm();
  if (!(len > 0.0)) {
    ProjectionResult r;
    r.status = ProjectionStatus::miss;
    return r;
  }
  return ray_newton(s, x, N / len, start, xi3_start * len, full_box(s), opt);
}

ProjectionResult ray_project(const PatchProjector& patch, const Vector3d& x, const Vector3d& N,
                             const ProjectionOptions& opt) {
  ProjectionResult best;
  best.status = ProjectionStatus::miss;
  const double len = N.norm();
  if (!(len > 0.0)) return best;
  const Vector3d n = N / len;
  const NurbsSurface& s = patch.surface();
  const std::vector<Box3>& boxes = patch.element_boxes();
  const Vector3d diag = patch.box().hi - patch.box().lo;
  const double pad = 1e-9 * diag.norm();
  // Candidates: elements whose box the line crosses, with a lower bound on |xi3| in each.
  thread_local std::vector<std::pair<double, int>> order;
  order.clear();
  for (std::size_t e = 0; e < boxes.size(); ++e) {
    double t0, t1;
    if (!line_box(boxes[e], x, n, pad, t0, t1)) continue;
    const double lb = (t0 <= 0.0 && t1 >= 0.0) ? 0.0 : std::min(std::abs(t0), std::abs(t1));
    order.emplace_back(lb, static_cast<int>(e));
  }
  std::sort(order.begin(), order.end());
  double best_abs = kInf;
  int iterations = 0;
  bool tangent_seen = false;
  for (const auto& [lb, e] : order) {
    if (lb > best_abs) break;
    const BezierPatch& el = patch.elements()[static_cast<std::size_t>(e)];
    // Seed: the element's sample nearest to the line (a 4 x 4 grid).
    Vector2d seed =
        Vector2d(0.5 * (el.range.u.lo + el.range.u.hi), 0.5 * (el.range.v.lo + el.range.v.hi));
    double seed_d = kInf, seed_xi = 0.0;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const Vector2d uv(el.range.u.lo + (el.range.u.hi - el.range.u.lo) * i / 3.0,
                          el.range.v.lo + (el.range.v.hi - el.range.v.lo) * j / 3.0);
        const Vector3d q = s.point(uv[0], uv[1]) - x;
        const double dl = q.cross(n).squaredNorm();
        if (dl < seed_d) seed_d = dl, seed = uv, seed_xi = q.dot(n);
      }
    const ProjectionResult r = ray_newton(s, x, n, seed, seed_xi, {el.range, false, false}, opt);
    iterations += r.iterations;
    if (r.status == ProjectionStatus::tangent) tangent_seen = true;
    if (found(r.status) && std::abs(r.distance) < best_abs) {
      best_abs = std::abs(r.distance);
      best = r;
    }
  }
  if (!found(best.status) && tangent_seen) best.status = ProjectionStatus::tangent;
  // Status relative to the patch (an element bound inside the patch is no edge).
  if (found(best.status)) best.status = boundary_status(s, best.uv);
  best.iterations = iterations;
  return best;
}

}  // namespace iga
