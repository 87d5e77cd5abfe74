// Multi-patch rigid surfaces ([KS15] Sect. 2.2, Remark 5).
#include "contact/rigid_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "contact/analytic_projection.hpp"
#include "contact/contact_search.hpp"
#include "contact/ray_projection.hpp"

namespace iga {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double box_distance(const Box3& b, const Vector3d& x) {
  return (b.lo - x).cwiseMax(x - b.hi).cwiseMax(0.0).norm();
}

// Samples along side `side` of a surface (0: u = lo, 1: u = hi, 2: v = lo, 3: v = hi).
std::vector<Vector3d> side_samples(const Surface& s, int side, int n) {
  const Domain2 d = s.domain();
  std::vector<Vector3d> pts;
  for (int k = 0; k < n; ++k) {
    const double t = (k + 0.5) / n;  // inner points: corners alone do not make a shared side
    const double u = side == 0 ? d.u.lo : side == 1 ? d.u.hi : d.u.lo + t * (d.u.hi - d.u.lo);
    const double v = side == 2 ? d.v.lo : side == 3 ? d.v.hi : d.v.lo + t * (d.v.hi - d.v.lo);
    pts.push_back(s.point(u, v));
  }
  return pts;
}

/// Side `side` of the domain d (numbered as in side_samples) lies at a finite parameter value
/// and spans a finite interval, so that it can be sampled.
bool side_is_finite(const Domain2& d, int side) {
  const Interval I = side < 2 ? d.u : d.v;
  if (!std::isfinite(side % 2 == 0 ? I.lo : I.hi)) return false;
  const Interval other = side < 2 ? d.v : d.u;
  return std::isfinite(other.lo) && std::isfinite(other.hi);
}

/// Every sample point lies within tol of a piece with bounding box `box`, whose closest point
/// to x is project(x) (the box rules a point out before the projection is paid for).
template <class Project>
bool samples_on_piece(const std::vector<Vector3d>& pts, const Box3& box, double tol,
                      const Project& project) {
  for (const Vector3d& x : pts) {
    if (box_distance(box, x) > tol) return false;
    const ProjectionResult r = project(x);
    if (!found(r.status) || std::abs(r.distance) > tol) return false;
  }
  return true;
}

}  // namespace

RigidSurface RigidSurface::from_geometry(const GeometryModel& g, const std::string& name) {
  const GeometryEntity* e = g.find(name);
  if (!e) throw std::invalid_argument("no geometric entity named '" + name + "'");
  if (std::holds_alternative<NurbsCurve>(*e))
    throw std::invalid_argument("'" + name + "' is a curve, not a rigid surface");
  RigidSurface rs;
  for (const Surface* s : g.surfaces_of(name)) rs.add(*s);
  return rs;
}

int RigidSurface::add(const Surface& s) {
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&s)) return add(*n);
  if (const auto* a = dynamic_cast<const AnalyticSurface*>(&s)) return add(*a);
  if (const auto* t = dynamic_cast<const TrimmedSurface*>(&s)) return add(*t);
  throw std::invalid_argument("a rigid surface cannot hold a " + s.type_name());
}

int RigidSurface::push(Piece p) {
  pieces_.push_back(std::move(p));
  box_.extend(pieces_.back().box.lo);
  box_.extend(pieces_.back().box.hi);
  detect_shared_sides();
  reset_index();
  return num_patches() - 1;
}

RigidSurface RigidSurface::piece(int i) const {
  RigidSurface r;
  r.push(pieces_.at(static_cast<std::size_t>(i)));
  return r;
}

int RigidSurface::add(const NurbsSurface& s) {
  Piece p;
  auto proj = std::make_shared<PatchProjector>(s);
  p.surface = std::shared_ptr<const Surface>(proj, &proj->surface());
  p.box = proj->box();
  p.nurbs = std::move(proj);
  return push(std::move(p));
}

