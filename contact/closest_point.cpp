// Closest point projection onto surfaces and curves ([KS15] eqs. 10-18, Sect. 2.2).
#include "contact/closest_point.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>

#include "contact/bounded_newton.hpp"
#include "contact/patch_bounds.hpp"
#include "geometry/differential_geometry.hpp"

namespace iga {

const char* to_string(ProjectionStatus s) {
  switch (s) {
    case ProjectionStatus::interior:
      return "interior";
    case ProjectionStatus::edge:
      return "edge";
    case ProjectionStatus::vertex:
      return "vertex";
    case ProjectionStatus::not_converged:
      return "not_converged";
    case ProjectionStatus::miss:
      return "miss";
    case ProjectionStatus::tangent:
      return "tangent";
    case ProjectionStatus::far:
      return "far";
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
  return at == 0   ? ProjectionStatus::interior
         : at == 1 ? ProjectionStatus::edge
                   : ProjectionStatus::vertex;
}

// ---------------------------------------------------------------------------------------------
// PatchProjector

PatchProjector::PatchProjector(const NurbsSurface& s, int samples_per_dir)
    : s_(s), bez_(s), samples_per_dir_(std::clamp(samples_per_dir, 2, 8)) {
  const int n = samples_per_dir_;
  boxes_.reserve(bez_.elements().size());
  samples_.resize(bez_.elements().size());
  hull_offset_.push_back(0);
  for (std::size_t e = 0; e < bez_.elements().size(); ++e) {
    const BezierPatch& b = bez_.elements()[e];
    for (const Vector4d& q : b.pw) hull_.push_back(q.head<3>() / q.w());
    hull_offset_.push_back(hull_.size());
    boxes_.push_back(bounding_box(b));
    box_.extend(boxes_.back().lo);
    box_.extend(boxes_.back().hi);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vector2d uv(b.range.u.lo + (b.range.u.hi - b.range.u.lo) * i / (n - 1),
                          b.range.v.lo + (b.range.v.hi - b.range.v.lo) * j / (n - 1));
        const SurfaceDerivs d = s_.derivs(uv[0], uv[1], 1);
        samples_[e].push_back({uv, d.S, d.Su, d.Sv});
      }
  }
  // The inner element borders where the patch may have a kink: knots of multiplicity >= the
  // degree (C0 there). A seam is never left to the other side either (shared_bound).
  const KnotVector* kv[2] = {&s_.knots_u(), &s_.knots_v()};
  const Domain2 dom = s_.domain();
  for (int dir = 0; dir < 2; ++dir) {
    const Interval& d = dir == 0 ? dom.u : dom.v;
    for (const double b : kv[dir]->breaks())
      if (b > d.lo && b < d.hi && kv[dir]->multiplicity(b) >= kv[dir]->degree())
        kinks_[dir].push_back(b);
  }
  const std::size_t n_el = boxes_.size(), n_s = static_cast<std::size_t>(n * n);
  box_coords_.resize(6 * n_el);
  sample_coords_.resize(3 * n_el * n_s);
  for (std::size_t e = 0; e < n_el; ++e)
    for (int c = 0; c < 3; ++c) {
      box_coords_[static_cast<std::size_t>(c) * n_el + e] = boxes_[e].lo[c];
      box_coords_[static_cast<std::size_t>(c + 3) * n_el + e] = boxes_[e].hi[c];
      for (std::size_t k = 0; k < n_s; ++k)
        sample_coords_[(3 * e + static_cast<std::size_t>(c)) * n_s + k] = samples_[e][k].x[c];
    }
  int degree = 0;
  for (const BezierPatch& b : bez_.elements()) degree = std::max({degree, b.degree_u, b.degree_v});
  if (degree <= detail::kMaxNetDegree)
    build_tree(tree_);
  else if (degree <= detail::kMaxHighNetDegree)
    build_tree(high_tree_);
}

int PatchProjector::element_of(const Vector2d& uv) const {
  return bez_.element_of(uv[0], uv[1]);
}

// Two elements at a time (SSE2, on every x86-64); the distances are those of box_distance2
// below (the same operations).
void PatchProjector::box_distances2(const Vector3d& x, double* d2) const {
  const std::size_t n = boxes_.size();
  const double* b = box_coords_.data();
  std::size_t e = 0;
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd();
  const __m128d xs[3] = {_mm_set1_pd(x[0]), _mm_set1_pd(x[1]), _mm_set1_pd(x[2])};
  for (; e + 2 <= n; e += 2) {
    __m128d sum = zero;
    for (std::size_t c = 0; c < 3; ++c) {
      const __m128d lo = _mm_loadu_pd(b + c * n + e), hi = _mm_loadu_pd(b + (c + 3) * n + e);
      const __m128d d = _mm_max_pd(_mm_max_pd(_mm_sub_pd(lo, xs[c]), _mm_sub_pd(xs[c], hi)), zero);
      sum = c == 0 ? _mm_mul_pd(d, d) : _mm_add_pd(sum, _mm_mul_pd(d, d));
    }
    _mm_storeu_pd(d2 + e, sum);
  }
#endif
  for (; e < n; ++e) {
    double sum = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = std::max(std::max(b[c * n + e] - x[static_cast<Eigen::Index>(c)],
                                         x[static_cast<Eigen::Index>(c)] - b[(c + 3) * n + e]),
                                0.0);
      sum = c == 0 ? d * d : sum + d * d;
    }
    d2[e] = sum;
  }
}

Vector2d PatchProjector::seed_from(const Sample& s, int e, const Vector3d& x) const {
  // Not on a patch with creases: the step may carry the start across one, where the Newton,
  // one side's derivatives on the crease, can stop short along it (seen: OCC17026-1.igs face 3,
  // a foot on the crease 7.6e-6 h from OpenCASCADE's at the same distance).
  if (!kinks_[0].empty() || !kinks_[1].empty()) return s.uv;
  const Vector3d r = x - s.x;
  const double a = s.xu.dot(s.xu), b = s.xu.dot(s.xv), c = s.xv.dot(s.xv);
  const double det = a * c - b * b;
  if (!(det > 1e-12 * a * c)) return s.uv;  // a degenerate tangent plane (a pole)
  const double gu = s.xu.dot(r), gv = s.xv.dot(r);
  const Vector2d uv = s.uv + Vector2d(c * gu - b * gv, a * gv - b * gu) / det;
  const Domain2& er = bez_.elements()[static_cast<std::size_t>(e)].range;
  const Domain2 dom = s_.domain();
  const bool near = std::abs(uv[0] - s.uv[0]) <= er.u.hi - er.u.lo &&
                    std::abs(uv[1] - s.uv[1]) <= er.v.hi - er.v.lo;
  const bool inside =
      uv[0] >= dom.u.lo && uv[0] <= dom.u.hi && uv[1] >= dom.v.lo && uv[1] <= dom.v.hi;
  return near && inside ? uv : s.uv;
}

namespace {
// d2[k] = |x - sample k|^2 for the n samples of an element, their coordinates as three arrays
// c[0 .. n), c[n .. 2n), c[2n .. 3n) (PatchProjector::sample_coords_): two at a time (SSE2).
void sample_distances2(const double* c, int n, const Vector3d& x, double* d2) {
  int k = 0;
#if defined(__SSE2__)
  const __m128d x0 = _mm_set1_pd(x[0]), x1 = _mm_set1_pd(x[1]), x2 = _mm_set1_pd(x[2]);
  for (; k + 2 <= n; k += 2) {
    const __m128d dx = _mm_sub_pd(_mm_loadu_pd(c + k), x0);
    const __m128d dy = _mm_sub_pd(_mm_loadu_pd(c + n + k), x1);
    const __m128d dz = _mm_sub_pd(_mm_loadu_pd(c + 2 * n + k), x2);
    _mm_storeu_pd(
        d2 + k, _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz)));
  }
#endif
  for (; k < n; ++k) {
    const double dx = c[k] - x[0], dy = c[n + k] - x[1], dz = c[2 * n + k] - x[2];
    d2[k] = dx * dx + dy * dy + dz * dz;
  }
}

