// Issue 15, items 1 and 2: faces of STEP and IGES files as the project's surfaces. The files
// are made here by OpenCASCADE's modelling API and writers (tests/support/cad_samples.hpp);
// every imported face is compared with what it should be: analytic faces with the analytic
// surface built directly (closest points of random points to 1e-12), B-spline faces with
// OpenCASCADE's own evaluation of the face read back (points and normals to 1e-12 relative).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Surface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Precision.hxx>
#include <STEPControl_Reader.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include "cad/cad_import.hpp"
#include "contact/rigid_surface.hpp"
#include "geometry/json_reader.hpp"
#include "tests/support/cad_samples.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_cad_import {

using namespace iga;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = std::numbers::pi;

/// A fresh folder per test case (CTest runs the cases as parallel processes).
std::string make_dir(const std::string& name) {
  std::string dir = test::fresh_out_dir("cad_import", name);
  std::filesystem::create_directories(dir);
  return dir;
}

CadOptions only(std::vector<int> faces, const std::string& unit = "mm") {
  CadOptions o;
  o.faces = std::move(faces);
  o.unit = unit;
  return o;
}

Vector3d unit_normal(const Surface& s, double u, double v) {
  const SurfaceDerivs d = s.derivs(u, v, 1);
  return s.normal_sign() * d.Su.cross(d.Sv).normalized();
}

const Surface& surface_of(const GeometryEntity& e) {
  const Surface* s = as_surface(e);
  REQUIRE(s != nullptr);
  return *s;
}

/// Closest points of random points around `box` agree (point and normal) to tol * size.
void same_closest_points(const Surface& a, const Surface& b, const Vector3d& lo, const Vector3d& hi,
                         double tol = 1e-12) {
  RigidSurface ra, rb;
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&a))
    ra.add(*n);
  else
    ra.add(dynamic_cast<const AnalyticSurface&>(a));
  if (const auto* n = dynamic_cast<const NurbsSurface*>(&b))
    rb.add(*n);
  else
    rb.add(dynamic_cast<const AnalyticSurface&>(b));
  std::mt19937 g(7);
  std::uniform_real_distribution<double> U(-0.2, 1.2);
  const double size = (hi - lo).norm();
  for (int k = 0; k < 200; ++k) {
    const Vector3d x = lo + Vector3d(U(g), U(g), U(g)).cwiseProduct(hi - lo);
    const ProjectionResult pa = ra.closest_point(x), pb = rb.closest_point(x);
    REQUIRE(found(pa.status));
    REQUIRE(found(pb.status));
    INFO("x = " << x.transpose() << ", feet " << pa.point.transpose() << " | "
                << pb.point.transpose() << ", status " << to_string(pa.status)
                << ", |d| / size = " << (pa.point - pb.point).norm() / size);
    // Interior feet are closed forms (round-off); a foot on an edge comes from the bounded
    // Newton along it, which stops at ProjectionOptions::tol_residual = 1e-13 on its scaled
    // residual: there the two agree to that, about 1e-12 of the size (10x margin).
    const double t = pa.status == ProjectionStatus::interior ? tol : std::max(tol, 1e-11);
    CHECK((pa.point - pb.point).norm() <= t * size);
    CHECK((pa.normal - pb.normal).norm() <= 1e-9);
  }
}

std::vector<TopoDS_Face> faces_read_back(const std::string& path) {
  STEPControl_Reader r;
  REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
  r.TransferRoots();
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(r.OneShape(), TopAbs_FACE, map);
  std::vector<TopoDS_Face> faces;
  for (int i = 1; i <= map.Extent(); ++i) faces.push_back(TopoDS::Face(map(i)));
  return faces;
}

}  // namespace

