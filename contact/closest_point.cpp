// Closest point projection onto surfaces and curves ([KS15] eqs. 10-18, Sect. 2.2).
#include "contact/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/bounded_newton.hpp"
#include "geometry/differential_geometry.hpp"

namespace iga {

const char* to_string(ProjectionStatus s) {
  switch (s) {
    case ProjectionStatus::interior: return "interior";
    case ProjectionStatus::edge: return "edge";
    case ProjectionStatus::vertex: return "vertex";
    case ProjectionStatus::not_converged: return "not_converged";
    case ProjectionStatus::miss: return "miss";
    case ProjectionStatus::tangent: return "tangent";
    case ProjectionStatus::far: return "far";
  }
  return "unknown";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTiny = 1e-300;

// (12), (16), (17) at (u, v): f = |r|^2/2, g = -[rho_1.r, rho_2.r], H = [a_ij - rho_ij.r].
// L: a length of the patch, so that the residual |g_i| / (|rho_i| max(|r|, L)) is the foot
// point's tangential error relative to the model size near the surface and the cosine of the
// angle between r and rho_i far from it (that cosine alone is ill-conditioned as |r| -> 0).
detail::LocalModel<2> surface_model(const SurfaceDerivs& d, const Vector3d& x,
                                    const Vector2d& widths, int order) {
  const Vector3d r = x - d.S;
  detail::LocalModel<2> m;
  m.f = 0.5 * r.squaredNorm();
  m.g << -d.Su.dot(r), -d.Sv.dot(r);  // (16)
  m.has_hessian = order >= 2;
  if (m.has_hessian)
    m.H << d.Su.dot(d.Su) - d.Suu.dot(r), d.Su.dot(d.Sv) - d.Suv.dot(r),  // (17)
        d.Su.dot(d.Sv) - d.Suv.dot(r), d.Sv.dot(d.Sv) - d.Svv.dot(r);
  const double su = d.Su.norm(), sv = d.Sv.norm();
  const double L = su * widths[0] + sv * widths[1];
  const double rn = std::max(r.norm(), L);
  m.scale << std::max(su * rn, kTiny), std::max(sv * rn, kTiny);
  return m;
}

// Foot point, normal, signed distance and status from the final parameters; `last` holds the
// derivatives of the last evaluation, at `last_uv` (reused when that is the final point).
ProjectionResult finish(const Surface& s, const Vector3d& x, const Vector2d& uv,
                        const detail::NewtonOutcome<2>& o, const SurfaceDerivs& last,
                        const Vector2d& last_uv) {
  ProjectionResult r;
  r.uv = uv;
  const SurfaceDerivs d = last_uv == uv ? last : s.derivs(uv[0], uv[1], 1);
  r.point = d.S;
  const Vector3d c = d.Su.cross(d.Sv);
  const double cn = c.norm();
  r.normal = cn > 0 ? Vector3d(s.normal_sign() * c / cn) : Vector3d::Zero();
  const Vector3d diff = x - d.S;
  const double dist = diff.norm();
  r.distance = diff.dot(r.normal) < 0 ? -dist : dist;  // (10): p along n
  r.iterations = o.iterations;
  r.residual = o.residual;
  if (!o.converged)
    r.status = ProjectionStatus::not_converged;
  else
    r.status = o.at_bound == 0   ? ProjectionStatus::interior
               : o.at_bound == 1 ? ProjectionStatus::edge
                                 : ProjectionStatus::vertex;
  return r;
}

detail::Box<2> box_of(const Surface& s, const Domain2& b) {
  detail::Box<2> box;
  box.lo << b.u.lo, b.v.lo;
  box.hi << b.u.hi, b.v.hi;
  // A closed direction wraps only when the box is the whole (closed) domain.
  const Domain2 dom = s.domain();
  box.wrap[0] = s.closed_u() && b.u == dom.u;
  box.wrap[1] = s.closed_v() && b.v == dom.v;
  return box;
}

double box_distance2(const Box3& b, const Vector3d& x) {
  const Vector3d d = (b.lo - x).cwiseMax(x - b.hi).cwiseMax(0.0);
  return d.squaredNorm();
}

}  // namespace

ProjectionResult closest_point_local(const Surface& s, const Vector3d& x, const Vector2d& start,
                                     const Domain2& bounds, const ProjectionOptions& opt) {
  const detail::Box<2> box = box_of(s, bounds);
  // Parameter widths of the patch for the residual's length scale (1 where unbounded).
  const Domain2 dom = s.domain();
  const Vector2d widths(std::isfinite(dom.u.hi - dom.u.lo) ? dom.u.hi - dom.u.lo : 1.0,
                        std::isfinite(dom.v.hi - dom.v.lo) ? dom.v.hi - dom.v.lo : 1.0);
  SurfaceDerivs last;
  Vector2d last_uv(NAN, NAN);
  const detail::NewtonOutcome<2> o = detail::bounded_newton<2>(
      [&](const Vector2d& t, int order) {
        last = s.derivs(t[0], t[1], order);
        last_uv = t;
        return surface_model(last, x, widths, order);
      },
      start, box, opt);
  return finish(s, x, o.t, o, last, last_uv);
}

ProjectionResult closest_point_local(const Surface& s, const Vector3d& x, const Vector2d& start,
                                     const ProjectionOptions& opt) {
  return closest_point_local(s, x, start, s.domain(), opt);
}

ProjectionStatus boundary_status(const Surface& s, const Vector2d& uv) {
  const Domain2 dom = s.domain();
  int at = 0;
  at += !s.closed_u() && (uv[0] <= dom.u.lo || uv[0] >= dom.u.hi);
  at += !s.closed_v() && (uv[1] <= dom.v.lo || uv[1] >= dom.v.hi);
  return at == 0 ? ProjectionStatus::interior
         : at == 1 ? ProjectionStatus::edge
                   : ProjectionStatus::vertex;
}

// ---------------------------------------------------------------------------------------------
// PatchProjector

PatchProjector::PatchProjector(const NurbsSurface& s, int samples_per_dir)
    : s_(s), elements_(bezier_extract(s)), samples_per_dir_(std::clamp(samples_per_dir, 2, 8)) {
  const int n = samples_per_dir_;
  boxes_.reserve(elements_.size());
  samples_.resize(elements_.size());
  hull_offset_.push_back(0);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const BezierPatch& b = elements_[e];
    for (const Vector4d& q : b.pw) hull_.push_back(q.head<3>() / q.w());
    hull_offset_.push_back(hull_.size());
    boxes_.push_back(bounding_box(b));
    box_.extend(boxes_.back().lo);
    box_.extend(boxes_.back().hi);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vector2d uv(b.range.u.lo + (b.range.u.hi - b.range.u.lo) * i / (n - 1),
                          b.range.v.lo + (b.range.v.hi - b.range.v.lo) * j / (n - 1));
        samples_[e].push_back({uv, s_.point(uv[0], uv[1])});
      }
  }
}