// The first index of the smallest of d[0 .. n), and that value: two lanes at a time, each
// keeping its first minimum, then the lower lane by value and index. n >= 1, and no NaN in d
// (a NaN would hide the values after it in its lane; the distances here are NaN only all
// together, for a non-finite x, and then the first is returned).
int first_minimum(const double* d, int n, double& value) {
  int k = 1, best = 0;
  value = d[0];
#if defined(__SSE2__)
  if (n >= 4) {
    __m128d bv = _mm_loadu_pd(d), bi = _mm_set_pd(1.0, 0.0), idx = bi;
    const __m128d two = _mm_set1_pd(2.0);
    for (k = 2; k + 2 <= n; k += 2) {
      const __m128d v = _mm_loadu_pd(d + k);
      idx = _mm_add_pd(idx, two);
      const __m128d m = _mm_cmplt_pd(v, bv);
      bv = _mm_or_pd(_mm_and_pd(m, v), _mm_andnot_pd(m, bv));
      bi = _mm_or_pd(_mm_and_pd(m, idx), _mm_andnot_pd(m, bi));
    }
    double v2[2], i2[2];
    _mm_storeu_pd(v2, bv);
    _mm_storeu_pd(i2, bi);
    const bool second = v2[1] < v2[0] || (v2[1] == v2[0] && i2[1] < i2[0]);
    value = v2[second ? 1 : 0];
    best = static_cast<int>(i2[second ? 1 : 0]);
  }
#endif
  for (; k < n; ++k)
    if (d[k] < value) value = d[k], best = k;
  return best;
}
}  // namespace

int PatchProjector::nearest_sample(int e, const Vector3d& x) const {
  const int n_s = samples_per_dir_ * samples_per_dir_;
  double d2[kMaxSamples];
  sample_distances2(sample_coords_.data() + static_cast<std::size_t>(3 * e * n_s), n_s, x, d2);
  double d2_min = 0.0;
  return first_minimum(d2, n_s, d2_min);
}

namespace {

// Whether uv lies in the parameter rectangle r.
bool inside(const Domain2& r, const Vector2d& uv) {
  return uv[0] >= r.u.lo && uv[0] <= r.u.hi && uv[1] >= r.v.lo && uv[1] <= r.v.hi;
}

// Whether the parameter rectangle `inner` lies in `outer`.
bool within(const Domain2& inner, const Domain2& outer) {
  return inner.u.lo >= outer.u.lo && inner.u.hi <= outer.u.hi && inner.v.lo >= outer.v.lo &&
         inner.v.hi <= outer.v.hi;
}

// The control points of a node, projected, and their box.
template <class N>
void finish_node(N& n) {
  n.box = Box3{};
  for (int k = 0; k < n.net.size(); ++k) {
    const Vector4d& q = n.net.pw[static_cast<std::size_t>(k)];
    n.points[static_cast<std::size_t>(k)] = q.head<3>() / q.w();
    n.box.extend(n.points[static_cast<std::size_t>(k)]);
  }
}

// Whether the border at cell index I of level l (2^l cells per element and direction) joins
// the cells on either side C1: inside an element, or an element border where the interior knot
// multiplicity is below the degree.
bool c1_border(const KnotVector& kv, const std::vector<double>& br, int I, int l) {
  if (I % (1 << l) != 0) return true;  // inside an element
  return kv.multiplicity(br[static_cast<std::size_t>(I >> l)]) < kv.degree();
}

// The piece of a Bezier net over the parameter rectangle r (within its range): four de
// Casteljau splits.
template <class Net>
Net sub_net(const Net& b, const Domain2& r) {
  Net lo, hi, piece = b;
  if (r.u.lo > piece.range.u.lo) detail::split_at(piece, 0, r.u.lo, lo, piece);
  if (r.u.hi < piece.range.u.hi) detail::split_at(piece, 0, r.u.hi, piece, hi);
  if (r.v.lo > piece.range.v.lo) detail::split_at(piece, 1, r.v.lo, lo, piece);
  if (r.v.hi < piece.range.v.hi) detail::split_at(piece, 1, r.v.hi, piece, hi);
  return piece;
}

// Regions: the cells around each node, across a border between cells that is an element
// border only where the surface is C1 there (interior knot multiplicity below the degree).
// grid[l][I + (nu 2^l) J] is the node of cell (I, J) at level l; cell and level, each node's.
// The region's bounds are those of its part in each element it meets (at most 2 x 2), each
// cut out of the element's net as one Bezier patch: tighter than the union of its cells' and
// fewer to compute.
template <class N, class C>
void set_regions(const std::vector<N>& tree, std::vector<C>& cert, const NurbsSurface& s,
                 const std::vector<double>& breaks_u, const std::vector<double>& breaks_v,
                 const std::vector<std::vector<int>>& grid,
                 const std::vector<std::array<int, 2>>& cell, const std::vector<int>& level) {
  const int nu = static_cast<int>(breaks_u.size()) - 1, nv = static_cast<int>(breaks_v.size()) - 1;
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t k = 0; k < tree.size(); ++k) {
    const int l = level[k], I = cell[k][0], J = cell[k][1];
    const int wu = nu << l, wv = nv << l;
    const int i0 = I > 0 && c1_border(s.knots_u(), breaks_u, I, l) ? I - 1 : I;
    const int i1 = I + 1 < wu && c1_border(s.knots_u(), breaks_u, I + 1, l) ? I + 1 : I;
    const int j0 = J > 0 && c1_border(s.knots_v(), breaks_v, J, l) ? J - 1 : J;
    const int j1 = J + 1 < wv && c1_border(s.knots_v(), breaks_v, J + 1, l) ? J + 1 : J;
    const N& node = tree[k];
    C& n = cert[k];
    auto range_of = [&](int i, int j) -> const Domain2& {
      return tree[static_cast<std::size_t>(
                      grid[static_cast<std::size_t>(l)][static_cast<std::size_t>(i + wu * j)])]
          .net.range;
    };
    n.region = {{range_of(i0, j0).u.lo, range_of(i1, j0).u.hi},
                {range_of(i0, j0).v.lo, range_of(i0, j1).v.hi}};
    detail::PatchBounds region_bounds;
    bool first = true;
    for (int ej = j0 >> l; ej <= j1 >> l; ++ej)
      for (int ei = i0 >> l; ei <= i1 >> l; ++ei) {
        const N& e =
            tree[static_cast<std::size_t>(grid[0][static_cast<std::size_t>(ei + nu * ej)])];
        const Domain2& er = e.net.range;
        const Domain2 part{{std::max(er.u.lo, n.region.u.lo), std::min(er.u.hi, n.region.u.hi)},
                           {std::max(er.v.lo, n.region.v.lo), std::min(er.v.hi, n.region.v.hi)}};
        const detail::PatchBounds b = detail::patch_bounds(sub_net(e.net, part), node.bounds.frame);
        if (first)
          region_bounds = b, first = false;
        else
          detail::unite(region_bounds, b);
      }
    n.region_chord = detail::chord_data(region_bounds);
  }
}