Box3 RigidSurface::sampled_box(const Surface& s, const Domain2& d, int n) {
  // Box: sampled over a bounded domain; unbounded pieces get an infinite box.
  Box3 box;
  if (std::isfinite(d.u.lo) && std::isfinite(d.u.hi) && std::isfinite(d.v.lo) &&
      std::isfinite(d.v.hi)) {
    // The bilinear interpolant of the samples lies in their box; the surface is within
    // (h_u^2 |S_uu| + h_v^2 |S_vv|) / 8 of it on each cell (the interpolation error bound),
    // the second derivatives' maximum taken over the samples and doubled for safety.
    const double hu = (d.u.hi - d.u.lo) / n, hv = (d.v.hi - d.v.lo) / n;
    double suu = 0.0, svv = 0.0;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const SurfaceDerivs dd = s.derivs(d.u.lo + hu * i, d.v.lo + hv * j, 2);
        box.extend(dd.S);
        suu = std::max(suu, dd.Suu.norm());
        svv = std::max(svv, dd.Svv.norm());
      }
    const double pad =
        2.0 * (hu * hu * suu + hv * hv * svv) / 8.0 + 1e-12 * (1.0 + (box.hi - box.lo).norm());
    box.lo.array() -= pad;
    box.hi.array() += pad;
  } else {
    box.lo.setConstant(-kInf);
    box.hi.setConstant(kInf);
  }
  return box;
}

int RigidSurface::add(const AnalyticSurface& s) {
  Piece p;
  // Copy the concrete type (the pieces outlive the caller's objects).
  p.surface = std::shared_ptr<const Surface>(s.clone());
  p.box = sampled_box(s, s.domain(), 24);
  return push(std::move(p));
}

int RigidSurface::add(const TrimmedSurface& s) {
  Piece p;
  p.trim = std::make_shared<TrimmedSurface>(s);
  p.surface = p.trim;
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&s.base()))
    p.base_nurbs = std::make_shared<PatchProjector>(*n);
  // The face's boxes: the cells of the base that meet the face (a NURBS base's Bezier
  // elements, bounded by their control nets; an analytic base's cells of an 8 x 8 grid over the
  // loops' rectangle, sampled); the face's box is their union. (The cells cover the loops'
  // rectangle, so the cells the loops cross are never none.)
  const Domain2 d = s.domain();
  if (p.base_nurbs) {
    for (std::size_t e = 0; e < p.base_nurbs->elements().size(); ++e)
      if (s.meets(p.base_nurbs->elements()[e].range))
        p.boxes.push_back(p.base_nurbs->element_boxes()[e]);
  } else {
    const int n = 8;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Domain2 cell{
            {d.u.lo + (d.u.hi - d.u.lo) * i / n, d.u.lo + (d.u.hi - d.u.lo) * (i + 1) / n},
            {d.v.lo + (d.v.hi - d.v.lo) * j / n, d.v.lo + (d.v.hi - d.v.lo) * (j + 1) / n}};
        if (s.meets(cell)) p.boxes.push_back(sampled_box(s.base(), cell, 4));
      }
  }
  for (const Box3& b : p.boxes) {
    p.box.extend(b.lo);
    p.box.extend(b.hi);
  }
  for (const TrimmedSurface::Loop& L : s.loops())
    for (const Vector2d& uv : L) p.rim.emplace_back(s.point(uv[0], uv[1]), uv);
  return push(std::move(p));
}

ProjectionResult RigidSurface::project_trimmed(const Piece& p, const Vector3d& x,
                                               const ProjectionOptions& opt) const {
  const TrimmedSurface& t = *p.trim;
  const Surface& base = t.base();
  ProjectionResult r =
      p.base_nurbs ? p.base_nurbs->project(x, opt)
                   : closest_point_analytic(dynamic_cast<const AnalyticSurface&>(base), x, opt);
  // (A foot held at the base's own domain boundary lies on the loops: the boundary's case.)
  if (r.status == ProjectionStatus::interior && t.inside(r.uv)) return r;
  // The boundary: the nearest point of the edge curves, its uv by a Newton on the base from
  // the nearest loop point.
  const bool planar = dynamic_cast<const Plane*>(&base) != nullptr;
  const bool certified = planar;  // one critical point: outside the loops, the face's minimum is on
                                  // its boundary (the curves' projections are global)
  int iterations = r.iterations;
  double best = kInf;
  Vector3d foot = Vector3d::Zero();
  for (const NurbsCurve& c : t.edges()) {
    const ProjectionResult q = iga::closest_point(c, x);
    iterations += q.iterations;
    if (found(q.status) && (q.point - x).norm() < best) best = (q.point - x).norm(), foot = q.point;
  }
  ProjectionResult out;
  out.status = ProjectionStatus::far;
  out.distance = kInf;
  out.iterations = iterations;
  if (!(best < kInf) || p.rim.empty()) return out;
  const auto nearest =
      std::min_element(p.rim.begin(), p.rim.end(), [&](const auto& a, const auto& b) {
        return (a.first - foot).squaredNorm() < (b.first - foot).squaredNorm();
      });
  const ProjectionResult on_base = closest_point_local(base, foot, nearest->second, opt);
  out.uv = on_base.uv;
  out.point = foot;
  const SurfaceDerivs d = base.derivs(out.uv[0], out.uv[1], 1);
  out.normal = t.normal_sign() * d.Su.cross(d.Sv).normalized();
  out.distance = (x - foot).dot(out.normal) < 0 ? -best : best;
  out.status = ProjectionStatus::edge;
  out.iterations += on_base.iterations;
  out.residual = on_base.residual;
  out.certified = certified;
  return out;
}

