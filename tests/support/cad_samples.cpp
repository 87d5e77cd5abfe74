// CAD files made by OpenCASCADE's modelling API (see cad_samples.hpp).
#include "tests/support/cad_samples.hpp"

#include <numbers>
#include <stdexcept>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <GC_MakeCircle.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Precision.hxx>
#include <STEPControl_Writer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>

namespace iga::test {

namespace {
void quiet() {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
}
}  // namespace

gp_Ax2 frame(const Eigen::Vector3d& o, const Eigen::Vector3d& axis, const Eigen::Vector3d& x) {
  return {gp_Pnt(o.x(), o.y(), o.z()), gp_Dir(axis.x(), axis.y(), axis.z()),
          gp_Dir(x.x(), x.y(), x.z())};
}

void write_step(const TopoDS_Shape& shape, const std::string& path) {
  quiet();
  STEPControl_Writer w;
  // The shape's lengths are in the session unit (an import may have changed it): mm, as written.
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  Interface_Static::SetCVal("write.step.unit", "MM");
  if (w.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone ||
      w.Write(path.c_str()) != IFSelect_RetDone)
    throw std::runtime_error("cannot write STEP file " + path);
}

void write_iges(const TopoDS_Shape& shape, const std::string& path) {
  quiet();
  IGESControl_Controller::Init();
  Interface_Static::SetIVal("write.iges.brep.mode", 1);
  Interface_Static::SetCVal("xstep.cascade.unit", "MM");
  IGESControl_Writer w("MM", 1);
  w.AddShape(shape);
  w.ComputeModel();
  if (!w.Write(path.c_str())) throw std::runtime_error("cannot write IGES file " + path);
}

TopoDS_Face bspline_face(bool periodic) {
  const int nu = 6, nv = 5;
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      const double x = 4.0 * (i - 1) / (nu - 1), y = 3.0 * (j - 1) / (nv - 1);
      const double z = 0.4 * std::sin(1.3 * x + 0.2) * std::cos(0.9 * y) + 0.1 * x;
      if (periodic) {
        const double a = 2 * std::numbers::pi * (i - 1) / nu, r = 1.0 + 0.2 * std::cos(y);
        poles(i, j) = gp_Pnt(r * std::cos(a), r * std::sin(a), y + 0.1 * std::sin(a));
      } else {
        poles(i, j) = gp_Pnt(x, y, z);
      }
      weights(i, j) = 1.0 + 0.3 * std::sin(0.7 * i + 1.1 * j) * std::sin(0.7 * i + 1.1 * j);
    }
  const int p = 3, q = 2;
  // u: clamped, knots 0, 0.3 (double), 1 -> nu = 6 = 3 + 1 + 2 ... sum of mults = nu + p + 1
  TColStd_Array1OfReal uk(1, periodic ? 7 : 3), vk(1, 4);
  TColStd_Array1OfInteger um(1, periodic ? 7 : 3), vm(1, 4);
  if (periodic) {  // periodic: nu + 1 knots of multiplicity 1
    for (int k = 1; k <= 7; ++k) uk(k) = (k - 1) / 6.0, um(k) = 1;
  } else {
    uk(1) = 0.0, uk(2) = 0.3, uk(3) = 1.0;
    um(1) = 4, um(2) = 2, um(3) = 4;
  }
  vk(1) = 0.0, vk(2) = 0.4, vk(3) = 0.7, vk(4) = 1.0;
  vm(1) = 3, vm(2) = 1, vm(3) = 1, vm(4) = 3;
  const Handle(Geom_BSplineSurface) s =
      new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, p, q, periodic, false);
  return BRepBuilderAPI_MakeFace(s, Precision::Confusion()).Face();
}

TopoDS_Face plate_with_hole(double a, double r) {
  BRepBuilderAPI_MakePolygon outer(gp_Pnt(-a / 2, -a / 2, 0), gp_Pnt(a / 2, -a / 2, 0),
                                   gp_Pnt(a / 2, a / 2, 0), gp_Pnt(-a / 2, a / 2, 0), true);
  const gp_Circ c(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), r);
  const TopoDS_Wire hole = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(c).Edge()).Wire();
  BRepBuilderAPI_MakeFace mf(outer.Wire(), true);
  mf.Add(TopoDS::Wire(hole.Reversed()));
  return mf.Face();
}

TopoDS_Shape sheave(double R_out, double w, double R_root, double alpha, double flat) {
  // Profile in the (x, z) half plane: x the radius. Flanks from (R_root, +-flat) out to the rim
  // at x = R_out, rising at the half-angle alpha from the radial direction's normal plane:
  // a flank point at radius x has |z| = flat + (x - R_root) tan(alpha).
  const double z_rim = flat + (R_out - R_root) * std::tan(alpha);
  if (z_rim >= w) throw std::invalid_argument("sheave: the groove is wider than the disc");
  const double R_hub = 0.3 * R_root;
  BRepBuilderAPI_MakePolygon poly;
  poly.Add(gp_Pnt(R_hub, 0, -w));
  poly.Add(gp_Pnt(R_out, 0, -w));
  poly.Add(gp_Pnt(R_out, 0, -z_rim));
  poly.Add(gp_Pnt(R_root, 0, -flat));
  if (flat > 0) poly.Add(gp_Pnt(R_root, 0, flat));
  poly.Add(gp_Pnt(R_out, 0, z_rim));
  poly.Add(gp_Pnt(R_out, 0, w));
  poly.Add(gp_Pnt(R_hub, 0, w));
  poly.Close();
  const TopoDS_Face profile = BRepBuilderAPI_MakeFace(poly.Wire(), true).Face();
  return BRepPrimAPI_MakeRevol(profile, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)),
                               2 * std::numbers::pi)
      .Shape();
}

TopoDS_Shape filleted_die(double a, double height, double r) {
  const TopoDS_Shape box =
      BRepPrimAPI_MakeBox(gp_Pnt(-a / 2, -a / 2, -height), a, a, height).Shape();
  BRepFilletAPI_MakeFillet fillet(box);
  for (TopExp_Explorer e(box, TopAbs_EDGE); e.More(); e.Next()) {
    const BRepAdaptor_Curve c(TopoDS::Edge(e.Current()));
    const gp_Pnt p = c.Value(c.FirstParameter()), q = c.Value(c.LastParameter());
    if (std::abs(p.Z()) < 1e-12 && std::abs(q.Z()) < 1e-12)
      fillet.Add(r, TopoDS::Edge(e.Current()));
  }
  fillet.Build();
  if (!fillet.IsDone()) throw std::runtime_error("filleted_die: OpenCASCADE could not fillet");
  return fillet.Shape();
}

TopoDS_Shape split_xy(const TopoDS_Shape& shape, double x_s, double y_s) {
  // The faces (the shell) are split, not the solid: a split solid would have the cut planes
  // inside it as faces of its parts.
  TopTools_ListOfShape arguments, tools;
  for (TopExp_Explorer e(shape, TopAbs_SHELL); e.More(); e.Next()) arguments.Append(e.Current());
  const double big = 100.0;
  tools.Append(
      BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(x_s, 0, 0), gp_Dir(1, 0, 0)), -big, big, -big, big)
          .Face());
  tools.Append(
      BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, y_s, 0), gp_Dir(0, 1, 0)), -big, big, -big, big)
          .Face());
  BRepAlgoAPI_Splitter splitter;
  splitter.SetArguments(arguments);
  splitter.SetTools(tools);
  splitter.Build();
  if (!splitter.IsDone()) throw std::runtime_error("split_xy: OpenCASCADE could not split");
  return splitter.Shape();
}

}  // namespace iga::test