// The squared distance between two boxes.
double box_gap2(const Box3& a, const Box3& b) {
  const Vector3d g = (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(0.0);
  return g.squaredNorm();
}

// the distance between a's box in its frame and the box of b's points in that frame
template <class N>
double frame_gap2(const N& a, const N& b) {
  Box3 in_a, own;
  for (int k = 0; k < b.net.size(); ++k)
    in_a.extend(a.bounds.frame * (b.points[static_cast<std::size_t>(k)] - a.bounds.centre));
  own.lo << a.bounds.S.c[0].lo, a.bounds.S.c[1].lo, a.bounds.S.c[2].lo;
  own.hi << a.bounds.S.c[0].hi, a.bounds.S.c[1].hi, a.bounds.S.c[2].hi;
  const Vector3d g = (own.lo - in_a.hi).cwiseMax(in_a.lo - own.hi).cwiseMax(0.0);
  return g.squaredNorm();
}

// Whether the parameter rectangles a and b do not overlap (they may touch).
bool apart(const Domain2& a, const Domain2& b) {
  return a.u.lo >= b.u.hi || a.u.hi <= b.u.lo || a.v.lo >= b.v.hi || a.v.hi <= b.v.lo;
}

// The gaps: a lower bound of the distance from a node to the surface outside its region, the
// least over the leaves outside it of the distance between their boxes, axis-aligned or in
// the tangent frame of either (a branch and bound down the tree). Nodes 0 .. n_el - 1 are the
// roots; cert[k] (region in, gap out) is tree[k]'s.
template <class N, class C>
void set_gaps(const std::vector<N>& tree, std::vector<C>& cert, std::size_t n_el) {
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < tree.size(); ++i) {
    const N& n = tree[i];
    const Domain2& region = cert[i].region;
    double g2 = std::numeric_limits<double>::infinity();
    auto descend = [&](auto&& self, const N& m) -> void {
      if (within(m.net.range, region)) return;
      if (box_gap2(n.box, m.box) >= g2) return;
      if (m.child < 0) {
        // a leaf overlapping the region (not split further) leaves no gap
        g2 = apart(m.net.range, region)
                 ? std::min(g2, std::max(box_gap2(n.box, m.box),
                                         std::max(frame_gap2(n, m), frame_gap2(m, n))))
                 : 0.0;
        return;
      }
      for (int k = 0; k < 4; ++k) self(self, tree[static_cast<std::size_t>(m.child + k)]);
    };
    for (std::size_t e = 0; e < n_el; ++e) descend(descend, tree[e]);
    cert[i].gap = std::sqrt(g2) * (1.0 - 1e-12);
  }
}

// The largest float not above g (a lower bound stays one).
float float_below(double g) {
  float f = static_cast<float>(g);
  if (static_cast<double>(f) > g) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

// The near lists: for each node, the coarsest nodes apart from its region (and the leaves
// overlapping it in part, at gap 0), by the lower bound of their distance to the node's points
// (boxes, axis-aligned and in either's tangent frame), the nearest C::kNear kept in order.
template <class N, class C>
void set_near_lists(const std::vector<N>& tree, std::vector<C>& cert, std::size_t n_el) {
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < tree.size(); ++i) {
    const N& n = tree[i];
    C& c = cert[i];
    std::vector<std::pair<double, int>> cut;
    auto descend = [&](auto&& self, int k) -> void {
      const N& m = tree[static_cast<std::size_t>(k)];
      if (within(m.net.range, c.region)) return;
      if (apart(m.net.range, c.region)) {
        const double g2 =
            std::max(box_gap2(n.box, m.box), std::max(frame_gap2(n, m), frame_gap2(m, n)));
        cut.emplace_back(std::sqrt(g2) * (1.0 - 1e-12), k);
        return;
      }
      if (m.child < 0) {
        cut.emplace_back(0.0, k);
        return;
      }
      for (int q = 0; q < 4; ++q) self(self, m.child + q);
    };
    for (std::size_t e = 0; e < n_el; ++e) descend(descend, static_cast<int>(e));
    std::sort(cut.begin(), cut.end());
    c.n_near = static_cast<int>(std::min<std::size_t>(cut.size(), C::kNear));
    for (int k = 0; k < c.n_near; ++k)
      c.near[static_cast<std::size_t>(k)] = {float_below(cut[static_cast<std::size_t>(k)].first),
                                             cut[static_cast<std::size_t>(k)].second};
    c.rest_gap = cut.size() > static_cast<std::size_t>(C::kNear)
                     ? cut[static_cast<std::size_t>(C::kNear)].first
                     : std::numeric_limits<double>::infinity();
  }
}

}  // namespace

namespace {
std::atomic<std::size_t> tree_budget_nodes{PatchProjector::kTreeNodes};
}  // namespace

void PatchProjector::set_tree_budget(std::size_t nodes) {
  tree_budget_nodes.store(nodes, std::memory_order_relaxed);
}

std::size_t PatchProjector::tree_budget() {
  return tree_budget_nodes.load(std::memory_order_relaxed);
}

template <class N>
void PatchProjector::build_tree(std::vector<N>& tree) {
  const int nu = static_cast<int>(bez_.breaks_u().size()) - 1,
            nv = static_cast<int>(bez_.breaks_v().size()) - 1;
  const std::size_t n_el = bez_.elements().size();
  if (static_cast<std::size_t>(nu * nv) != n_el) return;
  // (The constructor chose N by the largest degree: every element's net fits.)
  // Depth: as deep as the budget allows, at most 4 (256 leaves per element). A node takes
  // about 3.5 kB (the net and points held for degree 5), so a patch up to 21 MB with the
  // default budget (kTreeNodes); the budget is in bytes of such nodes, so the bigger nodes of
  // higher degrees (HighNode) go less deep.
  const std::size_t budget = tree_budget() * sizeof(Node) / sizeof(N);
  int depth = 0;
  while (depth < 4 && n_el * (((std::size_t{1} << (2 * (depth + 2))) - 1) / 3) <= budget) ++depth;
  // Nodes level by level; grid[l][I + (nu 2^l) J] is the node of cell (I, J) at level l.
  std::vector<std::vector<int>> grid(static_cast<std::size_t>(depth + 1));
  std::vector<std::array<int, 2>> cell;  // (I, J) of each node at its level
  std::vector<int> level;
  auto make = [&](N& n) {
    finish_node(n);
    const Domain2& r = n.net.range;
    n.centre = s_.derivs(0.5 * (r.u.lo + r.u.hi), 0.5 * (r.v.lo + r.v.hi), 1);
    n.bounds = detail::patch_bounds(n.net, detail::tangent_frame(n.centre));
  };
  tree.reserve(n_el * (((std::size_t{1} << (2 * (depth + 1))) - 1) / 3));
  tree.resize(n_el);
  grid[0].assign(n_el, -1);
  for (std::size_t e = 0; e < n_el; ++e) {
    detail::to_net(bez_.elements()[e], tree[e].net);
    make(tree[e]);
    tree[e].element = static_cast<int>(e);
    cell.push_back({bez_.elements()[e].element_u, bez_.elements()[e].element_v});
    level.push_back(0);
    grid[0][static_cast<std::size_t>(bez_.elements()[e].element_u +
                                     nu * bez_.elements()[e].element_v)] = static_cast<int>(e);
  }
  std::size_t first = 0, last = n_el;  // nodes of the current level
  for (int l = 1; l <= depth; ++l) {
    const int wu = nu << l;
    grid[static_cast<std::size_t>(l)].assign(static_cast<std::size_t>(wu * (nv << l)), -1);
    for (std::size_t k = first; k < last; ++k) {
      tree[k].child = static_cast<int>(tree.size());
      N c[4];
      decltype(N::net) lo, hi;
      detail::split_half(tree[k].net, 0, lo, hi);
      detail::split_half(lo, 1, c[0].net, c[1].net);
      detail::split_half(hi, 1, c[2].net, c[3].net);
      for (int q = 0; q < 4; ++q) {
        const int I = 2 * cell[k][0] + q / 2, J = 2 * cell[k][1] + q % 2;
        grid[static_cast<std::size_t>(l)][static_cast<std::size_t>(I + wu * J)] =
            static_cast<int>(tree.size());
        cell.push_back({I, J});
        level.push_back(l);
        c[q].element = tree[k].element;
        c[q].level = l;
        tree.push_back(c[q]);
      }
    }
#pragma omp parallel for schedule(dynamic, 16)
    for (std::size_t k = last; k < tree.size(); ++k) make(tree[k]);
    first = last;
    last = tree.size();
  }
  cert_.assign(tree.size(), Cert{});
  for (std::size_t k = 0; k < tree.size(); ++k) {
    Cert& c = cert_[k];
    c.range = tree[k].net.range;
    c.child = tree[k].child;
    c.box = tree[k].box;
    c.frame_box = detail::frame_box(tree[k].bounds);
  }
  set_regions(tree, cert_, s_, bez_.breaks_u(), bez_.breaks_v(), grid, cell, level);
  set_gaps(tree, cert_, n_el);
  set_near_lists(tree, cert_, n_el);
}

