// Exact NURBS constructions (lines, circular arcs, quadrics, surfaces of revolution, the bilinear
// saddle) and the cubic interpolation of a helix.
// References: [PT97] The NURBS Book: A7.1 and Sect. 7.5 (circular arcs and the 9-point circle),
// Sect. 8.3 (general cylinder), A8.1 (surface of revolution), A9.1 with eqs. (9.3), (9.8)
// (global interpolation); [KS15] eq. (11), (B.16), (B.23).
#include "geometry/constructions.hpp"

#include "geometry/refinement.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "geometry/analytic_surfaces.hpp"  // Placement::frame
#include "geometry/bspline_basis.hpp"
#include "geometry/fitting.hpp"
#include "geometry/knot_vector.hpp"
#include "geometry/number_text.hpp"

namespace iga {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::string num(double x) {
  return num_text(x, 12);
}

[[noreturn]] void fail(const std::string& msg) {
  throw GeometryError(msg);
}

void check_positive(const std::string& what, double x) {
  if (!(x > 0.0) || !std::isfinite(x)) fail(what + " must be finite and > 0, got " + num(x));
}

/// cos/sin values within 1e-15 of 0 or +-1 are set to those values, so that arcs through
/// quadrant angles (0, pi/2, pi, ...) have exact control points and full circles close exactly.
double snap(double x) {
  constexpr double tol = 1e-15;
  if (std::abs(x) < tol) return 0.0;
  if (std::abs(x - 1.0) < tol) return 1.0;
  if (std::abs(x + 1.0) < tol) return -1.0;
  return x;
}

/// A quadratic rational arc of the unit circle in local coordinates (x, y) = (cos t, sin t),
/// t in [start, end]: 2 narcs + 1 control points and weights, knots on [0, 1] ([PT97] A7.1).
struct UnitArc {
  std::vector<double> knots;
  std::vector<Vector2d> pts;
  std::vector<double> w;
};

UnitArc unit_arc(double start, double end) {
  const double theta = end - start;
  // A7.1: at most 90 degrees per segment (the tolerance keeps exactly 90, 180, 270 degrees
  // from picking up a needless extra segment through round-off).
  const double quarter = 0.5 * kPi * (1.0 + 1e-12);
  const int narcs = theta <= quarter ? 1 : theta <= 2 * quarter ? 2 : theta <= 3 * quarter ? 3 : 4;
  const double dth = theta / narcs;
  const double cos_d = snap(std::cos(dth));
  const double w1 = std::sqrt(0.5 * (1.0 + cos_d));  // cos(dth / 2), the middle weight
  const bool full = std::abs(theta - kTwoPi) <= 1e-12 * kTwoPi;

  UnitArc a;
  a.pts.reserve(static_cast<std::size_t>(2 * narcs + 1));
  a.w.reserve(static_cast<std::size_t>(2 * narcs + 1));
  Vector2d p0(snap(std::cos(start)), snap(std::sin(start)));
  const Vector2d first = p0;
  a.pts.push_back(p0);
  a.w.push_back(1.0);
  for (int i = 1; i <= narcs; ++i) {
    const double t = i == narcs ? end : start + i * dth;
    const Vector2d p2 =
        (i == narcs && full) ? first : Vector2d(snap(std::cos(t)), snap(std::sin(t)));
    // The middle point is the intersection of the end tangents: along the bisector at
    // distance 1/cos(dth/2), i.e. (p0 + p2) / (2 cos^2(dth/2)) = (p0 + p2) / (1 + cos dth).
    a.pts.push_back((p0 + p2) / (1.0 + cos_d));
    a.w.push_back(w1);
    a.pts.push_back(p2);
    a.w.push_back(1.0);
    p0 = p2;
  }
  // Knots {0,0,0, 1/narcs, 1/narcs, ..., 1,1,1}: C^0 joints between the arcs.
  a.knots = {0.0, 0.0, 0.0};
  for (int i = 1; i < narcs; ++i) {
    const double k = static_cast<double>(i) / narcs;
    a.knots.push_back(k);
    a.knots.push_back(k);
  }
  a.knots.insert(a.knots.end(), {1.0, 1.0, 1.0});
  return a;
}

/// Homogeneous point (w P, w).
Vector4d homogeneous(const Vector3d& p, double w) {
  return Vector4d(w * p.x(), w * p.y(), w * p.z(), w);
}

/// Unit vector of a direction argument, with a message naming the function and the value.
Vector3d unit(const std::string& what, const Vector3d& v) {
  const double len = v.norm();
  if (!(len > 0.0) || !std::isfinite(len))
    fail(what + " must be a finite non-zero vector, got (" + num(v.x()) + ", " + num(v.y()) + ", " +
         num(v.z()) + ")");
  return v / len;
}

}  // namespace

