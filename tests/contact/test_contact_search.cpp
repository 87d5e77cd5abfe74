// Tests of the broad phase of the contact search (contact/contact_search.hpp): CGAL
// box_intersection_d and RigidBoxIndex against the brute force on random configurations built
// to hit the closed predicate's boundary cases (points and boxes exactly on, and one ulp
// outside, the faces, edges and corners of the enlarged boxes; flat, line and point boxes;
// duplicate boxes; distance 0 and > 0), hand-checked cases, input validation, and the
// Bezier elements of a subdivided NURBS torus with points on and near the surface: no
// element whose enlarged box contains the point is missed, and the element(s) whose
// parameter rectangle contains the point's (u, v) are always reported.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <random>
#include <stdexcept>
#include <vector>

#include "contact/contact_search.hpp"
#include "geometry/constructions.hpp"
#include "geometry/differential_geometry.hpp"
#include "geometry/refinement.hpp"

namespace iga {
// Readable failure messages for REQUIRE(a == b) on pair vectors (internal linkage, so other
// test files of this executable may define their own).
static std::ostream& operator<<(std::ostream& os, const SearchPair& s) {
  return os << "(" << s.query << ", " << s.box << ")";
}
}  // namespace iga

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_contact_search {

using namespace iga;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Box3 box(const Vector3d& lo, const Vector3d& hi) {
  Box3 b;
  b.lo = lo;
  b.hi = hi;
  return b;
}

bool is_empty(const Box3& b) {
  return (b.lo.array() > b.hi.array()).any();
}

bool sorted_unique(const std::vector<SearchPair>& v) {
  return std::adjacent_find(v.begin(), v.end(), [](const SearchPair& a, const SearchPair& b) {
           return !(a < b);
         }) == v.end();
}

/// A random test world: boxes on a coarse dyadic lattice (exact ties) with zero extents in
/// some directions, some continuous boxes, and duplicates; plus a search distance.
struct World {
  std::vector<Box3> boxes;
  double distance = 0.0;
};

double lattice(std::mt19937& g) {
  return 0.25 * std::uniform_int_distribution<int>(-8, 8)(g);
}

World random_world(std::mt19937& g) {
  World w;
  const int sizes[] = {0, 1, 2, 5, 17, 60, 250};
  const int m = sizes[std::uniform_int_distribution<int>(0, 6)(g)];
  const double extents[] = {0.0, 0.0, 0.25, 0.5, 1.0};
  std::uniform_real_distribution<double> u(-2.0, 2.0), ext(0.0, 1.0), coin(0.0, 1.0);
  for (int e = 0; e < m; ++e) {
    if (coin(g) < 0.02) {  // an empty box: matches nothing
      w.boxes.push_back(Box3{});
      continue;
    }
    if (!w.boxes.empty() && coin(g) < 0.15) {  // duplicate of an earlier box
      w.boxes.push_back(
          w.boxes[std::uniform_int_distribution<std::size_t>(0, w.boxes.size() - 1)(g)]);
      continue;
    }
    Vector3d lo, hi;
    const bool on_lattice = coin(g) < 0.7;
    for (int k = 0; k < 3; ++k) {
      lo[k] = on_lattice ? lattice(g) : u(g);
      const double x = on_lattice ? extents[std::uniform_int_distribution<int>(0, 4)(g)]
                                  : (coin(g) < 0.3 ? 0.0 : ext(g));
      hi[k] = lo[k] + x;
    }
    w.boxes.push_back(box(lo, hi));
  }
  const double distances[] = {0.0, 0.0, 0.25, 0.1, 0.5};
  const int di = std::uniform_int_distribution<int>(0, 5)(g);
  w.distance = di < 5 ? distances[di] : 0.3 * coin(g);
  return w;
}

/// A coordinate at or near a face of the enlarged box e along axis k, computed with the same
/// arithmetic as the library (lo - d, hi + d): the faces, one ulp in or out, or inside.
double near_face(std::mt19937& g, const Box3& b, double d, int k) {
  const double lo = b.lo[k] - d, hi = b.hi[k] + d;
  switch (std::uniform_int_distribution<int>(0, 6)(g)) {
    case 0:
      return lo;
    case 1:
      return hi;
    case 2:
      return std::nextafter(lo, -kInf);  // just outside
    case 3:
      return std::nextafter(hi, kInf);
    case 4:
      return std::nextafter(lo, kInf);  // just inside (or outside a zero-width box)
    case 5:
      return std::nextafter(hi, -kInf);
    default:
      return std::uniform_real_distribution<double>(lo, hi)(g);
  }
}

std::vector<Vector3d> random_points(std::mt19937& g, const World& w) {
  const int sizes[] = {0, 1, 3, 40, 300, 1200};
  const int n = sizes[std::uniform_int_distribution<int>(0, 5)(g)];
  std::uniform_real_distribution<double> u(-2.8, 2.8), coin(0.0, 1.0);
  std::vector<Vector3d> p;
  for (int q = 0; q < n; ++q) {
    const double c = coin(g);
    if (c < 0.2 || w.boxes.empty()) {
      p.emplace_back(u(g), u(g), u(g));
    } else if (c < 0.4) {
      p.emplace_back(lattice(g), lattice(g), lattice(g));
    } else {  // on / near faces, edges and corners of a random enlarged box
      const Box3& b = w.boxes[std::uniform_int_distribution<std::size_t>(0, w.boxes.size() - 1)(g)];
      if (is_empty(b)) {
        p.emplace_back(u(g), u(g), u(g));
        continue;
      }
      p.emplace_back(near_face(g, b, w.distance, 0), near_face(g, b, w.distance, 1),
                     near_face(g, b, w.distance, 2));
    }
    if (!p.empty() && coin(g) < 0.05) p.push_back(p.back());  // duplicate query point
  }
  return p;
}

std::vector<Box3> random_query_boxes(std::mt19937& g, const World& w) {
  const std::vector<Vector3d> a = random_points(g, w);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  const double extents[] = {0.0, 0.0, 0.25, 0.5};
  std::vector<Box3> q;
  for (const Vector3d& lo : a) {
    Vector3d hi = lo;
    for (int k = 0; k < 3; ++k) hi[k] += extents[std::uniform_int_distribution<int>(0, 3)(g)];
    // Sometimes end exactly at a face of an enlarged rigid box, so the boxes only touch.
    if (!w.boxes.empty() && coin(g) < 0.3) {
      const Box3& b = w.boxes[std::uniform_int_distribution<std::size_t>(0, w.boxes.size() - 1)(g)];
      const int k = std::uniform_int_distribution<int>(0, 2)(g);
      if (!is_empty(b)) hi[k] = std::max(lo[k], b.lo[k] - w.distance);
    }
    q.push_back(box(lo, hi));
  }
  return q;
}

}  // namespace