void RigidSurface::detect_shared_sides() {
  // A side is shared when sample points along it lie on another piece (or, for a closed
  // direction, when the piece itself is closed there) to within 1e-9 of the model size.
  const double size = std::isfinite((box_.hi - box_.lo).norm()) ? (box_.hi - box_.lo).norm() : 1.0;
  const double tol = 1e-9 * size;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    Piece& p = pieces_[i];
    const Surface& s = *p.surface;
    const Domain2 d = s.domain();
    for (int side = 0; side < 4; ++side) {
      p.shared[side] = side < 2 ? s.closed_u() : s.closed_v();
      if (p.trim || p.shared[side] || !side_is_finite(d, side)) continue;
      const std::vector<Vector3d> pts = side_samples(s, side, 5);
      for (std::size_t j = 0; j < pieces_.size() && !p.shared[side]; ++j) {
        if (j == i) continue;
        p.shared[side] = samples_on_piece(pts, pieces_[j].box, tol, [&](const Vector3d& x) {
          return project_piece(static_cast<int>(j), x, kInf, {});
        });
      }
    }
  }
}

bool RigidSurface::side_shared(int patch, int side) const {
  return pieces_.at(static_cast<std::size_t>(patch)).shared[side];
}

ProjectionResult RigidSurface::project_piece(int i, const Vector3d& x, double max_distance,
                                             const ProjectionOptions& opt) const {
  const Piece& p = pieces_[static_cast<std::size_t>(i)];
  ProjectionResult r;
  if (p.nurbs) {  // unbounded: the near-surface shortcut first (a certified Newton), if it holds
    r = std::isinf(max_distance) ? p.nurbs->project(x, opt)
                                 : p.nurbs->project_within(x, max_distance, opt);
  } else {
    r = p.trim ? project_trimmed(p, x, opt)
               : closest_point_analytic(static_cast<const AnalyticSurface&>(*p.surface), x, opt);
    if (std::abs(r.distance) > max_distance) {
      r.status = ProjectionStatus::far;
      r.distance = kInf;
    }
  }
  r.patch = i;
  return r;
}

void RigidSurface::union_status(ProjectionResult& r) const {
  if (r.status != ProjectionStatus::edge && r.status != ProjectionStatus::vertex) return;
  const Piece& p = pieces_[static_cast<std::size_t>(r.patch)];
  if (p.trim) return;  // a trimmed face's boundary is its own (loops, not sides)
  const Domain2 d = p.surface->domain();
  int free_sides = 0;
  const bool on[4] = {r.uv[0] <= d.u.lo, r.uv[0] >= d.u.hi, r.uv[1] <= d.v.lo, r.uv[1] >= d.v.hi};
  for (int side = 0; side < 4; ++side) free_sides += on[side] && !p.shared[side];
  r.status = free_sides == 0   ? ProjectionStatus::interior
             : free_sides == 1 ? ProjectionStatus::edge
                               : ProjectionStatus::vertex;
}

