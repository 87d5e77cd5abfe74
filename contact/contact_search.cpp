// Broad phase of the contact search with CGAL's box_intersection_d, the uniform-grid
// RigidBoxIndex, and the brute-force references. See contact_search.hpp for the predicate and
// the conventions.
// References: [ZE02] A. Zomorodian, H. Edelsbrunner, Fast software for box intersections,
// Int. J. Comput. Geom. Appl. 12 (2002) 143-172 (the hybrid streamed segment tree that
// CGAL::box_intersection_d implements); [CGAL] L. Kettner, A. Meyer, A. Zomorodian,
// Intersecting Sequences of dD Iso-oriented Boxes, CGAL 5.5 User and Reference Manual;
// [Eri05] C. Ericson, Real-Time Collision Detection, Sect. 7.1 (uniform grids).
#include "contact/contact_search.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <CGAL/box_intersection_d.h>

namespace iga {

std::vector<std::size_t> first_pair_of_query(const std::vector<SearchPair>& pairs,
                                             std::size_t n_queries) {
  std::vector<std::size_t> first(n_queries + 1, pairs.size());
  std::size_t k = 0;
  for (std::size_t q = 0; q < n_queries; ++q) {
    while (k < pairs.size() && pairs[k].query < static_cast<int>(q)) ++k;
    first[q] = k;
  }
  return first;
}

namespace {

// ---- input checks -----------------------------------------------------------------------

void check_distance(const char* where, double distance) {
  if (!(distance >= 0.0) || !std::isfinite(distance)) {
    std::ostringstream msg;
    msg << where << ": distance must be finite and >= 0, got " << distance;
    throw std::invalid_argument(msg.str());
  }
}

void check_count(const char* where, const char* what, std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    std::ostringstream msg;
    msg << where << ": " << what << ": at most " << std::numeric_limits<int>::max()
        << " entries (SearchPair holds int indices), got " << n;
    throw std::invalid_argument(msg.str());
  }
}

[[noreturn]] void throw_not_finite(const char* where, const char* what, std::size_t i,
                                   const Vector3d& lo, const Vector3d& hi) {
  std::ostringstream msg;
  msg << where << ": " << what << "[" << i << "]: coordinates must be finite, got lo = ("
      << lo.transpose() << "), hi = (" << hi.transpose() << ")";
  throw std::invalid_argument(msg.str());
}

bool is_finite(const Vector3d& x) {
  return x.allFinite();
}

/// A box with lo(k) > hi(k) in some direction (e.g. a default Box3) is empty. NaN is not
/// empty: the caller rejects it as not finite.
bool is_empty(const Box3& b) {
  return (b.lo.array() > b.hi.array()).any();
}

/// The rigid box enlarged by d, or nothing for an empty box. The enlarged bounds are the
/// only numbers the predicate compares, so the CGAL and brute-force paths agree bit for bit.
/// Throws on non-finite (NaN, infinite, or overflowing) bounds.
bool enlarged(const char* where, const Box3& b, double d, std::size_t i, Box3& out) {
  if (!is_finite(b.lo) || !is_finite(b.hi)) {
    if (!b.lo.hasNaN() && !b.hi.hasNaN() && is_empty(b)) return false;
    throw_not_finite(where, "boxes", i, b.lo, b.hi);
  }
  if (is_empty(b)) return false;
  out.lo = b.lo.array() - d;
  out.hi = b.hi.array() + d;
  if (!is_finite(out.lo) || !is_finite(out.hi)) throw_not_finite(where, "boxes", i, out.lo, out.hi);
  return true;
}

/// A query box as given, or nothing if empty; throws on non-finite bounds.
bool query_box(const char* where, const Box3& b, std::size_t i) {
  if (!is_finite(b.lo) || !is_finite(b.hi)) {
    if (!b.lo.hasNaN() && !b.hi.hasNaN() && is_empty(b)) return false;
    throw_not_finite(where, "query_boxes", i, b.lo, b.hi);
  }
  return !is_empty(b);
}

void check_point(const char* where, const Vector3d& p, std::size_t i) {
  if (!is_finite(p)) throw_not_finite(where, "points", i, p, p);
}

/// The closed predicate: [a.lo, a.hi] and [b.lo, b.hi] share a point in every direction.
/// Touching boxes and zero-extent boxes count.
bool closed_overlap(const Box3& a, const Box3& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}
bool closed_contains(const Box3& b, const Vector3d& p) {
  return (b.lo.array() <= p.array()).all() && (p.array() <= b.hi.array()).all();
}

// ---- CGAL adapter -----------------------------------------------------------------------

/// The box handle CGAL reorders. id = 2 q for the query sequence and 2 e + 1 for the rigid
/// boxes: box_intersection_d breaks ties of equal lower bounds by id and skips pairs of
/// equal id, so ids must be distinct across both sequences (plain indices would silently
/// drop the pairs (q, q)).
struct CgalBox {
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};
  std::size_t id = 0;
};

