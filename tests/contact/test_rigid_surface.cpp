// Multi-patch rigid surfaces: a cylinder split into patches answers as the single patch does,
// shared edges are not edges, warm starts follow a moving point across patches and seams.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "contact/rigid_surface.hpp"
#include "geometry/constructions.hpp"
#include "geometry/json_reader.hpp"
#include "geometry/refinement.hpp"
#include "geometry/trimmed_surface.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_rigid_surface {

using namespace iga;

namespace {
constexpr double kPi = std::numbers::pi;

RigidSurface split_cylinder(int parts, double R, double H) {
  RigidSurface rs;
  for (int k = 0; k < parts; ++k)
    rs.add(make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), R, H,
                         2 * kPi * k / parts, 2 * kPi * (k + 1) / parts));
  return rs;
}
}  // namespace

TEST_CASE("RigidSurface: shared sides of a split cylinder are detected", "[contact][multipatch]") {
  const RigidSurface rs = split_cylinder(4, 1.0, 2.0);
  REQUIRE(rs.num_patches() == 4);
  for (int i = 0; i < 4; ++i) {
    CHECK(rs.side_shared(i, 0));   // u = lo: the previous sector
    CHECK(rs.side_shared(i, 1));   // u = hi: the next sector
    CHECK(!rs.side_shared(i, 2));  // bottom circle
    CHECK(!rs.side_shared(i, 3));  // top circle
  }
  RigidSurface one;
  one.add(make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  CHECK(one.side_shared(0, 0));  // closed in u: the seam is shared with itself
  CHECK(!one.side_shared(0, 2));
}

TEST_CASE("RigidSurface: a 4-patch cylinder gives the single patch's answers",
          "[contact][multipatch]") {
  const RigidSurface four = split_cylinder(4, 1.0, 2.0);
  RigidSurface one;
  one.add(make_cylinder(Vector3d::Zero(), Vector3d::UnitZ(), Vector3d::UnitX(), 1.0, 2.0));
  std::mt19937 g(7);
  std::uniform_real_distribution<double> ang(0, 2 * kPi), rad(0.2, 2.5), z(-0.5, 2.5);
  for (int k = 0; k < 5000; ++k) {
    // every 10th point exactly above a shared edge (angle a multiple of pi/2)
    const double a = k % 10 == 0 ? (k / 10 % 4) * kPi / 2 : ang(g);
    const Vector3d x(rad(g) * std::cos(a), rad(g) * std::sin(a), z(g));
    const ProjectionResult r4 = four.closest_point(x), r1 = one.closest_point(x);
    REQUIRE(found(r4.status));
    CHECK((r4.point - r1.point).norm() <= 1e-10);
    CHECK(r4.distance == Approx(r1.distance).margin(1e-10));
    CHECK(r4.status == r1.status);  // interior over shared edges, edge beyond the ends
  }
}

TEST_CASE("RigidSurface: warm starts follow a point around the cylinder across patches",
          "[contact][multipatch][warm]") {
  const RigidSurface four = split_cylinder(4, 1.0, 2.0);
  // The path starts at 0.1 rad (inside patch 0) and ends at 5 pi + 0.1 (inside patch 2), so
  // it crosses 10 sector boundaries; none of its points lies exactly on one.
  ProjectionResult prev =
      four.closest_point(Vector3d(1.2 * std::cos(0.1), 1.2 * std::sin(0.1), 1.0));
  int patch_changes = 0;
  for (int k = 1; k <= 800; ++k) {
    const double a = 0.1 + 2.5 * 2 * kPi * k / 800;  // 2.5 turns: seams and shared edges
    const Vector3d x(1.2 * std::cos(a), 1.2 * std::sin(a), 1.0 + 0.3 * std::sin(3 * a));
    const ProjectionResult r = four.closest_point(x, prev);
    REQUIRE(r.status == ProjectionStatus::interior);
    CHECK(r.distance == Approx(0.2).epsilon(1e-12));
    CHECK((r.point - Vector3d(std::cos(a), std::sin(a), x.z())).norm() <= 1e-12);
    patch_changes += r.patch != prev.patch;
    prev = r;
  }
  CHECK(patch_changes == 10);  // 2.5 turns over 4 sectors
}

TEST_CASE("RigidSurface: rays on a split cylinder hit as on the single patch",
          "[contact][multipatch][ray]") {
  const RigidSurface four = split_cylinder(4, 1.0, 2.0);
  std::mt19937 g(8);
  std::uniform_real_distribution<double> ang(0, 2 * kPi), z(0.1, 1.9);
  for (int k = 0; k < 500; ++k) {
    const double a = ang(g);
    const Vector3d foot(std::cos(a), std::sin(a), z(g));
    const Vector3d x = foot + 0.4 * Vector3d(std::cos(a), std::sin(a), 0.0);
    const ProjectionResult r = four.ray(x, -Vector3d(std::cos(a), std::sin(a), 0.0));
    REQUIRE(found(r.status));
    CHECK((r.point - foot).norm() <= 1e-10);
    CHECK(r.distance == Approx(0.4).epsilon(1e-10));
  }
}

TEST_CASE("RigidSurface: groups of a model file act as one surface", "[contact][multipatch]") {
  const std::string path = std::string(IGA_SOURCE_DIR) + "/data/cylinder_4patch.json";
  const GeometryModel m =
      parse_geometry(read_json_file(path)["geometry"], path, JsonPointer("/geometry"));
  const RigidSurface rs = RigidSurface::from_geometry(m, "cylinder");
  CHECK(rs.num_patches() == 4);
  const ProjectionResult r = rs.closest_point(Vector3d(0.0, -3.0, 2.0));
  CHECK(r.status == ProjectionStatus::interior);
  CHECK(r.distance == Approx(2.0).epsilon(1e-12));
  CHECK_THROWS_AS(RigidSurface::from_geometry(m, "nothing"), std::invalid_argument);
}

TEST_CASE("RigidSurface::closest_points: broad phase + narrow phase equals the full search",
          "[contact][multipatch][search]") {
  RigidSurface rs = split_cylinder(3, 1.0, 2.0);
  rs.add(make_torus(Vector3d(0, 0, 5), Vector3d::UnitZ(), 2.0, 0.5));
  std::mt19937 g(9);
  std::uniform_real_distribution<double> c(-3.0, 3.0), z(-1.0, 7.0);
  std::vector<Vector3d> pts;
  for (int k = 0; k < 3000; ++k) pts.emplace_back(c(g), c(g), z(g));
  const double d = 0.4;
  for (bool cgal : {false, true}) {
    const std::vector<ProjectionResult> batch = rs.closest_points(pts, d, cgal);
    REQUIRE(batch.size() == pts.size());
    int near = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const ProjectionResult full = rs.closest_point(pts[k]);
      const double dist = (full.point - pts[k]).norm();
      if (dist <= d * (1 - 1e-9)) {
        ++near;
        REQUIRE(found(batch[k].status));
        CHECK((batch[k].point - full.point).norm() <= 1e-10);
        CHECK(batch[k].status == full.status);
      } else if (dist > d * (1 + 1e-9)) {
        CHECK(batch[k].status == ProjectionStatus::far);
      }
    }
    CHECK(near > 300);  // the test has teeth: many points are within the search distance
  }
  // The grid index is built once per distance and kept (the same object), equals the CGAL
  // broad phase pair for pair, and a copy that gets another patch has an index of its own.
  const RigidBoxIndex& index = rs.element_index(d);
  CHECK(&rs.element_index(d) == &index);
  CHECK(&rs.element_index(2 * d) != &index);
  CHECK(index.query(pts) == broad_phase(pts, rs.element_boxes(), d));
  RigidSurface more = rs;
  CHECK(&more.element_index(d) == &index);
  more.add(make_torus(Vector3d(0, 0, -5), Vector3d::UnitZ(), 2.0, 0.5));
  CHECK(more.element_boxes().size() > rs.element_boxes().size());
  CHECK(&more.element_index(d) != &index);
  CHECK(rs.element_tag(static_cast<int>(rs.element_boxes().size()) - 1).first ==
        rs.num_patches() - 1);
}

