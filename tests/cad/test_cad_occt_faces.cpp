// Issue 34, item 4: real-world faces. Files of OpenCASCADE's public test data
// (tests/data/cad/occt/README.md) import whole, and the closest points of every face match
// OpenCASCADE's own projection (tests/support/occt_projection_check.hpp); trimmed revolutions
// and extrusions import in the face's own parameters; B-spline faces whose boundary overshoots
// the surface's range are clamped within the edge's tolerance, extended by the surface's own
// polynomials where their edges lie on them, and refused otherwise, with a message that says so.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <IGESControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include "cad/cad_face.hpp"
#include "cad/cad_import.hpp"
#include "contact/closest_point.hpp"
#include "tests/support/cad_samples.hpp"
#include "tests/support/files.hpp"
#include "tests/support/occt_projection_check.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_cad_occt_faces {

using namespace iga;
using Catch::Matchers::Contains;

namespace {

std::string occt_file(const std::string& name) {
  return std::string(IGA_SOURCE_DIR) + "/tests/data/cad/occt/" + name;
}

/// The file's faces in OCCT's order (as import_cad numbers them), read in mm.
std::vector<TopoDS_Face> faces_of_file(const std::string& path) {
  TopoDS_Shape shape;
  if (cad_format(path) == "step") {
    STEPControl_Reader r;
    REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
    r.TransferRoots();
    shape = r.OneShape();
  } else {
    IGESControl_Reader r;
    REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
    r.TransferRoots();
    shape = r.OneShape();
  }
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_FACE, map);
  std::vector<TopoDS_Face> faces;
  for (int i = 1; i <= map.Extent(); ++i) faces.push_back(TopoDS::Face(map(i)));
  return faces;
}

struct Totals {
  int points = 0, same = 0;
};

/// Every face of the file imports; each one's closest points pass the OCCT comparison.
Totals import_and_compare(const std::string& name) {
  const std::string path = occt_file(name);
  const CadImport imp = import_cad(path, "f");
  const std::vector<TopoDS_Face> faces = faces_of_file(path);
  REQUIRE(imp.entities.size() == faces.size());
  Totals t;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const test::OcctComparison c =
        test::compare_with_occt(faces[k], imp.entities[k].second, imp.faces[k].tolerance);
    INFO(name << " face " << k << " (" << imp.faces[k].cad_type << " -> "
              << imp.faces[k].entity_type << "): " << c.failure << "; " << c.ours_failed
              << " points without a foot, first: " << c.ours_failed_first);
    CHECK(c.failure.empty());
    // Our projection may end without a foot for a rare point (status not_converged, never a
    // wrong foot): trj9_ap209-td.stp face 26 for one of its 200 points when built with
    // -ffp-contract=fast -mfma, none otherwise here. A known weakness of the NURBS projector on
    // some CAD faces (issue 34's note), tolerated here for at most 1 % of the points; every
    // other point is compared with OpenCASCADE.
    CHECK(c.ours_failed <= 2);
    CHECK(c.points + c.ours_failed == 200);
    t.points += c.points;
    t.same += c.same;
  }
  return t;
}

}  // namespace

TEST_CASE(
    "cad import (OCCT data): every face of screw.step imports, cones on the far nappe and "
    "spindle tori as analytic surfaces, projecting as OpenCASCADE's",
    "[cad][occt]") {
  const CadImport imp = import_cad(occt_file("screw.step"), "screw");
  REQUIRE(imp.faces.size() > 6);
  // Face 6: a cone whose face lies where OCCT's radius R0 + v sin A is negative.
  CHECK(imp.faces[6].cad_type == "cone");
  CHECK(Contains("cone").match(imp.faces[6].entity_type));
  // Face 3: a torus of minor radius 54.9 > major radius 8.25 (a spindle torus).
  CHECK(imp.faces[3].cad_type == "torus");
  const Surface* s3 = as_surface(imp.entities[3].second);
  REQUIRE(s3 != nullptr);
  if (const auto* t = dynamic_cast<const TrimmedSurface*>(s3)) s3 = &t->base();
  const auto* torus = dynamic_cast<const Torus*>(s3);
  REQUIRE(torus != nullptr);
  CHECK(torus->minor_radius() > torus->major_radius());
  const Totals t = import_and_compare("screw.step");
  // Most feet are OpenCASCADE's own (the rest nearer than its extremum, e.g. on a bound).
  CHECK(t.same >= t.points / 2);
}