struct CgalBoxTraits {
  using Box_parameter = const CgalBox&;
  using NT = double;
  using ID = std::size_t;
  static NT min_coord(Box_parameter b, int k) { return b.lo[static_cast<std::size_t>(k)]; }
  static NT max_coord(Box_parameter b, int k) { return b.hi[static_cast<std::size_t>(k)]; }
  static ID id(Box_parameter b) { return b.id; }
  static int dimension() { return 3; }
};

CgalBox make_cgal_box(const Vector3d& lo, const Vector3d& hi, std::size_t id) {
  return CgalBox{{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}, id};
}

/// Below this many boxes in a segment-tree node, box_intersection_d scans instead of
/// recursing ([CGAL] "cutoff"). CGAL's default; 30, 100, 300 measured with
/// bench_contact_search were within the noise (+-10 %), 1000 and more slower.
constexpr std::ptrdiff_t kCutoff = 10;

/// Sort pairs by (query, box): a counting sort on the query, then a small sort per query.
void sort_pairs(std::vector<SearchPair>& pairs, std::size_t n_queries) {
  std::vector<std::size_t> start(n_queries + 1, 0);
  for (const SearchPair& s : pairs) ++start[static_cast<std::size_t>(s.query) + 1];
  for (std::size_t q = 0; q < n_queries; ++q) start[q + 1] += start[q];
  std::vector<SearchPair> sorted(pairs.size());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (const SearchPair& s : pairs) sorted[next[static_cast<std::size_t>(s.query)]++] = s;
  for (std::size_t q = 0; q < n_queries; ++q) {
    const auto first = sorted.begin() + static_cast<std::ptrdiff_t>(start[q]);
    const auto last = sorted.begin() + static_cast<std::ptrdiff_t>(start[q + 1]);
    std::sort(first, last);
  }
  pairs.swap(sorted);
}

/// Bipartite, closed box_intersection_d of the queries (even ids) against the rigid boxes
/// (odd ids); both vectors are reordered. Returns the sorted pairs.
std::vector<SearchPair> intersect(std::vector<CgalBox>& queries, std::vector<CgalBox>& rigid,
                                  std::size_t n_queries) {
  std::vector<SearchPair> pairs;
  if (queries.empty() || rigid.empty()) return pairs;
  // The callback is copied by CGAL: it holds a pointer to the output.
  std::vector<SearchPair>* out = &pairs;
  auto report = [out](const CgalBox& q, const CgalBox& e) {
    assert(q.id % 2 == 0 && e.id % 2 == 1);
    out->push_back(SearchPair{static_cast<int>(q.id / 2), static_cast<int>(e.id / 2)});
  };
  CGAL::box_intersection_d(queries.begin(), queries.end(), rigid.begin(), rigid.end(), report,
                           CgalBoxTraits(), kCutoff, CGAL::Box_intersection_d::CLOSED,
                           CGAL::Box_intersection_d::BIPARTITE);
  sort_pairs(pairs, n_queries);
  return pairs;
}

std::vector<CgalBox> rigid_cgal_boxes(const char* where, const std::vector<Box3>& boxes,
                                      double distance) {
  std::vector<CgalBox> rigid;
  rigid.reserve(boxes.size());
  Box3 e;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (enlarged(where, boxes[i], distance, i, e))
      rigid.push_back(make_cgal_box(e.lo, e.hi, 2 * i + 1));
  return rigid;
}

}  // namespace

