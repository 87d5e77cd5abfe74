// Rigid tools from CAD files (issue 15): the faces of a STEP or IGES file, read with
// OpenCASCADE (OCCT 7.6), as the project's own surfaces, each as what it is:
//   - B-spline and Bezier faces: NURBS patches with the same degrees, knots, weights and poles
//     (periodic ones made non-periodic, a face using part of its surface cut to that part, also
//     across a periodic seam: exact knot operations of OCCT; a boundary overshooting the
//     surface's range within the edge's tolerance clamped; a degree above kMaxDegree fitted on
//     the same parameters within a reported bound);
//   - planes, cylinders, cones, spheres and tori: the analytic surfaces of
//     geometry/analytic_surfaces.hpp (closed forms of [KS15] Appendices A and B), with their
//     placement and parameter ranges; OCCT's parameters map to ours by u' = a_u u + b_u,
//     v' = a_v v + b_v (the map is checked on a grid of every face: import fails loudly
//     rather than change the geometry);
//   - surfaces of revolution and extrusion of conics and B-spline curves: NURBS by OCCT's exact
//     conversion (GeomConvert); anything else (offset surfaces, ...) NURBS approximated by OCCT
//     within a stated tolerance, reported per face (CadFace::exact, ::tolerance).
// The normal of every face is the face's own (OCCT's orientation included): outward of the
// solid the face bounds.
//
// Notation (OCCT -> here): gp_Ax3 (O, X, Y, Z) -> Placement (center, ref_dir, axis); a
// left-handed gp_Ax3 (Y = -(Z x X)) -> axis -Z, and the parameter along Z changes sign.
// Cone (OCCT): P = O + (R0 + v sin A)(cos u X + sin u Y) + v cos A Z, A the semi-angle;
// here: apex c, radius s = |R0 + v sin A| (either nappe: R0 + v sin A < 0 is our cone with the
// axis reversed, u shifted by pi), alpha = pi/2 - |A| (angle to the plane normal to the axis,
// (B.23)).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/geometry_io.hpp"

namespace iga {

/// A CAD file that cannot be read or a face that cannot be imported; the message names the
/// file and the face.
class CadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Rigid placement of the imported shape: first the rotation by `angle` (radians, right-handed)
/// about `axis` through `point`, then the translation by `vector` (as "rigid_motions").
struct CadPlacement {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double angle = 0.0;
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();
};

struct CadOptions {
  /// Faces to import (0-based, in OCCT's face order of the file, as `iga info` lists them);
  /// empty: all.
  std::vector<int> faces;
  /// Length unit the file's lengths are converted into: "mm" (OCCT's default), "cm", "m",
  /// "in", "ft", "um", "km".
  std::string unit = "mm";
  CadPlacement placement;
};

/// One face of the file as read.
struct CadFace {
  int index = 0;            ///< 0-based face number
  std::string cad_type;     ///< OCCT's surface type: "plane", "bspline", "offset", ...
  std::string entity_type;  ///< what it became: "cylinder", "nurbs_surface", ...
  bool exact = true;        ///< false: approximated by OCCT within `tolerance`
  double tolerance = 0.0;   ///< distance bound of the approximation (0 if exact)
  bool trimmed = false;     ///< its boundary is not its parameter rectangle (or it has holes)
  int wires = 0;            ///< boundary loops (outer + holes)
  double area = 0.0;
  Eigen::Vector3d box_lo = Eigen::Vector3d::Zero(), box_hi = Eigen::Vector3d::Zero();
};

/// The imported faces, named `<prefix>.face<k>` (k the face number), and what each was.
struct CadImport {
  std::vector<std::pair<std::string, GeometryEntity>> entities;
  std::vector<CadFace> faces;  ///< the chosen faces, same order as entities
  double seconds = 0.0;        ///< wall time of reading and converting
};

/// The file's format from its extension: "step" (.step, .stp) or "iges" (.iges, .igs), any
/// case. Throws CadError otherwise.
std::string cad_format(const std::string& path);

/// Reads the file and converts the chosen faces; a trimmed face becomes a TrimmedSurface
/// (geometry/trimmed_surface.hpp: its base as above, its loops and edges). Throws CadError if
/// the file cannot be read, a face number is out of range, or a face cannot be converted (a
/// trimmed face on a surface OCCT must reparametrize); the message names file and face.
CadImport import_cad(const std::string& path, const std::string& prefix,
                     const CadOptions& options = {});

/// Every face of the file, described (nothing converted, trimmed faces included).
std::vector<CadFace> list_cad_faces(const std::string& path, const std::string& unit = "mm");

}  // namespace iga