std::size_t PatchProjector::memory_bytes() const {
  std::size_t b = sizeof(*this) + tree_.size() * sizeof(Node) +
                  high_tree_.size() * sizeof(HighNode) + cert_.size() * sizeof(Cert) +
                  boxes_.size() * sizeof(Box3) + hull_.size() * sizeof(Vector3d) +
                  hull_offset_.size() * sizeof(std::size_t);
  for (const auto& v : samples_) b += v.size() * sizeof(Sample);
  for (const BezierPatch& e : bez_.elements())
    b += sizeof(BezierPatch) + e.pw.size() * sizeof(e.pw[0]);
  return b;
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

namespace {

// Lower bound of |x - S| over a Bezier piece from its control points (convex hull property):
// the distance to their box, and for the unit directions d from the box centre towards x and
// from the best foot point so far towards x, d.x - max_i d.P_i (a supporting plane of the hull).
// Returns as soon as the bound exceeds `enough` (where the caller asks only whether it does).
double hull_lower_bound(const Box3& box, const Vector3d* pts, std::size_t n, const Vector3d& x,
                        const Vector3d* toward, double enough = kInf) {
  double lb = std::sqrt(box_distance2(box, x));
  if (lb > enough) return lb;  // the box's bound already prunes: the planes cannot undo that
  Vector3d dirs[2];
  int n_dirs = 0;
  const Vector3d a = x - 0.5 * (box.lo + box.hi);
  if (a.norm() > 0.0) dirs[n_dirs++] = a.normalized();
  if (toward) {
    const Vector3d b = x - *toward;
    if (b.norm() > 0.0) dirs[n_dirs++] = b.normalized();
  }
#if defined(__SSE2__)
  if (n_dirs == 2) {  // both supports at once, one direction per lane
    const __m128d dx = _mm_set_pd(dirs[1].x(), dirs[0].x());
    const __m128d dy = _mm_set_pd(dirs[1].y(), dirs[0].y());
    const __m128d dz = _mm_set_pd(dirs[1].z(), dirs[0].z());
    __m128d support = _mm_set1_pd(-kInf);
    for (std::size_t i = 0; i < n; ++i) {
      // d.P in the order of Vector3d::dot: (d_x P_x + d_y P_y) + d_z P_z
      const __m128d dot = _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, _mm_set1_pd(pts[i].x())),
                                                _mm_mul_pd(dy, _mm_set1_pd(pts[i].y()))),
                                     _mm_mul_pd(dz, _mm_set1_pd(pts[i].z())));
      support = _mm_max_pd(dot, support);  // max(support, dot) as std::max: NaN-free here
    }
    double sup[2];
    _mm_storeu_pd(sup, support);
    for (int k = 0; k < 2; ++k) lb = std::max(lb, dirs[k].dot(x) - sup[k]);
    return lb;
  }
#endif
  for (int k = 0; k < n_dirs; ++k) {
    double support = -kInf;
    for (std::size_t i = 0; i < n; ++i) support = std::max(support, dirs[k].dot(pts[i]));
    lb = std::max(lb, dirs[k].dot(x) - support);
  }
  return lb;
}

// The answer of a search that has found nothing (yet).
ProjectionResult far_result() {
  ProjectionResult r;
  r.status = ProjectionStatus::far;
  r.distance = kInf;
  return r;
}

// The kink of one direction (`kinks`, sorted) within rel times the domain's width `d` of the
// parameter a, if any.
std::optional<double> kink_near(const std::vector<double>& kinks, double a, const Interval& d,
                                double rel) {
  const double eps = rel * (d.hi - d.lo);
  for (const double k : kinks)
    if (std::abs(a - k) <= eps) return k;
  return std::nullopt;
}

// The Newton on the whole patch, finished on a kink it stopped at. Across a kink (a C0 element
// border) F has a corner: a Newton that reaches one zigzags across it, its line search fails,
// and it stops short along the crease, its residual above the tolerance (seen: 0.026 of 2842
// from the crease's minimum, by a distance 1.3e-7 larger). Where such an answer lies within
// 1e-7 of the domain of a kink, the 1-D Newton along the crease (that parameter held on the
// kink; the crease's curve and its derivatives along it are the same from both sides) is taken
// when it is not farther.
ProjectionResult newton_on_patch(const BezierSurface& s, const std::vector<double>* kinks,
                                 const Vector3d& x, const Vector2d& start,
                                 const ProjectionOptions& opt) {
  ProjectionResult r = closest_point_local(s, x, start, opt);
  // A Newton that met the optimality conditions stays as it is (a smooth minimum next to a
  // knot of multiplicity >= the degree, e.g. of a NURBS circle, which is C1 there): only one
  // that stopped with its residual above the tolerance can have stalled on a crease.
  if (!found(r.status) || r.residual <= 10.0 * opt.tol_residual) return r;
  const Domain2 dom = s.domain();
  Domain2 on = dom;
  Vector2d uv = r.uv;
  bool held = false;
  for (int dir = 0; dir < 2; ++dir) {
    Interval& b = dir == 0 ? on.u : on.v;
    if (const std::optional<double> k = kink_near(kinks[dir], uv[dir], b, 1e-7)) {
      uv[dir] = b.lo = b.hi = *k;
      held = true;
    }
  }
  if (!held) return r;
  ProjectionResult c = closest_point_local(s, x, uv, on, opt);
  c.iterations += r.iterations;
  if (!found(c.status) || (c.point - x).norm() > (r.point - x).norm()) {
    r.iterations = c.iterations;
    return r;
  }
  c.status = boundary_status(s, c.uv);
  return c;
}

// The patch evaluated on one of its Bezier elements (clamped into its range), also on the
// element's border, where the patch takes the element above (BezierSurface::derivs): for the
// Newton of CertifiedSearch::node_newton. Its domain and closedness are the patch's, so that
// the Newton's scales (the residual's length, the step tolerance) are the patch's.
class ElementSurface final : public Surface {
 public:
  ElementSurface(const BezierSurface& s, int e) : s_(s), e_(e) { set_normal_sign(s.normal_sign()); }
  SurfaceDerivs derivs(double u, double v, int order = 2) const override {
    return s_.derivs_on(e_, u, v, order);
  }
  Domain2 domain() const override { return s_.domain(); }
  bool closed_u() const override { return s_.closed_u(); }
  bool closed_v() const override { return s_.closed_v(); }
  std::string type_name() const override { return "bezier_element"; }

 private:
  const BezierSurface& s_;
  int e_;
};

// The state of one certified search (PatchProjector::search below) and its steps: the best
// answer so far, the upper bound, the regions proven. A template on the projector's node and
// sample types, which are private to it; `chord_region` calls its member of that name.
template <class Node, class Sample, int MaxSamples, class ChordRegion>
struct CertifiedSearch {
  // The projector's
  const BezierSurface& surface;  // the patch (by its Bezier elements)
  const std::vector<BezierPatch>& elements;
  const std::vector<std::vector<Sample>>& samples;  // per element
  const double* sample_coords;                      // the same, as PatchProjector's
  int samples_per_dir;
  const std::vector<Node>& tree;
  const std::vector<double>* kinks;  // [2]: the patch's C0 element borders in u and v
  ChordRegion chord_region;
  // The query
  const Vector3d& x;
  const ProjectionOptions& opt;
  Domain2 dom;
  bool cu, cv;
  bool all_elements;  // every element searched, not only the ids given
  double tol;
  // The best answer so far
  ProjectionResult best = far_result();
  double best_d = kInf;
  bool best_patch_kkt = false;  // best satisfies the optimality conditions on the whole patch
  int best_element = -1;
  Domain2 best_range{};  // the node that gave the best answer
  int iterations = 0;
  bool certified;
  bool warm = false;  // started from a found answer
  // An upper bound of the distance (a surface point at that distance exists, at ub_uv)
  double ub;
  Vector2d ub_uv = Vector2d::Zero();
  bool ub_seen = false;  // ub is the distance of the surface point at ub_uv
  // Regions proven to hold no point closer than the best (at most kMaxProven kept).
  static constexpr int kMaxProven = 4;
  const Domain2* proven[kMaxProven] = {};
  int n_proven = 0;
  bool everything_proven = false;
  static constexpr int kMaxDepth = 10;