// ---- CGAL broad phase -------------------------------------------------------------------

namespace {

/// The broad phase of `queries` (named `what` in errors) against `boxes`: query_box(q, i, out)
/// checks query i and sets out to its CGAL box, or returns false to leave it out.
template <class Query, class QueryBox>
std::vector<SearchPair> broad_phase_of(const char* where, const char* what,
                                       const std::vector<Query>& queries,
                                       const std::vector<Box3>& boxes, double distance,
                                       QueryBox query_box) {
  check_distance(where, distance);
  check_count(where, what, queries.size());
  check_count(where, "boxes", boxes.size());
  std::vector<CgalBox> rigid = rigid_cgal_boxes(where, boxes, distance);
  std::vector<CgalBox> cgal;
  cgal.reserve(queries.size());
  CgalBox b;
  for (std::size_t q = 0; q < queries.size(); ++q)
    if (query_box(queries[q], q, b)) cgal.push_back(b);
  return intersect(cgal, rigid, queries.size());
}

}  // namespace

std::vector<SearchPair> broad_phase(const std::vector<Vector3d>& points,
                                    const std::vector<Box3>& boxes, double distance) {
  constexpr const char* where = "broad_phase(points, boxes)";
  return broad_phase_of(where, "points", points, boxes, distance,
                        [where](const Vector3d& p, std::size_t q, CgalBox& b) {
                          check_point(where, p, q);
                          b = make_cgal_box(p, p, 2 * q);  // zero-extent box
                          return true;
                        });
}

std::vector<SearchPair> broad_phase(const std::vector<Box3>& query_boxes,
                                    const std::vector<Box3>& boxes, double distance) {
  constexpr const char* where = "broad_phase(query_boxes, boxes)";
  return broad_phase_of(where, "query_boxes", query_boxes, boxes, distance,
                        [where](const Box3& box, std::size_t q, CgalBox& b) {
                          if (!query_box(where, box, q)) return false;
                          b = make_cgal_box(box.lo, box.hi, 2 * q);
                          return true;
                        });
}

// ---- RigidBoxIndex: uniform grid ([Eri05] Sect. 7.1) -------------------------------------
//
// Correctness does not depend on the cell size: cell(x, k) = clamp(floor((x - lo_k) / h_k))
// is a non-decreasing function of x (subtraction, multiplication by a positive number and
// floor are monotone under round-to-nearest, overflow to +-inf included), so
// lo_e <= x <= hi_e implies cell(lo_e) <= cell(x) <= cell(hi_e): a box containing the point
// is registered in the point's cell. The exact closed predicate then decides, as in
// broad_phase. If the extent along k is 0 or overflows, 1 / h_k = 0 and there is one cell.

