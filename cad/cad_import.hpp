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
//
// Reading is guarded (issue 34): OpenCASCADE reads, transfers and converts in a child process
// (fork), which sends the result back through a pipe as JSON (the entities with
// geometry_io's writer, read back with its reader and its bounds); a failure inside
// OpenCASCADE, a crash included, becomes a CadError naming the file, and so does a reader that
// takes longer than 900 s (the environment variable IGA_CAD_TIMEOUT sets another limit, in
// seconds); the reader ends with the program that started it. The *_in_process entry
// points do the same work in this process (fuzzing, or where a crash is wanted).
//
// Units: "file unit" is the length unit the file declares (STEP: the length unit of its
// representation contexts; IGES: the global section's unit); "factor" = (file unit) / (the
// chosen unit), what OpenCASCADE multiplies the file's lengths by. A file unit that is not
// finite, not positive or outside [1e-9 m, 1e9 m] is refused; every number of an imported
// entity is within geometry_io's model bounds (|x| <= 1e100) or the import is refused.
// Skipped entities (entities of the file OpenCASCADE could not read or transfer), a damaged
// header that costs no entity, and, when no faces are chosen (the whole file), a face that
// covers no area of its surface (its boundary spans none, or none of its wires encloses any)
// are warnings (CadImport::warnings), errors with CadOptions::strict. A chosen face that does
// not convert is an error.
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
  /// For a face number out of range: its position in CadOptions::faces (else -1), so that a
  /// model's "faces" list can be located at the bad entry.
  CadError(const std::string& what, int option) : std::runtime_error(what), face_option(option) {}
  int face_option = -1;
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
  /// Warnings (CadImport::warnings: entities skipped by OpenCASCADE, a damaged header, faces
  /// covering no area skipped) are an error.
  bool strict = false;
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
  /// Listing only: why the face cannot be imported (entity_type then empty); empty if it can.
  std::string message;
  /// Listing only: false if not even the face's area, box and loops could be had (OpenCASCADE
  /// failed or crashed describing it); they are then 0.
  bool described = true;
};

/// The length unit the file declares, and the factor applied to its lengths.
struct CadUnits {
  std::vector<std::string> names;  ///< as declared ("millimetre", "INCH", ...); may be empty
  double file_unit_mm = 1.0;       ///< the file's length unit in mm
  std::string unit = "mm";         ///< the unit lengths are converted into
  double factor = 1.0;             ///< file lengths x factor = lengths in `unit`
};

/// The imported faces, named `<prefix>.face<k>` (k the face number), and what each was.
struct CadImport {
  std::vector<std::pair<std::string, GeometryEntity>> entities;
  std::vector<CadFace> faces;  ///< the chosen faces, same order as entities
  double seconds = 0.0;        ///< wall time of reading and converting
  CadUnits units;
  /// What was skipped (entities OpenCASCADE could not read or transfer, faces covering no
  /// area) or a damaged header, one sentence each, naming the file; empty for a complete
  /// import.
  std::vector<std::string> warnings;
};

/// Every face of a file, described and tried (CadFace::message for a face that does not
/// convert).
struct CadListing {
  std::string format;  ///< "step" or "iges"
  CadUnits units;
  std::vector<CadFace> faces;
  std::vector<std::string> warnings;  ///< as CadImport::warnings
  double seconds = 0.0;
};

/// The file's format from its extension: "step" (.step, .stp) or "iges" (.iges, .igs), any
/// case. Throws CadError otherwise.
std::string cad_format(const std::string& path);

/// Reads the file and converts the chosen faces; a trimmed face becomes a TrimmedSurface
/// (geometry/trimmed_surface.hpp: its base as above, its loops and edges). Throws CadError if
/// the file cannot be read, a face number is out of range, or a face cannot be converted (a
/// trimmed face on a surface OCCT must reparametrize); the message names file and face.
/// Also throws if the file's unit or a converted number is out of bounds (see above), or,
/// with options.strict, if OpenCASCADE skipped entities. Guarded: runs in a child process.
CadImport import_cad(const std::string& path, const std::string& prefix,
                     const CadOptions& options = {});
/// The same in this process: a crash inside OpenCASCADE is this process's crash.
CadImport import_cad_in_process(const std::string& path, const std::string& prefix,
                                const CadOptions& options = {});

/// Every face of the file with its OpenCASCADE type, trim loops and whether and to what it
/// converts; a face that does not convert has a message and the listing goes on. Throws
/// CadError only if the file cannot be read (or its unit is refused). Guarded as import_cad.
CadListing list_cad(const std::string& path, const std::string& unit = "mm");
CadListing list_cad_in_process(const std::string& path, const std::string& unit = "mm");

/// list_cad(path, unit).faces.
std::vector<CadFace> list_cad_faces(const std::string& path, const std::string& unit = "mm");

}  // namespace iga
