// STEP and IGES faces as the project's surfaces (see cad_import.hpp).
#include "cad/cad_import.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <sstream>
#include <type_traits>
#include <variant>

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Adaptor3d_CurveOnSurface.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepGProp.hxx>
#include <BRepLib_ValidateEdge.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_QuasiUniformDeflection.hxx>
#include <GProp_GProps.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <GeomConvert_ApproxSurface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Conic.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Precision.hxx>
#include <STEPConstruct_UnitContext.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <StepGeom_GeomRepContextAndGlobUnitAssCtxAndGlobUncertaintyAssCtx.hxx>
#include <StepRepr_GlobalUnitAssignedContext.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <gp_Ax3.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>
#include <gp_Trsf.hxx>

#include "cad/cad_face.hpp"
#include "geometry/bspline_basis.hpp"
#include "geometry/fitting.hpp"

namespace iga {

namespace {

/// A face that covers no area of its surface (its boundary spans none, or no wire of it
/// encloses any): nothing of the part is lost without it, so a whole-file import skips it with
/// a warning (import_cad_in_process) instead of refusing the file.
class FaceWithoutArea : public CadError {
 public:
  using CadError::CadError;
};

constexpr double kPi = std::numbers::pi;
/// Seconds the reader process may take before it is stopped (IGA_CAD_TIMEOUT overrides).
constexpr double kDefaultReaderTimeout = 900.0;

Vector3d vec(const gp_XYZ& p) {
  return {p.X(), p.Y(), p.Z()};
}
Vector3d vec(const gp_Pnt& p) {
  return vec(p.XYZ());
}
Vector3d vec(const gp_Dir& p) {
  return vec(p.XYZ());
}
gp_Pnt pnt(const Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// OCCT writes its transfer statistics to standard output: not ours to show.
void silence_occt() {
  static std::once_flag once;
  std::call_once(once, [] {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    m->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  });
}

const char* occt_unit(const std::string& unit) {
  static const std::array<std::pair<const char*, const char*>, 7> units = {{{"mm", "MM"},
                                                                            {"cm", "CM"},
                                                                            {"m", "M"},
                                                                            {"in", "INCH"},
                                                                            {"ft", "FT"},
                                                                            {"um", "UM"},
                                                                            {"km", "KM"}}};
  for (const auto& [ours, theirs] : units)
    if (unit == ours) return theirs;
  throw CadError("unknown length unit \"" + unit + "\" (expected mm, cm, m, in, ft, um or km)");
}

std::mutex& occt_mutex() {  // OCCT's reader settings are process-wide statics
  static std::mutex m;
  return m;
}

bool in_reader_child = false;  // this process is the reader child of run_guarded

/// Shortest text that reads back to x.
std::string num(double x) {
  return Json(x).dump();
}

double unit_in_mm(const std::string& unit) {
  static const std::array<std::pair<const char*, double>, 7> units = {{{"mm", 1.0},
                                                                       {"cm", 10.0},
                                                                       {"m", 1e3},
                                                                       {"in", 25.4},
                                                                       {"ft", 304.8},
                                                                       {"um", 1e-3},
                                                                       {"km", 1e6}}};
  for (const auto& [ours, mm] : units)
    if (unit == ours) return mm;
  return 1.0;  // occt_unit has refused it before
}

/// A declared length unit must be a length: finite, positive, 1e-9 m to 1e9 m.
void check_file_unit(const std::string& path, double mm, const std::string& name) {
  if (std::isfinite(mm) && mm >= 1e-6 && mm <= 1e12) return;
  throw CadError(path + ": the file's length unit" + (name.empty() ? "" : " \"" + name + "\"") +
                 " is " + num(mm) +
                 " mm: refused (a length unit must be positive and within 1e-9 m to 1e9 m)");
}

/// The entity's label in the file ("#13" in STEP, "D5" in IGES), or its number in the model.
std::string label_of(const Handle(Interface_InterfaceModel) & model, const Interface_Check& check,
                     int number) {
  if (!model.IsNull() && check.HasEntity()) {
    const Handle(TCollection_HAsciiString) l = model->StringLabel(check.Entity());
    if (!l.IsNull()) return l->ToCString();
  }
  return "entity " + std::to_string(number);
}

/// The entities a check list fails ("#13 (why)"); a failure of the file as a whole (no entity:
/// a syntax error) is returned in `global`.
std::vector<std::string> failed_entities(const Interface_CheckIterator& checks,
                                         const Handle(Interface_InterfaceModel) & model,
                                         std::string& global) {
  std::vector<std::string> out;
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& c = checks.Value();
    if (c.IsNull() || !c->HasFailed()) continue;
    const std::string why = c->CFail(1);
    if (checks.Number() == 0 && !c->HasEntity()) {
      if (global.empty()) global = why;
      continue;
    }
    out.push_back(label_of(model, *c, checks.Number()) + " (" + why + ")");
  }
  return out;
}

/// "FILE: OpenCASCADE could not <what> N entities of the file; skipped: #1 (..), ... and K more".
std::string skipped(const std::string& path, const char* what,
                    const std::vector<std::string>& entities) {
  std::string s = path + ": OpenCASCADE could not " + what + " " + std::to_string(entities.size()) +
                  (entities.size() == 1 ? " entity" : " entities") + " of the file; skipped: ";
  const std::size_t shown = std::min<std::size_t>(entities.size(), 3);
  for (std::size_t i = 0; i < shown; ++i) s += (i ? ", " : "") + entities[i];
  if (entities.size() > shown) s += " and " + std::to_string(entities.size() - shown) + " more";
  return s;
}

struct ReadResult {
  TopoDS_Shape shape;
  CadUnits units;
  std::vector<std::string> warnings;
};

/// STEP: the names FileUnits reports, and the length unit of every representation context
/// (each is checked; the first is the file's unit).
void step_units(STEPControl_Reader& reader, const std::string& path, ReadResult& r) {
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.FileUnits(lengths, angles, solid_angles);
  for (int i = 1; i <= lengths.Length(); ++i) r.units.names.emplace_back(lengths(i).ToCString());
  const Handle(Interface_InterfaceModel) model = reader.Model();
  bool first = true;
  for (int i = 1; !model.IsNull() && i <= model->NbEntities(); ++i) {
    const Handle(Standard_Transient) e = model->Value(i);
    Handle(StepRepr_GlobalUnitAssignedContext) g;
    if (const auto c =
            Handle(StepGeom_GeomRepContextAndGlobUnitAssCtxAndGlobUncertaintyAssCtx)::DownCast(e))
      g = c->GlobalUnitAssignedContext();
    else
      g = Handle(StepRepr_GlobalUnitAssignedContext)::DownCast(e);
    if (g.IsNull()) continue;
    STEPConstruct_UnitContext u;
    const int status = u.ComputeFactors(g);
    if (status != 0 || !u.LengthDone()) {
      const Handle(TCollection_HAsciiString) label = model->StringLabel(e);
      r.warnings.push_back(path + ": the length unit of " +
                           (label.IsNull() ? "entity " + std::to_string(i) : label->ToCString()) +
                           " is not understood by OpenCASCADE (" + u.StatusMessage(status) + ")");
      continue;
    }
    check_file_unit(path, u.LengthFactor(), r.units.names.empty() ? "" : r.units.names.front());
    if (first) r.units.file_unit_mm = u.LengthFactor();
    first = false;
  }
}

/// IGES: the global section's unit (OCCT 7.6's GlobalSection::UnitValue is in mm, whatever its
/// comment says: 25.4 for inches, 1 for mm, whichever unit OCCT is set to convert into).
void iges_units(IGESControl_Reader& reader, const std::string& path, ReadResult& r) {
  const Handle(IGESData_IGESModel) model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
  if (model.IsNull()) return;
  const IGESData_GlobalSection& g = model->GlobalSection();
  std::string name = g.UnitName().IsNull() ? "" : g.UnitName()->ToCString();
  if (name.empty()) name = "unit flag " + std::to_string(g.UnitFlag());
  r.units.names.push_back(name);
  check_file_unit(path, g.UnitValue(), name);
  r.units.file_unit_mm = g.UnitValue();
}

/// Reads with an XSControl reader (STEP or IGES) in the given OCCT unit. The session unit is a
/// process-wide setting: set for this read, then put back. A syntax error of the file is an
/// error; entities OpenCASCADE could not read or transfer are warnings.
template <class Reader>
ReadResult read_with(const std::string& path, const char* unit, const char* format) {
  Reader reader;
  const std::string before = Interface_Static::CVal("xstep.cascade.unit");
  struct Restore {
    const std::string& unit;
    ~Restore() { Interface_Static::SetCVal("xstep.cascade.unit", unit.c_str()); }
  } restore{before};
  Interface_Static::SetCVal("xstep.cascade.unit", unit);
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
    throw CadError(path + ": OpenCASCADE cannot read it as " + format);
  ReadResult r;
  const Handle(Interface_InterfaceModel) model = reader.Model();
  std::string global;
  const std::vector<std::string> unread =
      failed_entities(reader.WS()->ModelCheckList(), model, global);
  // A complaint about a parameter of an IGES global section (a date in the wrong format, seen
  // in OpenCASCADE's own test files) costs no entity: a warning (its unit is checked on its
  // own). Any other failure without an entity (a syntax error of a STEP file cut short) is an
  // error.
  if (!global.empty()) {
    if (!std::is_same_v<Reader, IGESControl_Reader> || global.rfind("Global Section", 0) != 0)
      throw CadError(path + ": the file is malformed: " + global);
    r.warnings.push_back(path + ": OpenCASCADE reports a damaged header (" + global + "); read on");
  }
  if constexpr (std::is_same_v<Reader, STEPControl_Reader>)
    step_units(reader, path, r);
  else
    iges_units(reader, path, r);
  if (!unread.empty()) r.warnings.push_back(skipped(path, "read", unread));
  reader.TransferRoots();
  const Handle(Transfer_TransientProcess) tp = reader.WS()->TransferReader()->TransientProcess();
  if (!tp.IsNull()) {
    std::string ignored;
    const std::vector<std::string> untransferred =
        failed_entities(tp->CheckList(false), model, ignored);
    if (!untransferred.empty()) r.warnings.push_back(skipped(path, "transfer", untransferred));
  }
  r.shape = reader.OneShape();
  return r;
}

void check_file(const std::string& path) {
  (void)cad_format(path);
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(st)) throw CadError(path + ": is a directory, not a CAD file");
  if (!std::filesystem::exists(st)) throw CadError(path + ": no such file");
  if (!std::filesystem::is_regular_file(st)) throw CadError(path + ": not a regular file");
  if (std::filesystem::file_size(path, ec) == 0 && !ec)
    throw CadError(path + ": the file is empty");
}

ReadResult read_shape(const std::string& path, const std::string& unit) {
  const std::string format = cad_format(path);
  check_file(path);
  silence_occt();
  // In the reader child no other thread exists (and a lock another thread of the parent held
  // at the fork would never be released).
  std::unique_lock<std::mutex> lock(occt_mutex(), std::defer_lock);
  if (!in_reader_child) lock.lock();
  const char* u = occt_unit(unit);
  ReadResult r;
  try {
    r = format == "step" ? read_with<STEPControl_Reader>(path, u, "STEP")
                         : read_with<IGESControl_Reader>(path, u, "IGES");
  } catch (const Standard_Failure& e) {
    throw CadError(path + ": OpenCASCADE failed reading it: " + e.GetMessageString());
  }
  if (r.shape.IsNull()) throw CadError(path + ": the file holds no shape");
  r.units.unit = unit;
  r.units.factor = r.units.file_unit_mm / unit_in_mm(unit);
  return r;
}

std::vector<TopoDS_Face> faces_of(const TopoDS_Shape& shape) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_FACE, map);
  std::vector<TopoDS_Face> faces;
  for (int i = 1; i <= map.Extent(); ++i) faces.push_back(TopoDS::Face(map(i)));
  return faces;
}