namespace {

/// Cell size = kCellFactor * median largest extent of the enlarged boxes (bench_contact_search,
/// 1e5 points x 1024 torus elements: 0.25 -> 11.6 ms, 0.35 -> 11.2 ms, 0.5 -> 13.5 ms,
/// 1.0 -> ~20 ms); then enlarged by kGrowth while the
/// grid exceeds min(kCellsPerBox * m + kMinCells, kMaxCells) cells or
/// kRegistrationsPerBox * m + kMinCells registrations (box-cell incidences), which bounds
/// the memory for any input.
constexpr double kCellFactor = 0.35;
constexpr double kGrowth = 1.25;
constexpr double kCellsPerBox = 8.0;
constexpr double kRegistrationsPerBox = 32.0;
constexpr double kMinCells = 64.0;
constexpr double kMaxCells = 67108864.0;  ///< 2^26: 256 MB of cell offsets at most

/// Cells along an extent ext for the cell size h (>= 1; 1 for a zero or overflowing extent).
double cells_along(double ext, double h) {
  if (!(ext > 0.0) || !std::isfinite(ext) || !(h > 0.0)) return 1.0;
  return std::max(1.0, std::ceil(ext / h));
}

/// The enlarged boxes (empty ones stay empty: they match nothing), their union, the indices of
/// the non-empty ones and the largest extent of each of those.
void enlarge_boxes(const char* where, const std::vector<Box3>& boxes, double distance,
                   std::vector<Box3>& enlarged_boxes, Box3& all, std::vector<int>& valid,
                   std::vector<double>& largest) {
  const std::size_t m = boxes.size();
  enlarged_boxes.assign(m, Box3{});
  for (std::size_t e = 0; e < m; ++e) {
    Box3 b;
    if (!enlarged(where, boxes[e], distance, e, b)) continue;
    enlarged_boxes[e] = b;
    all.extend(b.lo);
    all.extend(b.hi);
    valid.push_back(static_cast<int>(e));
    largest.push_back((b.hi - b.lo).maxCoeff());
  }
}

/// The starting cell size: kCellFactor times the median of `largest` (reordered), or, when
/// all boxes are degenerate, the size giving about one cell per box over the extent ext.
double initial_cell_size(std::vector<double>& largest, const Vector3d& ext, double n_valid) {
  const auto mid = largest.begin() + static_cast<std::ptrdiff_t>(largest.size() / 2);
  std::nth_element(largest.begin(), mid, largest.end());
  double h = kCellFactor * *mid;
  if (!(h > 0.0)) h = ext.maxCoeff() / std::cbrt(n_valid);  // all boxes degenerate
  return h;
}

/// Calls visit(x, y, z) for the cells (z outer, x inner) of the box b, with cell(x, k) the
/// cell index of the coordinate x along axis k.
template <class Cell, class Visit>
void for_each_cell(const Box3& b, const Cell& cell, Visit&& visit) {
  const int x0 = cell(b.lo.x(), 0), x1 = cell(b.hi.x(), 0);
  const int y0 = cell(b.lo.y(), 1), y1 = cell(b.hi.y(), 1);
  const int z0 = cell(b.lo.z(), 2), z1 = cell(b.hi.z(), 2);
  for (int z = z0; z <= z1; ++z)
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) visit(x, y, z);
}

/// Box-cell incidences of the boxes `valid` of `boxes`, with cell(x, k) as in for_each_cell.
template <class Cell>
double count_registrations(const std::vector<int>& valid, const std::vector<Box3>& boxes,
                           const Cell& cell) {
  double registrations = 0.0;
  for (int e : valid) {
    const Box3& b = boxes[static_cast<std::size_t>(e)];
    double r = 1.0;
    for (int k = 0; k < 3; ++k) r *= cell(b.hi[k], k) - cell(b.lo[k], k) + 1;
    registrations += r;
  }
  return registrations;
}

}  // namespace