namespace {
// A square [-2, 2]^2 with a round hole of radius 1 (a 256-gon of the loop; the edge curves are
// the exact square and circle), on the base `base` whose (u, v) are x and y.
TrimmedSurface plate_with_hole(const Surface& base) {
  TrimmedSurface::Loop outer{{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  TrimmedSurface::Loop hole;
  for (int k = 0; k < 256; ++k)
    hole.emplace_back(std::cos(2 * kPi * k / 256), std::sin(2 * kPi * k / 256));
  std::vector<NurbsCurve> edges{make_line({-2, -2, 0}, {2, -2, 0}),
                                make_line({2, -2, 0}, {2, 2, 0}), make_line({2, 2, 0}, {-2, 2, 0}),
                                make_line({-2, 2, 0}, {-2, -2, 0}),
                                make_circle(Vector3d::Zero(), Vector3d::UnitZ(), 1.0)};
  return TrimmedSurface(base, {outer, hole}, std::move(edges), 1e-4);
}
}  // namespace

TEST_CASE("RigidSurface::closest_points: trimmed faces are in the broad phase by their own boxes",
          "[contact][trimmed]") {
  // The same face on an analytic plane and on a NURBS plane of 8 x 8 elements.
  const Plane plane;
  const NurbsSurface patch =
      subdivide(make_plane_patch({-2, -2, 0}, {4, 0, 0}, {0, 4, 0}), 8, 8);  // u = (x + 2) / 4
  // The NURBS patch's parameters are not x and y: its face's loops are mapped.
  const TrimmedSurface on_plane = plate_with_hole(plane);
  std::vector<TrimmedSurface::Loop> loops = on_plane.loops();
  for (auto& L : loops)
    for (Vector2d& uv : L) uv = (uv.array() + 2.0) / 4.0;
  const TrimmedSurface on_patch(patch, loops, on_plane.edges(), 1e-4);
  for (const TrimmedSurface* t : {&on_plane, &on_patch}) {
    RigidSurface rs;
    rs.add(*t);
    rs.add(make_cylinder(Vector3d(0, 0, -3), Vector3d::UnitX(), Vector3d::UnitY(), 0.5, 1.0));
    // Cells wholly in the hole are not boxes of the face: over the hole's centre there is
    // no candidate of it nearer than the hole's edge.
    int face_boxes = 0;
    for (std::size_t b = 0; b < rs.element_boxes().size(); ++b)
      if (rs.element_tag(static_cast<int>(b)).first == 0) {
        CHECK(rs.element_tag(static_cast<int>(b)).second == -1);
        ++face_boxes;
      }
    CHECK(face_boxes > 0);
    CHECK(face_boxes < 64);
    const std::vector<Vector3d> centre{Vector3d(0, 0, 0.05)};
    for (const SearchPair& p : rs.element_index(0.3).query(centre))
      CHECK(rs.element_tag(p.box).first != 0);
    // Batch answers equal the full search's, with either broad phase.
    std::mt19937 g(11);
    std::uniform_real_distribution<double> U(-2.5, 2.5), Z(-0.6, 0.6);
    std::vector<Vector3d> pts;
    for (int k = 0; k < 600; ++k) pts.emplace_back(U(g), U(g), Z(g));
    const double d = 0.5;
    for (const bool cgal : {false, true}) {
      const std::vector<ProjectionResult> batch = rs.closest_points(pts, d, cgal);
      int near = 0, on_edge = 0;
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const ProjectionResult full = rs.closest_point(pts[k]);
        const double dist = (full.point - pts[k]).norm();
        INFO("x = " << pts[k].transpose() << (cgal ? " (CGAL)" : " (grid)"));
        if (dist <= d * (1 - 1e-9)) {
          ++near;
          on_edge += full.status == ProjectionStatus::edge;
          REQUIRE(found(batch[k].status));
          CHECK((batch[k].point - full.point).norm() <= 1e-9);
          CHECK(batch[k].patch == full.patch);
        } else if (dist > d * (1 + 1e-9)) {
          CHECK(batch[k].status == ProjectionStatus::far);
        }
      }
      CHECK(near > 200);
      CHECK(on_edge > 20);  // feet on the hole's and the outer edges are among them
    }
  }
}

}  // namespace test_rigid_surface