NurbsCurve make_line(const Vector3d& a, const Vector3d& b) {
  return NurbsCurve(1, {0.0, 0.0, 1.0, 1.0}, {a, b});
}

NurbsCurve make_circular_arc(const Vector3d& center, const Vector3d& x_axis, const Vector3d& y_axis,
                             double r, double start, double end) {
  check_positive("make_circular_arc: radius", r);
  if (!std::isfinite(start) || !std::isfinite(end) || !(end > start))
    fail("make_circular_arc: need finite start < end, got start " + num(start) + ", end " +
         num(end));
  if (end - start > kTwoPi * (1.0 + 1e-12))
    fail("make_circular_arc: end - start must be <= 2 pi, got " + num(end - start));
  constexpr double tol = 1e-10;
  if (std::abs(x_axis.norm() - 1.0) > tol || std::abs(y_axis.norm() - 1.0) > tol ||
      std::abs(x_axis.dot(y_axis)) > tol)
    fail("make_circular_arc: x_axis and y_axis must be orthonormal, got |x| = " +
         num(x_axis.norm()) + ", |y| = " + num(y_axis.norm()) +
         ", x.y = " + num(x_axis.dot(y_axis)));

  const UnitArc a = unit_arc(start, end);
  std::vector<Vector4d> pw;
  pw.reserve(a.pts.size());
  for (std::size_t i = 0; i < a.pts.size(); ++i) {
    const Vector3d p = center + r * (a.pts[i].x() * x_axis + a.pts[i].y() * y_axis);
    pw.push_back(homogeneous(p, a.w[i]));
  }
  return NurbsCurve(KnotVector(2, a.knots), std::move(pw));
}

NurbsCurve make_circle(const Vector3d& center, const Vector3d& normal, double r) {
  // Sect. 7.5: four 90-degree arcs, i.e. the 9-point square control polygon with weights 1 at
  // the touching points and sqrt(2)/2 at the corners. Counter-clockwise about `normal`.
  const Vector3d ez = unit("make_circle: normal", normal);
  const Matrix3d E = Placement{center, ez}.frame();
  return make_circular_arc(center, E.col(0), E.col(1), r, 0.0, kTwoPi);
}

NurbsSurface make_plane_patch(const Vector3d& origin, const Vector3d& du, const Vector3d& dv) {
  // u fastest: (0,0), (1,0), (0,1), (1,1).
  return NurbsSurface(1, {0.0, 0.0, 1.0, 1.0}, 1, {0.0, 0.0, 1.0, 1.0},
                      {origin, origin + du, origin + dv, origin + du + dv});
}

NurbsSurface make_cylinder(const Vector3d& base, const Vector3d& axis, const Vector3d& ref_dir,
                           double r, double h, double start, double end) {
  check_positive("make_cylinder: radius", r);
  check_positive("make_cylinder: height", h);
  const Vector3d ez = unit("make_cylinder: axis", axis);
  const Matrix3d E = Placement{base, ez, ref_dir}.frame();
  // Sect. 8.3 general cylinder S(u, v) = C(u) + v h e_z: the arc translated along the axis.
  // S_u ~ e_phi, S_v = h e_z, so S_u x S_v ~ e_phi x e_z = e_r points outward.
  const NurbsCurve arc = make_circular_arc(base, E.col(0), E.col(1), r, start, end);
  const std::vector<Vector4d>& c = arc.homogeneous();
  std::vector<Vector4d> pw(2 * c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    pw[i] = c[i];
    pw[i + c.size()] = c[i];
    pw[i + c.size()].head<3>() += c[i].w() * h * ez;
  }
  return NurbsSurface(arc.knots(), KnotVector(1, {0.0, 0.0, 1.0, 1.0}), std::move(pw));
}