TEST_CASE("cad import: a STEP cylinder's side is the analytic cylinder, exactly placed", "[cad]") {
  const std::string dir = make_dir("cylinder");
  const Vector3d o(1, -2, 0.5), axis = Vector3d(1, 2, 3).normalized(), xd(3, 0, -1);
  const std::string path = dir + "/cylinder.step";
  test::write_step(BRepPrimAPI_MakeCylinder(test::frame(o, axis, xd), 2.5, 4.0).Shape(), path);
  const std::vector<CadFace> faces = list_cad_faces(path);
  REQUIRE(faces.size() == 3);
  CHECK(faces[0].cad_type == "cylinder");
  CHECK_FALSE(faces[0].trimmed);
  CHECK(faces[1].trimmed);  // the end discs: a circle in the plane's parameters
  CHECK(faces[0].area == Approx(2 * kPi * 2.5 * 4.0).epsilon(1e-9));

  const CadImport imp = import_cad(path, "drum", only({0}));
  REQUIRE(imp.entities.size() == 1);
  CHECK(imp.entities[0].first == "drum.face0");
  REQUIRE(std::holds_alternative<Cylinder>(imp.entities[0].second));
  CHECK(imp.faces[0].entity_type == "cylinder");
  CHECK(imp.faces[0].exact);
  const auto& c = std::get<Cylinder>(imp.entities[0].second);
  CHECK(c.radius() == Approx(2.5).epsilon(1e-14));
  // OCCT's STEP writer prints 12 significant digits (DIRECTION('',(0.267261241912, ...))):
  // the file holds the frame to about 5e-13.
  CHECK((c.placement().center - o).norm() <= 1e-11);
  CHECK((c.placement().frame() - Placement{o, axis, xd}.frame()).norm() <= 5e-12);
  CHECK(c.closed_u());
  const Cylinder direct(Placement{o, axis, xd}, 2.5, {{0, 2 * kPi}, {0, 4.0}});
  CHECK(c.normal_sign() == 1);  // the side of a solid: outward
  same_closest_points(c, direct, o - Vector3d(4, 4, 4), o + Vector3d(4, 4, 4) + 4 * axis);
}

TEST_CASE("cad import: sphere, torus and cones (both ways) are the analytic surfaces", "[cad]") {
  const std::string dir = make_dir("analytic");
  const Vector3d o(0.3, 0.2, -1), axis = Vector3d(0, 1, 1).normalized(), xd(1, 0, 0);
  const Vector3d lo = o - Vector3d(5, 5, 5), hi = o + Vector3d(5, 5, 5);
  SECTION("sphere") {
    const std::string path = dir + "/sphere.step";
    test::write_step(BRepPrimAPI_MakeSphere(test::frame(o, axis, xd), 1.7).Shape(), path);
    const CadImport imp = import_cad(path, "ball");
    REQUIRE(imp.entities.size() == 1);
    REQUIRE(std::holds_alternative<Sphere>(imp.entities[0].second));
    same_closest_points(surface_of(imp.entities[0].second), Sphere(Placement{o, axis, xd}, 1.7), lo,
                        hi);
  }
  SECTION("torus") {
    const std::string path = dir + "/torus.step";
    test::write_step(BRepPrimAPI_MakeTorus(test::frame(o, axis, xd), 3.0, 0.8).Shape(), path);
    const CadImport imp = import_cad(path, "ring");
    REQUIRE(std::holds_alternative<Torus>(imp.entities[0].second));
    CHECK_FALSE(imp.faces[0].trimmed);
    same_closest_points(surface_of(imp.entities[0].second), Torus(Placement{o, axis, xd}, 3.0, 0.8),
                        lo, hi);
  }
  SECTION("cones widening and narrowing along the axis") {
    for (const auto& [r1, r2] : {std::pair{1.0, 2.0}, std::pair{2.5, 0.5}}) {
      const std::string path = dir + "/cone.step";
      const double h = 3.0;
      test::write_step(BRepPrimAPI_MakeCone(test::frame(o, axis, xd), r1, r2, h).Shape(), path);
      const std::vector<CadFace> faces = list_cad_faces(path);
      int side = -1;
      for (const CadFace& f : faces)
        if (f.cad_type == "cone") side = f.index;
      REQUIRE(side >= 0);
      const CadImport imp = import_cad(path, "cone", only({side}));
      REQUIRE(std::holds_alternative<Cone>(imp.entities[0].second));
      // The same cone built directly: apex where the radius reaches zero.
      const double slope = (r2 - r1) / h;  // radius change per height
      const Vector3d apex = o - (r1 / slope) * axis;
      const double alpha = std::atan(1.0 / std::abs(slope));
      const Vector3d ax = slope > 0 ? axis : Vector3d(-axis);
      const Cone direct(Placement{apex, ax, xd}, alpha,
                        {{0, 2 * kPi}, {std::min(r1, r2), std::max(r1, r2)}});
      INFO("r1 = " << r1 << ", r2 = " << r2);
      same_closest_points(surface_of(imp.entities[0].second), direct, lo, hi);
      // Outward (away from the axis) like the solid's face.
      const Surface& s = surface_of(imp.entities[0].second);
      const Vector3d p = s.point(1.0, 0.5 * (r1 + r2));
      const Vector3d radial = (p - o) - (p - o).dot(axis) * axis;
      CHECK(unit_normal(s, 1.0, 0.5 * (r1 + r2)).dot(radial) > 0);
    }
  }
  SECTION("a box: six planes with outward normals") {
    const std::string path = dir + "/box.step";
    test::write_step(BRepPrimAPI_MakeBox(test::frame(o, axis, xd), 1.0, 2.0, 3.0).Shape(), path);
    const CadImport imp = import_cad(path, "box");
    REQUIRE(imp.entities.size() == 6);
    const Vector3d ex = (xd - xd.dot(axis) * axis).normalized(), ey = axis.cross(ex);
    const Vector3d centre = o + 0.5 * ex + 1.0 * ey + 1.5 * axis;
    for (const auto& [name, e] : imp.entities) {
      REQUIRE(std::holds_alternative<Plane>(e));
      const Surface& s = surface_of(e);
      const Domain2 d = s.domain();
      const double u = 0.5 * (d.u.lo + d.u.hi), v = 0.5 * (d.v.lo + d.v.hi);
      CHECK(unit_normal(s, u, v).dot(s.point(u, v) - centre) > 0);
    }
  }
}