TEST_CASE("broad_phase: hand-checked closed predicate (touching, flat, distance)",
          "[contact][search]") {
  const std::vector<Box3> unit = {box(Vector3d(0, 0, 0), Vector3d(1, 1, 1))};
  const auto hits = [&](const Vector3d& p, double d) {
    const std::vector<SearchPair> r = broad_phase(std::vector<Vector3d>{p}, unit, d);
    CHECK(r == broad_phase_brute_force(std::vector<Vector3d>{p}, unit, d));
    CHECK(r == RigidBoxIndex(unit, d).query(std::vector<Vector3d>{p}));
    return r.size();
  };
  CHECK(hits(Vector3d(0.5, 0.5, 0.5), 0.0) == 1);
  CHECK(hits(Vector3d(1, 1, 1), 0.0) == 1);    // corner: closed
  CHECK(hits(Vector3d(0, 0.5, 1), 0.0) == 1);  // edge
  CHECK(hits(Vector3d(std::nextafter(1.0, 2.0), 0.5, 0.5), 0.0) == 0);
  CHECK(hits(Vector3d(1.5, 1.5, 1.5), 0.5) == 1);  // corner of the enlarged box
  CHECK(hits(Vector3d(1.5, 1.5, std::nextafter(1.5, 2.0)), 0.5) == 0);
  // L-infinity, not Euclidean: (1.3, 1.3, 1.3) is 0.52 from the corner, reported for d = 0.4.
  CHECK(hits(Vector3d(1.3, 1.3, 1.3), 0.4) == 1);

  // Touching boxes: a face, an edge, a corner; and a gap closed by the distance.
  const std::vector<Box3> q = {
      box(Vector3d(1, 0, 0), Vector3d(2, 1, 1)), box(Vector3d(1, 1, 0), Vector3d(2, 2, 1)),
      box(Vector3d(1, 1, 1), Vector3d(2, 2, 2)), box(Vector3d(1.25, 0, 0), Vector3d(2, 1, 1))};
  const std::vector<SearchPair> touching = {{0, 0}, {1, 0}, {2, 0}};
  CHECK(broad_phase(q, unit, 0.0) == touching);
  CHECK(broad_phase_brute_force(q, unit, 0.0) == touching);
  CHECK(RigidBoxIndex(unit, 0.0).query(q) == touching);
  const std::vector<SearchPair> all = {{0, 0}, {1, 0}, {2, 0}, {3, 0}};
  CHECK(broad_phase(q, unit, 0.25) == all);
  CHECK(broad_phase_brute_force(q, unit, 0.25) == all);
}