TEST_CASE(
    "cad import (OCCT data): a global section with a date OpenCASCADE cannot parse is a "
    "warning, the faces import",
    "[cad][occt]") {
  const std::string path = occt_file("OCC131-1.igs");
  const CadImport imp = import_cad(path, "occ131");
  REQUIRE(imp.faces.size() == 1);
  REQUIRE(imp.warnings.size() == 1);
  CHECK_THAT(imp.warnings[0],
             Contains(path) && Contains("damaged header") && Contains("Incorrect Date Format"));
  // a strict import refuses it, with the same words
  CadOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(import_cad(path, "occ131", strict),
                    Contains("damaged header") && Contains("strict"));
  const Totals t = import_and_compare("OCC131-1.igs");
  CHECK(t.points == 200);
}

TEST_CASE(
    "cad import (OCCT data): tubes with creases and collapsed caps project as OpenCASCADE's, "
    "also on and next to the creases",
    "[cad][occt]") {
  // Each face is a quarter tube of rectangular section (degree 1 around it: four creases) with
  // caps collapsing to a point at both ends, whose first control row is repeated: on the cap's
  // side of the crease between cap and tube the derivative is zero. Our search missed minima
  // just next to such a crease and stopped short along creases (issue 34); OCCT's own extremum
  // on a crease is often not converged along it (occt_unconverged: the first-order condition,
  // by OCCT's derivatives, holds at our foot and not at OCCT's).
  for (const char* name : {"OCC17026-1.igs", "OCC17026-2.igs"}) {
    const Totals t = import_and_compare(name);
    CHECK(t.points == 800);
    CHECK(t.same >= t.points / 2);
  }
}

