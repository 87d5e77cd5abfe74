// Exact NURBS constructions of lines, conics and quadrics, surfaces of revolution, the
// bilinear hyperboloid patch of the reference paper, and an interpolated helix.
// References: [PT97] The NURBS Book: A7.1 (circular arc), Sect. 7.5 (full circle, 9 points,
// weights 1 and sqrt(2)/2), A8.1 (surface of revolution), Sect. 8.3 (general cylinder),
// A9.1 (global curve interpolation); [KS15] eq. (11) for z = a x y.
#pragma once

#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"

namespace iga {

/// Size limits of the constructions (docs/model_format.md, Sect. 3.5): elements of a
/// constructed curve (wrap_path: arc_elements + 2 span_elements; line: elements; helix:
/// points - 3) and control points of a constructed (refined) surface. Chosen so that the
/// largest allowed model, analysis included, is set up in a few seconds and some hundred MB
/// per process: a rod of 100,000 elements in about 2 s and 0.5 GB, a shell of 50,000 control
/// points (about 220 x 220 bicubic elements) in about 6 s and 2.5 GB (a shell costs some 50 KB
/// per control point: element matrices). The shell's bound is a process's: a shell cut over P
/// processes (a run under mpirun, docs/parallel.md) may have about P times as many. A surface
/// itself (its net of points, 24 bytes each) may hold up to kMaxSurfaceNetPoints. Analysis
/// bodies given by explicit NURBS obey the same bounds.
inline constexpr int kMaxCurveElements = 100000;
inline constexpr long kMaxSurfaceControlPoints = 50000;
inline constexpr long kMaxSurfaceNetPoints = 1000000;
/// Smallest element of a fitted curve relative to its whole length: below it the knots are
/// no longer distinct in double precision (and the fit is ill-conditioned).
inline constexpr double kMinRelativeElement = 1e-9;

/// Input of a construction that cannot be built, naming the input at fault by the key of the
/// model format (`radius`, `span_length`, `mid_dir`, ...), so that the loader can report it at
/// that JSON path.
class ConstructionError : public GeometryError {
 public:
  ConstructionError(std::string key, const std::string& message)
      : GeometryError(message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

/// Straight segment from a to b, degree 1 (elevate for higher degree).
NurbsCurve make_line(const Vector3d& a, const Vector3d& b);

/// A7.1: circular arc of radius r around center in the plane spanned by the orthonormal
/// x_axis, y_axis, from angle start to end (radians, end > start, end - start <= 2 pi),
/// quadratic rational, as few segments as needed (<= 90 degrees each). Parameter in [0, 1].
NurbsCurve make_circular_arc(const Vector3d& center, const Vector3d& x_axis, const Vector3d& y_axis,
                             double r, double start, double end);
/// Full circle: 9 control points, weights 1 and sqrt(2)/2, knots {0,0,0,1/4,1/4,...,1,1,1}.
NurbsCurve make_circle(const Vector3d& center, const Vector3d& normal, double r);

/// Bilinear plane patch with corners origin, origin + du, origin + du + dv, origin + dv.
NurbsSurface make_plane_patch(const Vector3d& origin, const Vector3d& du, const Vector3d& dv);

/// Cylinder of radius r about the axis through `base` with unit direction `axis`, height h,
/// angular range [start, end] measured from `ref_dir` (projected normal to the axis).
/// u runs around (the arc), v in [0, 1] along the axis (height v h); the normal S_u x S_v
/// points outward.
NurbsSurface make_cylinder(const Vector3d& base, const Vector3d& axis, const Vector3d& ref_dir,
                           double r, double h, double start = 0.0,
                           double end = 2.0 * std::numbers::pi);

/// Sphere of radius r (revolution of a half circle); u around the axis, v from south to north
/// pole; outward normal.
NurbsSurface make_sphere(const Vector3d& center, double r);
/// A zone of a sphere: latitudes [lat0, lat1] (radians, in [-pi/2, pi/2], from the plane normal
/// to `axis`) and longitudes [lon0, lon1] (from ref_dir, counter-clockwise about `axis`,
/// lon1 - lon0 <= 2 pi). u along the longitude, v from lat0 to lat1; outward normal as
/// make_sphere. Exact (rational quadratic in both directions).
NurbsSurface make_sphere_zone(const Vector3d& center, const Vector3d& axis, const Vector3d& ref_dir,
                              double r, double lat0, double lat1, double lon0, double lon1);

/// Torus about the axis through center: major radius R (tube centre circle), minor radius
/// r < R; full in both directions; outward normal.
NurbsSurface make_torus(const Vector3d& center, const Vector3d& axis, double R, double r);

/// Cone frustum with the conventions of the analytic Cone ([KS15] B.23): points
/// apex + s e_r + s tan(alpha) e_z for radial distance s in [s1, s2] (0 <= s1 < s2), alpha the
/// angle of the generator to the plane normal to `axis`. u around the axis (from ref_dir),
/// v along the generator; the normal S_u x S_v is the "outward" sin(a) e_r - cos(a) e_z.
NurbsSurface make_cone(const Vector3d& apex, const Vector3d& axis, const Vector3d& ref_dir,
                       double alpha, double s1, double s2);

/// A8.1: revolve a NURBS profile (in 3-D) about the axis through `axis_point` with unit
/// direction `axis`, by `angle` radians (<= 2 pi). u around the axis, v along the profile.
NurbsSurface make_revolution(const NurbsCurve& profile, const Vector3d& axis_point,
                             const Vector3d& axis, double angle = 2.0 * std::numbers::pi);

/// [KS15] (11): z = a x y over [x0,x1] x [y0,y1] is exactly a bilinear (1x1) patch. Its knots
/// span [x0,x1] x [y0,y1], so (u, v) = (x, y) as for the analytic Hyperboloid.
NurbsSurface make_bilinear_hyperboloid(double a, double x0, double x1, double y0, double y1);

/// A cubic B-spline interpolating the helix (R cos t, R sin t, pitch t / 2pi), t in
/// [0, angle], at n_points points equally spaced in t (A9.1, parameters = t / angle, with
/// averaged knots). max_deviation is the largest |C(s) - H(s angle)| over a dense sample.
struct HelixApproximation {
  NurbsCurve curve;
  double max_deviation = 0.0;
};
HelixApproximation make_helix_cubic(double R, double pitch, double angle, int n_points);

/// The centre line of a rope wrapped around a cylinder ([KS15] Sects. 6.3-6.4): a straight span,
/// a helical arc of radius `radius` (the centre line's distance from the axis) over the polar
/// angle `angle` with rise `pitch` per turn (0: a circular arc), and a straight span, each span
/// tangent to the arc and of length `span_length`. Frame: e_z = axis, e_y = mid_dir (made
/// normal to the axis: the direction from the axis to the middle of the arc), e_x = e_y x e_z;
/// the arc runs clockwise about e_z from the polar angle (from e_x) pi/2 + angle/2 to
/// pi/2 - angle/2, rising along e_z by pitch * angle / (2 pi), centred on the plane through
/// `center` normal to the axis. Unit travel direction at polar angle theta:
///   tau = (radius (sin theta e_x - cos theta e_y) + c e_z) / sqrt(radius^2 + c^2),  c = pitch/2pi.
/// The curve is the least-squares fit ([PT97] 9.4.1) of a cubic B-spline with arc-length
/// parameter, `span_elements` equal elements on each span, `arc_elements` on the arc, and
/// double knots (C1) at the two tangent points, where the curvature jumps; 16 samples per
/// element, ends interpolated. `degree` 4 or 5 elevates the fit ([PT97] 5.5): the same curve
/// with C2 continuity at the inner knots and C1 at the tangent points, a richer space for the
/// rod (the sliding rope's T/T0 swings far less, docs/contact.md, "The sliding plateau").
struct WrapPathSpec {
  Vector3d center = Vector3d::Zero();
  Vector3d axis = Vector3d::UnitZ();
  Vector3d mid_dir = Vector3d::UnitY();
  double radius = 1.0;
  double angle = std::numbers::pi;
  double pitch = 0.0;
  double span_length = 1.0;
  int arc_elements = 10;
  int span_elements = 3;
  int degree = 3;  ///< 3, 4 or 5
};
struct WrapPath {
  NurbsCurve curve;
  double max_deviation = 0.0;  ///< largest distance of the fit from line + arc + line (samples)
  double arc_length = 0.0;     ///< angle sqrt(radius^2 + c^2)
  Vector3d tangent_start = Vector3d::Zero();  ///< unit travel direction at the start (span A)
  Vector3d tangent_end = Vector3d::Zero();    ///< ... at the end (span B)
};
/// Throws ConstructionError (key: radius, angle_deg, pitch, span_length, arc_elements,
/// span_elements, degree, axis, mid_dir) before fitting anything for radius, angle,
/// span_length <= 0 or non-finite, a non-finite pitch, a degree other than 3, 4, 5, element
/// counts < 1 or above kMaxCurveElements in all, an
/// axis parallel to mid_dir, or an element shorter than kMinRelativeElement times the path.
WrapPath make_wrap_path(const WrapPathSpec& spec);

}  // namespace iga