  // The warm start: a found answer of the Newton on the whole patch, so one that satisfies the
  // optimality conditions of the patch, unless it lies on a kink (on_kink).
  void start_from(const ProjectionResult& start) {
    warm = true;
    best = start;
    best_d = (start.point - x).norm();
    best_patch_kkt = !on_kink(start.uv);
    iterations = start.iterations;
  }

  double threshold() const { return std::min(ub, best_d - tol); }

  // The Newton within a box of an element's node. The patch is evaluated as everywhere else,
  // except where the answer rests on a kink on the box's bound and F, by the element's own
  // derivative there, decreases into the box: then the answer took the neighbour's side of the
  // kink (BezierSurface::derivs), which is no minimum of the node (seen: a zero derivative on
  // the far side, from repeated control points, stopped the Newton on the border as if it were
  // stationary, short of the node's minimum next to it), and the Newton is run again on the
  // element's polynomial (ElementSurface).
  ProjectionResult node_newton(int element, const Vector2d& start, const Domain2& box) {
    ProjectionResult r = closest_point_local(surface, x, start, box, opt);
    if (!found(r.status) || !on_kink(r.uv)) return r;
    const SurfaceDerivs d = surface.derivs_on(element, r.uv[0], r.uv[1], 1);
    const Vector3d g = d.S - x;  // F_,u = g . S_u, F_,v = g . S_v
    const double scale = 1e-10 * g.norm();
    const double fu = g.dot(d.Su), fv = g.dot(d.Sv);
    const bool inward = (r.uv[0] >= box.u.hi && fu > scale * d.Su.norm()) ||
                        (r.uv[0] <= box.u.lo && fu < -scale * d.Su.norm()) ||
                        (r.uv[1] >= box.v.hi && fv > scale * d.Sv.norm()) ||
                        (r.uv[1] <= box.v.lo && fv < -scale * d.Sv.norm());
    if (!inward) return r;
    ProjectionResult e = closest_point_local(ElementSurface(surface, element), x, start, box, opt);
    e.iterations += r.iterations;
    return found(e.status) ? e : r;
  }

  // Whether uv lies on a kink (a C0 element border): the Newton's optimality conditions there
  // hold for one side only (the derivative it evaluates is one side's), so a Newton's answer
  // there is no optimum of the patch. Seen: a zero derivative on one side (repeated control
  // points) made a point on a crease look stationary while F decreased into the other side.
  bool on_kink(const Vector2d& uv) const {
    return kink_near(kinks[0], uv[0], dom.u, 1e-12) || kink_near(kinks[1], uv[1], dom.v, 1e-12);
  }

  bool is_proven(const Domain2& r) const {
    for (int k = 0; k < n_proven; ++k)
      if (within(r, *proven[k])) return true;
    return false;
  }

  // When the best answer satisfies the optimality conditions of the patch: the coarsest
  // region holding it that passes the chord test is proven.
  void prove_region() {
    if (!opt.certify || !best_patch_kkt || n_proven == kMaxProven) return;
    const auto* n = chord_region(best.uv, x - best.point);
    if (n == nullptr) return;
    if (!is_proven(n->region)) proven[n_proven++] = &n->region;
    // Every surface point outside the region is at least gap from the foot, so at least
    // gap - best_d from x: the foot is the global minimum when best_d <= gap / 2.
    if (best_d <= 0.5 * n->gap) everything_proven = true;
  }

  void consider(const ProjectionResult& r, int e, const Domain2& node_range, bool patch_kkt) {
    iterations += r.iterations;
    if (!found(r.status)) return;
    // Only a clearly closer answer replaces the best: one equal to round-off would make the
    // foot jump between two converged iterates of the same minimum.
    const double d = (r.point - x).norm();
    if (d < best_d - tol) {
      best_d = d;
      best = r;
      best_element = e;
      best_range = node_range;
      // An answer off its node's bounds (but those of the patch) satisfies the optimality
      // conditions of the whole patch, so those of every node that holds it.
      auto off = [](double t, const Interval& n, const Interval& dm, bool closed) {
        return (t > n.lo || (n.lo <= dm.lo && !closed)) && (t < n.hi || (n.hi >= dm.hi && !closed));
      };
      best_patch_kkt = patch_kkt || (off(r.uv[0], node_range.u, dom.u, cu) &&
                                     off(r.uv[1], node_range.v, dom.v, cv));
      prove_region();
    }
  }

  // Whether the minimum of F over a node, lying on its bound `side` (0 lo, 1 hi) in direction
  // `dir`, is held by another node that searches it: the bound is inside the element, or (all
  // elements searched) an element border inside the patch across which the patch is C1. Not
  // across a kink (an inner knot of multiplicity >= the degree) or a seam: there F_,dir may
  // change sign, F of the nodes on both sides may decrease towards the bound, and each would
  // leave the bound to the other (seen: a minimum at the corner of four degree-1 elements
  // pruned by all four). Such a node is solved on its bound instead (settled_by_bounds).
  bool shared_bound(const Domain2& range, int element, int dir, int side) const {
    const Interval& r = dir == 0 ? range.u : range.v;
    const Domain2& er = elements[static_cast<std::size_t>(element)].range;
    const Interval& el = dir == 0 ? er.u : er.v;
    const Interval& d = dir == 0 ? dom.u : dom.v;
    const double b = side == 0 ? r.lo : r.hi;
    if (b > el.lo && b < el.hi) return true;
    if (!all_elements || !(b > d.lo && b < d.hi)) return false;
    const std::vector<double>& k = kinks[dir];
    return !std::binary_search(k.begin(), k.end(), b);
  }