ProjectionResult PatchProjector::project_within(const Vector3d& x, double max_distance,
                                                const ProjectionOptions& opt) const {
  return search(x, nullptr, boxes_.size(), max_distance, opt);
}

ProjectionResult PatchProjector::project_among(const Vector3d& x, std::span<const int> ids,
                                               double max_distance,
                                               const ProjectionOptions& opt) const {
  return search(x, ids.data(), ids.size(), max_distance, opt);
}

ProjectionResult PatchProjector::search(const Vector3d& x, const int* ids, std::size_t n_ids,
                                        double max_distance, const ProjectionOptions& opt) const {
  // Branch and bound over the Bezier elements (all, or the ids given). Lower bound: distance to
  // the element's box (convex hull property); upper bound: the best foot point so far. Each
  // visited element is searched by Newtons restricted to it, seeded at its sample minima.
  thread_local std::vector<std::pair<double, int>> order;
  order.clear();
  const double limit2 = max_distance < kInf ? max_distance * max_distance : kInf;
  double ub2 = limit2;
  for (std::size_t k = 0; k < n_ids; ++k) {
    const int e = ids ? ids[k] : static_cast<int>(k);
    const double lb2 = box_distance2(boxes_[static_cast<std::size_t>(e)], x);
    if (lb2 <= limit2) order.emplace_back(lb2, e);
  }
  ProjectionResult best;
  best.status = ProjectionStatus::far;
  best.distance = kInf;
  if (order.empty()) return best;
  // A first upper bound from the samples of the most promising element.
  {
    const auto first = std::min_element(order.begin(), order.end());
    for (const Sample& smp : samples_[static_cast<std::size_t>(first->second)])
      ub2 = std::min(ub2, (smp.x - x).squaredNorm());
    ub2 *= (1.0 + 1e-12);
  }
  std::sort(order.begin(), order.end());
  double best2 = kInf;
  int iterations = 0, best_element = 0;
  for (const auto& [lb2, e] : order) {
    if (lb2 > std::min(ub2, best2)) break;
    // A second lower bound from the convex hull of the element's control points: for the
    // direction d from the element's centre towards x, |x - S| >= d.x - max_i d.P_i. Tight
    // for far points, where the box bound is loose.
    {
      const Box3& b = boxes_[static_cast<std::size_t>(e)];
      Vector3d dir = x - 0.5 * (b.lo + b.hi);
      const double len = dir.norm();
      if (len > 0.0) {
        dir /= len;
        double support = -kInf;
        const std::size_t first = hull_offset_[static_cast<std::size_t>(e)];
        const std::size_t last = hull_offset_[static_cast<std::size_t>(e) + 1];
        for (std::size_t k = first; k < last; ++k) support = std::max(support, dir.dot(hull_[k]));
        const double lb_hull = dir.dot(x) - support;
        if (lb_hull > 0.0 && lb_hull * lb_hull > std::min(ub2, best2)) continue;
      }
    }
    // Seeds: the discrete local minima of the distance over the element's sample grid (far
    // from the surface one element can hold several local minima, e.g. on an edge and near
    // it), nearest first, at most kMaxSeeds.
    const std::vector<Sample>& smp = samples_[static_cast<std::size_t>(e)];
    const int n = samples_per_dir_;
    double d2s[kMaxSamples];
    for (int k = 0; k < n * n; ++k) d2s[k] = (smp[static_cast<std::size_t>(k)].x - x).squaredNorm();
    constexpr int kMaxSeeds = 3;
    std::pair<double, int> seeds[kMaxSeeds];
    int n_seeds = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double d = d2s[i + n * j];
        bool is_min = true;
        for (int dj = -1; dj <= 1 && is_min; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int ii = i + di, jj = j + dj;
            if ((di == 0 && dj == 0) || ii < 0 || jj < 0 || ii >= n || jj >= n) continue;
            if (d2s[ii + n * jj] < d) {
              is_min = false;
              break;
            }
          }
        if (!is_min) continue;
        // keep the kMaxSeeds nearest minima, sorted
        std::pair<double, int> cand{d, i + n * j};
        for (int q = 0; q < n_seeds; ++q)
          if (cand < seeds[q]) std::swap(cand, seeds[q]);
        if (n_seeds < kMaxSeeds) seeds[n_seeds++] = cand;
      }
    const Domain2& range = elements_[static_cast<std::size_t>(e)].range;
    for (int q = 0; q < n_seeds; ++q) {
      const Vector2d& start = smp[static_cast<std::size_t>(seeds[q].second)].uv;
      const ProjectionResult r = closest_point_local(s_, x, start, range, opt);
      iterations += r.iterations;
      const double d2 = (r.point - x).squaredNorm();
      if (d2 < best2) {
        best2 = d2;
        best = r;
        best_element = e;
      }
    }
  }
  if (best2 == kInf) return best;
  // The element's answer is a local minimum of the patch unless it rests on an element bound
  // inside the patch or on a seam (the bound of a closed direction); then polish on the whole
  // patch, which also wraps across the seam.
  const Domain2& er = elements_[static_cast<std::size_t>(best_element)].range;
  const Domain2 dom = s_.domain();
  const bool cu = s_.closed_u(), cv = s_.closed_v();
  const bool inner_bound = (best.uv[0] <= er.u.lo && (er.u.lo > dom.u.lo || cu)) ||
                           (best.uv[0] >= er.u.hi && (er.u.hi < dom.u.hi || cu)) ||
                           (best.uv[1] <= er.v.lo && (er.v.lo > dom.v.lo || cv)) ||
                           (best.uv[1] >= er.v.hi && (er.v.hi < dom.v.hi || cv));
  if (!inner_bound && found(best.status)) {
    best.iterations = iterations;
    best.status = boundary_status(s_, best.uv);
    return best;
  }
  ProjectionResult r = closest_point_local(s_, x, best.uv, opt);
  r.iterations += iterations;
  if ((r.point - x).squaredNorm() > best2 * (1.0 + 1e-12) + 1e-300) {
    // The polish can only lower the distance; keep the element's answer if it did not.
    best.iterations = r.iterations;
    return best;
  }
  return r;
}