NurbsSurface make_revolution(const NurbsCurve& profile, const Vector3d& axis_point,
                             const Vector3d& axis, double angle) {
  const Vector3d a = unit("make_revolution: axis", axis);
  if (!(angle > 0.0) || angle > kTwoPi * (1.0 + 1e-12))
    fail("make_revolution: angle must lie in (0, 2 pi], got " + num(angle));
  if (profile.num_control_points() == 0) fail("make_revolution: the profile is empty");

  // A8.1: every profile control point P_j sweeps a circular arc about the axis (its centre
  // O_j is the projection of P_j on the axis); the arc's control points carry the arc weights
  // times w_j. Written with the rotation d cos t + (a x d) sin t of d = P_j - O_j, which
  // also covers points on the axis (d = 0: a degenerate arc, all points at O_j).
  const UnitArc arc = unit_arc(0.0, angle);
  const std::size_t nu = arc.pts.size();
  const std::vector<Vector4d>& prof = profile.homogeneous();
  std::vector<Vector4d> pw(nu * prof.size());
  for (std::size_t j = 0; j < prof.size(); ++j) {
    const double wj = prof[j].w();
    const Vector3d p = prof[j].head<3>() / wj;
    const Vector3d o = axis_point + (p - axis_point).dot(a) * a;
    const Vector3d d = p - o;
    const Vector3d b = a.cross(d);
    for (std::size_t i = 0; i < nu; ++i) {
      const Vector3d q = o + arc.pts[i].x() * d + arc.pts[i].y() * b;
      pw[i + nu * j] = homogeneous(q, wj * arc.w[i]);
    }
  }
  return NurbsSurface(KnotVector(2, arc.knots), profile.knots(), std::move(pw));
}

NurbsSurface make_sphere(const Vector3d& center, double r) {
  check_positive("make_sphere: radius", r);
  // Profile: half circle in the (e_x, e_z) plane from the south pole (angle -pi/2) to the
  // north pole. Revolving it counter-clockwise about e_z gives S_u ~ e_phi and S_v ~ +e_z at
  // the equator, so S_u x S_v ~ e_phi x e_z = e_r: outward, no reversal needed.
  const Vector3d ex = Vector3d::UnitX(), ez = Vector3d::UnitZ();
  const NurbsCurve half = make_circular_arc(center, ex, ez, r, -0.5 * kPi, 0.5 * kPi);
  return make_revolution(half, center, ez);
}

NurbsSurface make_sphere_zone(const Vector3d& center, const Vector3d& axis, const Vector3d& ref_dir,
                              double r, double lat0, double lat1, double lon0, double lon1) {
  check_positive("make_sphere_zone: radius", r);
  if (!(lat0 >= -0.5 * kPi && lat1 <= 0.5 * kPi && lat1 > lat0))
    throw std::invalid_argument(
        "make_sphere_zone: latitudes must satisfy -pi/2 <= lat0 < lat1 "
        "<= pi/2");
  if (!(lon1 > lon0 && lon1 - lon0 <= 2.0 * kPi * (1.0 + 1e-12)))
    throw std::invalid_argument(
        "make_sphere_zone: longitudes must satisfy lon0 < lon1 <= lon0 "
        "+ 2 pi");
  const Vector3d ez = axis.normalized();
  const Vector3d e0 = (ref_dir - ref_dir.dot(ez) * ez).normalized();
  // The profile at longitude lon0, from lat0 to lat1, revolved about the axis as in make_sphere.
  const Vector3d ex = std::cos(lon0) * e0 + std::sin(lon0) * ez.cross(e0);
  const NurbsCurve arc = make_circular_arc(center, ex, ez, r, lat0, lat1);
  return make_revolution(arc, center, ez, lon1 - lon0);
}

NurbsSurface make_torus(const Vector3d& center, const Vector3d& axis, double R, double r) {
  check_positive("make_torus: major radius R", R);
  check_positive("make_torus: minor radius r", r);
  if (!(r < R))
    fail("make_torus: minor radius must be < major radius " + num(R) + ", got " + num(r));
  const Vector3d ez = unit("make_torus: axis", axis);
  const Matrix3d E = Placement{center, ez}.frame();
  // Tube circle (R + r cos v) e_x + r sin v e_z, counter-clockwise in the (e_x, e_z) plane, as
  // in the analytic Torus; revolved about e_z its normal S_u x S_v ~ e_phi x (tube tangent)
  // = cos v e_r + sin v e_z points out of the tube (see the Torus comment in
  // analytic_surfaces.cpp for the algebra).
  const NurbsCurve tube = make_circular_arc(center + R * E.col(0), E.col(0), ez, r, 0.0, kTwoPi);
  return make_revolution(tube, center, ez);
}