  // Newtons in an element from the discrete local minima of the distance over its sample grid,
  // nearest first, at most kMaxSeeds: a good answer early prunes the most.
  void seed_newtons(int element) {
    const Domain2& range = elements[static_cast<std::size_t>(element)].range;
    const std::vector<Sample>& smp = samples[static_cast<std::size_t>(element)];
    const int n = samples_per_dir;
    double d2s[MaxSamples];
    sample_distances2(sample_coords + static_cast<std::ptrdiff_t>(3 * element * n * n), n * n, x,
                      d2s);
    constexpr int kMaxSeeds = 3;
    std::pair<double, int> seeds[kMaxSeeds];
    int n_seeds = 0;
    // A sample is a discrete local minimum when no sample of its 3 x 3 block is nearer: the
    // block's minimum, by rows then columns (std::min leaves a NaN neighbour out, as the
    // comparison < would), is not below its own distance.
    double row_min[MaxSamples], block_min[MaxSamples];
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int k = i + n * j;
        double m = d2s[k];
        if (i > 0) m = std::min(m, d2s[k - 1]);
        if (i + 1 < n) m = std::min(m, d2s[k + 1]);
        row_min[k] = m;
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int k = i + n * j;
        double m = row_min[k];
        if (j > 0) m = std::min(m, row_min[k - n]);
        if (j + 1 < n) m = std::min(m, row_min[k + n]);
        block_min[k] = m;
      }
    for (int k = 0; k < n * n; ++k) {
      if (block_min[k] < d2s[k]) continue;
      std::pair<double, int> cand{d2s[k], k};
      for (int q = 0; q < n_seeds; ++q)
        if (cand < seeds[q]) std::swap(cand, seeds[q]);
      if (n_seeds < kMaxSeeds) seeds[n_seeds++] = cand;
    }
    for (int q = 0; q < n_seeds; ++q)
      consider(node_newton(element, smp[static_cast<std::size_t>(seeds[q].second)].uv, range),
               element, range, false);
  }

  // Visits a node: one of the tree (`stored`: its centre's derivatives precomputed) or a piece
  // split off below the tree's depth (its bounds from its parent's, patch_bounds_within);
  // `element` is its Bezier element.
  void visit(const Node& node, bool stored, int element, int depth) {
    const Domain2& range = node.net.range;
    if (is_proven(range)) return;
    if (hull_lower_bound(node.box, node.points.data(), static_cast<std::size_t>(node.net.size()), x,
                         best_d < kInf ? &best.point : nullptr, threshold()) > threshold())
      return;
    if (!opt.certify) {  // the sampled search: seeded Newtons in the element, no proof
      seed_newtons(element);
      return;
    }
    // The distance to the box of the node's points in its tangent frame (thin across the
    // surface: close to the distance to the piece where the surface curves towards x).
    if (std::sqrt(detail::frame_box_distance2(node.bounds.frame, node.bounds.centre, node.bounds.S,
                                              x)) > threshold())
      return;
    if (settled_by_bounds(node, stored, element)) return;
    if (depth == 0 && !warm) {  // seeds for a good optimum early (a warm start has one)
      seed_newtons(element);
      if (is_proven(range) ||
          hull_lower_bound(node.box, node.points.data(), static_cast<std::size_t>(node.net.size()),
                           x, &best.point, threshold()) > threshold())
        return;
    }
    if (depth >= kMaxDepth) {
      const Vector2d c(0.5 * (range.u.lo + range.u.hi), 0.5 * (range.v.lo + range.v.hi));
      consider(node_newton(element, c, range), element, range, false);
      certified = false;
      return;
    }
    visit_children(node, stored, element, depth);
  }

  // The interval bounds of F over a node, about the exact derivatives at its centre: true when
  // they prune the node or show that F has one minimum there, which a Newton then finds.
  bool settled_by_bounds(const Node& node, bool stored, int element) {
    const Domain2& range = node.net.range;
    // The exact derivatives at the node's centre: the mean value forms, and a surface point
    // there as an upper bound.
    const double a = 0.5 * (range.u.hi - range.u.lo), b = 0.5 * (range.v.hi - range.v.lo);
    SurfaceDerivs dc_here;
    if (!stored) dc_here = surface.derivs(range.u.lo + a, range.v.lo + b, 1);
    const SurfaceDerivs& dc = stored ? node.centre : dc_here;
    const double dist_c = (x - dc.S).norm();
    if (dist_c < ub) ub = dist_c, ub_uv = Vector2d(range.u.lo + a, range.v.lo + b), ub_seen = true;
    const detail::PatchBounds& pb = node.bounds;
    // The node holding the best answer, an optimum of the patch: the chord test.
    if (best_patch_kkt && inside(range, best.uv) && detail::chord_test(pb, x - best.point))
      return true;
    detail::DistanceBounds db = detail::distance_bounds(pb, x);
    const double f_lo = detail::refine_about_centre(db, dc, x, a, b);
    if (f_lo > 0.0 && std::sqrt(2.0 * f_lo) > threshold()) return true;
    // -1: F increases with the parameter (minimum on the lower bound), +1: decreases, 0: open
    const int mono_u = db.gu.lo > 0.0 ? -1 : db.gu.hi < 0.0 ? 1 : 0;
    const int mono_v = db.gv.lo > 0.0 ? -1 : db.gv.hi < 0.0 ? 1 : 0;
    if (mono_u != 0 && shared_bound(range, element, 0, mono_u > 0)) return true;
    if (mono_v != 0 && shared_bound(range, element, 1, mono_v > 0)) return true;
    const bool solvable = detail::convex(db, pb, x) || (mono_u != 0 && mono_v != 0) ||
                          (mono_u != 0 && db.H22.lo > 0.0) || (mono_v != 0 && db.H11.lo > 0.0);
    return solvable && solved(range, a, b, element, db, pb, dc, mono_u, mono_v);
  }

  // A node on which F has one minimum (convex, or monotone in a parameter): the Newton from
  // its centre, or from the bound a monotone direction points to. True when the node needs no
  // further search. a, b: the node's half-widths.
  bool solved(const Domain2& range, double a, double b, int element,
              const detail::DistanceBounds& db, const detail::PatchBounds& pb,
              const SurfaceDerivs& dc, int mono_u, int mono_v) {
    // The best answer, a KKT point of the whole patch lying on this node, is the node's too.
    if (best_patch_kkt && inside(range, best.uv)) return true;
    // F convex on the node lies above its tangent plane at the centre c:
    // F >= F(c) - |F_,1(c)| a - |F_,2(c)| b over the node.
    if (detail::convex(db, pb, x)) {
      const Vector3d rc = x - dc.S;
      const double lb =
          0.5 * rc.squaredNorm() - std::abs(dc.Su.dot(rc)) * a - std::abs(dc.Sv.dot(rc)) * b;
      if (lb > 0.0 && std::sqrt(2.0 * lb) > threshold()) return true;
    }
    // F monotone in a parameter: the node's minimum lies on the bound it points to, so the
    // search is on that bound alone (the Newton's box closed to it). That also keeps the Newton
    // off the other side of a kink, whose derivative an evaluation on the bound may take.
    Vector2d s0(0.5 * (range.u.lo + range.u.hi), 0.5 * (range.v.lo + range.v.hi));
    Domain2 on = range;
    if (mono_u != 0) s0[0] = on.u.lo = on.u.hi = mono_u < 0 ? range.u.lo : range.u.hi;
    if (mono_v != 0) s0[1] = on.v.lo = on.v.hi = mono_v < 0 ? range.v.lo : range.v.hi;
    const ProjectionResult r = node_newton(element, s0, on);
    consider(r, element, range, false);
    return found(r.status);
  }

  // The node's four children, nearest first (by their boxes): the tree's, or the halves in u
  // and v of a piece below the tree's depth.
  void visit_children(const Node& node, bool stored, int element, int depth) {
    std::pair<double, int> by_bound[4];
    if (stored && node.child >= 0) {  // the tree's children
      const Node* c = &tree[static_cast<std::size_t>(node.child)];
      for (int k = 0; k < 4; ++k) by_bound[k] = {box_distance2(c[k].box, x), k};
      std::sort(by_bound, by_bound + 4);
      for (const auto& [lb2, k] : by_bound) visit(c[k], true, element, depth + 1);
      return;
    }
    // The four children and the halves they come from: on the heap for the nodes of high
    // degrees (HighNode), which would take tens of kB of stack at each of kMaxDepth levels.
    if constexpr (sizeof(Split) > 16384) {
      const auto split = std::make_unique<Split>();
      visit_pieces(node, *split, element, depth);
    } else {
      Split split;
      visit_pieces(node, split, element, depth);
    }
  }
  struct Split {
    std::array<Node, 4> children;
    decltype(Node::net) lo, hi;
  };
  // The halves in u and v of a piece below the tree's depth, visited nearest first.
  void visit_pieces(const Node& node, Split& split, int element, int depth) {
    std::array<Node, 4>& children = split.children;
    std::pair<double, int> by_bound[4];
    detail::split_half(node.net, 0, split.lo, split.hi);
    detail::split_half(split.lo, 1, children[0].net, children[1].net);
    detail::split_half(split.hi, 1, children[2].net, children[3].net);
    for (int k = 0; k < 4; ++k) {
      finish_node(children[k]);
      children[k].bounds = detail::patch_bounds_within(children[k].net, node.bounds);
      by_bound[k] = {box_distance2(children[k].box, x), k};
    }
    std::sort(by_bound, by_bound + 4);
    for (const auto& [lb2, k] : by_bound) visit(children[k], false, element, depth + 1);
  }

  // The answer when the search is over: the best found, polished where it rests on a bound of
  // its node or element that is not one of the patch; none found: a Newton from the nearest
  // surface point seen, if it is within max_distance.
  ProjectionResult answer(double max_distance) {
    if (best_d == kInf) {
      if (ub < max_distance) {  // only the sample's node held points this close: solve there
        ProjectionResult r = newton_on_patch(surface, kinks, x, ub_uv, opt);
        r.iterations += iterations;
        r.certified = false;
        return r;
      }
      best.iterations = iterations;
      return best;
    }
    // A surface point seen closer than the best answer (a sample or a node's centre) means the
    // search missed the minimum: never so by construction; if it happens, the answer is not
    // certified and the Newton from that point is taken where it comes closer.
    if (ub_seen && ub < best_d - tol) {
      certified = false;
      ProjectionResult r = newton_on_patch(surface, kinks, x, ub_uv, opt);
      if (found(r.status) && (r.point - x).norm() < best_d)
        best = r, best_d = (r.point - x).norm(), best_patch_kkt = !on_kink(r.uv), best_element = -1;
    }
    best.certified = certified;
    best.iterations = iterations;
    if (best_patch_kkt) {
      best.status = boundary_status(surface, best.uv);
      return best;
    }
    // The node's answer is a local minimum of the patch unless it rests on an element bound
    // inside the patch or on a seam (the bound of a closed direction); then polish on the whole
    // patch, which also wraps across the seam.
    // No node's answer (a Newton on the whole patch ending on a kink: the warm start or the
    // safety net above): polish on the whole patch.
    const Domain2& er =
        best_element >= 0 ? elements[static_cast<std::size_t>(best_element)].range : dom;
    const bool inner_bound = best_element < 0 ||
                             (best.uv[0] <= er.u.lo && (er.u.lo > dom.u.lo || cu)) ||
                             (best.uv[0] >= er.u.hi && (er.u.hi < dom.u.hi || cu)) ||
                             (best.uv[1] <= er.v.lo && (er.v.lo > dom.v.lo || cv)) ||
                             (best.uv[1] >= er.v.hi && (er.v.hi < dom.v.hi || cv));
    if (!inner_bound) {
      // A node's answer on a bound of the node inside its element: polish on the element.
      const bool node_bound = (best.uv[0] <= best_range.u.lo && best_range.u.lo > er.u.lo) ||
                              (best.uv[0] >= best_range.u.hi && best_range.u.hi < er.u.hi) ||
                              (best.uv[1] <= best_range.v.lo && best_range.v.lo > er.v.lo) ||
                              (best.uv[1] >= best_range.v.hi && best_range.v.hi < er.v.hi);
      if (node_bound) {
        const ProjectionResult r = node_newton(best_element, best.uv, er);
        if (found(r.status) && (r.point - x).norm() <= best_d) {
          best = r;
          best.iterations += iterations;
          best.certified = certified;
        }
      }
      best.status = boundary_status(surface, best.uv);
      return best;
    }
    ProjectionResult r = newton_on_patch(surface, kinks, x, best.uv, opt);
    r.iterations += iterations;
    r.certified = certified;
    if (!found(r.status) || (r.point - x).norm() > best_d * (1.0 + 1e-12) + 1e-300) return best;
    return r;
  }
};

}  // namespace