ProjectionResult PatchProjector::project(const Vector3d& x, const ProjectionOptions& opt) const {
  return project_within(x, kInf, opt);
}

ProjectionResult PatchProjector::project(const Vector3d& x, const Vector2d& guess,
                                         const ProjectionOptions& opt) const {
  ProjectionResult r = closest_point_local(s_, x, guess, opt);
  if (r.status == ProjectionStatus::not_converged) {
    const int used = r.iterations;
    r = project(x, opt);
    r.iterations += used;
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Curves

namespace {

detail::LocalModel<1> curve_model(const NurbsCurve& c, const Vector3d& x, double u,
                                  double width) {
  const CurveDerivs d = c.derivs(u, 2);
  const Vector3d r = x - d.d[0];
  detail::LocalModel<1> m;
  m.f = 0.5 * r.squaredNorm();
  m.g[0] = -d.d[1].dot(r);                                 // (16), one parameter
  m.H(0, 0) = d.d[1].squaredNorm() - d.d[2].dot(r);        // (17)
  const double sp = d.d[1].norm();
  m.scale[0] = std::max(sp * std::max(r.norm(), sp * width), kTiny);  // as for surfaces
  return m;
}

ProjectionResult curve_local(const NurbsCurve& c, const Vector3d& x, double u0, Interval range,
                             const ProjectionOptions& opt) {
  detail::Box<1> box;
  box.lo[0] = range.lo;
  box.hi[0] = range.hi;
  Eigen::Matrix<double, 1, 1> t0;
  t0[0] = u0;
  const detail::NewtonOutcome<1> o = detail::bounded_newton<1>(
      [&](const Eigen::Matrix<double, 1, 1>& t, int) {
        return curve_model(c, x, t[0], c.domain().hi - c.domain().lo);
      }, t0, box, opt);
  ProjectionResult r;
  r.uv = Vector2d(o.t[0], 0.0);
  r.point = c.point(o.t[0]);
  r.distance = (x - r.point).norm();  // a curve has no normal: unsigned
  r.iterations = o.iterations;
  r.residual = o.residual;
  const Interval dom = c.domain();
  const bool at_end = o.t[0] <= dom.lo || o.t[0] >= dom.hi;
  r.status = !o.converged ? ProjectionStatus::not_converged
             : at_end     ? ProjectionStatus::vertex
                          : ProjectionStatus::interior;
  return r;
}

}  // namespace

ProjectionResult closest_point_local(const NurbsCurve& c, const Vector3d& x, double u0,
                                     const ProjectionOptions& opt) {
  return curve_local(c, x, u0, c.domain(), opt);
}

ProjectionResult closest_point(const NurbsCurve& c, const Vector3d& x,
                               const ProjectionOptions& opt) {
  // Branch and bound over Bezier segments, as for patches (segment boxes bound from below).
  const std::vector<BezierSegment> segs = bezier_extract(c);
  std::vector<std::pair<double, int>> order;
  for (std::size_t e = 0; e < segs.size(); ++e)
    order.emplace_back(box_distance2(bounding_box(segs[e]), x), static_cast<int>(e));
  std::sort(order.begin(), order.end());
  ProjectionResult best;
  double best2 = kInf;
  int iterations = 0;
  for (const auto& [lb2, e] : order) {
    if (lb2 > best2) break;
    const Interval range = segs[static_cast<std::size_t>(e)].range;
    double seed = range.lo, seed2 = kInf;
    for (int k = 0; k <= 4; ++k) {
      const double u = range.lo + (range.hi - range.lo) * k / 4.0;
      const double d2 = (c.point(u) - x).squaredNorm();
      if (d2 < seed2) seed2 = d2, seed = u;
    }
    const ProjectionResult r = curve_local(c, x, seed, range, opt);
    iterations += r.iterations;
    const double d2 = (r.point - x).squaredNorm();
    if (d2 < best2) best2 = d2, best = r;
  }
  ProjectionResult r = curve_local(c, x, best.uv[0], c.domain(), opt);
  r.iterations += iterations;
  return (r.point - x).squaredNorm() <= best2 * (1.0 + 1e-12) + 1e-300 ? r : best;
}

}  // namespace iga
