// Knot insertion and refinement, degree elevation and Bezier extraction of NURBS curves and
// surfaces. All operations leave the geometry unchanged (up to round-off).
// References: [PT97] The NURBS Book: A5.1 (knot insertion), A5.4 (knot refinement),
// Sect. 5.5 (degree elevation), A5.6 (decomposition into Bezier pieces).
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"

namespace iga {

/// A5.1: insert the knot u r times (the result stays C^0 at most: multiplicity <= p).
NurbsCurve insert_knot(const NurbsCurve& c, double u, int r = 1);
/// A5.4: insert all knots of X (non-decreasing, inside the domain) at once.
NurbsCurve refine_knots(const NurbsCurve& c, std::span<const double> X);
NurbsSurface refine_knots(const NurbsSurface& s, std::span<const double> Xu,
                          std::span<const double> Xv);
/// Uniform h-refinement: split every element into `parts` equal parts.
NurbsCurve subdivide(const NurbsCurve& c, int parts);
NurbsSurface subdivide(const NurbsSurface& s, int parts_u, int parts_v);

/// Degree elevation by t: same geometry, degree p+t, every distinct knot's multiplicity
/// raised by t (so the continuity is kept). Computed as the exact representation in the
/// elevated spline space, by collocation at its Greville abscissae in homogeneous
/// coordinates (the space contains the curve, so the solution is exact up to round-off).
NurbsCurve elevate_degree(const NurbsCurve& c, int t);
NurbsSurface elevate_degree(const NurbsSurface& s, int tu, int tv);

/// One Bezier element of a curve: parameter interval and its p+1 homogeneous control points.
struct BezierSegment {
  Interval range;
  std::vector<Vector4d> pw;  ///< p+1 points (w P, w)
};
/// One Bezier element of a surface: (p+1)(q+1) homogeneous points, u fastest.
struct BezierPatch {
  Domain2 range;
  int degree_u = 0, degree_v = 0;
  int element_u = 0, element_v = 0;  ///< element indices in u and v
  std::vector<Vector4d> pw;
  Vector4d pw_at(int i, int j) const {
    return pw[static_cast<std::size_t>(i + (degree_u + 1) * j)];
  }
};

/// A5.6-equivalent: raise every interior knot to multiplicity p and cut into elements.
std::vector<BezierSegment> bezier_extract(const NurbsCurve& c);
std::vector<BezierPatch> bezier_extract(const NurbsSurface& s);

/// Axis-aligned bounding box of the (projected) control points of a Bezier element; by the
/// convex hull property it contains the element.
struct Box3 {
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
  Vector3d hi = Vector3d::Constant(-std::numeric_limits<double>::infinity());
  void extend(const Vector3d& x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
};
Box3 bounding_box(const BezierPatch& b);
Box3 bounding_box(const BezierSegment& b);

}  // namespace iga