// The certified search (issue 12, item 5). Every Bezier element (or the ids given) is a node;
// a node is
//  - pruned when the lower bound of its control net (hull_lower_bound) is not below the best
//    distance found, less the tolerance tol: it holds no closer point;
//  - pruned when F = 1/2 |x - S|^2 is monotone over it in a parameter (the interval bound of
//    the gradient (16) has one sign) towards a bound it shares with another node: its minimum
//    lies on that bound, which the other node holds;
//  - solved when F has one minimum on it that the bound-constrained Newton finds from any
//    start: F convex there (interval bound of the Hessian (17) positive definite), or monotone
//    in one parameter and convex along the other, or monotone in both (a corner);
//  - otherwise halved in u and v and its four children visited nearest first.
// So the best answer is the global minimum over all nodes up to tol, by construction. Depth is
// capped; a node still open at the cap is solved by a Newton from its centre and the answer is
// marked not certified (`ProjectionResult::certified`).
ProjectionResult PatchProjector::search(const Vector3d& x, const int* ids, std::size_t n_ids,
                                        double max_distance, const ProjectionOptions& opt,
                                        const ProjectionResult* start, bool pieces,
                                        const double* box_d2) const {
  if (!high_tree_.empty())
    return search_in(high_tree_, x, ids, n_ids, max_distance, opt, start, pieces, box_d2);
  return search_in(tree_, x, ids, n_ids, max_distance, opt, start, pieces, box_d2);
}

template <class N>
ProjectionResult PatchProjector::search_in(const std::vector<N>& tree, const Vector3d& x,
                                           const int* ids, std::size_t n_ids, double max_distance,
                                           const ProjectionOptions& opt,
                                           const ProjectionResult* start, bool pieces,
                                           const double* box_d2) const {
  thread_local std::vector<std::pair<double, int>> order;
  order.clear();
  const double limit2 = max_distance < kInf ? max_distance * max_distance : kInf;
  thread_local std::vector<double> all_d2;  // every element's, at once (box_distances2)
  const bool all = ids == nullptr && !pieces;
  if (all && box_d2 == nullptr) {
    all_d2.resize(boxes_.size());
    box_distances2(x, all_d2.data());
    box_d2 = all_d2.data();
  }
  for (std::size_t k = 0; k < n_ids; ++k) {
    const int e = ids ? ids[k] : static_cast<int>(k);
    const double lb2 = all ? box_d2[k]
                           : box_distance2(pieces ? tree[static_cast<std::size_t>(e)].box
                                                  : boxes_[static_cast<std::size_t>(e)],
                                           x);
    if (lb2 <= limit2) order.emplace_back(lb2, e);
  }
  const auto region_of = [this](const Vector2d& uv, const Vector3d& r_star) {
    return chord_region(uv, r_star);
  };
  CertifiedSearch<N, Sample, kMaxSamples, decltype(region_of)> cs{
      .surface = bez_,
      .elements = bez_.elements(),
      .samples = samples_,
      .sample_coords = sample_coords_.data(),
      .samples_per_dir = samples_per_dir_,
      .tree = tree,
      .kinks = kinks_,
      .chord_region = region_of,
      .x = x,
      .opt = opt,
      .dom = s_.domain(),
      .cu = s_.closed_u(),
      .cv = s_.closed_v(),
      // The pieces and the rest of the patch (proven by the caller) cover it: a node's minimum
      // on a bound inside the patch is another node's, as with all elements.
      .all_elements = ids == nullptr || pieces,
      .tol = 1e-11 * (box_.hi - box_.lo).norm(),
      .certified = opt.certify,
      .ub = max_distance};
  if (start && found(start->status)) cs.start_from(*start);
  if (order.empty()) {
    cs.best.certified = cs.certified && cs.best_d < kInf;
    return cs.best;
  }
  // A first upper bound from the samples of the most promising element (a surface point at
  // that distance exists), so that far elements are pruned before any Newton.
  if (!cs.warm && !pieces) {
    const auto first = std::min_element(order.begin(), order.end());
    const int k = nearest_sample(first->second, x);
    const Sample& smp =
        samples_[static_cast<std::size_t>(first->second)][static_cast<std::size_t>(k)];
    const double d = (smp.x - x).norm();
    if (d < cs.ub) cs.ub = d, cs.ub_uv = smp.uv, cs.ub_seen = true;
    cs.ub *= 1.0 + 1e-12;
  }
  std::sort(order.begin(), order.end());
  cs.prove_region();  // the start's
  for (const auto& [lb2, e] : order) {
    if (cs.everything_proven) break;
    const double t = cs.threshold();
    if (t < 0.0 || lb2 > t * t) break;
    if (!tree.empty()) {
      const N& n = tree[static_cast<std::size_t>(e)];
      cs.visit(n, true, n.element, n.level);
    } else {  // no tree (the elements are not a full grid): the sampled search, not certified
      const std::size_t k = static_cast<std::size_t>(e);
      if (hull_lower_bound(
              boxes_[k], hull_.data() + hull_offset_[k], hull_offset_[k + 1] - hull_offset_[k], x,
              cs.best_d < kInf ? &cs.best.point : nullptr, cs.threshold()) > cs.threshold())
        continue;
      cs.seed_newtons(e);
      cs.certified = false;
    }
  }
  return cs.answer(max_distance);
}