const char* type_name(GeomAbs_SurfaceType t) {
  switch (t) {
    case GeomAbs_Plane:
      return "plane";
    case GeomAbs_Cylinder:
      return "cylinder";
    case GeomAbs_Cone:
      return "cone";
    case GeomAbs_Sphere:
      return "sphere";
    case GeomAbs_Torus:
      return "torus";
    case GeomAbs_BezierSurface:
      return "bezier";
    case GeomAbs_BSplineSurface:
      return "bspline";
    case GeomAbs_SurfaceOfRevolution:
      return "revolution";
    case GeomAbs_SurfaceOfExtrusion:
      return "extrusion";
    case GeomAbs_OffsetSurface:
      return "offset";
    default:
      return "other";
  }
}

struct UvBox {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};

UvBox uv_bounds(const TopoDS_Face& f) {
  UvBox b;
  BRepTools::UVBounds(f, b.u0, b.u1, b.v0, b.v1);
  return b;
}

/// Every boundary edge of the face runs along one side of its parameter rectangle, in one
/// loop: the face is its surface's rectangle (no trimming to represent).
bool natural_boundary(const TopoDS_Face& f, const UvBox& b, int& wires) {
  wires = 0;
  for (TopExp_Explorer w(f, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  if (wires != 1) return false;
  const double tol = 1e-7 * std::max(b.u1 - b.u0, b.v1 - b.v0);
  // Irregular fractions: a circle inscribed in the rectangle touches it at quarter points.
  constexpr std::array<double, 7> fractions = {0.0, 0.13, 0.29, 0.5, 0.71, 0.87, 1.0};
  for (TopExp_Explorer e(f, TopAbs_EDGE); e.More(); e.Next()) {
    const BRepAdaptor_Curve2d c(TopoDS::Edge(e.Current()), f);
    const double t0 = c.FirstParameter(), t1 = c.LastParameter();
    std::array<bool, 4> on_side = {true, true, true, true};  // u0, u1, v0, v1
    for (const double s : fractions) {
      const gp_Pnt2d p = c.Value(t0 + s * (t1 - t0));
      on_side[0] = on_side[0] && std::abs(p.X() - b.u0) <= tol;
      on_side[1] = on_side[1] && std::abs(p.X() - b.u1) <= tol;
      on_side[2] = on_side[2] && std::abs(p.Y() - b.v0) <= tol;
      on_side[3] = on_side[3] && std::abs(p.Y() - b.v1) <= tol;
    }
    if (!(on_side[0] || on_side[1] || on_side[2] || on_side[3])) return false;
  }
  return true;
}

/// A planar face bounded by one rectangle whose sides are not along the plane's parameter
/// lines (STEP writers choose a plane's frame freely): the corner, the side vectors in 3-D.
struct PlaneRectangle {
  Vector3d corner, side1, side2;
};

std::optional<PlaneRectangle> plane_rectangle(const TopoDS_Face& f, int wires) {
  const Handle(Geom_Surface) s = BRep_Tool::Surface(f);
  if (wires != 1 || GeomAdaptor_Surface(s).GetType() != GeomAbs_Plane) return std::nullopt;
  std::vector<std::pair<gp_Pnt2d, gp_Pnt2d>> sides;
  double scale = 0.0;
  for (TopExp_Explorer e(f, TopAbs_EDGE); e.More(); e.Next()) {
    const BRepAdaptor_Curve2d c(TopoDS::Edge(e.Current()), f);
    const double t0 = c.FirstParameter(), t1 = c.LastParameter();
    const gp_Pnt2d a = c.Value(t0), b = c.Value(t1), m = c.Value(0.5 * (t0 + t1));
    const gp_Pnt2d q = c.Value(t0 + 0.31 * (t1 - t0));
    scale = std::max(scale, a.Distance(b));
    const gp_XY ab = b.XY() - a.XY();
    // straight: the mid point and another point on the chord
    const double off = std::max(std::abs(ab ^ (m.XY() - a.XY())), std::abs(ab ^ (q.XY() - a.XY())));
    if (ab.Modulus() == 0.0 || off > 1e-9 * ab.SquareModulus()) return std::nullopt;
    sides.emplace_back(a, b);
  }
  if (sides.size() != 4) return std::nullopt;
  const double tol = 1e-9 * scale;
  // The two sides at the first side's start point, then the opposite corner.
  const gp_Pnt2d p0 = sides[0].first;
  std::vector<gp_XY> out;
  for (const auto& [a, b] : sides) {
    if (a.Distance(p0) <= tol)
      out.push_back(b.XY() - p0.XY());
    else if (b.Distance(p0) <= tol)
      out.push_back(a.XY() - p0.XY());
  }
  if (out.size() != 2 || std::abs(out[0] * out[1]) > 1e-9 * out[0].Modulus() * out[1].Modulus())
    return std::nullopt;
  const gp_XY far = p0.XY() + out[0] + out[1];
  int meets = 0;
  for (const auto& [a, b] : sides)
    meets += (a.XY() - far).Modulus() <= tol || (b.XY() - far).Modulus() <= tol;
  if (meets != 2) return std::nullopt;
  const gp_Pln pl = GeomAdaptor_Surface(s).Plane();
  const gp_Ax3 ax = pl.Position();
  const Vector3d X = vec(ax.XDirection()), Y = vec(ax.YDirection());
  return PlaneRectangle{vec(ax.Location()) + p0.X() * X + p0.Y() * Y,
                        out[0].X() * X + out[0].Y() * Y, out[1].X() * X + out[1].Y() * Y};
}

CadFace describe(const TopoDS_Face& f, int index) {
  CadFace d;
  d.index = index;
  d.cad_type = type_name(GeomAdaptor_Surface(BRep_Tool::Surface(f)).GetType());
  d.trimmed = !natural_boundary(f, uv_bounds(f), d.wires) && !plane_rectangle(f, d.wires);
  GProp_GProps props;
  BRepGProp::SurfaceProperties(f, props);
  d.area = props.Mass();
  Bnd_Box box;
  BRepBndLib::AddOptimal(f, box, false, false);
  if (!box.IsVoid()) {
    d.box_lo = vec(box.CornerMin());
    d.box_hi = vec(box.CornerMax());
  }
  return d;
}

// ---- conversion -------------------------------------------------------------------------------

/// Our frame of an OCCT gp_Ax3: right-handed (X, Y, +-Z); `flip` when OCCT's was left-handed.
Placement placement_of(const gp_Ax3& ax, bool& flip) {
  flip = !ax.Direct();
  Placement p;
  p.center = vec(ax.Location());
  p.axis = flip ? Vector3d(-vec(ax.Direction())) : vec(ax.Direction());
  p.ref_dir = vec(ax.XDirection());
  return p;
}

/// The parameter of a conic arc's exact NURBS (rational quadratic, [PT97] Sect. 7.5) as a
/// function of the conic's angle t (OCCT's parameter of a circle or ellipse: P = O + cos t A +
/// sin t B). The arc [t0, t0 + n theta] is cut into n segments of equal sweep theta <= pi/2; the
/// knots are t0 + i theta, so the NURBS parameter s equals t at the knots and at the segments'
/// mid points. Within a segment, with phi = t - (its mid angle) and r = 2 (s - s_i) / theta - 1
/// in [-1, 1], the segment is P = O + cos(phi) A' + sin(phi) B' with tan(phi / 2) = r tan(theta /
/// 4) (the half-angle substitution of the rational quadratic with middle weight cos(theta / 2)).
struct ArcMap {
  double t0 = 0, theta = 1;
  int n = 1;
  double operator()(double t) const {
    const int i = std::clamp(static_cast<int>(std::floor((t - t0) / theta)), 0, n - 1);
    const double phi = t - (t0 + (i + 0.5) * theta);
    const double r = std::tan(0.5 * phi) / std::tan(0.25 * theta);
    return t0 + theta * (i + 0.5 * (1.0 + r));
  }
  /// max |ds/dt| (at the segments' ends): theta / (2 sin(theta / 2)).
  double slope() const { return theta / (2.0 * std::sin(0.5 * theta)); }
};

/// Our parameters from OCCT's: u' = au u + bu, v' = av v + bv; or, in a direction holding a conic
/// arc of an exact conversion (revolutions, extrusions), its ArcMap.
struct UvMap {
  double au = 1, bu = 0, av = 1, bv = 0;
  std::optional<ArcMap> arc_u, arc_v;
  double u(double x) const { return arc_u ? (*arc_u)(x) : au * x + bu; }
  double v(double y) const { return arc_v ? (*arc_v)(y) : av * y + bv; }
  /// max |du'/du|, |dv'/dv|
  double slope() const {
    return std::max(arc_u ? arc_u->slope() : std::abs(au), arc_v ? arc_v->slope() : std::abs(av));
  }
  Domain2 domain(const UvBox& b) const {
    const double ua = u(b.u0), ub = u(b.u1);
    const double va = v(b.v0), vb = v(b.v1);
    return {{std::min(ua, ub), std::max(ua, ub)}, {std::min(va, vb), std::max(va, vb)}};
  }
};

struct Converted {
  GeometryEntity entity;
  const Surface* surface = nullptr;
  /// The OCCT parameter box the surface was made on: the face's, or (B-spline faces whose
  /// boundary overshoots the surface's range within the edges' tolerance) clamped into it.
  std::optional<UvBox> box;
  UvMap map;           // our (u, v) from OCCT's (analytic faces and unchanged NURBS)
  bool mapped = true;  // false: OCCT reparametrized it (exact conversion or approximation)
  bool exact = true;
  double tolerance = 0.0;
};

NurbsSurface nurbs_of(const Geom_BSplineSurface& bs) {
  const int nu = bs.NbUPoles(), nv = bs.NbVPoles(), p = bs.UDegree(), q = bs.VDegree();
  TColStd_Array1OfReal ku(1, nu + p + 1), kv(1, nv + q + 1);
  bs.UKnotSequence(ku);
  bs.VKnotSequence(kv);
  std::vector<double> knots_u(ku.begin(), ku.end()), knots_v(kv.begin(), kv.end());
  std::vector<Vector3d> points;
  std::vector<double> weights;
  const bool rational = bs.IsURational() || bs.IsVRational();
  for (int j = 1; j <= nv; ++j)
    for (int i = 1; i <= nu; ++i) {  // u fastest
      points.push_back(vec(bs.Pole(i, j)));
      if (rational) weights.push_back(bs.Weight(i, j));
    }
  return {p, std::move(knots_u), q, std::move(knots_v), points, weights};
}

std::string number(double x) {
  std::ostringstream os;
  os.precision(3);
  os << x;
  return os.str();
}

/// OpenCASCADE's own check that the edge lies on the face (BRepCheck_Edge's, by
/// BRepLib_ValidateEdge): its 3-D curve against the face's surface at its parameter curve,
/// S(p(t)) (beyond a B-spline's range: its polynomial continuation), at 23 parameters, within
/// the edge's tolerance plus the curve's and the surface's resolution. `dist`: the distance
/// found; -1 where the edge has no 3-D curve or the check fails.
bool edge_on_face(const TopoDS_Edge& edge, const TopoDS_Face& f, double& dist) {
  dist = -1.0;
  if (!BRep_Tool::IsGeometric(edge)) return false;
  double p0 = 0, p1 = 0;
  const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(edge, f, p0, p1);
  if (pc.IsNull()) return false;
  const Handle(Adaptor3d_Curve) c3 = new BRepAdaptor_Curve(edge);
  const Handle(Adaptor3d_CurveOnSurface) on = new Adaptor3d_CurveOnSurface(
      new Geom2dAdaptor_Curve(pc, p0, p1), new BRepAdaptor_Surface(f, false));
  BRepLib_ValidateEdge check(c3, on, BRep_Tool::SameParameter(edge));
  check.Process();
  if (!check.IsDone()) return false;
  dist = check.GetMaxDistance();
  return check.CheckTolerance(BRep_Tool::Tolerance(edge));
}

/// The face's box `b` on a non-periodic direction [lo, hi] of the B-spline `bs` (u: dir 0,
/// v: dir 1): within it, clamped into it, or (returns true) kept beyond it, the surface to be
/// extended (extend_bspline). Where an edge's parameter curve p(t) leaves the range, at 65 points
/// of the edge where p(t) is outside:
///   - reach: the 3-D distance from S(p(t)) (OCCT's polynomial continuation of the end span:
///     OCCT's own surface of the face there) to S(clamp(p(t))). Within the edge's tolerance
///     (BRep_Tool::Tolerance: the distance OCCT itself allows between the edge and the face)
///     for every edge: the box is clamped (the face is its surface's within tolerance).
///   - otherwise, where the edge passes OpenCASCADE's own check against S(p(t)) (edge_on_face):
///     the edge lies on the continuation, the face really reaches past the range (a surface
///     made too short by its writer, OCCT's face is the continuation there), and the box is
///     kept: the surface is extended by its own end polynomials.
/// Beyond both, the face is refused, the message giving the overshoot in parameter, the
/// distance of its edge to the continuation and to the surface's side, and the tolerance.
bool fit_into_range(const TopoDS_Face& f, const Geom_BSplineSurface& bs, int dir, double lo,
                    double hi, UvBox& b) {
  double& a = dir == 0 ? b.u0 : b.v0;
  double& z = dir == 0 ? b.u1 : b.v1;
  const double round_off = 1e-12 * (hi - lo);
  if (a >= lo - round_off && z <= hi + round_off) {
    a = std::max(a, lo);
    z = std::min(z, hi);
    return false;
  }
  double su0 = 0, su1 = 0, sv0 = 0, sv1 = 0;
  bs.Bounds(su0, su1, sv0, sv1);
  const char* name = dir == 0 ? "u" : "v";
  bool extend = false;
  int k = 0;
  for (TopExp_Explorer e(f, TopAbs_EDGE); e.More(); e.Next(), ++k) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    const BRepAdaptor_Curve2d pc(edge, f);
    const double t0 = pc.FirstParameter(), t1 = pc.LastParameter();
    const double tol = BRep_Tool::Tolerance(edge);
    double delta = 0.0, reach = 0.0, off = 0.0;
    double c0 = 0, c1 = 0;
    const Handle(Geom_Curve) c3 = BRep_Tool::Curve(edge, c0, c1);
    for (int i = 0; i <= 64; ++i) {
      const double t = t0 + (t1 - t0) * i / 64;
      const gp_Pnt2d q = pc.Value(t);
      const double w = dir == 0 ? q.X() : q.Y();
      const double past = std::max(lo - w, w - hi);
      if (past <= round_off) continue;
      delta = std::max(delta, past);
      const gp_Pnt side = bs.Value(std::clamp(q.X(), su0, su1), std::clamp(q.Y(), sv0, sv1));
      const gp_Pnt continued = bs.Value(q.X(), q.Y());
      reach = std::max(reach, side.Distance(continued));
      if (!c3.IsNull() && BRep_Tool::SameParameter(edge))
        off = std::max(off, c3->Value(t).Distance(side));
    }
    if (reach <= tol) continue;
    double on = -1.0;
    if (edge_on_face(edge, f, on)) {
      extend = true;
      continue;
    }
    const std::string past = "its boundary (edge " + std::to_string(k) + ") reaches " +
                             number(delta) + " past the B-spline surface's " + name + " range [" +
                             number(lo) + ", " + number(hi) + "], " + number(reach) + " in 3-D";
    if (!(on >= 0.0))
      throw CadError(past + ", more than the edge's tolerance " + number(tol) +
                     ", and OpenCASCADE cannot check the edge "
                     "against the surface's continuation (no 3-D curve, or its check failed): the "
                     "face does not lie on its surface");
    throw CadError(past + "; the edge is " + number(on) +
                   " from the surface's continuation (OpenCASCADE's edge check) and " +
                   number(off) + " from its side, more than the edge's tolerance " + number(tol) +
                   ": the edge does not lie on its face");
  }
  if (!extend) {
    a = std::max(a, lo);
    z = std::min(z, hi);
  }
  return extend;
}

/// The Bezier poles h (on [0, 1]) of the same polynomial on [0, s]: de Casteljau at s, the
/// first point of each level ([PT97] A5.6; s > 1 continues the polynomial past its end).
std::vector<Eigen::Vector4d> bezier_continued(std::vector<Eigen::Vector4d> h, double s) {
  std::vector<Eigen::Vector4d> left;
  for (std::size_t r = 0; r < h.size(); ++r) {
    left.push_back(h[0]);
    for (std::size_t i = 0; i + r + 1 < h.size(); ++i) h[i] = (1 - s) * h[i] + s * h[i + 1];
  }
  return left;
}

/// bs (not periodic in dir) extended in direction dir (u: 0, v: 1) to [to_lo, to_hi], a range
/// containing its own, by its own end polynomials: the end span's knot [a, e] raised to
/// multiplicity p (InsertUKnot: exact), its last p + 1 poles are the Bezier form of the end
/// span; de Casteljau at s = (to - a) / (e - a) > 1 in homogeneous coordinates ([PT97] A5.6
/// run beyond [0, 1]) gives the Bezier form of the same rational polynomial on [a, to]. The
/// other direction is made non-periodic (its parameters kept). Throws where a weight of the
/// extension is not positive.
void extend_bspline(Handle(Geom_BSplineSurface) & bs, int dir, double to_lo, double to_hi) {
  bs = Handle(Geom_BSplineSurface)::DownCast(bs->Copy());
  if (dir == 1) bs->ExchangeUV();
  if (bs->IsVPeriodic()) bs->SetVNotPeriodic();
  const int p = bs->UDegree();
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  bs->Bounds(u0, u1, v0, v1);
  if (bs->UMultiplicity(1) != p + 1 || bs->UMultiplicity(bs->NbUKnots()) != p + 1)
    throw CadError(
        "internal error: a non-periodic B-spline without end knots of multiplicity "
        "degree + 1");
  const bool low = to_lo < u0;
  const bool high = to_hi > u1;
  if (high && bs->NbUKnots() > 2) bs->InsertUKnot(bs->UKnot(bs->NbUKnots() - 1), p, 0.0, false);
  if (low && bs->NbUKnots() > 2) bs->InsertUKnot(bs->UKnot(2), p, 0.0, false);
  const int n = bs->NbUPoles(), m = bs->NbVPoles(), nk = bs->NbUKnots();
  TColgp_Array2OfPnt poles(1, n, 1, m);
  TColStd_Array2OfReal weights(1, n, 1, m);
  TColStd_Array1OfReal uk(1, nk), vk(1, bs->NbVKnots());
  TColStd_Array1OfInteger um(1, nk), vm(1, bs->NbVKnots());
  bs->Poles(poles);
  weights.Init(1.0);
  if (bs->IsURational() || bs->IsVRational()) bs->Weights(weights);
  bs->UKnots(uk);
  bs->VKnots(vk);
  bs->UMultiplicities(um);
  bs->VMultiplicities(vm);
  auto continue_end = [&](bool at_high, double to) {
    const double a = at_high ? uk(nk - 1) : uk(2), e = at_high ? uk(nk) : uk(1);
    const double s = (to - a) / (e - a);
    for (int j = 1; j <= m; ++j) {
      // the end span's Bezier poles from a (index 0) to e (index p), homogeneous
      std::vector<Eigen::Vector4d> h;
      for (int r = 0; r <= p; ++r) {
        const int i = at_high ? n - p + r : p + 1 - r;
        const double w = weights(i, j);
        h.emplace_back(w * poles(i, j).X(), w * poles(i, j).Y(), w * poles(i, j).Z(), w);
      }
      const std::vector<Eigen::Vector4d> q = bezier_continued(h, s);
      for (int r = 0; r <= p; ++r) {
        const Eigen::Vector4d& x = q[static_cast<std::size_t>(r)];
        if (!(x[3] > 0.0))
          throw CadError("its surface's polynomial continuation past its range has a weight " +
                         number(x[3]) + " <= 0");
        const int i = at_high ? n - p + r : p + 1 - r;
        poles(i, j).SetCoord(x[0] / x[3], x[1] / x[3], x[2] / x[3]);
        weights(i, j) = x[3];
      }
    }
    (at_high ? uk(nk) : uk(1)) = to;
  };
  if (high) continue_end(true, to_hi);
  if (low) continue_end(false, to_lo);
  bs = new Geom_BSplineSurface(poles, weights, uk, vk, um, vm, p, bs->VDegree());
  if (dir == 1) bs->ExchangeUV();
}

/// A B-spline of degree above kMaxDegree as a polynomial B-spline of degree 7 on the same
/// parameter rectangle: least squares with fixed ends ([PT97] Sect. 9.4.1, fit_curve) on a
/// uniform grid of (2 (n + 7) + 1)^2 samples S(u_i, v_j), n uniform spans per direction:
/// first every row of samples along u, then every column of the rows' control points along v
/// (the tensor-product fit, separable on a grid). n doubles from 4 to 64 until the deviation
/// |ours(u, v) - S(u, v)| at equal parameters, sampled on a 40 x 40 grid off the fitting
/// samples and on the rectangle's sides, is within 1e-10 of the face's size; `bound` is that
/// deviation (the last one if 1e-10 is not reached).
NurbsSurface fit_high_degree(const Geom_BSplineSurface& bs, double size, double& bound) {
  constexpr int p = 7;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  bs.Bounds(u0, u1, v0, v1);
  NurbsSurface best;
  bound = std::numeric_limits<double>::infinity();
  for (int n = 4; n <= 64 && !(bound <= 1e-10 * size); n *= 2) {
    const int m = 2 * (n + p) + 1;
    auto knots = [&](double lo, double hi) {
      std::vector<double> k(p + 1, lo);
      for (int i = 1; i < n; ++i) k.push_back(lo + (hi - lo) * i / n);
      k.insert(k.end(), p + 1, hi);
      return k;
    };
    const std::vector<double> ku = knots(u0, u1), kv = knots(v0, v1);
    std::vector<double> tu(static_cast<std::size_t>(m)), tv(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) {
      tu[static_cast<std::size_t>(i)] = i == m - 1 ? u1 : u0 + (u1 - u0) * i / (m - 1);
      tv[static_cast<std::size_t>(i)] = i == m - 1 ? v1 : v0 + (v1 - v0) * i / (m - 1);
    }
    const int nc = n + p;                     // control points per direction
    std::vector<std::vector<Vector3d>> rows;  // rows[j][k]: control point k of row v_j
    rows.reserve(static_cast<std::size_t>(m));
    for (int j = 0; j < m; ++j) {
      std::vector<Vector3d> q;
      q.reserve(static_cast<std::size_t>(m));
      for (int i = 0; i < m; ++i)
        q.push_back(
            vec(bs.Value(tu[static_cast<std::size_t>(i)], tv[static_cast<std::size_t>(j)])));
      rows.push_back(fit_curve(q, tu, p, ku).curve.control_points());
    }
    std::vector<Vector3d> net(static_cast<std::size_t>(nc * nc));
    for (int k = 0; k < nc; ++k) {
      std::vector<Vector3d> q;
      q.reserve(static_cast<std::size_t>(m));
      for (int j = 0; j < m; ++j)
        q.push_back(rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)]);
      const std::vector<Vector3d> col = fit_curve(q, tv, p, kv).curve.control_points();
      for (int l = 0; l < nc; ++l)
        net[static_cast<std::size_t>(l * nc + k)] = col[static_cast<std::size_t>(l)];  // u fastest
    }
    NurbsSurface fit(p, ku, p, kv, net, {});
    // 40 x 40 points off the fitting samples, and the four sides (where the deviation peaks)
    auto at = [](int i, double off) { return i == 0 ? 0.0 : i == 41 ? 1.0 : (i - 1 + off) / 40; };
    double dev = 0.0;
    for (int j = 0; j <= 41; ++j)
      for (int i = 0; i <= 41; ++i) {
        const double u = u0 + (u1 - u0) * at(i, 0.37), v = v0 + (v1 - v0) * at(j, 0.41);
        dev = std::max(dev, (fit.point(u, v) - vec(bs.Value(u, v))).norm());
      }
    if (dev < bound) {
      bound = dev;
      best = std::move(fit);
    }
  }
  return best;
}