TEST_CASE(
    "cad import (OCCT data): B-spline faces of degrees 7 and 8 project as OpenCASCADE's, "
    "certified (trj3_t2-db-214.stp, whole)",
    "[cad][occt]") {
  // Faces 6 and 7 are B-splines of degree 8 and 7. The certified search held the nets of its
  // subdivision for degrees up to 5 and fell back to seeded Newtons on higher degrees, without
  // a proof: on face 7 they missed OCCT's (nearer) foot (issue 34's corpus study, 14 faces of
  // degree 7 or 8 in 17,407). Now such patches get bigger nets (detail::HighNet) and the same
  // certified search.
  const std::string path = occt_file("trj3_t2-db-214.stp");
  const CadImport imp = import_cad(path, "trj3");
  int high = 0, uncertified = 0;
  std::mt19937 g(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (const auto& [name, entity] : imp.entities) {
    const Surface* s = as_surface(entity);
    if (const auto* t = dynamic_cast<const TrimmedSurface*>(s)) s = &t->base();
    const auto* n = dynamic_cast<const NurbsSurface*>(s);
    if (n == nullptr || std::max(n->degree_u(), n->degree_v()) <= 5) continue;
    ++high;
    const PatchProjector P(*n);
    CHECK(P.tree_nodes() > 0);
    const Vector3d c = 0.5 * (P.box().lo + P.box().hi), h = P.box().hi - P.box().lo;
    for (int i = 0; i < 50; ++i)
      uncertified += !P.project(c + h.cwiseProduct(Vector3d(U(g), U(g), U(g)))).certified;
  }
  CHECK(high >= 2);
  CHECK(uncertified == 0);
  const Totals t = import_and_compare("trj3_t2-db-214.stp");
  CHECK(t.same >= t.points / 2);
}

TEST_CASE(
    "cad import (OCCT data): a periodic degree-12 B-spline torus across its seam imports, "
    "fitted at a lower degree",
    "[cad][occt]") {
  const CadImport imp = import_cad(occt_file("OCC26138_Torus.igs"), "torus");
  REQUIRE_FALSE(imp.faces.empty());
  CHECK(imp.faces[0].cad_type == "bspline");
  for (const auto& [name, e] : imp.entities)
    if (const auto* n = std::get_if<NurbsSurface>(&e)) {
      CHECK(n->degree_u() <= 10);
      CHECK(n->degree_v() <= 10);
    }
}

TEST_CASE(
    "cad import (OCCT data): a periodic degree-12 B-spline torus across its seam projects as "
    "OpenCASCADE's",
    "[cad][occt][heavy]") {
  const Totals t = import_and_compare("OCC26138_Torus.igs");
  CHECK(t.same >= t.points / 2);
}

TEST_CASE(
    "cad import (OCCT data): B-spline faces whose boundary overshoots the surface's range "
    "within the edge tolerance import clamped (trj9_ap209-td.stp, whole)",
    "[cad][occt]") {
  const std::string path = occt_file("trj9_ap209-td.stp");
  // The file exercises the clamping: faces whose UV box leaves a non-periodic B-spline's range.
  int overshooting = 0;
  for (const TopoDS_Face& f : faces_of_file(path)) {
    const Handle(Geom_BSplineSurface) bs =
        Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(f));
    if (bs.IsNull()) continue;
    double a = 0, b = 0, c = 0, d = 0, u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    BRepTools::UVBounds(f, a, b, c, d);
    bs->Bounds(u0, u1, v0, v1);
    const double du = 1e-12 * (u1 - u0), dv = 1e-12 * (v1 - v0);
    overshooting += (!bs->IsUPeriodic() && (a < u0 - du || b > u1 + du)) ||
                    (!bs->IsVPeriodic() && (c < v0 - dv || d > v1 + dv));
  }
  CHECK(overshooting >= 1);
  const Totals t = import_and_compare("trj9_ap209-td.stp");
  CHECK(t.same >= t.points / 2);
}

TEST_CASE(
    "cad import (OCCT data): trimmed extrusions of B-spline curves keep OCCT's parameters "
    "and import trimmed (trj4_k1_top-pe-203.stp, whole)",
    "[cad][occt]") {
  const CadImport imp = import_cad(occt_file("trj4_k1_top-pe-203.stp"), "k1");
  int trimmed_extrusions = 0;
  for (const CadFace& f : imp.faces)
    trimmed_extrusions += f.cad_type == "extrusion" && f.entity_type == "trimmed nurbs_surface";
  CHECK(trimmed_extrusions >= 3);
  const Totals t = import_and_compare("trj4_k1_top-pe-203.stp");
  CHECK(t.same >= t.points / 2);
}

TEST_CASE(
    "cad import (OCCT data): trimmed revolutions and extrusions of lines, conic arcs and "
    "B-spline curves import in the face's own parameters, their loops following",
    "[cad][occt]") {
  // PRO19800.igs: one trimmed revolution of a line (its u, the angle, is a conic arc).
  // trj5_k1-ug-214.stp: a trimmed extrusion of an ellipse whose face crosses the ellipse's
  // origin (u in [-1.37, 4.51]). bug22566_test_Bad.igs: revolutions of circle arcs (conic arcs
  // in both directions) on OCCT trimmed surfaces whose v range the face's box leaves by 1e-8.
  // UKI60998.igs: an extrusion of a circle arc sweeping 2 pi + 3e-9.
  struct Case {
    const char* file;
    int face;
    const char* cad_type;
    const char* entity_type;
  };
  for (const Case& c : {Case{"PRO19800.igs", 0, "revolution", "trimmed nurbs_surface"},
                        Case{"trj5_k1-ug-214.stp", 4, "extrusion", "trimmed nurbs_surface"},
                        Case{"bug22566_test_Bad.igs", 0, "revolution", "nurbs_surface"},
                        Case{"UKI60998.igs", 1, "extrusion", "nurbs_surface"}}) {
    INFO(c.file << " face " << c.face);
    const CadImport imp = import_cad(occt_file(c.file), "f");
    REQUIRE(static_cast<int>(imp.faces.size()) > c.face);
    CHECK(imp.faces[static_cast<std::size_t>(c.face)].cad_type == c.cad_type);
    CHECK(imp.faces[static_cast<std::size_t>(c.face)].entity_type == c.entity_type);
    CHECK(imp.faces[static_cast<std::size_t>(c.face)].exact);
    const Totals t = import_and_compare(c.file);
    CHECK(t.same >= t.points / 2);
  }
}