NurbsSurface make_cone(const Vector3d& apex, const Vector3d& axis, const Vector3d& ref_dir,
                       double alpha, double s1, double s2) {
  if (!(alpha > 0.0 && alpha < 0.5 * kPi))
    fail("make_cone: alpha must lie in (0, pi/2), got " + num(alpha));
  if (!(s1 >= 0.0) || !(s2 > s1) || !std::isfinite(s2))
    fail("make_cone: need 0 <= s1 < s2, got s1 = " + num(s1) + ", s2 = " + num(s2));
  const Vector3d ez = unit("make_cone: axis", axis);
  const Matrix3d E = Placement{apex, ez, ref_dir}.frame();
  // Generator apex + s (e_x + tan(alpha) e_z), s in [s1, s2] ([KS15] B.23). Its tangent
  // e_r + tan(alpha) e_z revolved gives S_u x S_v ~ e_phi x (e_r + tan a e_z)
  // = tan a e_r - e_z ~ sin a e_r - cos a e_z, the documented normal.
  const Vector3d g = E.col(0) + std::tan(alpha) * ez;
  const NurbsCurve generator = make_line(apex + s1 * g, apex + s2 * g);
  return make_revolution(generator, apex, ez);
}

NurbsSurface make_bilinear_hyperboloid(double a, double x0, double x1, double y0, double y1) {
  if (!std::isfinite(a)) fail("make_bilinear_hyperboloid: a must be finite, got " + num(a));
  if (!(x0 < x1) || !std::isfinite(x0) || !std::isfinite(x1))
    fail("make_bilinear_hyperboloid: need finite x0 < x1, got [" + num(x0) + ", " + num(x1) + "]");
  if (!(y0 < y1) || !std::isfinite(y0) || !std::isfinite(y1))
    fail("make_bilinear_hyperboloid: need finite y0 < y1, got [" + num(y0) + ", " + num(y1) + "]");
  // (11): x y is bilinear, so interpolating z = a x y at the four corners with the degree 1x1
  // basis is exact. Knots on [x0, x1] x [y0, y1] make (u, v) = (x, y), the parametrization of
  // the analytic Hyperboloid; S_u x S_v = (-a y, -a x, 1) as in (22).
  auto corner = [a](double x, double y) { return Vector3d(x, y, a * x * y); };
  return NurbsSurface(1, {x0, x0, x1, x1}, 1, {y0, y0, y1, y1},
                      {corner(x0, y0), corner(x1, y0), corner(x0, y1), corner(x1, y1)});
}