/// The face's range g on bs, direction by direction: a periodic direction may cross the seam
/// (its range anywhere, not longer than the period; returns true then); a non-periodic one lies
/// within the range, or is clamped into it, or reaches past it (fit_into_range; `extend[dir]`).
bool fit_range(const TopoDS_Face& f, const Geom_BSplineSurface& bs, UvBox& g,
               std::array<bool, 2>& extend) {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  bs.Bounds(u0, u1, v0, v1);  // a periodic direction: its first period
  bool across = false;
  const std::array<bool, 2> periodic = {bs.IsUPeriodic(), bs.IsVPeriodic()};
  for (int dir = 0; dir < 2; ++dir) {
    const double lo = dir == 0 ? u0 : v0, hi = dir == 0 ? u1 : v1;
    const double a = dir == 0 ? g.u0 : g.v0, z = dir == 0 ? g.u1 : g.v1;
    if (!periodic[static_cast<std::size_t>(dir)]) {
      extend[static_cast<std::size_t>(dir)] = fit_into_range(f, bs, dir, lo, hi, g);
      continue;
    }
    const double period = hi - lo, round_off = 1e-12 * period;
    if (z - a > period + std::max(round_off, Precision::PConfusion()))
      throw CadError(std::string("its ") + (dir == 0 ? "u" : "v") + " range [" + number(a) + ", " +
                     number(z) + "] is longer than the B-spline's period " + number(period));
    // Past the period's ends by at most OCCT's parametric confusion (1e-9): the same
    // parameter to OCCT (Segment snaps to it), clamped; farther: across the seam.
    const double snap = std::max(round_off, Precision::PConfusion());
    if (a >= lo - snap && z <= hi + snap) {
      (dir == 0 ? g.u0 : g.v0) = std::max(a, lo);
      (dir == 0 ? g.u1 : g.v1) = std::min(z, hi);
    } else {
      across = true;
    }
  }
  return across;
}