RigidBoxIndex::RigidBoxIndex(const std::vector<Box3>& boxes, double distance)
    : distance_(distance) {
  constexpr const char* where = "RigidBoxIndex";
  check_distance(where, distance);
  check_count(where, "boxes", boxes.size());
  std::vector<int> valid;
  std::vector<double> largest;
  enlarge_boxes(where, boxes, distance, enlarged_, all_, valid, largest);
  if (valid.empty()) return;  // n_ = 0: every query is empty

  const Vector3d ext = all_.hi - all_.lo;
  const double n_valid = static_cast<double>(valid.size());
  double h = initial_cell_size(largest, ext, n_valid);
  const auto cell_of = [this](double x, int k) { return cell(x, k); };

  // Grow h until the cell and registration counts are O(m); at h >= max extent there is a
  // single cell and m registrations, so the loop ends.
  const double max_cells = std::min(kCellsPerBox * n_valid + kMinCells, kMaxCells);
  const double max_registrations =  // int offsets; m <= INT_MAX keeps the loop finite
      std::min(kRegistrationsPerBox * n_valid + kMinCells,
               static_cast<double>(std::numeric_limits<int>::max()));
  for (;; h *= kGrowth) {
    std::array<double, 3> n{};
    for (int k = 0; k < 3; ++k) n[static_cast<std::size_t>(k)] = cells_along(ext[k], h);
    if (!(n[0] * n[1] * n[2] <= max_cells)) continue;
    for (int k = 0; k < 3; ++k) {
      n_[static_cast<std::size_t>(k)] = static_cast<int>(n[static_cast<std::size_t>(k)]);
      inv_h_[k] =
          ext[k] > 0.0 && std::isfinite(ext[k]) ? n[static_cast<std::size_t>(k)] / ext[k] : 0.0;
    }
    if (count_registrations(valid, enlarged_, cell_of) <= max_registrations) break;
  }

  // Compressed rows: count, prefix sums, scatter in box order (ascending within a cell).
  const std::size_t n_cells = static_cast<std::size_t>(n_[0]) * static_cast<std::size_t>(n_[1]) *
                              static_cast<std::size_t>(n_[2]);
  start_.assign(n_cells + 1, 0);
  for (int e : valid)
    for_each_cell(enlarged_[static_cast<std::size_t>(e)], cell_of,
                  [this](int x, int y, int z) { ++start_[cell_id(x, y, z) + 1]; });
  for (std::size_t c = 0; c < n_cells; ++c) start_[c + 1] += start_[c];
  items_.resize(static_cast<std::size_t>(start_[n_cells]));
  std::vector<int> next(start_.begin(), start_.end() - 1);
  for (int e : valid)
    for_each_cell(enlarged_[static_cast<std::size_t>(e)], cell_of, [&](int x, int y, int z) {
      items_[static_cast<std::size_t>(next[cell_id(x, y, z)]++)] = e;
    });
}

std::size_t RigidBoxIndex::cell_id(int x, int y, int z) const {
  return static_cast<std::size_t>(x) +
         static_cast<std::size_t>(n_[0]) *
             (static_cast<std::size_t>(y) +
              static_cast<std::size_t>(n_[1]) * static_cast<std::size_t>(z));
}

int RigidBoxIndex::cell(double x, int k) const {
  const std::size_t kk = static_cast<std::size_t>(k);
  const double t = std::floor((x - all_.lo[k]) * inv_h_[k]);
  if (!(t > 0.0)) return 0;
  const double last = static_cast<double>(n_[kk] - 1);
  return t >= last ? n_[kk] - 1 : static_cast<int>(t);
}

void RigidBoxIndex::candidates(const Vector3d& p, std::vector<int>& out) const {
  if (n_[0] == 0 || !closed_contains(all_, p)) return;  // outside every enlarged box
  const std::size_t c = cell_id(cell(p.x(), 0), cell(p.y(), 1), cell(p.z(), 2));
  for (int i = start_[c]; i < start_[c + 1]; ++i) {
    const int e = items_[static_cast<std::size_t>(i)];
    if (closed_contains(enlarged_[static_cast<std::size_t>(e)], p)) out.push_back(e);
  }
}

void RigidBoxIndex::query(const Vector3d& p, std::vector<int>& out) const {
  if (!is_finite(p)) {
    std::ostringstream msg;
    msg << "RigidBoxIndex::query: point coordinates must be finite, got (" << p.transpose() << ")";
    throw std::invalid_argument(msg.str());
  }
  candidates(p, out);
}

std::vector<SearchPair> RigidBoxIndex::query(const std::vector<Vector3d>& points) const {
  constexpr const char* where = "RigidBoxIndex::query(points)";
  check_count(where, "points", points.size());
  std::vector<SearchPair> pairs;
  std::vector<int> hits;
  for (std::size_t q = 0; q < points.size(); ++q) {
    check_point(where, points[q], q);
    hits.clear();
    candidates(points[q], hits);
    for (int e : hits) pairs.push_back(SearchPair{static_cast<int>(q), e});
  }
  return pairs;
}