HelixApproximation make_helix_cubic(double R, double pitch, double angle, int n_points) {
  check_positive("make_helix_cubic: radius R", R);
  check_positive("make_helix_cubic: angle", angle);
  if (!std::isfinite(pitch)) fail("make_helix_cubic: pitch must be finite, got " + num(pitch));
  constexpr int p = 3;
  if (n_points < p + 1)
    fail("make_helix_cubic: need n_points >= 4 for a cubic, got " + std::to_string(n_points));
  if (n_points - p > kMaxCurveElements)
    fail("make_helix_cubic: n_points " + std::to_string(n_points) + " exceeds the limit of " +
         std::to_string(kMaxCurveElements + p) + " (" + std::to_string(kMaxCurveElements) +
         " elements of a curve)");

  const double c = pitch / kTwoPi;
  auto helix = [R, c](double t) { return Vector3d(R * std::cos(t), R * std::sin(t), c * t); };

  // A9.1. Parameters: the helix has constant speed, so chord length and uniform parameters
  // coincide: t_k = k / (N) with N = n_points - 1 (eq. 9.3 for equal chords).
  const int N = n_points - 1;
  std::vector<double> t(static_cast<std::size_t>(n_points));
  for (int k = 0; k <= N; ++k) t[static_cast<std::size_t>(k)] = static_cast<double>(k) / N;
  t.back() = 1.0;

  // Knots by averaging, eq. (9.8): u_{j+p} = (1/p) sum_{i=j}^{j+p-1} t_i, j = 1..N-p.
  std::vector<double> U(static_cast<std::size_t>(n_points + p + 1), 0.0);
  for (int j = 1; j <= N - p; ++j) {
    double sum = 0.0;
    for (int i = j; i < j + p; ++i) sum += t[static_cast<std::size_t>(i)];
    U[static_cast<std::size_t>(j + p)] = sum / p;
  }
  for (int j = n_points; j < n_points + p + 1; ++j) U[static_cast<std::size_t>(j)] = 1.0;
  const KnotVector kv(p, U);

  // Collocation system A P = Q with A_kj = N_{j,p}(t_k): banded (p + 1 entries a row) and
  // totally positive, solved as a sparse LU (O(n) for the band, where a dense LU is O(n^3)).
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(n_points) * (p + 1));
  Eigen::MatrixXd Q(n_points, 3);
  BasisValues Nv{};
  for (int k = 0; k <= N; ++k) {
    const double tk = t[static_cast<std::size_t>(k)];
    const int span = kv.find_span(tk);
    basis_funs(span, tk, p, kv.span(), Nv);
    for (int j = 0; j <= p; ++j)
      trip.emplace_back(k, span - p + j, Nv[static_cast<std::size_t>(j)]);
    Q.row(k) = helix(tk * angle).transpose();
  }
  Eigen::SparseMatrix<double> A(n_points, n_points);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>> lu(A);
  if (lu.info() != Eigen::Success)
    fail("make_helix_cubic: the collocation matrix is singular for " + std::to_string(n_points) +
         " points");
  const Eigen::MatrixXd P = lu.solve(Q);
  std::vector<Vector3d> points(static_cast<std::size_t>(n_points));
  for (int i = 0; i < n_points; ++i) points[static_cast<std::size_t>(i)] = P.row(i).transpose();

  HelixApproximation out{NurbsCurve(p, U, points), 0.0};

  // Parametric deviation |C(s) - H(s angle)|, 200 samples per knot span.
  constexpr int samples = 200;
  const std::vector<double> br = kv.breaks();
  for (std::size_t e = 0; e + 1 < br.size(); ++e) {
    for (int k = 0; k <= samples; ++k) {
      const double s = br[e] + (br[e + 1] - br[e]) * k / samples;
      out.max_deviation =
          std::max(out.max_deviation, (out.curve.point(s) - helix(s * angle)).norm());
    }
  }
  return out;
}