/// Cuts the periodic bs to the range g that crosses its seam. Segment puts the piece's
/// parameters into the first period: ours are OCCT's shifted by a whole number of periods,
/// u' = u + b_u (v alike), found from the new bounds, checked, and returned in map.
void cut_across_seam(Geom_BSplineSurface& bs, const UvBox& g, UvMap& map) {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  bs.Bounds(u0, u1, v0, v1);
  const std::array<bool, 2> periodic = {bs.IsUPeriodic(), bs.IsVPeriodic()};
  const std::array<double, 2> periods = {u1 - u0, v1 - v0};
  bs.Segment(g.u0, g.u1, g.v0, g.v1);
  bs.Bounds(u0, u1, v0, v1);
  map.bu = u0 - g.u0;
  map.bv = v0 - g.v0;
  for (int dir = 0; dir < 2; ++dir) {
    const double shift = dir == 0 ? map.bu : map.bv;
    const double len = dir == 0 ? g.u1 - g.u0 : g.v1 - g.v0;
    const double new_len = dir == 0 ? u1 - u0 : v1 - v0;
    const double P = periods[static_cast<std::size_t>(dir)];
    const double turns = periodic[static_cast<std::size_t>(dir)] ? std::round(shift / P) : 0.0;
    const double snap = std::max(1e-12 * P, Precision::PConfusion());
    if (std::abs(shift - turns * P) > snap || std::abs(new_len - len) > snap)
      throw CadError("internal error: OpenCASCADE's cut across the periodic seam made the " +
                     std::string(dir == 0 ? "u" : "v") + " range " + number(len) +
                     " long, shifted by " + number(shift) + ", into one " + number(new_len) +
                     " long (expected the same length shifted by whole periods " + number(P) + ")");
    (dir == 0 ? map.bu : map.bv) = turns * P;
  }
}

/// Makes bs non-periodic and cuts it to the range g (clamped to its bounds) where the face
/// uses part of it or its ends are not clamped (a periodic surface made non-periodic keeps its
/// knot pattern): exactly, by knot insertion.
void cut_to_range(Geom_BSplineSurface& bs, UvBox& g) {
  if (bs.IsUPeriodic()) bs.SetUNotPeriodic();
  if (bs.IsVPeriodic()) bs.SetVNotPeriodic();
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  bs.Bounds(u0, u1, v0, v1);
  const double tu = 1e-12 * (u1 - u0), tv = 1e-12 * (v1 - v0);
  const bool clamped = bs.UMultiplicity(1) == bs.UDegree() + 1 &&
                       bs.UMultiplicity(bs.NbUKnots()) == bs.UDegree() + 1 &&
                       bs.VMultiplicity(1) == bs.VDegree() + 1 &&
                       bs.VMultiplicity(bs.NbVKnots()) == bs.VDegree() + 1;
  g.u0 = std::max(g.u0, u0), g.u1 = std::min(g.u1, u1);
  g.v0 = std::max(g.v0, v0), g.v1 = std::min(g.v1, v1);
  // Knots closer than OCCT's default 1e-9 to the cut are not snapped to (trj2_io1-ca-214.stp
  // face 0: the face starts 1e-10 before a knot; snapped, our surface would miss its first
  // 1e-10, 2.5e-9 in 3-D).
  if (!clamped || g.u0 > u0 + tu || g.u1 < u1 - tu || g.v0 > v0 + tv || g.v1 < v1 - tv)
    bs.Segment(g.u0, g.u1, g.v0, g.v1, tu, tv);
}

Converted from_bspline(const TopoDS_Face& f, Handle(Geom_BSplineSurface) bs, const UvBox& b,
                       double size) {
  bs = Handle(Geom_BSplineSurface)::DownCast(bs->Copy());
  UvBox g = b;
  Converted c;
  std::array<bool, 2> extend = {false, false};
  const bool across = fit_range(f, *bs, g, extend);
  c.box = g;  // the face's range on the surface (before cut_to_range's clamp to its bounds)
  for (int dir = 0; dir < 2; ++dir) {
    if (!extend[static_cast<std::size_t>(dir)]) continue;
    if (across)
      throw CadError("its boundary reaches past the B-spline surface's " +
                     std::string(dir == 0 ? "u" : "v") +
                     " range and crosses its periodic seam in the other direction: not supported");
    extend_bspline(bs, dir, dir == 0 ? g.u0 : g.v0, dir == 0 ? g.u1 : g.v1);
  }
  if (across)
    cut_across_seam(*bs, g, c.map);
  else
    cut_to_range(*bs, g);
  if (bs->IsUPeriodic()) bs->SetUNotPeriodic();
  if (bs->IsVPeriodic()) bs->SetVNotPeriodic();
  if (bs->UDegree() <= kMaxDegree && bs->VDegree() <= kMaxDegree) {
    c.entity = nurbs_of(*bs);
    return c;
  }
  // Our B-spline basis stops at degree kMaxDegree (fixed-size scratch space,
  // geometry/bspline_basis.hpp): a higher degree is approximated on the same parameters
  // (fit_high_degree), the bound reported.
  double bound = 0.0;
  c.entity = fit_high_degree(*bs, size, bound);
  c.exact = false;
  c.tolerance = bound;
  return c;
}

Converted from_analytic(const GeomAdaptor_Surface& ad, const UvBox& b) {
  Converted c;
  bool flip = false;
  switch (ad.GetType()) {
    case GeomAbs_Plane: {
      const Placement p = placement_of(ad.Plane().Position(), flip);
      c.entity = Plane(p, c.map.domain(b));
      break;
    }
    case GeomAbs_Cylinder: {
      const gp_Cylinder g = ad.Cylinder();
      const Placement p = placement_of(g.Position(), flip);
      if (flip) c.map.av = -1;  // v Z = (-v)(-Z)
      c.entity = Cylinder(p, g.Radius(), c.map.domain(b));
      break;
    }
    case GeomAbs_Sphere: {
      const gp_Sphere g = ad.Sphere();
      const Placement p = placement_of(g.Position(), flip);
      if (flip) c.map.av = -1;  // sin(v) Z = sin(-v)(-Z)
      c.entity = Sphere(p, g.Radius(), c.map.domain(b));
      break;
    }
    case GeomAbs_Torus: {
      const gp_Torus g = ad.Torus();
      const Placement p = placement_of(g.Position(), flip);
      if (flip) c.map.av = -1;
      c.entity = Torus(p, g.MajorRadius(), g.MinorRadius(), c.map.domain(b));
      break;
    }
    case GeomAbs_Cone: {
      // P = O + (R0 + v sin A)(cos u X + sin u Y) + v cos A Z: apex at v_a = -R0 / sin A; with
      // rho = R0 + v sin A (signed radius), P - apex = |rho| e_r(u + delta) + rho cot A Z,
      // delta = 0 on the nappe rho > 0 and pi on the other (rho < 0). Each nappe is one of our
      // cones: radius v' = |rho|, axis along the side it opens to (sign of rho cot A along
      // Zeff = s Z, s = -1 for a left-handed frame, Y = Zeff x X); where that is -Zeff the
      // frame turns over X (e_y = -Y) and u' = -(u + delta) + 2 pi.
      const gp_Cone g = ad.Cone();
      const double A = g.SemiAngle(), R0 = g.RefRadius();
      Placement p = placement_of(g.Position(), flip);
      const double s = flip ? -1.0 : 1.0;
      const double va = -R0 / std::sin(A);
      p.center = vec(g.Position().Location()) + va * std::cos(A) * vec(g.Position().Direction());
      const double rho0 = R0 + b.v0 * std::sin(A), rho1 = R0 + b.v1 * std::sin(A);
      const double tol = 1e-12 * std::max(std::abs(rho0), std::abs(rho1));
      const double nappe = rho0 + rho1 >= 0 ? 1.0 : -1.0;  // sign of rho on the face
      if (std::min(nappe * rho0, nappe * rho1) < -tol)
        throw CadError("internal error: a face across the cone's apex reached from_analytic");
      const double delta = nappe > 0 ? 0.0 : kPi;
      c.map.av = nappe * std::sin(A);
      c.map.bv = nappe * R0;  // v' = |rho|, the radius
      if (s * nappe * std::cos(A) / std::sin(A) > 0) {
        c.map.bu = delta;
      } else {  // opens along -Zeff: turn the frame over X
        p.axis = -p.axis;
        c.map.au = -1;
        c.map.bu = 2 * kPi - delta;
      }
      const Domain2 d = c.map.domain(b);
      c.entity = Cone(p, 0.5 * kPi - std::abs(A), {d.u, {std::max(d.v.lo, 0.0), d.v.hi}});
      break;
    }
    default:
      throw CadError("not an analytic surface");
  }
  return c;
}

/// A curve as an exact NURBS in its own parameter t over [t0, t1] (`arc`: for a circle or an
/// ellipse, the NURBS parameter is arc(t); otherwise it is t).
struct CurveNurbs {
  int degree = 1;
  std::vector<double> knots;  // the full sequence
  std::vector<gp_Pnt> poles;
  std::vector<double> weights;
  std::optional<ArcMap> arc;
};