TEST_CASE("cad import: B-spline faces are the same NURBS as OpenCASCADE's face", "[cad]") {
  const std::string dir = make_dir("bspline");
  for (const bool periodic : {false, true}) {
    INFO("periodic " << periodic);
    const std::string path = dir + "/bspline.step";
    test::write_step(test::bspline_face(periodic), path);
    const CadImport imp = import_cad(path, "free");
    REQUIRE(imp.entities.size() == 1);
    REQUIRE(std::holds_alternative<NurbsSurface>(imp.entities[0].second));
    const auto& n = std::get<NurbsSurface>(imp.entities[0].second);
    CHECK(n.degree_u() == 3);
    CHECK(n.degree_v() == 2);
    CHECK(n.is_rational());
    // OCCT's own evaluation of the face read back from the file: same parameters.
    const std::vector<TopoDS_Face> faces = faces_read_back(path);
    REQUIRE(faces.size() == 1);
    const Handle(Geom_Surface) occ = BRep_Tool::Surface(faces[0]);
    const double sign = faces[0].Orientation() == TopAbs_REVERSED ? -1.0 : 1.0;
    const Domain2 d = n.domain();
    double size = 0.0;
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i)
        size = std::max(
            size, n.point(d.u.lo + (d.u.hi - d.u.lo) * i / 10, d.v.lo + (d.v.hi - d.v.lo) * j / 10)
                      .norm());
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i) {
        const double u = d.u.lo + (d.u.hi - d.u.lo) * (i + 0.37) / 11.0;
        const double v = d.v.lo + (d.v.hi - d.v.lo) * (j + 0.61) / 11.0;
        gp_Pnt P;
        gp_Vec Su, Sv;
        occ->D1(u, v, P, Su, Sv);
        const Vector3d p(P.X(), P.Y(), P.Z());
        const gp_Vec N = Su.Crossed(Sv).Normalized() * sign;
        CHECK((n.point(u, v) - p).norm() <= 1e-12 * size);
        CHECK((unit_normal(n, u, v) - Vector3d(N.X(), N.Y(), N.Z())).norm() <= 1e-12);
      }
  }
}