WrapPath make_wrap_path(const WrapPathSpec& w) {
  // Every input is checked here, before any knot is made, so that the error names the input at
  // fault rather than a symptom inside the fit (a repeated knot, a singular system).
  auto bad = [](const char* key, const std::string& msg) {
    throw ConstructionError(key, "make_wrap_path: " + std::string(key) + " " + msg);
  };
  auto positive = [&](const char* key, double x) {
    if (!(x > 0.0) || !std::isfinite(x)) bad(key, "must be finite and > 0, got " + num(x));
  };
  positive("radius", w.radius);
  positive("angle", w.angle);
  positive("span_length", w.span_length);
  if (!std::isfinite(w.pitch)) bad("pitch", "must be finite, got " + num(w.pitch));
  if (w.arc_elements < 1)
    bad("arc_elements", "must be >= 1, got " + std::to_string(w.arc_elements));
  if (w.span_elements < 1)
    bad("span_elements", "must be >= 1, got " + std::to_string(w.span_elements));
  if (w.degree < 3 || w.degree > 5)
    bad("degree", "must be 3, 4 or 5, got " + std::to_string(w.degree));
  if (static_cast<long>(w.arc_elements) + 2L * w.span_elements > kMaxCurveElements)
    bad(w.arc_elements >= w.span_elements ? "arc_elements" : "span_elements",
        "too large: arc_elements + 2 span_elements = " +
            std::to_string(static_cast<long>(w.arc_elements) + 2L * w.span_elements) +
            " exceeds the limit of " + std::to_string(kMaxCurveElements) +
            " elements of a curve (arc_elements " + std::to_string(w.arc_elements) +
            ", span_elements " + std::to_string(w.span_elements) + ")");
  if (!(w.axis.norm() > 0.0) || !w.axis.allFinite())
    bad("axis", "must be a finite non-zero vector");
  if (!w.mid_dir.allFinite() || !w.center.allFinite())
    bad(w.center.allFinite() ? "mid_dir" : "center", "must be finite");
  const Vector3d ez = w.axis.normalized();
  const Vector3d ey_raw = w.mid_dir - w.mid_dir.dot(ez) * ez;
  if (!(ey_raw.norm() > 1e-12 * std::max(1.0, w.mid_dir.norm())))
    bad("mid_dir", "must not be parallel to the axis");
  {
    // Element lengths against the whole path: the knots must stay distinct in double
    // precision (and the fit well posed).
    const double c = w.pitch / kTwoPi, speed = std::sqrt(w.radius * w.radius + c * c);
    const double La = w.angle * speed, total = 2.0 * w.span_length + La;
    if (!std::isfinite(La))
      bad("radius", "and pitch give an arc length that overflows, got radius " + num(w.radius) +
                        ", pitch " + num(w.pitch));
    if (!std::isfinite(total))
      bad("span_length", "gives a path length that overflows, got " + num(w.span_length));
    const double arc_el = La / w.arc_elements, span_el = w.span_length / w.span_elements;
    const double least = kMinRelativeElement * total;
    if (!(arc_el >= least))
      bad("radius",
          "too small for this path: the arc (angle " + num(w.angle) + " rad, pitch " +
              num(w.pitch) + ") is " + num(La) + " long, its " + std::to_string(w.arc_elements) +
              " elements " + num(arc_el) + " each, below " + num(kMinRelativeElement) +
              " of the path's length " + num(total) +
              " (use a larger radius, shorter spans or fewer arc_elements), got " + num(w.radius));
    if (!(span_el >= least))
      bad("span_length",
          "too small for this path: its " + std::to_string(w.span_elements) + " elements of " +
              num(span_el) + " are below " + num(kMinRelativeElement) + " of the path's length " +
              num(total) + " (use longer spans or fewer span_elements), got " + num(w.span_length));
  }
  const Vector3d ey = ey_raw.normalized(), ex = ey.cross(ez);

  const double rho = w.radius, c = w.pitch / kTwoPi, speed = std::sqrt(rho * rho + c * c);
  const double thA = 0.5 * std::numbers::pi + 0.5 * w.angle;
  const double L = w.span_length, La = w.angle * speed;
  const double s1 = L, s2 = L + La, s3 = 2.0 * L + La;
  // Arc point and unit travel direction at the polar angle theta (clockwise travel).
  auto arc = [&](double th) -> Vector3d {
    return w.center + rho * (std::cos(th) * ex + std::sin(th) * ey) +
           c * (thA - th - 0.5 * w.angle) * ez;
  };
  auto travel = [&](double th) -> Vector3d {
    return (rho * (std::sin(th) * ex - std::cos(th) * ey) + c * ez) / speed;
  };
  const double thB = thA - w.angle;
  const Vector3d PA = arc(thA), PB = arc(thB), tA = travel(thA), tB = travel(thB);
  auto path = [&](double s) -> Vector3d {
    if (s <= s1) return PA - (s1 - s) * tA;
    if (s >= s2) return PB + (s - s2) * tB;
    return arc(thA - (s - s1) / speed);
  };

  std::vector<double> knots(4, 0.0);
  for (int k = 1; k < w.span_elements; ++k) knots.push_back(L * k / w.span_elements);
  knots.insert(knots.end(), 2, s1);  // C1: the curvature jumps at the tangent point
  for (int k = 1; k < w.arc_elements; ++k) knots.push_back(s1 + La * k / w.arc_elements);
  knots.insert(knots.end(), 2, s2);
  for (int k = 1; k < w.span_elements; ++k) knots.push_back(s2 + L * k / w.span_elements);
  knots.insert(knots.end(), 4, s3);

  std::vector<double> t;
  std::vector<Vector3d> Q;
  constexpr int kSamples = 16;
  for (std::size_t k = 3; k + 4 < knots.size(); ++k) {
    const double a = knots[k], b = knots[k + 1];
    if (!(b > a)) continue;
    for (int j = 0; j < kSamples; ++j) t.push_back(a + (b - a) * j / kSamples);
  }
  t.push_back(s3);
  Q.reserve(t.size());
  for (double s : t) Q.push_back(path(s));
  CurveFit fit = fit_curve(Q, t, 3, knots);
  // Degree elevation keeps the curve and each knot's continuity (C2 inside, C1 at the tangent
  // points) and enriches the space the rod is analysed in.
  if (w.degree > 3) fit.curve = elevate_degree(fit.curve, w.degree - 3);
  return WrapPath{std::move(fit.curve), fit.max_deviation, La, tA, tB};
}

}  // namespace iga