bool PatchProjector::proves_global(const Vector3d& x, const ProjectionResult& r,
                                   Uncleared* left) const {
  const Cert* n = chord_region(r.uv, x - r.point);
  if (n == nullptr) {
    if (left) left->overflow = true;
    return false;
  }
  const double d = (x - r.point).norm();
  if (d <= 0.5 * n->gap) return true;
  return ball_clear_near(*n, x, r.point, d - 1e-11 * (box_.hi - box_.lo).norm(), left);
}

ProjectionResult PatchProjector::certify(const Vector3d& x, ProjectionResult r,
                                         const ProjectionOptions& opt) const {
  Uncleared left;
  if (proves_global(x, r, &left)) {
    r.certified = true;
    return r;
  }
  if (!left.overflow && left.n > 0)
    return search(x, left.nodes.data(), static_cast<std::size_t>(left.n), kInf, opt, &r, true);
  return search(x, nullptr, boxes_.size(), kInf, opt, &r);
}

namespace {
// Notes m as uncleared in `left` (nullptr: not kept); past U::kMax the list overflows.
template <class U>
void keep_uncleared(U* left, int m) {
  if (left == nullptr || left->overflow) return;
  if (left->n == U::kMax) {
    left->overflow = true;
    return;
  }
  left->nodes[static_cast<std::size_t>(left->n++)] = m;
}
// Whether a walk that met an uncleared piece stops there: no list keeps them, or it overflowed.
template <class U>
bool walk_stops(const U* left) {
  return left == nullptr || left->overflow;
}
}  // namespace

bool PatchProjector::clear_of(const Cert& m, const Ball& ball, const Domain2& region,
                              Uncleared* left) const {
  if (within(m.range, region)) return true;
  if (box_distance2(m.box, ball.x) >= ball.r2 ||
      detail::frame_box_distance2(m.frame_box, ball.x) >= ball.r2)
    return true;
  if (m.child < 0) {  // a piece outside the region may hold a closer point
    keep_uncleared(left, static_cast<int>(&m - cert_.data()));
    return false;
  }
  bool clear = true;
  for (int c = 0; c < 4; ++c)
    if (!clear_of(cert_[static_cast<std::size_t>(m.child + c)], ball, region, left)) {
      clear = false;
      if (walk_stops(left)) return false;
    }
  return clear;
}

bool PatchProjector::ball_clear_near(const Cert& n, const Vector3d& x, const Vector3d& foot,
                                     double radius, Uncleared* left) const {
  if (!(radius > 0.0)) {
    if (left) left->overflow = true;
    return false;
  }
  const double d = (x - foot).norm();
  const Ball ball{x, radius * radius};
  // A piece at least g from the points of n is at least g - d from x.
  if (n.rest_gap < d + radius) return ball_clear(ball, n.region, left);
  bool clear = true;
  for (int k = 0; k < n.n_near; ++k) {
    const Cert::Near& m = n.near[static_cast<std::size_t>(k)];
    if (m.gap >= d + radius) break;
    if (!clear_of(cert_[static_cast<std::size_t>(m.node)], ball, n.region, left)) {
      clear = false;
      if (walk_stops(left)) return false;
    }
  }
  return clear;
}

const PatchProjector::Cert* PatchProjector::chord_region(const Vector2d& uv,
                                                         const Vector3d& r_star) const {
  if (cert_.empty()) return nullptr;
  // The nodes holding uv, element to leaf; then the coarsest whose region passes by bisection
  // over the levels (a region holds the finer ones' around uv, so a coarser pass mostly means
  // a finer pass: where not, a finer region is found, as sound).
  std::array<const Cert*, 8> path{};
  int n_path = 0;
  const Cert* n = &cert_[static_cast<std::size_t>(element_of(uv))];
  while (true) {
    path[static_cast<std::size_t>(n_path++)] = n;
    if (n->child < 0 || n_path == static_cast<int>(path.size())) break;
    const Domain2& g = n->range;
    n = &cert_[static_cast<std::size_t>(n->child + (uv[0] >= 0.5 * (g.u.lo + g.u.hi) ? 2 : 0) +
                                        (uv[1] >= 0.5 * (g.v.lo + g.v.hi) ? 1 : 0))];
  }
  const Cert* found_region = nullptr;
  int lo = 0, hi = n_path - 1;
  while (lo <= hi) {
    const int mid = (lo + hi) / 2;
    const Cert* m = path[static_cast<std::size_t>(mid)];
    if (inside(m->region, uv) && detail::chord_test(m->region_chord, r_star)) {
      found_region = m;
      hi = mid - 1;
    } else {
      lo = mid + 1;
    }
  }
  return found_region;
}

bool PatchProjector::ball_clear(const Ball& ball, const Domain2& region, Uncleared* left) const {
  bool clear = true;
  for (std::size_t e = 0; e < bez_.elements().size(); ++e)
    if (!clear_of(cert_[e], ball, region, left)) {
      clear = false;
      if (walk_stops(left)) return false;
    }
  return clear;
}

ProjectionResult PatchProjector::project(const Vector3d& x, const ProjectionOptions& opt) const {
  std::size_t first = 0;
  double first2 = kInf;
  thread_local std::vector<double> d2;  // every element box's, for the search too
  const double* box_d2 = nullptr;
  if (opt.certify && has_tree()) {
    d2.resize(boxes_.size());
    box_distances2(x, d2.data());
    box_d2 = d2.data();
    first = static_cast<std::size_t>(first_minimum(box_d2, static_cast<int>(d2.size()), first2));
  }
  // Near the surface (within the size of the nearest element's box) first the Newton from the
  // nearest sample of that element: its answer proven global without a search where the
  // certificate holds (the chord test fails far from a curved surface: there, search at once).
  if (first2 < (boxes_[first].hi - boxes_[first].lo).squaredNorm()) {
    const Sample* seed =
        &samples_[first][static_cast<std::size_t>(nearest_sample(static_cast<int>(first), x))];
    ProjectionResult r =
        newton_on_patch(bez_, kinks_, x, seed_from(*seed, static_cast<int>(first), x), opt);
    // Proven global, or else the search started from that answer (an upper bound that prunes
    // from the first node on).
    if (found(r.status)) return certify(x, r, opt);
    const int used = r.iterations;
    r = search(x, nullptr, boxes_.size(), kInf, opt, nullptr, false, box_d2);
    r.iterations += used;
    return r;
  }
  return search(x, nullptr, boxes_.size(), kInf, opt, nullptr, false, box_d2);
}

ProjectionResult PatchProjector::project(const Vector3d& x, const Vector2d& guess,
                                         const ProjectionOptions& opt) const {
  // The local Newton from the guess, then the certified search bounded by its answer: it
  // either proves that answer global or finds the closer foot (the true foot may have jumped).
  ProjectionResult r = opt.certify ? newton_on_patch(bez_, kinks_, x, guess, opt)
                                   : closest_point_local(bez_, x, guess, opt);
  if (opt.certify) {
    if (found(r.status)) return certify(x, r, opt);
    return search(x, nullptr, boxes_.size(), kInf, opt);
  }
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

detail::LocalModel<1> curve_model(const NurbsCurve& c, const Vector3d& x, double u, double width) {
  const CurveDerivs d = c.derivs(u, 2);
  const Vector3d r = x - d.d[0];
  detail::LocalModel<1> m;
  m.f = 0.5 * r.squaredNorm();
  m.g[0] = -d.d[1].dot(r);                           // (16), one parameter
  m.H(0, 0) = d.d[1].squaredNorm() - d.d[2].dot(r);  // (17)
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
      },
      t0, box, opt);
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