ProjectionResult RigidSurface::closest_point_within(const Vector3d& x, double max_distance,
                                                    const ProjectionOptions& opt) const {
  // Pieces in the order of their box distance; each one's search is bounded by the best so far.
  thread_local std::vector<std::pair<double, int>> order;
  order.clear();
  for (int i = 0; i < num_patches(); ++i) {
    const double lb = box_distance(pieces_[static_cast<std::size_t>(i)].box, x);
    if (lb <= max_distance) order.emplace_back(lb, i);
  }
  std::sort(order.begin(), order.end());
  ProjectionResult best;
  best.status = ProjectionStatus::far;
  best.distance = kInf;
  double best_d = max_distance;
  int iterations = 0;
  for (const auto& [lb, i] : order) {
    if (lb > best_d) break;
    const ProjectionResult r = project_piece(i, x, best_d, opt);
    iterations += r.iterations;
    if (r.status == ProjectionStatus::far) continue;
    const double d = (r.point - x).norm();
    if (d > max_distance) continue;
    // Ties (a point over a shared edge) keep the first piece: no jumping between patches.
    if (best.status == ProjectionStatus::far || d < best_d * (1.0 - 1e-12)) {
      best_d = d;
      best = r;
    }
  }
  best.iterations = iterations;
  union_status(best);
  return best;
}

ProjectionResult RigidSurface::closest_point(const Vector3d& x,
                                             const ProjectionOptions& opt) const {
  return closest_point_within(x, kInf, opt);
}

ProjectionResult RigidSurface::closest_point(const Vector3d& x, const ProjectionResult& previous,
                                             const ProjectionOptions& opt) const {
  if (previous.patch < 0 || previous.patch >= num_patches() || !found(previous.status))
    return closest_point(x, opt);
  const Piece& p = pieces_[static_cast<std::size_t>(previous.patch)];
  ProjectionResult r;
  if (p.nurbs)  // certified: the warm answer is checked against the piece's control nets
    r = opt.certify ? p.nurbs->project(x, previous.uv, opt)
                    : closest_point_local(p.nurbs->surface(), x, previous.uv, opt);
  else if (p.trim)
    r = project_trimmed(p, x, opt);
  else
    r = closest_point_analytic(static_cast<const AnalyticSurface&>(*p.surface), x, opt);
  r.patch = previous.patch;
  if (opt.certify && found(r.status)) {
    // The other pieces, each bounded by this answer (ties keep it: no jumping between pieces).
    double best_d = (r.point - x).norm();
    ProjectionResult best = r;
    int iterations = r.iterations;
    for (int i = 0; i < num_patches(); ++i) {
      if (i == previous.patch) continue;
      if (box_distance(pieces_[static_cast<std::size_t>(i)].box, x) > best_d) continue;
      const ProjectionResult q = project_piece(i, x, best_d, opt);
      iterations += q.iterations;
      if (!found(q.status)) continue;
      const double d = (q.point - x).norm();
      if (d < best_d * (1.0 - 1e-12)) {
        best_d = d;
        best = q;
      } else if ((nurbs(i) || trimmed(i)) && !q.certified) {
        best.certified = false;
      }
    }
    best.iterations = iterations;
    union_status(best);
    return best;
  }
  if (r.status == ProjectionStatus::interior) return r;
  // At an edge (possibly shared) or not converged: search all pieces, bounded by this answer.
  const double bound = found(r.status) ? (r.point - x).norm() * (1.0 + 1e-12) : kInf;
  ProjectionResult g = closest_point_within(x, bound, opt);
  g.iterations += r.iterations;
  if (g.status == ProjectionStatus::far) {
    union_status(r);
    return r;
  }
  return g;
}

void RigidSurface::reset_index() {
  // A new index object: copies made before keep theirs (of their pieces).
  index_ = std::make_shared<ElementIndex>();
  for (int i = 0; i < num_patches(); ++i) {
    if (const PatchProjector* P = nurbs(i))
      for (std::size_t e = 0; e < P->element_boxes().size(); ++e) {
        index_->boxes.push_back(P->element_boxes()[e]);
        index_->tags.emplace_back(i, static_cast<int>(e));
      }
    for (const Box3& b : pieces_[static_cast<std::size_t>(i)].boxes) {
      index_->boxes.push_back(b);
      index_->tags.emplace_back(i, -1);
    }
  }
}

const RigidBoxIndex& RigidSurface::element_index(double distance) const {
  ElementIndex& x = *index_;
  const std::lock_guard<std::mutex> lock(x.mutex);
  for (const auto& [d, index] : x.by_distance)
    if (d == distance) return *index;
  x.by_distance.emplace_back(distance, std::make_unique<RigidBoxIndex>(x.boxes, distance));
  return *x.by_distance.back().second;
}

const std::pair<int, int>& RigidSurface::element_tag(int box) const {
  return index_->tags.at(static_cast<std::size_t>(box));
}

const std::vector<Box3>& RigidSurface::element_boxes() const {
  return index_->boxes;
}