/// The conic arc P(t) = O + cos t A + sin t B, t in [t0, t1] (t1 - t0 <= 2 pi), as the
/// rational quadratic of ArcMap: n segments of sweep theta <= pi/2, each with its end points
/// and the intersection of the end tangents, O + (cos t_m A + sin t_m B) / cos(theta / 2), of
/// weight cos(theta / 2) ([PT97] Sect. 7.5, A7.1). Returned as the coefficients (a, b, w) of
/// each pole O + a A + b B.
struct ArcPoles {
  std::vector<std::array<double, 3>> abw;
  std::vector<double> knots;
  ArcMap map;
};
ArcPoles arc_poles(double t0, double t1) {
  ArcPoles r;
  const int n = std::max(1, static_cast<int>(std::ceil((t1 - t0) / (0.5 * kPi) * (1 - 1e-12))));
  const double theta = (t1 - t0) / n, w = std::cos(0.5 * theta);
  r.map = {t0, theta, n};
  r.knots = {t0, t0, t0};
  for (int i = 0; i < n; ++i) {
    const double a = t0 + i * theta, m = a + 0.5 * theta;
    r.abw.push_back({std::cos(a), std::sin(a), 1.0});
    r.abw.push_back({std::cos(m) / w, std::sin(m) / w, w});
    const double e = i + 1 == n ? t1 : a + theta;
    r.knots.insert(r.knots.end(), i + 1 == n ? 3 : 2, e);
  }
  r.abw.push_back({std::cos(t1), std::sin(t1), 1.0});
  return r;
}

/// The longest arc swept: a full turn, and the few 1e-9 a closed face's boundary curves may
/// reach past it (UKI60998.igs face 1: 2 pi + 3e-9); the arc overlaps itself by that much.
constexpr double kMaxSweep = 2 * kPi * (1 + 1e-6);

/// The basis curve of a revolution or an extrusion over [t0, t1] as an exact NURBS in its own
/// parameter: lines, circles, ellipses, B-spline and Bezier curves (through trimmed curves,
/// which keep their basis' parameter); nullopt for other curves or a range beyond a bounded
/// curve's (left to OCCT's conversion).
std::optional<CurveNurbs> curve_in_own_parameter(Handle(Geom_Curve) c, double t0, double t1) {
  while (const auto tc = Handle(Geom_TrimmedCurve)::DownCast(c)) c = tc->BasisCurve();
  CurveNurbs r;
  if (!(t0 < t1)) return std::nullopt;
  if (const auto line = Handle(Geom_Line)::DownCast(c)) {
    r.knots = {t0, t0, t1, t1};
    r.poles = {line->Value(t0), line->Value(t1)};
    r.weights = {1.0, 1.0};
    return r;
  }
  if (const auto conic = Handle(Geom_Conic)::DownCast(c)) {
    double ra = 0, rb = 0;
    if (const auto circle = Handle(Geom_Circle)::DownCast(c))
      ra = rb = circle->Radius();
    else if (const auto ellipse = Handle(Geom_Ellipse)::DownCast(c))
      ra = ellipse->MajorRadius(), rb = ellipse->MinorRadius();
    else
      return std::nullopt;  // parabola, hyperbola
    if (t1 - t0 > kMaxSweep) return std::nullopt;
    const gp_Ax2 ax = conic->Position();
    const gp_XYZ O = ax.Location().XYZ(), A = ra * ax.XDirection().XYZ(),
                 B = rb * ax.YDirection().XYZ();
    const ArcPoles a = arc_poles(t0, t1);
    r.degree = 2;
    r.knots = a.knots;
    for (const auto& [x, y, w] : a.abw) {
      r.poles.emplace_back(O + x * A + y * B);
      r.weights.push_back(w);
    }
    r.arc = a.map;
    return r;
  }
  if (c->IsKind(STANDARD_TYPE(Geom_BSplineCurve)) || c->IsKind(STANDARD_TYPE(Geom_BezierCurve))) {
    Handle(Geom_BSplineCurve) bs = GeomConvert::CurveToBSplineCurve(c);
    bs = Handle(Geom_BSplineCurve)::DownCast(bs->Copy());
    if (bs->IsPeriodic()) bs->SetNotPeriodic();  // its first period
    const double f = bs->FirstParameter(), l = bs->LastParameter(), eps = 1e-12 * (l - f);
    if (t0 < f - eps || t1 > l + eps) return std::nullopt;
    t0 = std::max(t0, f);
    t1 = std::min(t1, l);
    if (t0 > f + eps || t1 < l - eps) bs->Segment(t0, t1);  // keeps the parameter
    if (bs->Degree() > kMaxDegree) return std::nullopt;
    r.degree = bs->Degree();
    TColStd_Array1OfReal k(1, bs->NbPoles() + bs->Degree() + 1);
    bs->KnotSequence(k);
    r.knots.assign(k.begin(), k.end());
    for (int i = 1; i <= bs->NbPoles(); ++i) {
      r.poles.push_back(bs->Pole(i));
      r.weights.push_back(bs->Weight(i));
    }
    return r;
  }
  return std::nullopt;
}

/// A surface of revolution or of linear extrusion over the face's box b as an exact NURBS in
/// the face's own parameters (OCCT's GeomConvert reparametrizes conic arcs, so a trimmed face's
/// loops would not follow): the basis curve's exact NURBS (curve_in_own_parameter) swept
///   - revolution: S(u, v) = L + R(D, u)(C(v) - L), each pole Q of C(v) turned on its circle
///     about the axis (center O_Q on the axis, A = Q - O_Q, B = D x A) by the arc of u, the
///     weights multiplied ([PT97] A8.1); u maps by the arc's ArcMap;
///   - extrusion: S(u, v) = C(u) + v D, linear in v (degree 1, the same v).
/// A Geom_RectangularTrimmedSurface around it is unwrapped (OCCT evaluates it by its basis, at
/// the same parameters, also beyond its trim). nullopt where the basis curve is not one of
/// curve_in_own_parameter's (OCCT's conversion then).
std::optional<Converted> from_swept(Handle(Geom_Surface) s, const UvBox& b) {
  while (const auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
  std::vector<double> ku, kv, weights;
  std::vector<Vector3d> points;  // u fastest
  int p = 0, q = 0;
  Converted c;
  if (const auto rev = Handle(Geom_SurfaceOfRevolution)::DownCast(s)) {
    if (b.u1 - b.u0 > kMaxSweep) return std::nullopt;
    const std::optional<CurveNurbs> m = curve_in_own_parameter(rev->BasisCurve(), b.v0, b.v1);
    if (!m) return std::nullopt;
    const gp_XYZ L = rev->Axis().Location().XYZ(), D = rev->Axis().Direction().XYZ();
    const ArcPoles a = arc_poles(b.u0, b.u1);
    p = 2, q = m->degree, ku = a.knots, kv = m->knots;
    for (std::size_t j = 0; j < m->poles.size(); ++j) {
      const gp_XYZ Q = m->poles[j].XYZ();
      const gp_XYZ O = L + ((Q - L) * D) * D, A = Q - O, B = D ^ A;
      for (const auto& [x, y, w] : a.abw) {
        points.push_back(vec(O + x * A + y * B));
        weights.push_back(w * m->weights[j]);
      }
    }
    c.map.arc_u = a.map;
    c.map.arc_v = m->arc;
  } else if (const auto ext = Handle(Geom_SurfaceOfLinearExtrusion)::DownCast(s)) {
    const std::optional<CurveNurbs> m = curve_in_own_parameter(ext->BasisCurve(), b.u0, b.u1);
    if (!m) return std::nullopt;
    const gp_XYZ D = ext->Direction().XYZ();
    p = m->degree, q = 1, ku = m->knots, kv = {b.v0, b.v0, b.v1, b.v1};
    for (const double v : {b.v0, b.v1})
      for (std::size_t i = 0; i < m->poles.size(); ++i) {
        points.push_back(vec(m->poles[i].XYZ() + v * D));
        weights.push_back(m->weights[i]);
      }
    c.map.arc_u = m->arc;
  } else {
    return std::nullopt;
  }
  if (std::all_of(weights.begin(), weights.end(), [](double w) { return w == 1.0; }))
    weights.clear();
  c.entity = NurbsSurface(p, std::move(ku), q, std::move(kv), points, weights);
  return c;
}

Converted from_other(const Handle(Geom_Surface) & s, const UvBox& b, double size) {
  Converted c;
  c.mapped = false;
  const Handle(Geom_RectangularTrimmedSurface) patch =
      new Geom_RectangularTrimmedSurface(s, b.u0, b.u1, b.v0, b.v1);
  // Exact for revolutions and extrusions (of conics and B-spline curves) and cones (rational
  // quadratic in u, linear in v: Convert_ConeToBSplineSurface); for other types
  // (offset surfaces) GeomConvert approximates silently, so they take the approximation below,
  // whose bound is known.
  const GeomAbs_SurfaceType type = GeomAdaptor_Surface(s).GetType();
  if (type == GeomAbs_SurfaceOfRevolution || type == GeomAbs_SurfaceOfExtrusion ||
      type == GeomAbs_Cone) {  // a cone face across its apex (convert)
    try {
      const Handle(Geom_BSplineSurface) bs = GeomConvert::SurfaceToBSplineSurface(patch);
      c.entity = nurbs_of(*bs);
      // Where the conversion kept OCCT's parameters (an extrusion of a B-spline curve keeps
      // the curve's u and the length v along the direction): the same rectangle and the same
      // points at equal (u, v) on a 9 x 9 grid, within 1e-10 of the size; then the map is the
      // identity and a trimmed face's loops follow (convert checks its grid again).
      double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
      bs->Bounds(u0, u1, v0, v1);
      const double pt =
          1e-12 * std::max({1.0, std::abs(b.u0), std::abs(b.u1), std::abs(b.v0), std::abs(b.v1)});
      bool kept = std::abs(u0 - b.u0) <= pt && std::abs(u1 - b.u1) <= pt &&
                  std::abs(v0 - b.v0) <= pt && std::abs(v1 - b.v1) <= pt;
      for (int j = 0; j <= 8 && kept; ++j)
        for (int i = 0; i <= 8 && kept; ++i) {
          const double u = b.u0 + (b.u1 - b.u0) * i / 8, v = b.v0 + (b.v1 - b.v0) * j / 8;
          kept = s->Value(u, v).Distance(bs->Value(u, v)) <= 1e-10 * std::max(size, 1.0);
        }
      c.mapped = kept;
      return c;
    } catch (const Standard_Failure&) {  // not convertible exactly: approximate
    }
  }
  // Approximated within 1e-6 of the face's size: C2 where OCCT reaches it, else C0 (a face
  // with a kink, e.g. the offset of a C1 surface); the bound reported is the larger of OCCT's
  // and the deviation sampled on a 41 x 41 grid (the approximation keeps the parameters).
  const double tol = 1e-6 * size;
  Handle(Geom_BSplineSurface) result;
  double bound = 0.0;
  for (const GeomAbs_Shape continuity : {GeomAbs_C2, GeomAbs_C0}) {
    GeomConvert_ApproxSurface approx(patch, tol, continuity, continuity, 9, 9, 400, 0);
    if (!approx.HasResult()) continue;
    result = approx.Surface();
    bound = approx.MaxError();
    if (approx.IsDone()) break;
  }
  if (result.IsNull())
    throw CadError("OpenCASCADE could not approximate it by NURBS within " + std::to_string(tol));
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i) {
      const double u = b.u0 + (b.u1 - b.u0) * i / 40, v = b.v0 + (b.v1 - b.v0) * j / 40;
      bound = std::max(bound, s->Value(u, v).Distance(result->Value(u, v)));
    }
  c.entity = nurbs_of(*result);
  c.exact = false;
  c.tolerance = bound;
  return c;
}