std::vector<SearchPair> RigidBoxIndex::query(const std::vector<Box3>& query_boxes) const {
  constexpr const char* where = "RigidBoxIndex::query(query_boxes)";
  check_count(where, "query_boxes", query_boxes.size());
  std::vector<char> nonempty(query_boxes.size());
  for (std::size_t q = 0; q < query_boxes.size(); ++q)
    nonempty[q] = query_box(where, query_boxes[q], q);
  std::vector<SearchPair> pairs;
  if (n_[0] == 0) return pairs;
  // seen[e] == q: box e was already tested for query q (it is registered in several cells).
  std::vector<int> seen(enlarged_.size(), -1);
  for (std::size_t q = 0; q < query_boxes.size(); ++q) {
    const Box3& b = query_boxes[q];
    if (!nonempty[q] || !closed_overlap(b, all_)) continue;
    const std::size_t first = pairs.size();
    const int x0 = cell(b.lo.x(), 0), x1 = cell(b.hi.x(), 0);
    const int y0 = cell(b.lo.y(), 1), y1 = cell(b.hi.y(), 1);
    const int z0 = cell(b.lo.z(), 2), z1 = cell(b.hi.z(), 2);
    for (int z = z0; z <= z1; ++z)
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const std::size_t c = cell_id(x, y, z);
          for (int i = start_[c]; i < start_[c + 1]; ++i) {
            const int e = items_[static_cast<std::size_t>(i)];
            if (seen[static_cast<std::size_t>(e)] == static_cast<int>(q)) continue;
            seen[static_cast<std::size_t>(e)] = static_cast<int>(q);
            if (closed_overlap(b, enlarged_[static_cast<std::size_t>(e)]))
              pairs.push_back(SearchPair{static_cast<int>(q), e});
          }
        }
    std::sort(pairs.begin() + static_cast<std::ptrdiff_t>(first), pairs.end());
  }
  return pairs;
}

// ---- brute force ------------------------------------------------------------------------

namespace {

/// The rigid boxes of a brute-force reference, enlarged by the distance; valid[e] is 0 for an
/// empty box.
struct EnlargedBoxes {
  std::vector<Box3> box;
  std::vector<char> valid;
};

/// The set-up both brute-force references share, in this order: the distance and the counts
/// checked (`queries` names the query vector in the message), then the rigid boxes enlarged.
EnlargedBoxes brute_force_setup(const char* where, const char* queries, std::size_t n_queries,
                                const std::vector<Box3>& boxes, double distance) {
  check_distance(where, distance);
  check_count(where, queries, n_queries);
  check_count(where, "boxes", boxes.size());
  EnlargedBoxes rigid{std::vector<Box3>(boxes.size()), std::vector<char>(boxes.size())};
  for (std::size_t e = 0; e < boxes.size(); ++e)
    rigid.valid[e] = enlarged(where, boxes[e], distance, e, rigid.box[e]);
  return rigid;
}

}  // namespace

std::vector<SearchPair> broad_phase_brute_force(const std::vector<Vector3d>& points,
                                                const std::vector<Box3>& boxes, double distance) {
  constexpr const char* where = "broad_phase_brute_force(points, boxes)";
  const EnlargedBoxes rigid = brute_force_setup(where, "points", points.size(), boxes, distance);
  std::vector<SearchPair> pairs;
  for (std::size_t q = 0; q < points.size(); ++q) {
    check_point(where, points[q], q);
    for (std::size_t e = 0; e < boxes.size(); ++e)
      if (rigid.valid[e] && closed_contains(rigid.box[e], points[q]))
        pairs.push_back(SearchPair{static_cast<int>(q), static_cast<int>(e)});
  }
  return pairs;
}

std::vector<SearchPair> broad_phase_brute_force(const std::vector<Box3>& query_boxes,
                                                const std::vector<Box3>& boxes, double distance) {
  constexpr const char* where = "broad_phase_brute_force(query_boxes, boxes)";
  const EnlargedBoxes rigid =
      brute_force_setup(where, "query_boxes", query_boxes.size(), boxes, distance);
  std::vector<SearchPair> pairs;
  for (std::size_t q = 0; q < query_boxes.size(); ++q) {
    if (!query_box(where, query_boxes[q], q)) continue;
    for (std::size_t e = 0; e < boxes.size(); ++e)
      if (rigid.valid[e] && closed_overlap(query_boxes[q], rigid.box[e]))
        pairs.push_back(SearchPair{static_cast<int>(q), static_cast<int>(e)});
  }
  return pairs;
}

}  // namespace iga