TEST_CASE("broad_phase: zero-thickness boxes of planar elements", "[contact][search]") {
  // A flat Bezier element in z = 0 (its box has zero extent in z), a line box and a point box.
  const NurbsSurface plane =
      make_plane_patch(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0));
  const Box3 flat = bounding_box(bezier_extract(plane).front());
  REQUIRE(flat.lo.z() == 0.0);
  REQUIRE(flat.hi.z() == 0.0);
  const std::vector<Box3> boxes = {flat, box(Vector3d(0, 0, 0), Vector3d(0, 0, 1)),
                                   box(Vector3d(2, 2, 2), Vector3d(2, 2, 2))};
  const std::vector<Vector3d> on = {Vector3d(0.3, 0.7, 0.0), Vector3d(0, 0, 0), Vector3d(2, 2, 2),
                                    Vector3d(0.5, 0.5, 1e-300)};
  const std::vector<SearchPair> exact = {{0, 0}, {1, 0}, {1, 1}, {2, 2}};
  CHECK(broad_phase(on, boxes, 0.0) == exact);
  CHECK(broad_phase_brute_force(on, boxes, 0.0) == exact);
  CHECK(RigidBoxIndex(boxes, 0.0).query(on) == exact);
  // The tiniest distance makes the slab thick enough for z = 1e-300.
  const std::vector<SearchPair> thick = {{0, 0}, {1, 0}, {1, 1}, {2, 2}, {3, 0}};
  CHECK(broad_phase(on, boxes, 1e-300) == thick);
  CHECK(RigidBoxIndex(boxes, 1e-300).query(on) == thick);
  // Two flat boxes in the same plane, touching along an edge.
  const std::vector<Box3> q = {box(Vector3d(1, 0.2, 0), Vector3d(3, 0.4, 0))};
  CHECK(broad_phase(q, boxes, 0.0) == (std::vector<SearchPair>{{0, 0}}));
}

