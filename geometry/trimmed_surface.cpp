// Trimmed faces: the even-odd inside test over banded loop segments (see trimmed_surface.hpp).
#include "geometry/trimmed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/nurbs_surface.hpp"

namespace iga {

namespace {

constexpr int kBands = 256;

std::shared_ptr<const Surface> copy_of(const Surface& s) {
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&s))
    return std::make_shared<NurbsSurface>(*n);
  if (const auto* a = dynamic_cast<const AnalyticSurface*>(&s))
    return std::shared_ptr<const Surface>(a->clone());
  throw GeometryError("a trimmed surface's base must be a NURBS or analytic surface, got a " +
                      s.type_name());
}

double segment_distance(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double L2 = ab.squaredNorm();
  const double t = L2 > 0.0 ? std::clamp((p - a).dot(ab) / L2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Whether segment ab meets the closed rectangle r (Liang-Barsky clipping).
bool segment_meets(const Vector2d& a, const Vector2d& b, const Domain2& r) {
  double t0 = 0.0, t1 = 1.0;
  const Vector2d d = b - a;
  const double p[4] = {-d[0], d[0], -d[1], d[1]};
  const double q[4] = {a[0] - r.u.lo, r.u.hi - a[0], a[1] - r.v.lo, r.v.hi - a[1]};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;  // parallel to this side and outside it
    } else {
      const double t = q[k] / p[k];
      if (p[k] < 0.0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
      if (t0 > t1) return false;
    }
  }
  return true;
}

}  // namespace

TrimmedSurface::TrimmedSurface(const Surface& base, std::vector<Loop> loops,
                               std::vector<NurbsCurve> edges, double deflection)
    : base_(copy_of(base)),
      loops_(std::move(loops)),
      edges_(std::move(edges)),
      deflection_(deflection) {
  if (loops_.empty()) throw GeometryError("a trimmed surface needs at least one loop");
  if (!(deflection_ >= 0.0) || !std::isfinite(deflection_))
    throw GeometryError("trim deflection must be finite and >= 0, got " +
                        std::to_string(deflection_));
  const Domain2 d = base_->domain();
  const double size = std::max(d.u.hi - d.u.lo, d.v.hi - d.v.lo);
  const double tol = std::isfinite(size) ? 1e-9 * size : 0.0;
  box_ = {{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()},
          {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}};
  for (std::size_t k = 0; k < loops_.size(); ++k) {
    if (loops_[k].size() < 3)
      throw GeometryError("trim loop " + std::to_string(k) + " has " +
                          std::to_string(loops_[k].size()) + " points, needs at least 3");
    for (const Vector2d& p : loops_[k]) {
      if (!p.allFinite() || p[0] < d.u.lo - tol || p[0] > d.u.hi + tol || p[1] < d.v.lo - tol ||
          p[1] > d.v.hi + tol)
        throw GeometryError("trim loop " + std::to_string(k) + ": point (" + std::to_string(p[0]) +
                            ", " + std::to_string(p[1]) + ") is outside the base's domain");
      box_.u.lo = std::min(box_.u.lo, p[0]);
      box_.u.hi = std::max(box_.u.hi, p[0]);
      box_.v.lo = std::min(box_.v.lo, p[1]);
      box_.v.hi = std::max(box_.v.hi, p[1]);
    }
  }
  if (!(box_.u.lo < box_.u.hi && box_.v.lo < box_.v.hi))
    throw GeometryError("the trim loops enclose no area");
  set_normal_sign(base_->normal_sign());
  build_bands();
}

void TrimmedSurface::build_bands() {
  v0_ = box_.v.lo;
  dv_ = (box_.v.hi - box_.v.lo) / kBands;
  bands_.assign(kBands, {});
  for (std::size_t k = 0; k < loops_.size(); ++k) {
    const Loop& L = loops_[k];
    for (std::size_t i = 0; i < L.size(); ++i) {
      const Vector2d& a = L[i];
      const Vector2d& b = L[(i + 1) % L.size()];
      const int lo =
          std::clamp(static_cast<int>((std::min(a[1], b[1]) - v0_) / dv_), 0, kBands - 1);
      const int hi =
          std::clamp(static_cast<int>((std::max(a[1], b[1]) - v0_) / dv_), 0, kBands - 1);
      for (int band = lo; band <= hi; ++band)
        bands_[static_cast<std::size_t>(band)].emplace_back(static_cast<int>(k),
                                                            static_cast<int>(i));
    }
  }
}

bool TrimmedSurface::inside(const Vector2d& uv) const {
  if (uv[0] < box_.u.lo || uv[0] > box_.u.hi || uv[1] < box_.v.lo || uv[1] > box_.v.hi)
    return false;
  const int band = std::clamp(static_cast<int>((uv[1] - v0_) / dv_), 0, kBands - 1);
  bool in = false;
  for (const auto& [k, i] : bands_[static_cast<std::size_t>(band)]) {
    const Loop& L = loops_[static_cast<std::size_t>(k)];
    const Vector2d& a = L[static_cast<std::size_t>(i)];
    const Vector2d& b = L[(static_cast<std::size_t>(i) + 1) % L.size()];
    // half-open in v: a vertex on the ray is counted once
    if ((a[1] > uv[1]) != (b[1] > uv[1])) {
      const double u_cross = a[0] + (uv[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (u_cross > uv[0]) in = !in;
    }
  }
  return in || distance_to_loops(uv) <= 1e-12 * (box_.u.hi - box_.u.lo + box_.v.hi - box_.v.lo);
}

double TrimmedSurface::distance_to_loops(const Vector2d& uv) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Loop& L : loops_)
    for (std::size_t i = 0; i < L.size(); ++i)
      best = std::min(best, segment_distance(uv, L[i], L[(i + 1) % L.size()]));
  return best;
}

bool TrimmedSurface::meets(const Domain2& r) const {
  if (r.u.hi < box_.u.lo || r.u.lo > box_.u.hi || r.v.hi < box_.v.lo || r.v.lo > box_.v.hi)
    return false;
  for (const Loop& L : loops_)
    for (std::size_t i = 0; i < L.size(); ++i)
      if (segment_meets(L[i], L[(i + 1) % L.size()], r)) return true;
  // No loop crosses r: it is wholly inside or wholly outside.
  return inside({0.5 * (r.u.lo + r.u.hi), 0.5 * (r.v.lo + r.v.hi)});
}

SurfaceDerivs TrimmedSurface::derivs(double u, double v, int order) const {
  return base_->derivs(u, v, order);
}

Domain2 TrimmedSurface::domain() const {
  return box_;
}

bool TrimmedSurface::operator==(const TrimmedSurface& o) const {
  return same_surface(*base_, *o.base_) && loops_ == o.loops_ && edges_ == o.edges_ &&
         deflection_ == o.deflection_ && normal_sign() == o.normal_sign();
}

bool same_surface(const Surface& a, const Surface& b) {
  if (a.type_name() != b.type_name()) return false;
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&a))
    return *n == dynamic_cast<const NurbsSurface&>(b);
  if (const auto* t = dynamic_cast<const TrimmedSurface*>(&a))
    return *t == dynamic_cast<const TrimmedSurface&>(b);
  bool same = false;
  visit_analytic(dynamic_cast<const AnalyticSurface&>(a), [&](const auto& x) {
    same = x == dynamic_cast<const std::decay_t<decltype(x)>&>(b);
  });
  return same;
}

}  // namespace iga
