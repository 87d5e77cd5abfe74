// Tests that knot insertion, refinement, degree elevation and Bezier extraction leave the
// geometry unchanged ([PT97] Ch. 5).
#include <catch2/catch.hpp>

#include <random>

#include "geometry/refinement.hpp"
#include "tests/support/random_nurbs.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_refinement {

using namespace iga;

namespace {
double max_curve_diff(const NurbsCurve& a, const NurbsCurve& b, int samples = 2000) {
  double e = 0.0;
  for (int k = 0; k <= samples; ++k) {
    const double u = static_cast<double>(k) / samples;
    e = std::max(e, (a.point(u) - b.point(u)).norm());
  }
  return e;
}
double max_surface_diff(const NurbsSurface& a, const NurbsSurface& b, int samples = 60) {
  double e = 0.0;
  for (int i = 0; i <= samples; ++i)
    for (int j = 0; j <= samples; ++j) {
      const double u = static_cast<double>(i) / samples, v = static_cast<double>(j) / samples;
      e = std::max(e, (a.point(u, v) - b.point(u, v)).norm());
    }
  return e;
}
Vector3d rational_bernstein(const std::vector<Vector4d>& pw, double t) {
  std::vector<Vector4d> q = pw;
  for (std::size_t r = 1; r < q.size(); ++r)
    for (std::size_t i = 0; i + r < q.size(); ++i) q[i] = (1 - t) * q[i] + t * q[i + 1];
  return q[0].head<3>() / q[0].w();
}
}  // namespace

TEST_CASE("insert_knot: geometry unchanged, multiplicity raised", "[geometry][refine]") {
  std::mt19937 rng(21);
  for (int p = 1; p <= 5; ++p) {
    const NurbsCurve c = test::random_curve(rng, p, p + 6, true);
    const double u = 0.37;
    const NurbsCurve c1 = insert_knot(c, u, p);
    CHECK(c1.num_control_points() == c.num_control_points() + p);
    CHECK(c1.knots().multiplicity(u) == c.knots().multiplicity(u) + p);
    CHECK(max_curve_diff(c, c1) <= 1e-13);
  }
}

TEST_CASE("refine_knots: random refinement of curves and surfaces leaves geometry unchanged",
          "[geometry][refine]") {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unif(0.01, 0.99);
  for (int p = 1; p <= 5; ++p) {
    const NurbsCurve c = test::random_curve(rng, p, p + 4, true, p);
    std::vector<double> X;
    for (int k = 0; k < 12; ++k) X.push_back(unif(rng));
    std::sort(X.begin(), X.end());
    const NurbsCurve r = refine_knots(c, X);
    CHECK(r.num_control_points() == c.num_control_points() + 12);
    CHECK(max_curve_diff(c, r) <= 1e-13);

    const NurbsSurface s = test::random_surface(rng, p, std::max(1, 4 - p), p + 3, 5, true);
    const NurbsSurface sr = subdivide(s, 3, 2);
    CHECK(sr.knots_u().num_elements() == 3 * s.knots_u().num_elements());
    CHECK(sr.knots_v().num_elements() == 2 * s.knots_v().num_elements());
    CHECK(max_surface_diff(s, sr) <= 1e-13);
  }
}

TEST_CASE("elevate_degree: geometry unchanged, continuity kept", "[geometry][refine]") {
  std::mt19937 rng(29);
  for (int p = 1; p <= 4; ++p) {
    for (int t = 1; t <= 2; ++t) {
      const NurbsCurve c = test::random_curve(rng, p, p + 5, true, p);
      const NurbsCurve e = elevate_degree(c, t);
      CHECK(e.degree() == p + t);
      for (double k : c.knots().breaks())
        CHECK(e.knots().multiplicity(k) == c.knots().multiplicity(k) + t);
      CHECK(max_curve_diff(c, e) <= 1e-13);
    }
    const NurbsSurface s = test::random_surface(rng, p, 2, p + 3, 4, true);
    const NurbsSurface es = elevate_degree(s, 1, 2);
    CHECK(es.degree_u() == p + 1);
    CHECK(es.degree_v() == 4);
    CHECK(max_surface_diff(s, es) <= 1e-13);
  }
}

TEST_CASE("bezier_extract: each element is the rational Bezier form of its span",
          "[geometry][refine][bezier]") {
  std::mt19937 rng(31);
  for (int p = 1; p <= 5; ++p) {
    const NurbsCurve c = test::random_curve(rng, p, p + 6, true, p);
    const std::vector<BezierSegment> segs = bezier_extract(c);
    REQUIRE(static_cast<int>(segs.size()) == c.knots().num_elements());
    for (const BezierSegment& s : segs) {
      REQUIRE(static_cast<int>(s.pw.size()) == p + 1);
      const Box3 box = bounding_box(s);
      for (double t = 0; t <= 1.0; t += 0.02) {
        const double u = s.range.lo + t * (s.range.hi - s.range.lo);
        const Vector3d x = c.point(u);
        // The mapping u = lo + t (hi - lo) is exact only to an ulp of u; on a short element
        // the curve moves |C'(u)| * ulp per ulp, so that term belongs to the tolerance.
        const double cond = c.derivs(u, 1).d[1].norm() * 4e-16;
        CHECK((rational_bernstein(s.pw, t) - x).norm() <= 1e-13 + cond);
        CHECK((x.array() >= box.lo.array() - 1e-14).all());
        CHECK((x.array() <= box.hi.array() + 1e-14).all());
      }
    }
  }
  const NurbsSurface s = test::random_surface(rng, 3, 2, 7, 5, true);
  const std::vector<BezierPatch> patches = bezier_extract(s);
  REQUIRE(static_cast<int>(patches.size()) ==
          s.knots_u().num_elements() * s.knots_v().num_elements());
  for (const BezierPatch& b : patches) {
    const Box3 box = bounding_box(b);
    for (double tu = 0; tu <= 1.0; tu += 0.1)
      for (double tv = 0; tv <= 1.0; tv += 0.1) {
        // tensor-product de Casteljau: along u for every row, then along v
        std::vector<Vector4d> col;
        for (int j = 0; j <= b.degree_v; ++j) {
          std::vector<Vector4d> row;
          for (int i = 0; i <= b.degree_u; ++i) row.push_back(b.pw_at(i, j));
          for (std::size_t r = 1; r < row.size(); ++r)
            for (std::size_t i = 0; i + r < row.size(); ++i)
              row[i] = (1 - tu) * row[i] + tu * row[i + 1];
          col.push_back(row[0]);
        }
        const Vector3d xb = rational_bernstein(col, tv);
        const double u = b.range.u.lo + tu * (b.range.u.hi - b.range.u.lo);
        const double v = b.range.v.lo + tv * (b.range.v.hi - b.range.v.lo);
        const Vector3d x = s.point(u, v);
        CHECK((xb - x).norm() <= 1e-13);
        CHECK((x.array() >= box.lo.array() - 1e-14).all());
        CHECK((x.array() <= box.hi.array() + 1e-14).all());
      }
  }
}

TEST_CASE("refine_knots: rejects knots outside the domain", "[geometry][refine][errors]") {
  std::mt19937 rng(37);
  const NurbsCurve c = test::random_curve(rng, 2, 5, false);
  const std::vector<double> bad = {1.5};
  CHECK_THROWS_AS(refine_knots(c, bad), GeometryError);
  CHECK_THROWS_AS(insert_knot(c, 0.3, 3), GeometryError);  // multiplicity 3 > degree 2
}

}  // namespace test_refinement