Converted convert(const TopoDS_Face& f, const UvBox& b, double size) {
  if (!(b.u0 < b.u1 && b.v0 < b.v1))
    throw FaceWithoutArea("its boundary spans no area in its surface's parameters (u [" +
                          number(b.u0) + ", " + number(b.u1) + "], v [" + number(b.v0) + ", " +
                          number(b.v1) + "]): a degenerate face");
  const Handle(Geom_Surface) s = BRep_Tool::Surface(f);
  const GeomAdaptor_Surface ad(s);
  Converted c;
  int wires = 0;
  const bool natural = natural_boundary(f, b, wires);
  const std::optional<PlaneRectangle> r = natural ? std::nullopt : plane_rectangle(f, wires);
  if (r) {
    // The plane re-framed on its rectangle: corner, first side along e_x (checked below).
    Placement p;
    p.center = r->corner;
    p.ref_dir = r->side1.normalized();
    p.axis = r->side1.cross(r->side2).normalized();
    c.entity = Plane(p, {{0, r->side1.norm()}, {0, r->side2.norm()}});
    c.mapped = false;
    const Surface& pl = *as_surface(c.entity);
    const double l1 = r->side1.norm(), l2 = r->side2.norm();
    const double err = std::max({(pl.point(l1, 0) - (r->corner + r->side1)).norm(),
                                 (pl.point(0, l2) - (r->corner + r->side2)).norm(),
                                 (pl.point(l1, l2) - (r->corner + r->side1 + r->side2)).norm()});
    if (err > 1e-10 * std::max(size, 1.0))
      throw CadError("internal error: the re-framed plane misses the face's corners by " +
                     std::to_string(err));
  }
  if (!r) switch (ad.GetType()) {
      case GeomAbs_Plane:
      case GeomAbs_Cylinder:
      case GeomAbs_Sphere:
      case GeomAbs_Torus:
        c = from_analytic(ad, b);
        break;
      case GeomAbs_Cone: {
        // A face across the apex (its signed radius R0 + v sin A changes sign) holds parts of
        // both nappes: one of our cones is one nappe, so it becomes the exact NURBS of OCCT's
        // conversion (reparametrized in u: a trimmed one is refused in import_cad).
        const gp_Cone g = ad.Cone();
        const double A = g.SemiAngle(), R0 = g.RefRadius();
        const double rho0 = R0 + b.v0 * std::sin(A), rho1 = R0 + b.v1 * std::sin(A);
        const double tol = 1e-12 * std::max(std::abs(rho0), std::abs(rho1));
        c = std::min(rho0, rho1) < -tol && std::max(rho0, rho1) > tol ? from_other(s, b, size)
                                                                      : from_analytic(ad, b);
        break;
      }
      case GeomAbs_BSplineSurface:
        c = from_bspline(f, ad.BSpline(), b, size);
        break;
      case GeomAbs_BezierSurface:
        c = from_bspline(f, GeomConvert::SurfaceToBSplineSurface(ad.Bezier()), b, size);
        break;
      default:
        if (std::optional<Converted> swept = from_swept(s, b))
          c = std::move(*swept);
        else
          c = from_other(s, b, size);
    }
  Surface& ours = std::visit(
      [](auto& e) -> Surface& {
        if constexpr (std::is_base_of_v<Surface, std::decay_t<decltype(e)>>)
          return e;
        else
          throw CadError("internal error: a face became a " + entity_type(GeometryEntity(e)));
      },
      c.entity);
  // Where the parametrization was kept: the same points as OCCT's, checked on a grid (an
  // approximation on the same parameters: within its bound).
  const double tol = std::max(1e-10 * std::max(size, 1.0), c.exact ? 0.0 : c.tolerance);
  const UvBox g = c.box.value_or(b);
  double worst = 0.0;
  for (int j = 0; j <= 4 && c.mapped; ++j)
    for (int i = 0; i <= 4; ++i) {
      const double u = g.u0 + (g.u1 - g.u0) * i / 4, v = g.v0 + (g.v1 - g.v0) * j / 4;
      const Vector3d theirs = vec(s->Value(u, v));
      const Vector3d mine = ours.point(c.map.u(u), c.map.v(v));
      worst = std::max(worst, (mine - theirs).norm());
    }
  // An approximation's bound is a sampled deviation: where this grid finds more (ec_turbine-A.stp
  // face 18, a degree-11 fit: 3.4e-8 here, 2.3e-8 on the fit's grid), the larger is reported,
  // up to the 1e-6 of the size an approximation may deviate (from_other).
  if (!c.exact && worst > tol && worst <= 1e-6 * size) c.tolerance = worst;
  if (worst > std::max(tol, c.exact ? 0.0 : c.tolerance)) {
    std::ostringstream os;
    os << "internal error: the imported " << entity_type(c.entity) << " is " << worst
       << " away from OpenCASCADE's surface (tolerance " << tol << ")";
    throw CadError(os.str());
  }
  // The face's own normal (OCCT's orientation included): compared at an inner point, OCCT's
  // parameters mapped to ours (a reparametrization by OCCT keeps both directions).
  const double fu = 0.623, fv = 0.571;
  const double um = g.u0 + fu * (g.u1 - g.u0), vm = g.v0 + fv * (g.v1 - g.v0);
  gp_Pnt P;
  gp_Vec Su, Sv;
  s->D1(um, vm, P, Su, Sv);
  Vector3d theirs = vec(Su.Crossed(Sv).XYZ());
  if (f.Orientation() == TopAbs_REVERSED) theirs = -theirs;
  Vector2d uv(c.map.u(um), c.map.v(vm));
  if (!c.mapped) {
    const Domain2 d = ours.domain();
    uv = {d.u.lo + fu * (d.u.hi - d.u.lo), d.v.lo + fv * (d.v.hi - d.v.lo)};
  }
  const SurfaceDerivs dm = ours.derivs(uv[0], uv[1], 1);
  ours.set_normal_sign(dm.Su.cross(dm.Sv).dot(theirs) < 0 ? -1 : 1);
  return c;
}

NurbsCurve nurbs_of(Handle(Geom_BSplineCurve) bs) {
  if (bs->IsPeriodic()) {
    bs = Handle(Geom_BSplineCurve)::DownCast(bs->Copy());
    bs->SetNotPeriodic();
  }
  const int n = bs->NbPoles(), p = bs->Degree();
  TColStd_Array1OfReal k(1, n + p + 1);
  bs->KnotSequence(k);
  std::vector<Vector3d> points;
  std::vector<double> weights;
  for (int i = 1; i <= n; ++i) {
    points.push_back(vec(bs->Pole(i)));
    if (bs->IsRational()) weights.push_back(bs->Weight(i));
  }
  return {p, std::vector<double>(k.begin(), k.end()), points, weights};
}

/// An edge's B-spline curve as ours; a degree above kMaxDegree (our basis' limit) fitted at
/// degree 7 on the same parameter (least squares with fixed ends, fit_curve, n uniform spans,
/// n doubling from 4 to 256 until the deviation at equal parameters, sampled at 401 points off
/// the fitting samples, is within 1e-12 of `scale`, else the closest fit is kept).
NurbsCurve curve_of(const Handle(Geom_BSplineCurve) & bs, double scale) {
  if (bs->Degree() <= kMaxDegree) return nurbs_of(bs);
  constexpr int p = 7;
  const double t0 = bs->FirstParameter(), t1 = bs->LastParameter();
  NurbsCurve best;
  double bound = std::numeric_limits<double>::infinity();
  for (int n = 4; n <= 256 && !(bound <= 1e-12 * scale); n *= 2) {
    std::vector<double> k(p + 1, t0);
    for (int i = 1; i < n; ++i) k.push_back(t0 + (t1 - t0) * i / n);
    k.insert(k.end(), p + 1, t1);
    const int m = 2 * (n + p) + 1;
    std::vector<double> t;
    std::vector<Vector3d> q;
    for (int i = 0; i < m; ++i) {
      t.push_back(i == m - 1 ? t1 : t0 + (t1 - t0) * i / (m - 1));
      q.push_back(vec(bs->Value(t.back())));
    }
    NurbsCurve fit = fit_curve(q, t, p, k).curve;
    double dev = 0.0;
    for (int i = 0; i < 400; ++i) {
      const double s = t0 + (t1 - t0) * (i + 0.43) / 400;
      dev = std::max(dev, (fit.point(s) - vec(bs->Value(s))).norm());
    }
    if (dev < bound) bound = dev, best = std::move(fit);
  }
  return best;
}

/// A wire too short to be a loop, described: its walk in OCCT's parameters (from `first` to
/// `last`, `gap` the largest gap between its parameter curves, the closure included), whether
/// it closes there, and its vertices' tolerance (what closes it in 3-D).
std::string short_wire_text(const TopoDS_Wire& w, int index, int edges, std::size_t points,
                            const gp_Pnt2d& first, const gp_Pnt2d& last, double gap,
                            double deflection) {
  double vertex_tol = 0.0;
  for (TopExp_Explorer v(w, TopAbs_VERTEX); v.More(); v.Next())
    vertex_tol = std::max(vertex_tol, BRep_Tool::Tolerance(TopoDS::Vertex(v.Current())));
  return "wire " + std::to_string(index) + " (" + std::to_string(edges) +
         (edges == 1 ? " edge" : " edges") + ", sampled as " + std::to_string(points) +
         (points == 1 ? " point" : " points") + ", from (" + number(first.X()) + ", " +
         number(first.Y()) + ") to (" + number(last.X()) + ", " + number(last.Y()) + ")" +
         (gap > deflection ? "): its parameter curves leave gaps up to " + number(gap) +
                                 " (joined in 3-D only within its vertices' tolerance " +
                                 number(vertex_tol) + ")"
                           : "): closed, but along straight parameter curves that enclose no "
                             "area") +
         ": the face covers no area of its surface";
}

/// The face's trimming: its loops as polylines in our (u, v) (each edge's parameter curve
/// traversed along the wire, sampled within `deflection` by OCCT), its edges as exact NURBS
/// curves in 3-D (degenerate edges, e.g. at a pole, have none).
TrimmedSurface trimmed_face(const TopoDS_Face& f, const Surface& base, const UvMap& map,
                            const UvBox& b) {
  const double deflection = 1e-6 * std::hypot(b.u1 - b.u0, b.v1 - b.v0);
  const Domain2 dom = base.domain();
  std::vector<TrimmedSurface::Loop> loops;
  int wires = 0, short_wires = 0, walked = 0, edges_in_wires = 0;
  std::string short_wire;
  for (TopExp_Explorer w(f, TopAbs_WIRE); w.More(); w.Next()) {
    ++wires;
    for (TopExp_Explorer e(w.Current(), TopAbs_EDGE); e.More(); e.Next()) ++edges_in_wires;
    TrimmedSurface::Loop loop;
    gp_Pnt2d first, last;    // the walk's start and end in OCCT's parameters
    double joint_gap = 0.0;  // the largest gap between an edge's end and the next one's start
    int wire_edges = 0;
    for (BRepTools_WireExplorer e(TopoDS::Wire(w.Current()), f); e.More(); e.Next(), ++walked) {
      ++wire_edges;
      const BRepAdaptor_Curve2d c(e.Current(), f);
      const GCPnts_QuasiUniformDeflection pts(c, deflection);
      if (!pts.IsDone()) throw CadError("OpenCASCADE could not sample a trimming curve");
      std::vector<double> t;
      for (int i = 1; i <= pts.NbPoints(); ++i) t.push_back(pts.Parameter(i));
      if (e.Current().Orientation() == TopAbs_REVERSED) std::reverse(t.begin(), t.end());
      if (wire_edges == 1) first = c.Value(t.front());
      if (wire_edges > 1) joint_gap = std::max(joint_gap, last.Distance(c.Value(t.front())));
      last = c.Value(t.back());
      for (std::size_t i = 0; i + 1 < t.size(); ++i) {  // the end is the next edge's start
        const gp_Pnt2d q = c.Value(t[i]);
        // Into the base's domain: a B-spline face whose boundary overshoots its surface's range
        // within the edges' tolerance was clamped (fit_into_range); elsewhere (the surface
        // extended where the face reaches past it) the domain holds the face's box and this
        // changes nothing.
        loop.emplace_back(std::clamp(map.u(q.X()), dom.u.lo, dom.u.hi),
                          std::clamp(map.v(q.Y()), dom.v.lo, dom.v.hi));
      }
    }
    if (loop.size() >= 3) {
      loops.push_back(std::move(loop));
      continue;
    }
    if (short_wires++ > 0) continue;
    short_wire =
        short_wire_text(TopoDS::Wire(w.Current()), wires - 1, wire_edges, loop.size(), first, last,
                        std::max(joint_gap, first.Distance(last)), deflection);
  }
  if (loops.empty()) {
    const std::string why =
        "none of its " + std::to_string(wires) +
        " boundary wires is a loop of 3 or more points in its parameters (" +
        std::to_string(walked) + " of " + std::to_string(edges_in_wires) +
        " edges reached walking the wires: fewer means a wire that is not connected); " +
        short_wire;
    // Every edge walked and no wire with 3 points: no wire encloses any area. A wire not
    // walked whole may, so that face is refused.
    if (walked == edges_in_wires) throw FaceWithoutArea(why);
    throw CadError(why);
  }
  std::vector<NurbsCurve> edges;
  // Length scale of the face's coordinates (its position and its corner-to-corner extent).
  const Vector3d lo = base.point(dom.u.lo, dom.v.lo), hi = base.point(dom.u.hi, dom.v.hi);
  const double scale3d = lo.norm() + (hi - lo).norm();
  TopTools_IndexedMapOfShape seen;
  TopExp::MapShapes(f, TopAbs_EDGE, seen);
  for (int i = 1; i <= seen.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(seen(i));
    if (BRep_Tool::Degenerated(edge)) continue;
    double t0 = 0, t1 = 0;
    const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, t0, t1);
    if (c.IsNull()) continue;
    edges.push_back(
        curve_of(GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(c, t0, t1)), scale3d));
  }
  const double scale = map.slope();
  return {base, std::move(loops), std::move(edges), deflection * scale};
}