TEST_CASE(
    "cad import (OCCT data): B-spline faces reaching past their surface's range beyond the edge "
    "tolerance, their edges on the surface's continuation, import extended "
    "(bug27693_cornetta-step.stp)",
    "[cad][occt]") {
  // These faces' boundaries reach 1e-7 .. 2.4e-4 (parameter) past a rational B-spline's u or v
  // range, up to 1.3e-3 in 3-D, more than their edges' tolerance from the surface's side; their
  // edges pass OpenCASCADE's own check on the face, against the surface's polynomial
  // continuation: the surface is extended by its end polynomials. (The whole file imports; its
  // other faces are left out here to keep the test fast.)
  const std::string path = occt_file("bug27693_cornetta-step.stp");
  CadOptions options;
  options.faces = {9, 11, 14, 17, 19, 24, 26, 37, 82, 88, 105};
  const CadImport imp = import_cad(path, "c", options);
  const std::vector<TopoDS_Face> faces = faces_of_file(path);
  REQUIRE(imp.entities.size() == options.faces.size());
  for (std::size_t i = 0; i < options.faces.size(); ++i) {
    const TopoDS_Face& face = faces[static_cast<std::size_t>(options.faces[i])];
    INFO("face " << options.faces[i]);
    CHECK(imp.faces[i].exact);
    // the imported surface reaches past the B-spline's own range
    const Handle(Geom_BSplineSurface) bs =
        Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(face));
    REQUIRE_FALSE(bs.IsNull());
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    bs->Bounds(u0, u1, v0, v1);
    const Surface* s = as_surface(imp.entities[i].second);
    REQUIRE(s != nullptr);
    if (const auto* t = dynamic_cast<const TrimmedSurface*>(s)) s = &t->base();
    const Domain2 d = s->domain();
    CHECK((d.u.lo < u0 - 1e-7 || d.u.hi > u1 + 1e-7 || d.v.lo < v0 - 1e-7 || d.v.hi > v1 + 1e-7));
    const test::OcctComparison c =
        test::compare_with_occt(face, imp.entities[i].second, imp.faces[i].tolerance);
    INFO(c.failure << "; " << c.ours_failed << " points without a foot");
    CHECK(c.failure.empty());
    CHECK(c.ours_failed == 0);
    // Long thin strips: many feet on a bound (OCCT's there not converged along it, or none).
    CHECK(c.same >= c.points / 3);
  }
}

TEST_CASE(
    "cad import (OCCT data): a B-spline face starting 1e-10 before a knot is cut there, not at "
    "the knot (trj2_io1-ca-214.stp, whole)",
    "[cad][occt]") {
  // Faces 0, 2, 15, 22: their v range [0.2499999999, 0.7500000001] starts and ends 1e-10 off
  // the knots 0.25 and 0.75; OCCT's Segment by default snaps to a knot within 1e-9, which
  // would leave out 1e-10 of the face (2.5e-9 in 3-D, more than the 1e-10 of the size the
  // conversion is checked to).
  const std::string path = occt_file("trj2_io1-ca-214.stp");
  const std::vector<TopoDS_Face> faces = faces_of_file(path);
  CadOptions options;
  options.faces = {0};
  const CadImport imp = import_cad(path, "io", options);
  const Surface* s = as_surface(imp.entities[0].second);
  REQUIRE(s != nullptr);
  if (const auto* t = dynamic_cast<const TrimmedSurface*>(s)) s = &t->base();
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(faces[0], u0, u1, v0, v1);
  CHECK(v0 < 0.25 - 5e-11);
  CHECK(s->domain().v.lo == Approx(v0).epsilon(1e-14));
  CHECK(s->domain().v.hi == Approx(v1).epsilon(1e-14));
  const Totals t = import_and_compare("trj2_io1-ca-214.stp");
  CHECK(t.same >= t.points / 2);
}