std::vector<ProjectionResult> RigidSurface::closest_points(const std::vector<Vector3d>& points,
                                                           double search_distance, bool use_cgal,
                                                           const ProjectionOptions& opt) const {
  // Broad phase: every Bezier element of every NURBS piece, tagged (piece, element).
  const std::vector<std::pair<int, int>>& tag = index_->tags;
  const std::vector<SearchPair> pairs = use_cgal
                                            ? broad_phase(points, index_->boxes, search_distance)
                                            : element_index(search_distance).query(points);
  // Narrow phase: per point, per piece, the projection among the candidate elements; the points
  // in parallel (each its own answer: the same for any number of threads).
  std::vector<ProjectionResult> out(points.size());
  const std::vector<std::size_t> first = first_pair_of_query(pairs, points.size());
  const auto n_points = static_cast<std::ptrdiff_t>(points.size());
#pragma omp parallel for schedule(dynamic, 64) if (n_points >= kParallelQueries)
  for (std::ptrdiff_t qi = 0; qi < n_points; ++qi) {
    const auto q = static_cast<std::size_t>(qi);
    thread_local std::vector<int> ids;
    std::size_t k = first[q];
    const Vector3d& x = points[q];
    ProjectionResult best;
    best.status = ProjectionStatus::far;
    best.distance = kInf;
    double best_d = search_distance;
    auto consider = [&](ProjectionResult r, int piece) {
      r.patch = piece;
      if (r.status == ProjectionStatus::far) return;
      const double d = (r.point - x).norm();
      if (d > search_distance) return;
      if (best.status == ProjectionStatus::far || d < best_d * (1.0 - 1e-12)) best_d = d, best = r;
    };
    // pairs are sorted by query, then by box: the boxes of one piece are contiguous
    while (k < pairs.size() && pairs[k].query == static_cast<int>(q)) {
      const int piece = tag[static_cast<std::size_t>(pairs[k].box)].first;
      ids.clear();
      while (k < pairs.size() && pairs[k].query == static_cast<int>(q) &&
             tag[static_cast<std::size_t>(pairs[k].box)].first == piece)
        ids.push_back(tag[static_cast<std::size_t>(pairs[k++].box)].second);
      consider(nurbs(piece) ? nurbs(piece)->project_among(x, ids, best_d, opt)
                            : project_piece(piece, x, best_d, opt),  // a trimmed face
               piece);
    }
    for (int i = 0; i < num_patches(); ++i)
      if (!nurbs(i) && !trimmed(i) &&
          box_distance(pieces_[static_cast<std::size_t>(i)].box, x) <= best_d)
        consider(project_piece(i, x, best_d, opt), i);
    union_status(best);
    out[q] = best;
  }
  return out;
}

ProjectionResult RigidSurface::ray_piece(int i, const Vector3d& x, const Vector3d& N,
                                         const ProjectionOptions& opt) const {
  const Piece& p = pieces_[static_cast<std::size_t>(i)];
  ProjectionResult r;
  if (p.nurbs) {
    r = ray_project(*p.nurbs, x, N, opt);
  } else if (p.trim) {
    r = p.base_nurbs
            ? ray_project(*p.base_nurbs, x, N, opt)
            : ray_project_analytic(dynamic_cast<const AnalyticSurface&>(p.trim->base()), x, N, opt);
    if (found(r.status) && !p.trim->inside(r.uv)) r.status = ProjectionStatus::miss;
  } else {
    r = ray_project_analytic(static_cast<const AnalyticSurface&>(*p.surface), x, N, opt);
  }
  r.patch = i;
  return r;
}

ProjectionResult RigidSurface::ray(const Vector3d& x, const Vector3d& N,
                                   const ProjectionOptions& opt) const {
  ProjectionResult best;
  best.status = ProjectionStatus::miss;
  bool tangent = false;
  int iterations = 0;
  for (int i = 0; i < num_patches(); ++i) {
    const ProjectionResult r = ray_piece(i, x, N, opt);
    iterations += r.iterations;
    tangent = tangent || r.status == ProjectionStatus::tangent;
    if (found(r.status) && (!found(best.status) || std::abs(r.distance) < std::abs(best.distance)))
      best = r;
  }
  if (!found(best.status) && tangent) best.status = ProjectionStatus::tangent;
  best.iterations = iterations;
  union_status(best);
  return best;
}

}  // namespace iga