TopoDS_Shape placed(const TopoDS_Shape& shape, const CadPlacement& pl) {
  if (pl.angle == 0.0 && pl.vector.isZero(0.0)) return shape;
  if (!(pl.axis.norm() > 0.0)) throw CadError("placement: the rotation axis is zero");
  gp_Trsf rot, move;
  rot.SetRotation(gp_Ax1(pnt(pl.point), gp_Dir(pl.axis.x(), pl.axis.y(), pl.axis.z())), pl.angle);
  move.SetTranslation(gp_Vec(pl.vector.x(), pl.vector.y(), pl.vector.z()));
  return BRepBuilderAPI_Transform(shape, move.Multiplied(rot), true).Shape();  // rot first
}

}  // namespace

std::string cad_format(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".step" || ext == ".stp") return "step";
  if (ext == ".iges" || ext == ".igs") return "iges";
  throw CadError(path + ": not a CAD file this program reads (.step, .stp, .iges, .igs)");
}

namespace {

// ---- the import loop ----------------------------------------------------------------------------

constexpr double kModelBound = 1e100;  // geometry_io's bound on every number of a model

/// Every number of the entity as the model file would hold it is within the model bounds.
void check_bounds(const Json& j, const std::string& type) {
  if (j.is_number()) {
    const double x = j.get<double>();
    if (!std::isfinite(x) || std::abs(x) > kModelBound)
      throw CadError("a number of the converted " + type + " is " + num(x) +
                     ", beyond the model bounds (|x| <= 1e100)");
  } else if (j.is_structured()) {
    for (const Json& v : j) check_bounds(v, type);
  }
}

/// The face described; its size and area within the model bounds.
CadFace describe_checked(const TopoDS_Face& face, int index) {
  CadFace f = describe(face, index);
  bool ok = std::isfinite(f.area);  // a length squared: finite is enough
  for (int i = 0; i < 3; ++i)
    ok = ok && std::isfinite(f.box_lo[i]) && std::isfinite(f.box_hi[i]) &&
         std::abs(f.box_lo[i]) <= kModelBound && std::abs(f.box_hi[i]) <= kModelBound;
  if (!ok) {
    f.area = 0.0;
    f.box_lo.setZero();
    f.box_hi.setZero();
    throw CadError("its size is beyond the model bounds (|x| <= 1e100)");
  }
  return f;
}

/// The face converted (f's entity_type, exact and tolerance set), or nullopt and `why`.
std::optional<GeometryEntity> try_convert(const TopoDS_Face& face, CadFace& f, std::string& why,
                                          bool* no_area = nullptr) {
  try {
    const UvBox b = uv_bounds(face);
    const Converted c = convert(face, b, (f.box_hi - f.box_lo).norm());
    f.entity_type = entity_type(c.entity);
    f.exact = c.exact;
    f.tolerance = c.tolerance;
    GeometryEntity e = c.entity;
    if (f.trimmed) {
      if (!c.mapped)
        throw CadError("trimmed, on a surface OpenCASCADE had to reparametrize (" + f.cad_type +
                       "): its trimming curves cannot follow; not supported");
      e = trimmed_face(face, *as_surface(c.entity), c.map, b);
      f.entity_type = "trimmed " + entity_type(c.entity);
    }
    check_bounds(entity_to_json(e), f.entity_type);
    return e;
  } catch (const FaceWithoutArea& e) {
    why = e.what();
    if (no_area != nullptr) *no_area = true;
  } catch (const CadError& e) {
    why = e.what();
  } catch (const std::exception& e) {  // GeometryError of our constructors
    why = std::string("cannot be imported: ") + e.what();
  } catch (const Standard_Failure& e) {
    why = std::string("OpenCASCADE failed: ") + e.GetMessageString();
  }
  f.entity_type.clear();
  return std::nullopt;
}

// ---- the result through a pipe ----------------------------------------------------------------

Json vec_json(const Eigen::Vector3d& v) {
  return Json::array({v.x(), v.y(), v.z()});
}
Eigen::Vector3d vec_from(const Json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

Json face_json(const CadFace& f) {
  return Json{{"index", f.index},
              {"cad_type", f.cad_type},
              {"entity_type", f.entity_type},
              {"exact", f.exact},
              {"tolerance", f.tolerance},
              {"trimmed", f.trimmed},
              {"wires", f.wires},
              {"area", f.area},
              {"box_lo", vec_json(f.box_lo)},
              {"box_hi", vec_json(f.box_hi)},
              {"message", f.message},
              {"described", f.described}};
}
CadFace face_from(const Json& j) {
  CadFace f;
  f.index = j.at("index").get<int>();
  f.cad_type = j.at("cad_type").get<std::string>();
  f.entity_type = j.at("entity_type").get<std::string>();
  f.exact = j.at("exact").get<bool>();
  f.tolerance = j.at("tolerance").get<double>();
  f.trimmed = j.at("trimmed").get<bool>();
  f.wires = j.at("wires").get<int>();
  f.area = j.at("area").get<double>();
  f.box_lo = vec_from(j.at("box_lo"));
  f.box_hi = vec_from(j.at("box_hi"));
  f.message = j.at("message").get<std::string>();
  f.described = j.at("described").get<bool>();
  return f;
}

Json units_json(const CadUnits& u) {
  return Json{
      {"names", u.names}, {"file_unit_mm", u.file_unit_mm}, {"unit", u.unit}, {"factor", u.factor}};
}
CadUnits units_from(const Json& j) {
  CadUnits u;
  u.names = j.at("names").get<std::vector<std::string>>();
  u.file_unit_mm = j.at("file_unit_mm").get<double>();
  u.unit = j.at("unit").get<std::string>();
  u.factor = j.at("factor").get<double>();
  return u;
}

Json faces_json(const std::vector<CadFace>& faces) {
  Json a = Json::array();
  for (const CadFace& f : faces) a.push_back(face_json(f));
  return a;
}
std::vector<CadFace> faces_from(const Json& j) {
  std::vector<CadFace> out;
  for (const Json& f : j) out.push_back(face_from(f));
  return out;
}

const char* signal_name(int s) {
  switch (s) {
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGABRT:
      return "SIGABRT";
    case SIGFPE:
      return "SIGFPE";
    case SIGILL:
      return "SIGILL";
    case SIGKILL:
      return "SIGKILL";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

/// The reader's time limit in seconds: IGA_CAD_TIMEOUT if set (a positive number), else
/// kDefaultReaderTimeout. A bad value is an error naming the variable and the value.
double reader_timeout_seconds() {
  const char* env = std::getenv("IGA_CAD_TIMEOUT");
  if (env == nullptr || *env == '\0') return kDefaultReaderTimeout;
  char* end = nullptr;
  const double t = std::strtod(env, &end);
  if (end == env || *end != '\0' || !std::isfinite(t) || t <= 0)
    throw CadError(std::string("IGA_CAD_TIMEOUT = \"") + env +
                   "\": not a positive number of seconds");
  return t;
}

std::string format_seconds(double s) {
  std::ostringstream os;
  os << s;
  return os.str();
}

void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0)
      done += static_cast<std::size_t>(n);
    else if (n < 0 && errno == EINTR)
      continue;
    else
      return;
  }
}

/// Sends one part of a reader's answer to the parent as it is made (one line of JSON).
using Emit = std::function<void(const Json&)>;

/// One line of a reader's answer. Messages may quote the file's bytes: not necessarily UTF-8.
std::string answer_line(const Json& j) {
  return j.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

/// The reader child of run_guarded: runs `work`, writes its parts and its answer to `fd` and
/// ends with _exit (no destructors, no atexit handlers: nothing of the parent's state is run
/// twice, and a sanitizer's leak check is the parent's alone).
[[noreturn]] void reader_child(int fd, pid_t parent, const std::string& path,
                               const std::function<Json(const Emit&)>& work) {
  in_reader_child = true;
  // The child ends with its parent (killed, or timed out by a test harness): a reader never
  // outlives the program that started it.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);
  // A crash ends the child by its signal, which the parent reports: no core file, and no
  // handler of the parent's (a test framework's, a sanitizer's) reporting it as its own.
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  for (const int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::signal(s, SIG_DFL);
  std::string text;
  try {
    Json answer;
    try {
      answer = Json{{"result", work([&](const Json& part) {
                       write_all(fd, answer_line(Json{{"part", part}}));
                     })}};
    } catch (const CadError& e) {
      answer = Json{{"error", e.what()}, {"face_option", e.face_option}};
    } catch (const std::exception& e) {
      answer = Json{{"error", path + ": " + e.what()}};
    } catch (const Standard_Failure& e) {
      answer = Json{{"error", path + ": OpenCASCADE failed: " + e.GetMessageString()}};
    }
    text = answer_line(answer);
  } catch (...) {
    text = answer_line(Json{{"error", path + ": the reader process failed"}});
  }
  write_all(fd, text);
  ::close(fd);
  ::_exit(0);
}

/// What the parent reads of a reader: its parts (each kept as it arrives) and its answer.
struct ReaderAnswer {
  explicit ReaderAnswer(std::vector<Json>* p) : parts(p) {}
  std::vector<Json>* parts;
  Json answer;
  bool malformed = false;
  std::string pending;  ///< the start of a line not yet complete

  void take(const char* data, std::size_t n) {
    pending.append(data, n);
    std::size_t start = 0;
    for (std::size_t end; (end = pending.find('\n', start)) != std::string::npos; start = end + 1) {
      Json j = Json::parse(pending.begin() + static_cast<std::ptrdiff_t>(start),
                           pending.begin() + static_cast<std::ptrdiff_t>(end), nullptr, false);
      if (j.is_object() && j.contains("part")) {
        if (parts != nullptr) parts->push_back(std::move(j["part"]));
      } else if (j.is_object() && (j.contains("result") || j.contains("error"))) {
        answer = std::move(j);
      } else {
        malformed = true;
      }
    }
    pending.erase(0, start);
  }
};

/// How reading a reader's pipe ended.
enum class PipeEnd {
  closed,     ///< the writer closed it: the reader has ended or is ending
  timed_out,  ///< `limit` seconds passed first
  failed      ///< poll or read failed with anything but EINTR/EAGAIN
};

/// Reads `fd` into `to` until the writer closes it, `limit` seconds have passed, or poll/read
/// fail with anything but EINTR/EAGAIN (`error` is then their errno).
PipeEnd read_until_closed(int fd, double limit, ReaderAnswer& to, int& error) {
  std::array<char, 65536> buf;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit);
  for (;;) {
    const double left =
        std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return PipeEnd::timed_out;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min(left * 1e3 + 1, 6e4)));
    if (ready < 0 && errno != EINTR) {
      error = errno;
      return PipeEnd::failed;
    }
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n > 0) {
      to.take(buf.data(), static_cast<std::size_t>(n));
    } else if (n == 0) {
      return PipeEnd::closed;
    } else if (errno != EINTR && errno != EAGAIN) {
      error = errno;
      return PipeEnd::failed;
    }
  }
}