TEST_CASE(
    "cad import (OCCT data): faces covering no area of their surface are refused, the message "
    "naming why (bug25415_part_of_hdrv8w64p254_4x2_1016x502h838p.stp)",
    "[cad][occt]") {
  const std::string path = occt_file("bug25415_part_of_hdrv8w64p254_4x2_1016x502h838p.stp");
  CadOptions options;
  // Face 6: two straight edges whose parameter curves do not join (a gap of 0.171; the 3-D
  // edges are 0.44 off the plane, joined only within vertex tolerances of 0.755).
  options.faces = {6};
  REQUIRE_THROWS_WITH(import_cad(path, "f", options),
                      Contains("face 6 (plane)") &&
                          Contains("its parameter curves leave gaps up to 0.171") &&
                          Contains("vertices' tolerance 0.755") &&
                          Contains("the face covers no area of its surface"));
  // Face 13: both edges along the line v = 8.08.
  options.faces = {13};
  REQUIRE_THROWS_WITH(import_cad(path, "f", options), Contains("face 13 (plane)") &&
                                                          Contains("spans no area") &&
                                                          Contains("v [8.08, 8.08]"));
  // The whole file: nothing of the part is lost without them, so both are skipped with a
  // warning each, every other face imports; a strict import refuses the first.
  const CadImport all = import_cad(path, "f");
  const std::vector<TopoDS_Face> faces = faces_of_file(path);
  CHECK(all.entities.size() == faces.size() - 2);
  std::vector<std::string> skipped;
  for (const std::string& w : all.warnings)
    if (w.find("skipped, it covers no area") != std::string::npos) skipped.push_back(w);
  REQUIRE(skipped.size() == 2);
  CHECK_THAT(skipped[0],
             Contains(path) && Contains("face 6 (plane)") && Contains("gaps up to 0.171"));
  CHECK_THAT(skipped[1],
             Contains(path) && Contains("face 13 (plane)") && Contains("spans no area"));
  for (const CadFace& f : all.faces) CHECK((f.index != 6 && f.index != 13));
  CadOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(import_cad(path, "f", strict),
                    Contains("face 6 (plane)") && Contains("refused: strict import"));
}