TEST_CASE("cad import: IGES, length units and placement", "[cad]") {
  const std::string dir = make_dir("iges_units");
  const Vector3d o(0, 0, -1.5), axis(0, 0, 1), xd(0, -1, 0);
  const TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(test::frame(o, axis, xd), 1.0, 3.0).Shape();
  const Cylinder direct(Placement{o, axis, xd}, 1.0, {{0, 2 * kPi}, {0, 3.0}});
  SECTION("IGES: the side face, as whatever IGES keeps, has the cylinder's closest points") {
    const std::string path = dir + "/cylinder.igs";
    test::write_iges(cyl, path);
    const std::vector<CadFace> faces = list_cad_faces(path);
    int side = -1;
    for (const CadFace& f : faces)
      if (!f.trimmed && side < 0) side = f.index;
    REQUIRE(side >= 0);
    const CadImport imp = import_cad(path, "drum", only({side}));
    INFO("IGES side face read as " << imp.faces[0].cad_type << " -> " << imp.faces[0].entity_type);
    CHECK(imp.faces[0].exact);
    same_closest_points(surface_of(imp.entities[0].second), direct, Vector3d(-2, -2, -1),
                        Vector3d(2, 2, 1), 1e-10);
  }
  SECTION("a file in mm read in m and in cm") {
    const std::string path = dir + "/cylinder_mm.step";
    test::write_step(cyl, path);
    const CadImport m = import_cad(path, "d", only({0}, "m"));
    CHECK(std::get<Cylinder>(m.entities[0].second).radius() == Approx(1e-3).epsilon(1e-12));
    const CadImport cm = import_cad(path, "d", only({0}, "cm"));
    CHECK(std::get<Cylinder>(cm.entities[0].second).radius() == Approx(0.1).epsilon(1e-12));
  }
  SECTION("placement: turned a quarter about x through (0, 0, 1), then moved by (5, 0, 0)") {
    const std::string path = dir + "/cylinder_placed.step";
    test::write_step(cyl, path);
    CadOptions opt = only({0});
    opt.placement.point = Vector3d(0, 0, 1);
    opt.placement.axis = Vector3d(1, 0, 0);
    opt.placement.angle = 0.5 * kPi;
    opt.placement.vector = Vector3d(5, 0, 0);
    const CadImport imp = import_cad(path, "d", opt);
    // The axis (0, 0, 1) turns to (0, -1, 0); the base point (0, 0, -1.5) goes to
    // (0, 2.5, 1) + (5, 0, 0).
    const Cylinder placed(Placement{Vector3d(5, 2.5, 1), Vector3d(0, -1, 0), Vector3d(0, 0, -1)},
                          1.0, {{0, 2 * kPi}, {0, 3.0}});
    same_closest_points(surface_of(imp.entities[0].second), placed, Vector3d(3, -2, -1),
                        Vector3d(7, 4, 3));
  }
}

TEST_CASE("cad import: bad files and faces are errors that say what is wrong", "[cad]") {
  const std::string dir = make_dir("errors");
  const std::string path = dir + "/errors.step";
  test::write_step(BRepPrimAPI_MakeCylinder(1.0, 2.0).Shape(), path);
  CHECK_THROWS_WITH(import_cad(dir + "/none.step", "x"), Contains("no such file"));
  CHECK_THROWS_WITH(import_cad(dir + "/a.obj", "x"), Contains("not a CAD file"));
  CHECK_THROWS_WITH(import_cad(path, "x", only({3})),
                    Contains("face 3 does not exist (the file has 3 faces"));
  CHECK_THROWS_WITH(import_cad(path, "x", only({}, "furlong")), Contains("unknown length unit"));
  { std::ofstream(dir + "/garbage.step") << "not a step file\n"; }
  CHECK_THROWS_WITH(import_cad(dir + "/garbage.step", "x"), Contains("garbage.step"));
}