/// How a reader process that gave no answer ended: "signal 11, SIGSEGV" or "status 1"; empty
/// if it ended normally.
std::string reader_end(int status) {
  if (WIFSIGNALED(status)) {
    const int s = WTERMSIG(status);
    return "signal " + std::to_string(s) + ", " + signal_name(s);
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  return "";
}

/// Runs `work` (reading, transfer and conversion) in a child process and returns its result; a
/// CadError of the child is thrown here, a crash of the child is a CadError naming the file
/// unless `crash` is given (then it is set to how the child ended, "signal 11, SIGSEGV" or
/// "status 1", and null is returned). The child sends its parts (`emit`, collected in `parts`
/// as they arrive, so that a crash keeps what came before it) and then {"result": ...} or
/// {"error": ..., "face_option": ...}, one line of JSON each, through a pipe.
Json run_guarded(const std::string& path, const std::function<Json(const Emit&)>& work,
                 std::vector<Json>* parts = nullptr, std::string* crash = nullptr) {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);  // what is buffered is written once, by the parent
  int fds[2];
  if (::pipe(fds) != 0)
    throw CadError(path + ": cannot start the reader process: " + std::strerror(errno));
  const pid_t parent = ::getpid();
  const double limit = reader_timeout_seconds();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw CadError(path + ": cannot start the reader process: " + std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    reader_child(fds[1], parent, path, work);
  }
  ::close(fds[1]);
  ReaderAnswer got(parts);
  int pipe_error = 0;
  const PipeEnd end = read_until_closed(fds[0], limit, got, pipe_error);
  ::close(fds[0]);
  // A reader that has not closed its end may still run: it is stopped before it is waited for.
  if (end != PipeEnd::closed) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw CadError(path + ": lost the reader process: " + std::strerror(errno));
  if (end == PipeEnd::failed)
    throw CadError(path + ": lost the reader process's answer (" + std::strerror(pipe_error) +
                   "); the process was stopped");
  if (end == PipeEnd::timed_out)
    throw CadError("OpenCASCADE did not finish reading " + path + " within " +
                   format_seconds(limit) +
                   " s; its reader process was stopped (IGA_CAD_TIMEOUT sets the limit, in "
                   "seconds)");
  if (const std::string how = reader_end(status); !how.empty()) {
    if (crash != nullptr) {
      *crash = how;
      return Json();
    }
    throw CadError(WIFSIGNALED(status) ? "OpenCASCADE crashed (" + how + ") while reading " + path
                                       : "OpenCASCADE failed (its reader process ended with " +
                                             how + ") while reading " + path);
  }
  if (got.malformed || !got.pending.empty() || got.answer.is_null())
    throw CadError(path + ": internal error: the reader process's answer is malformed");
  if (got.answer.contains("error"))
    throw CadError(got.answer["error"].is_string() ? got.answer["error"].get<std::string>()
                                                   : path + ": the reader process failed",
                   got.answer.value("face_option", -1));
  return got.answer["result"];
}

/// Reads the parent's copy of what the child sent; the entities through geometry_io's reader
/// (its checks and bounds: what `iga info` would accept of the written model).
template <class F>
auto from_answer(const std::string& path, F read) {
  try {
    return read();
  } catch (const ModelError& e) {
    throw CadError(path + ": the converted faces are refused: " + e.what());
  } catch (const Json::exception& e) {
    throw CadError(path + ": internal error: the reader process's answer is malformed (" +
                   std::string(e.what()) + ")");
  }
}

/// Test hook: the face number IGA_CAD_TEST_CRASH_FACE crashes its reader process (SIGSEGV)
/// while it is listed, as a face that crashes OpenCASCADE does. Only in a reader child.
int test_crash_face() {
  const char* env = std::getenv("IGA_CAD_TEST_CRASH_FACE");
  return in_reader_child && env != nullptr ? std::atoi(env) : -1;
}

/// Describes and tries to convert faces[from], faces[from + 1], ...: `starting(k, type)` before
/// face k, `done(face)` after it (CadFace::message says why a face does not convert).
void list_faces(const std::vector<TopoDS_Face>& faces, int from,
                const std::function<void(int, const std::string&)>& starting,
                const std::function<void(const CadFace&)>& done) {
  const int crash_at = test_crash_face();
  for (int k = std::max(from, 0); k < static_cast<int>(faces.size()); ++k) {
    const TopoDS_Face& face = faces[static_cast<std::size_t>(k)];
    CadFace f;
    f.index = k;
    f.cad_type = type_name(GeomAdaptor_Surface(BRep_Tool::Surface(face)).GetType());
    starting(k, f.cad_type);
    if (k == crash_at) std::raise(SIGSEGV);
    try {
      f = describe_checked(face, k);
    } catch (const CadError& e) {
      f.message = e.what();
      f.described = false;
    } catch (const Standard_Failure& e) {
      f.message = std::string("OpenCASCADE failed describing it: ") + e.GetMessageString();
      f.described = false;
    }
    if (f.message.empty() && !try_convert(face, f, f.message)) f.entity_type.clear();
    done(f);
  }
}

}  // namespace

std::pair<GeometryEntity, CadFace> import_face(const TopoDS_Face& face, int index) {
  CadFace f = describe(face, index);
  std::string why;
  std::optional<GeometryEntity> e = try_convert(face, f, why);
  if (!e) throw CadError("face " + std::to_string(index) + " (" + f.cad_type + "): " + why);
  return {std::move(*e), f};
}

std::vector<CadFace> list_cad_faces(const std::string& path, const std::string& unit) {
  return list_cad(path, unit).faces;
}

CadListing list_cad_in_process(const std::string& path, const std::string& unit) {
  const auto t0 = std::chrono::steady_clock::now();
  CadListing out;
  out.format = cad_format(path);
  ReadResult r = read_shape(path, unit);
  out.units = r.units;
  out.warnings = r.warnings;
  try {
    list_faces(
        faces_of(r.shape), 0, [](int, const std::string&) {},
        [&](const CadFace& f) { out.faces.push_back(f); });
  } catch (const Standard_Failure& e) {
    throw CadError(path + ": OpenCASCADE failed: " + e.GetMessageString());
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

CadListing list_cad(const std::string& path, const std::string& unit) {
  const auto t0 = std::chrono::steady_clock::now();
  (void)occt_unit(unit);
  check_file(path);
  CadListing out;
  out.format = cad_format(path);
  // A reader lists the faces from `from` on, each sent as it is done. A face that crashes its
  // reader is listed with the crash, and a new reader goes on after it.
  int from = 0;
  int count = -1;  // faces of the file (known once the first reader has read it)
  for (;;) {
    std::vector<Json> parts;
    std::string crash;
    const int first = from;
    (void)run_guarded(
        path,
        [&](const Emit& emit) {
          ReadResult r = read_shape(path, unit);
          try {
            const std::vector<TopoDS_Face> faces = faces_of(r.shape);
            emit(Json{
                {"units", units_json(r.units)}, {"warnings", r.warnings}, {"count", faces.size()}});
            list_faces(
                faces, first,
                [&](int k, const std::string& type) {
                  emit(Json{{"start", k}, {"cad_type", type}});
                },
                [&](const CadFace& f) {
                  emit(Json{{"face", face_json(f)}});
                });
          } catch (const Standard_Failure& e) {
            throw CadError(path + ": OpenCASCADE failed: " + e.GetMessageString());
          }
          return Json::object();
        },
        &parts, &crash);
    std::string started_type;
    from_answer(path, [&] {
      for (const Json& part : parts) {
        if (part.contains("count")) {
          out.units = units_from(part.at("units"));
          out.warnings = part.at("warnings").get<std::vector<std::string>>();
          count = part.at("count").get<int>();
        } else if (part.contains("start")) {
          started_type = part.at("cad_type").get<std::string>();
        } else {
          out.faces.push_back(face_from(part.at("face")));
          from = out.faces.back().index + 1;
          started_type.clear();
        }
      }
    });
    if (crash.empty() || (count >= 0 && from >= count)) break;
    if (count < 0)  // the reading itself crashed: no face to blame
      throw CadError("OpenCASCADE crashed (" + crash + ") while reading " + path);
    CadFace f;
    f.index = from;
    f.cad_type = started_type.empty() ? "unknown" : started_type;
    f.message = "OpenCASCADE crashed (" + crash + ") describing or converting this face";
    f.described = false;
    out.faces.push_back(f);
    if (++from >= count) break;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

CadImport import_cad_in_process(const std::string& path, const std::string& prefix,
                                const CadOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  ReadResult r = read_shape(path, options.unit);
  if (options.strict && !r.warnings.empty())
    throw CadError(r.warnings.front() + " (refused: strict import)");
  CadImport out;
  out.units = r.units;
  out.warnings = r.warnings;
  try {
    const std::vector<TopoDS_Face> all = faces_of(placed(r.shape, options.placement));
    if (all.empty()) throw CadError(path + ": the file holds no faces");
    std::vector<int> chosen = options.faces;
    if (chosen.empty())
      for (std::size_t k = 0; k < all.size(); ++k) chosen.push_back(static_cast<int>(k));
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      const int k = chosen[i];
      if (k < 0 || k >= static_cast<int>(all.size()))
        throw CadError(path + ": face " + std::to_string(k) + " does not exist (the file has " +
                           std::to_string(all.size()) + " faces, numbered from 0)",
                       options.faces.empty() ? -1 : static_cast<int>(i));
      const TopoDS_Face& face = all[static_cast<std::size_t>(k)];
      CadFace f;
      f.cad_type = type_name(GeomAdaptor_Surface(BRep_Tool::Surface(face)).GetType());
      std::string why;
      try {
        f = describe_checked(face, k);
      } catch (const CadError& e) {
        why = e.what();
      }
      std::optional<GeometryEntity> e;
      bool no_area = false;
      if (why.empty()) e = try_convert(face, f, why, &no_area);
      const std::string named = path + ": face " + std::to_string(k) + " (" + f.cad_type + ")";
      if (!e && no_area && options.faces.empty()) {  // nothing of the part is lost without it
        if (options.strict) throw CadError(named + ": " + why + " (refused: strict import)");
        out.warnings.push_back(named + " skipped, it covers no area: " + why);
        continue;
      }
      if (!e) throw CadError(named + ": " + why);
      out.entities.emplace_back(prefix + ".face" + std::to_string(k), std::move(*e));
      out.faces.push_back(f);
    }
    if (out.entities.empty()) throw CadError(path + ": the file holds no face that covers an area");
  } catch (const Standard_Failure& e) {
    throw CadError(path + ": OpenCASCADE failed: " + e.GetMessageString());
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

CadImport import_cad(const std::string& path, const std::string& prefix,
                     const CadOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  (void)occt_unit(options.unit);
  check_file(path);
  const Json j = run_guarded(path, [&](const Emit&) {
    const CadImport imp = import_cad_in_process(path, prefix, options);
    Json entities = Json::array();
    for (const auto& [name, e] : imp.entities)
      entities.push_back(Json::array({name, entity_to_json(e)}));
    return Json{{"entities", std::move(entities)},
                {"faces", faces_json(imp.faces)},
                {"units", units_json(imp.units)},
                {"warnings", imp.warnings}};
  });
  CadImport out = from_answer(path, [&] {
    CadImport imp;
    for (const Json& pair : j.at("entities")) {
      Json one = Json::object();
      one[pair.at(0).get<std::string>()] = pair.at(1);
      GeometryModel m = parse_geometry(one, path, JsonPointer());
      imp.entities.push_back(std::move(m.entities.front()));
    }
    imp.faces = faces_from(j.at("faces"));
    imp.units = units_from(j.at("units"));
    imp.warnings = j.at("warnings").get<std::vector<std::string>>();
    return imp;
  });
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace iga