TEST_CASE(
    "cad import: a B-spline face overshooting its surface's range is clamped within the "
    "edge tolerance, extended by the surface's own polynomials where its edges lie on them, "
    "refused otherwise",
    "[cad]") {
  // Bicubic patches on [0, 1]^2 and their faces; then each face's surface is replaced by the
  // same patch cut to u <= 0.999 (Segment keeps the parameters): the face's boundary reaches
  // 1e-3 past the new surface's u range, about 1e-3 |S_u| ~ 4e-3 in 3-D.
  //   smooth: one polynomial span, so the cut surface's polynomial continuation past 0.999 is
  //     the full patch, on which the face's edges lie;
  //   kinked: u knots {0, 0.999, 1}, 0.999 of multiplicity 3 (C0), the last span's poles
  //     raised by 0.5: the edge at u = 1 is far from the cut surface's continuation.
  TColStd_Array1OfReal knots(1, 2);
  knots(1) = 0, knots(2) = 1;
  TColStd_Array1OfInteger mults(1, 2);
  mults(1) = 4, mults(2) = 4;
  TColgp_Array2OfPnt poles(1, 4, 1, 4);
  for (int j = 1; j <= 4; ++j)
    for (int i = 1; i <= 4; ++i)
      poles(i, j) = gp_Pnt(4.0 * (i - 1) / 3, 3.0 * (j - 1) / 3, 0.1 * i * j);
  const Handle(Geom_BSplineSurface) smooth =
      new Geom_BSplineSurface(poles, knots, knots, mults, mults, 3, 3);
  TColgp_Array2OfPnt kinked_poles(1, 7, 1, 4);
  for (int j = 1; j <= 4; ++j)
    for (int i = 1; i <= 7; ++i)
      kinked_poles(i, j) =
          gp_Pnt(4.0 * (i - 1) / 6, 3.0 * (j - 1) / 3, 0.1 * i * j + (i == 7 ? 0.5 : 0.0));
  TColStd_Array1OfReal kinked_knots(1, 3);
  kinked_knots(1) = 0, kinked_knots(2) = 0.999, kinked_knots(3) = 1;
  TColStd_Array1OfInteger kinked_mults(1, 3);
  kinked_mults(1) = 4, kinked_mults(2) = 3, kinked_mults(3) = 4;
  const Handle(Geom_BSplineSurface) kinked =
      new Geom_BSplineSurface(kinked_poles, kinked_knots, knots, kinked_mults, mults, 3, 3);
  // The face on the full patch, then its surface replaced by the cut one, and its edges'
  // parameter curves (stored per surface) attached to the new surface, with the edge tolerance.
  auto face_with = [&](const Handle(Geom_BSplineSurface) & full, double edge_tol) {
    const Handle(Geom_BSplineSurface) cut = Handle(Geom_BSplineSurface)::DownCast(full->Copy());
    cut->Segment(0.0, 0.999, 0.0, 1.0);
    TopoDS_Face f = BRepBuilderAPI_MakeFace(full, 0.0, 1.0, 0.0, 1.0, 1e-7).Face();
    std::vector<std::pair<TopoDS_Edge, Handle(Geom2d_Curve)>> pcurves;
    for (TopExp_Explorer e(f, TopAbs_EDGE); e.More(); e.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
      double t0 = 0, t1 = 0;
      pcurves.emplace_back(edge, BRep_Tool::CurveOnSurface(edge, f, t0, t1));
    }
    BRep_Builder b;
    b.UpdateFace(f, cut, TopLoc_Location(), BRep_Tool::Tolerance(f));
    for (const auto& [edge, pc] : pcurves) b.UpdateEdge(edge, pc, f, edge_tol);
    return f;
  };
  SECTION("within the edges' tolerance (1e-2): clamped to the range") {
    const TopoDS_Face f = face_with(smooth, 1e-2);
    const auto [entity, d] = import_face(f, 0);
    REQUIRE(std::holds_alternative<NurbsSurface>(entity));
    CHECK_FALSE(d.trimmed);
    const Domain2 dom = std::get<NurbsSurface>(entity).domain();
    CHECK(dom.u.hi == Approx(0.999).epsilon(1e-12));
    CHECK(dom.v.hi == Approx(1.0).epsilon(1e-12));
    const test::OcctComparison c = test::compare_with_occt(f, entity);
    INFO(c.failure);
    CHECK(c.failure.empty());
  }
  SECTION("beyond it (1e-4), the edges on the continuation: extended to the face's range") {
    const TopoDS_Face f = face_with(smooth, 1e-4);
    const auto [entity, d] = import_face(f, 0);
    REQUIRE(std::holds_alternative<NurbsSurface>(entity));
    CHECK(d.exact);
    const NurbsSurface& ns = std::get<NurbsSurface>(entity);
    const Domain2 dom = ns.domain();
    CHECK(dom.u.hi == Approx(1.0).epsilon(1e-12));
    CHECK(dom.v.hi == Approx(1.0).epsilon(1e-12));
    // the extension is the full patch again (its polynomial): the same points at equal (u, v)
    for (const double u : {0.0, 0.5, 0.9995, 1.0})
      for (const double v : {0.0, 0.3, 1.0}) {
        const gp_Pnt p = smooth->Value(u, v);
        CHECK((ns.point(u, v) - Vector3d(p.X(), p.Y(), p.Z())).norm() < 1e-13);
      }
    const test::OcctComparison c = test::compare_with_occt(f, entity);
    INFO(c.failure);
    CHECK(c.failure.empty());
  }
  SECTION("beyond it (1e-4), an edge off the continuation: refused, naming both distances") {
    REQUIRE_THROWS_WITH(import_face(face_with(kinked, 1e-4), 0),
                        Contains("past the B-spline surface's u range") &&
                            Contains("from the surface's continuation") &&
                            Contains("more than the edge's tolerance") &&
                            Contains("the edge does not lie on its face") &&
                            !Contains("periodic seam"));
  }
}