TEST_CASE("cad import: a plate with a hole is a trimmed plane: feet over the hole are on its edge",
          "[cad][trimmed]") {
  const std::string dir = make_dir("plate_hole");
  const std::string path = dir + "/plate.step";
  const double a = 4.0, r = 1.0;
  test::write_step(test::plate_with_hole(a, r), path);
  const CadImport imp = import_cad(path, "plate");
  REQUIRE(imp.entities.size() == 1);
  CHECK(imp.faces[0].trimmed);
  CHECK(imp.faces[0].wires == 2);
  CHECK(imp.faces[0].entity_type == "trimmed plane");
  REQUIRE(std::holds_alternative<TrimmedSurface>(imp.entities[0].second));
  const auto& t = std::get<TrimmedSurface>(imp.entities[0].second);
  CHECK(t.loops().size() == 2);
  CHECK(t.edges().size() == 5);  // 4 sides and the circle
  RigidSurface rs;
  rs.add(t);
  std::mt19937 g(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int over_hole = 0, over_plate = 0;
  for (int k = 0; k < 400; ++k) {
    const Vector3d x(0.5 * a * U(g), 0.5 * a * U(g), 0.5 * U(g));
    const double rho = std::hypot(x.x(), x.y());
    if (std::abs(x.z()) < 1e-3 || std::abs(rho - r) < 1e-3) continue;
    const ProjectionResult p = rs.closest_point(x);
    REQUIRE(found(p.status));
    INFO("x = " << x.transpose() << ", foot " << p.point.transpose());
    const Vector3d down(0, 0, x.z() > 0 ? -1 : 1);
    if (rho < r) {  // over the hole: the nearest point of the hole's edge circle
      ++over_hole;
      CHECK(p.status == ProjectionStatus::edge);
      const Vector3d expected(r * x.x() / rho, r * x.y() / rho, 0.0);
      CHECK((p.point - expected).norm() <= 1e-10);
      CHECK(std::abs(p.distance) == Approx(std::hypot(r - rho, x.z())).epsilon(1e-10));
      CHECK(p.certified);  // a plane: no other local minimum inside the loops
      CHECK_FALSE(found(rs.ray(x, down).status));  // a ray straight down passes through
    } else {                                       // over the plate: straight below, on its normal
      ++over_plate;
      CHECK(p.status == ProjectionStatus::interior);
      CHECK((p.point - Vector3d(x.x(), x.y(), 0)).norm() <= 1e-12);
      CHECK(found(rs.ray(x, down).status));
    }
  }
  CHECK(over_hole > 20);
  CHECK(over_plate > 200);
  // Beyond the outer boundary: the nearest point of the square's side.
  const ProjectionResult side = rs.closest_point(Vector3d(3.0, 0.5, 0.2));
  CHECK(side.status == ProjectionStatus::edge);
  CHECK((side.point - Vector3d(2.0, 0.5, 0.0)).norm() <= 1e-10);
  // Written as JSON and read back: the same face.
  GeometryModel m;
  m.entities = imp.entities;
  CHECK(parse_geometry(geometry_to_json(m), "t.json", JsonPointer()) == m);
}

TEST_CASE("cad import: extrusions convert exactly, offset surfaces within the stated bound",
          "[cad]") {
  const std::string dir = make_dir("other");
  // A B-spline curve extruded along z (a surface of linear extrusion), and the offset (0.2) of
  // the B-spline face: OCCT keeps both types in STEP.
  TColgp_Array1OfPnt poles(1, 4);
  poles(1) = gp_Pnt(0, 0, 0), poles(2) = gp_Pnt(1, 1, 0), poles(3) = gp_Pnt(2, -1, 0),
  poles(4) = gp_Pnt(3, 0.5, 0);
  const Handle(Geom_BezierCurve) profile = new Geom_BezierCurve(poles);
  const Handle(Geom_Surface) extrusion =
      new Geom_SurfaceOfLinearExtrusion(profile, gp_Dir(0, 0.2, 1));
  // (the offset of a smooth bicubic Bezier patch: OCCT approximates it C2 within 1e-6; the
  // offset of a face with a kink is approximated C0, with a larger bound, reported too)
  TColgp_Array2OfPnt net(1, 4, 1, 4);
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; j <= 4; ++j)
      net(i, j) = gp_Pnt(i, j, 0.3 * std::sin(1.1 * i) * std::cos(0.7 * j));
  const Handle(Geom_Surface) offset = new Geom_OffsetSurface(new Geom_BezierSurface(net), 0.2);
  struct Case {
    const char* name;
    Handle(Geom_Surface) surface;
    double u0, u1, v0, v1;
    bool exact;
  };
  for (const Case& c : {Case{"extrusion", extrusion, 0.0, 1.0, 0.0, 2.0, true},
                        Case{"offset", offset, 0.0, 1.0, 0.0, 1.0, false}}) {
    INFO(c.name);
    const std::string path = dir + "/" + c.name + ".step";
    test::write_step(
        BRepBuilderAPI_MakeFace(c.surface, c.u0, c.u1, c.v0, c.v1, Precision::Confusion()).Face(),
        path);
    const CadImport imp = import_cad(path, "s");
    REQUIRE(imp.entities.size() == 1);
    CHECK(imp.faces[0].cad_type == c.name);
    CHECK(imp.faces[0].entity_type == "nurbs_surface");
    CHECK(imp.faces[0].exact == c.exact);
    const double size = (imp.faces[0].box_hi - imp.faces[0].box_lo).norm();
    if (!c.exact) CHECK(imp.faces[0].tolerance <= 1e-6 * size);
    // OCCT's points of the face lie on the imported surface: to round-off when exact, within
    // the reported bound (and a margin for the closest point's own tolerance) when not.
    RigidSurface rs;
    rs.add(std::get<NurbsSurface>(imp.entities[0].second));
    const double bound = c.exact ? 1e-10 * size : imp.faces[0].tolerance + 1e-10 * size;
    for (int j = 0; j <= 6; ++j)
      for (int i = 0; i <= 6; ++i) {
        const gp_Pnt P =
            c.surface->Value(c.u0 + (c.u1 - c.u0) * i / 6, c.v0 + (c.v1 - c.v0) * j / 6);
        const Vector3d x(P.X(), P.Y(), P.Z());
        CHECK(std::abs(rs.closest_point(x).distance) <= bound);
      }
  }
}

}  // namespace test_cad_import