TEST_CASE("broad_phase: degenerate inputs and validation", "[contact][search]") {
  const std::vector<Box3> boxes = {box(Vector3d(0, 0, 0), Vector3d(1, 1, 1))};
  const std::vector<Vector3d> points = {Vector3d(0.5, 0.5, 0.5)};
  const std::vector<Vector3d> no_points;
  const std::vector<Box3> no_boxes;

  SECTION("empty sets give no pairs") {
    CHECK(broad_phase(no_points, boxes, 1.0).empty());
    CHECK(broad_phase(points, no_boxes, 1.0).empty());
    CHECK(broad_phase(no_points, no_boxes, 0.0).empty());
    CHECK(broad_phase(no_boxes, boxes, 1.0).empty());
    CHECK(broad_phase(boxes, no_boxes, 1.0).empty());
    CHECK(RigidBoxIndex(no_boxes, 1.0).query(points).empty());
    CHECK(RigidBoxIndex().query(points).empty());
    CHECK(RigidBoxIndex(boxes, 1.0).query(no_points).empty());
  }
  SECTION("empty boxes (lo > hi, e.g. a default Box3) match nothing, even enlarged") {
    const std::vector<Box3> with_empty = {Box3{}, boxes[0],
                                          box(Vector3d(1, 1, 1), Vector3d(0, 2, 2))};
    const std::vector<SearchPair> expected = {{0, 1}};
    CHECK(broad_phase(points, with_empty, 10.0) == expected);
    CHECK(broad_phase_brute_force(points, with_empty, 10.0) == expected);
    CHECK(RigidBoxIndex(with_empty, 10.0).query(points) == expected);
    CHECK(broad_phase(with_empty, boxes, 10.0) == (std::vector<SearchPair>{{1, 0}}));
    CHECK(RigidBoxIndex(boxes, 10.0).query(with_empty) == (std::vector<SearchPair>{{1, 0}}));
  }
  SECTION("negative or non-finite distance throws std::invalid_argument") {
    for (double d : {-1e-300, -1.0, kNaN, kInf}) {
      CHECK_THROWS_AS(broad_phase(points, boxes, d), std::invalid_argument);
      CHECK_THROWS_AS(broad_phase(boxes, boxes, d), std::invalid_argument);
      CHECK_THROWS_AS(broad_phase_brute_force(points, boxes, d), std::invalid_argument);
      CHECK_THROWS_AS(broad_phase_brute_force(boxes, boxes, d), std::invalid_argument);
      CHECK_THROWS_AS(RigidBoxIndex(boxes, d), std::invalid_argument);
    }
    CHECK_THROWS_WITH(broad_phase(points, boxes, -3.0), Catch::Contains("got -3"));
  }
  SECTION("non-finite coordinates throw, naming the entry") {
    const std::vector<Vector3d> bad_points = {Vector3d(0, 0, 0), Vector3d(kNaN, 0, 0)};
    CHECK_THROWS_WITH(broad_phase(bad_points, boxes, 0.0), Catch::Contains("points[1]"));
    CHECK_THROWS_AS(broad_phase_brute_force(bad_points, boxes, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(RigidBoxIndex(boxes, 0.0).query(bad_points), std::invalid_argument);
    const std::vector<Box3> bad_boxes = {boxes[0], box(Vector3d(0, 0, 0), Vector3d(kInf, 1, 1))};
    CHECK_THROWS_WITH(broad_phase(points, bad_boxes, 0.0), Catch::Contains("boxes[1]"));
    CHECK_THROWS_AS(broad_phase(bad_boxes, boxes, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(RigidBoxIndex(bad_boxes, 0.0), std::invalid_argument);
    // Overflow of the enlarged box is caught too.
    const std::vector<Box3> huge = {box(Vector3d(0, 0, 0), Vector3d(1.7e308, 1, 1))};
    CHECK_THROWS_AS(broad_phase(points, huge, 1e308), std::invalid_argument);
  }
}

TEST_CASE("broad_phase: CGAL and the grid index equal the brute force on random worlds",
          "[contact][search]") {
  std::mt19937 g(20240611);
  std::size_t total_pairs = 0, boundary_worlds = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const World w = random_world(g);
    const RigidBoxIndex index(w.boxes, w.distance);
    CAPTURE(trial, w.boxes.size(), w.distance);

    const std::vector<Vector3d> points = random_points(g, w);
    const std::vector<SearchPair> ref = broad_phase_brute_force(points, w.boxes, w.distance);
    const std::vector<SearchPair> cgal = broad_phase(points, w.boxes, w.distance);
    REQUIRE(sorted_unique(ref));
    REQUIRE(cgal == ref);
    REQUIRE(index.query(points) == ref);
    total_pairs += ref.size();

    // The point variant is the box variant with zero-extent query boxes.
    std::vector<Box3> as_boxes;
    for (const Vector3d& p : points) as_boxes.push_back(box(p, p));
    REQUIRE(broad_phase(as_boxes, w.boxes, w.distance) == ref);

    const std::vector<Box3> qb = random_query_boxes(g, w);
    const std::vector<SearchPair> ref_b = broad_phase_brute_force(qb, w.boxes, w.distance);
    REQUIRE(sorted_unique(ref_b));
    REQUIRE(broad_phase(qb, w.boxes, w.distance) == ref_b);
    REQUIRE(index.query(qb) == ref_b);
    total_pairs += ref_b.size();
    if (!ref.empty() && ref.size() < points.size() * w.boxes.size()) ++boundary_worlds;
  }
  // The worlds are not trivial: many pairs, and worlds with both hits and misses.
  CHECK(total_pairs > 10000);
  CHECK(boundary_worlds > 100);
}

TEST_CASE("RigidBoxIndex: equals the brute force for widely varying box sizes and clusters",
          "[contact][search]") {
  // Stresses the cell-size rule: tiny clustered boxes plus huge ones, far apart.
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Box3> boxes;
  for (int e = 0; e < 300; ++e) {
    const Vector3d lo(1e-3 * u(g), 1e-3 * u(g), 1e-3 * u(g));
    boxes.push_back(box(lo, lo + Vector3d::Constant(1e-5 * u(g))));
  }
  for (int e = 0; e < 20; ++e) {
    const Vector3d lo(1e3 * u(g), 1e3 * u(g), -1e3 * u(g));
    boxes.push_back(box(lo, lo + Vector3d(5e2 * u(g), 5e2 * u(g), 0.0)));
  }
  std::vector<Vector3d> points;
  for (int q = 0; q < 3000; ++q) {
    const double s = q % 2 == 0 ? 1e-3 : 2e3;
    points.emplace_back(s * u(g), s * u(g), (q % 2 == 0 ? s : -s) * u(g));
  }
  for (const Box3& b : boxes) points.push_back(b.hi);  // corners: certain hits
  for (double d : {0.0, 1e-6, 10.0}) {
    const RigidBoxIndex index(boxes, d);
    const std::array<int, 3> n = index.cells();
    CHECK(static_cast<double>(n[0]) * n[1] * n[2] <= 8.0 * boxes.size() + 64.0);
    const std::vector<SearchPair> ref = broad_phase_brute_force(points, boxes, d);
    CHECK(ref.size() >= boxes.size());
    CHECK(index.query(points) == ref);
    CHECK(broad_phase(points, boxes, d) == ref);
  }
  // Coordinates near the overflow limit: the extent of the union overflows to infinity.
  const std::vector<Box3> far = {box(Vector3d(-1.5e308, 0, 0), Vector3d(-1e308, 1, 1)),
                                 box(Vector3d(1e308, 0, 0), Vector3d(1.5e308, 1, 1)),
                                 box(Vector3d(-1, -1, -1), Vector3d(1, 1, 1))};
  const std::vector<Vector3d> far_points = {Vector3d(-1.2e308, 0.5, 0.5), Vector3d(1.5e308, 1, 1),
                                            Vector3d(0, 0, 0), Vector3d(1e300, 0, 0)};
  const std::vector<SearchPair> far_pairs = {{0, 0}, {1, 1}, {2, 2}};
  CHECK(broad_phase_brute_force(far_points, far, 0.0) == far_pairs);
  CHECK(broad_phase(far_points, far, 0.0) == far_pairs);
  CHECK(RigidBoxIndex(far, 0.0).query(far_points) == far_pairs);
  CHECK(RigidBoxIndex(far, 1e307).query(far_points) ==
        broad_phase_brute_force(far_points, far, 1e307));

  // All boxes in one point: a single cell.
  const std::vector<Box3> same(10, box(Vector3d(1, 2, 3), Vector3d(1, 2, 3)));
  const RigidBoxIndex one(same, 0.0);
  CHECK(one.cells() == (std::array<int, 3>{1, 1, 1}));
  std::vector<int> hits;
  one.query(Vector3d(1, 2, 3), hits);
  CHECK(hits.size() == 10);
}

TEST_CASE("broad_phase: torus elements, points on and near the surface, nothing missed",
          "[contact][search]") {
  constexpr double R = 2.0, r = 0.5;
  const NurbsSurface torus =
      subdivide(make_torus(Vector3d(0.1, -0.2, 0.3), Vector3d(1, 1, 2), R, r), 3, 2);
  const std::vector<BezierPatch> patches = bezier_extract(torus);
  REQUIRE(patches.size() == 96);  // 4 x 4 quadratic elements, subdivided 3 x 2
  std::vector<Box3> boxes;
  for (const BezierPatch& b : patches) boxes.push_back(bounding_box(b));

  std::mt19937 g(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const Domain2 D = torus.domain();
  // Knot lines (element boundaries) as parameters too: the point then lies on 2 or 4 elements.
  std::vector<double> knots_u, knots_v;
  for (const BezierPatch& b : patches) {
    knots_u.push_back(b.range.u.lo);
    knots_v.push_back(b.range.v.lo);
  }
  const auto param = [&](const Interval& I, const std::vector<double>& knots) {
    if (u01(g) < 0.2)
      return knots[std::uniform_int_distribution<std::size_t>(0, knots.size() - 1)(g)];
    return I.lo + u01(g) * (I.hi - I.lo);
  };

  // Round-off margin: the surface point and the control-point boxes are computed along
  // different paths (evaluation vs. knot insertion), both to ~1e-15 relative.
  constexpr double tol = 1e-10;
  for (double h : {0.0, 0.01, 0.1}) {
    const double d = h + tol;
    std::vector<Vector3d> points;
    std::vector<Vector2d> uv;
    for (int q = 0; q < 2000; ++q) {
      const double u = param(D.u, knots_u), v = param(D.v, knots_v);
      const SurfaceDerivs sd = torus.derivs(u, v, 1);
      const double t = h * (2.0 * u01(g) - 1.0);  // |offset| <= h along the normal
      points.push_back(sd.S + t * surface_frame(sd).n);
      uv.emplace_back(u, v);
    }
    const std::vector<SearchPair> pairs = broad_phase(points, boxes, d);
    REQUIRE(pairs == broad_phase_brute_force(points, boxes, d));
    REQUIRE(pairs == RigidBoxIndex(boxes, d).query(points));

    // Per query: every element whose enlarged box contains the point (computed here,
    // independently) is reported, and so is every element containing the parameter.
    std::vector<std::vector<int>> found(points.size());
    for (const SearchPair& s : pairs) found[static_cast<std::size_t>(s.query)].push_back(s.box);
    std::size_t missed = 0, missed_param = 0;
    for (std::size_t q = 0; q < points.size(); ++q) {
      const auto reported = [&](int e) {
        return std::binary_search(found[q].begin(), found[q].end(), e);
      };
      for (std::size_t e = 0; e < boxes.size(); ++e) {
        const Vector3d lo = boxes[e].lo.array() - d, hi = boxes[e].hi.array() + d;
        const bool inside =
            (lo.array() <= points[q].array()).all() && (points[q].array() <= hi.array()).all();
        if (inside && !reported(static_cast<int>(e))) ++missed;
        const Domain2& P = patches[e].range;
        const bool has_param = P.u.lo <= uv[q].x() && uv[q].x() <= P.u.hi && P.v.lo <= uv[q].y() &&
                               uv[q].y() <= P.v.hi;
        if (has_param && !reported(static_cast<int>(e))) ++missed_param;
      }
    }
    CAPTURE(h);
    CHECK(missed == 0);
    CHECK(missed_param == 0);
    // A useful broad phase: on average far fewer candidates than elements.
    CHECK(static_cast<double>(pairs.size()) / static_cast<double>(points.size()) < 12.0);
  }
}

}  // namespace test_contact_search