TEST_CASE(
    "cad import: cone faces on either nappe are our cones, a face across the apex exact "
    "NURBS, all projecting as OpenCASCADE's",
    "[cad]") {
  // OCCT's cone: P = O + (R0 + v sin A)(cos u X + sin u Y) + v cos A Z, apex at v = -R0 / sin A
  // = -4 here (R0 = 2, A = pi/6); frames right- and left-handed, both signs of A.
  const double R0 = 2.0;
  for (const double A : {std::numbers::pi / 6, -std::numbers::pi / 6})
    for (const bool direct : {true, false}) {
      gp_Ax3 ax(gp_Pnt(1, -2, 0.5), gp_Dir(1, 2, 3), gp_Dir(3, 0, -1));
      if (!direct) ax.YReverse();
      const Handle(Geom_ConicalSurface) cone = new Geom_ConicalSurface(ax, A, R0);
      const double apex = -R0 / std::sin(A);
      struct Case {
        double v0, v1;
        const char* entity;
      };
      // Beyond the apex (radius < 0), on the near side, and across it.
      const Case cases[] = {{apex + (A > 0 ? -3.0 : 0.5), apex + (A > 0 ? -0.5 : 3.0), "cone"},
                            {apex + (A > 0 ? 0.5 : -3.0), apex + (A > 0 ? 3.0 : -0.5), "cone"},
                            {apex - 1.5, apex + 2.0, "nurbs_surface"}};
      for (const Case& c : cases) {
        const TopoDS_Face f = BRepBuilderAPI_MakeFace(cone, 0.3, 4.0, c.v0, c.v1, 1e-7).Face();
        INFO("A = " << A << (direct ? ", right-handed" : ", left-handed") << ", v in [" << c.v0
                    << ", " << c.v1 << "]");
        const auto [entity, d] = import_face(f, 0);
        CHECK(d.entity_type == c.entity);
        CHECK(d.exact);
        const test::OcctComparison cmp = test::compare_with_occt(f, entity);
        INFO(cmp.failure);
        CHECK(cmp.failure.empty());
        CHECK(cmp.same >= cmp.points / 2);
      }
    }
}

TEST_CASE(
    "cad import: spherical faces reaching a pole project as OpenCASCADE's (the comparison "
    "accepts a foot at the pole, whose longitude is any)",
    "[cad]") {
  // As bug33398.step face 294 and bug25013_25013face.stp face 0: u in [0.12, pi/2] or
  // [0.5, 2.64], v up to the pole pi/2. OCCT finds no interior extremum for a foot at the pole,
  // and ShapeAnalysis_Surface gives it a longitude outside the face's box.
  const Handle(Geom_SphericalSurface) sphere =
      new Geom_SphericalSurface(gp_Ax3(gp_Pnt(1, 2, -3), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), 15.0);
  for (const auto& [u0, u1] :
       {std::pair{0.1206, std::numbers::pi / 2}, std::pair{0.5043, 2.6372}}) {
    const TopoDS_Face f =
        BRepBuilderAPI_MakeFace(sphere, u0, u1, 0.0, std::numbers::pi / 2, 1e-7).Face();
    const auto [entity, d] = import_face(f, 0);
    CHECK(d.entity_type == "sphere");
    const test::OcctComparison c = test::compare_with_occt(f, entity, 0.0, 400);
    INFO(c.failure);
    CHECK(c.failure.empty());
    CHECK(c.same >= c.points / 2);
  }
}

}  // namespace test_cad_occt_faces
