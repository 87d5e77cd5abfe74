// JSON (de)serialization of geometric entities (format: docs/model_format.md).
// The loader re-checks every invariant the constructors enforce ([PT97] Sect. 2.2: clamped,
// non-decreasing knots, interior multiplicity <= p, m + 1 = n + p + 2 knots) before building
// anything, so that each error names the JSON element at fault, not just the entity.
#include "geometry/geometry_io.hpp"

#include "geometry/constructions.hpp"
#include "geometry/refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace iga {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Bounds on the values of a geometry file, checked where they are read (docs/model_format.md,
// section 2). Doubles reach 1.8e308, but evaluation forms squares and products of lengths
// (|x - y|^2, metric a_ij = rho_i . rho_j, Gauss curvature 1/R^2, w P): a coordinate of 1e308
// is accepted by JSON and then makes every evaluation overflow. With every length and
// coordinate in [1e-100, 1e100], products of up to three of them stay within 1e300 and
// above 1e-300.
constexpr double kMaxCoordinate = 1e100;  // |x|: coordinates, directions, domain bounds
constexpr double kMinLength = 1e-100;     // radii and other positive lengths lie in
constexpr double kMaxLength = 1e100;      //   [kMinLength, kMaxLength]
// Weights: each in [1e-100, 1e100] (so w P stays finite), and max/min <= 1e10 in one entity:
// rational derivatives grow with the weight ratio, and beyond 1e10 the patch is numerically a
// lower-degree one (circles use ratios below 2, typical free forms below 100).
constexpr double kMinWeight = 1e-100;
constexpr double kMaxWeight = 1e100;
constexpr double kMaxWeightRatio = 1e10;  // named "1e10" in the message

/// Shortest text that reads back to x (the same digits the JSON output uses).
std::string num(double x) {
  return Json(x).dump();
}

// ---- reading ------------------------------------------------------------------------------

int parse_degree(const JsonCursor& c) {
  const int p = c.as_int();
  if (p < 1 || p > kMaxDegree) c.fail("degree must be in 1.." + std::to_string(kMaxDegree));
  return p;
}

/// A finite number with |x| <= kMaxCoordinate.
double parse_coordinate(const JsonCursor& c) {
  const double x = c.as_number();
  if (!(std::abs(x) <= kMaxCoordinate))
    c.fail("must lie within +-" + num(kMaxCoordinate) +
           " (geometric values are bounded so that their squares and products stay finite)");
  return x;
}

/// A clamped knot vector of degree p, checked element by element. n_cp >= 0 requires exactly
/// n_cp + p + 1 knots (a curve); n_cp < 0 only the minimum 2 (p + 1) (a surface direction,
/// whose control net size is derived from the knots).
std::vector<double> parse_knots(const JsonCursor& c, int p, int n_cp) {
  c.expect_array();
  std::vector<double> U(c.size());
  for (std::size_t i = 0; i < U.size(); ++i) U[i] = parse_coordinate(c[i]);
  const std::size_t m = U.size(), np1 = static_cast<std::size_t>(p) + 1;
  for (std::size_t i = 1; i < m; ++i)
    if (U[i] < U[i - 1])
      c[i].fail_plain("knots must be non-decreasing, got " + num(U[i]) + " after " + num(U[i - 1]));
  if (n_cp >= 0 && m != static_cast<std::size_t>(n_cp) + np1)
    c.fail_plain("expected " + std::to_string(static_cast<std::size_t>(n_cp) + np1) + " knots (" +
                 std::to_string(n_cp) + " control points + degree " + std::to_string(p) +
                 " + 1), got " + std::to_string(m));
  if (m < 2 * np1)
    c.fail_plain("a degree-" + std::to_string(p) + " knot vector needs at least " +
                 std::to_string(2 * np1) + " knots, got " + std::to_string(m));
  // Runs of equal knots: the end runs must have length exactly p + 1 (clamped, non-empty
  // domain), interior runs at most p (the basis stays at least C^0).
  std::size_t first = 1, last = 1;
  while (first < m && U[first] == U[0]) ++first;
  while (last < m && U[m - 1 - last] == U[m - 1]) ++last;
  if (first < np1)
    c[first].fail_plain(
        "knot vector must be clamped: the first degree + 1 = " + std::to_string(np1) +
        " knots must be equal, got " + num(U[first]) + " after " + num(U[0]));
  if (first > np1)
    c[np1].fail_plain("end knot " + num(U[0]) + " is repeated " + std::to_string(first) +
                      " times, more than degree + 1 = " + std::to_string(np1));
  if (last < np1)
    c[m - 1 - last].fail_plain(
        "knot vector must be clamped: the last degree + 1 = " + std::to_string(np1) +
        " knots must be equal, got " + num(U[m - 1 - last]) + " before " + num(U[m - 1]));
  if (last > np1)
    c[m - 1 - np1].fail_plain("end knot " + num(U[m - 1]) + " is repeated " + std::to_string(last) +
                              " times, more than degree + 1 = " + std::to_string(np1));
  for (std::size_t s = first; s < m - last;) {
    std::size_t e = s + 1;
    while (e < m - last && U[e] == U[s]) ++e;
    if (e - s > static_cast<std::size_t>(p))
      c[s + np1 - 1].fail_plain("interior knot " + num(U[s]) + " has multiplicity " +
                                std::to_string(e - s) + " > degree " + std::to_string(p));
    s = e;
  }
  return U;
}

Vector3d parse_vec3(const JsonCursor& c) {
  if (!c.json().is_array() || c.json().size() != 3) c.fail_type("3 coordinates [x, y, z]");
  return Vector3d(parse_coordinate(c[0]), parse_coordinate(c[1]), parse_coordinate(c[2]));
}

std::vector<Vector3d> parse_points(const JsonCursor& c, std::size_t n_expected,
                                   const std::string& why) {
  c.expect_array();
  if (c.size() != n_expected)
    c.fail_plain("expected " + std::to_string(n_expected) + " control points (" + why + "), got " +
                 std::to_string(c.size()));
  std::vector<Vector3d> P(n_expected);
  for (std::size_t i = 0; i < n_expected; ++i) P[i] = parse_vec3(c[i]);
  return P;
}

/// Optional "weights": one per control point, each > 0 and within the bounds above. Empty
/// means all 1.
std::vector<double> parse_weights(const JsonCursor& e, std::size_t n) {
  if (!e.has("weights")) return {};
  const JsonCursor c = e["weights"];
  std::vector<double> w = c.as_numbers();
  if (w.size() != n)
    c.fail_plain("expected " + std::to_string(n) + " weights (one per control point), got " +
                 std::to_string(w.size()));
  for (std::size_t i = 0; i < n; ++i) {
    if (!(w[i] > 0.0)) c[i].fail("weight must be > 0");
    if (!(w[i] >= kMinWeight && w[i] <= kMaxWeight))
      c[i].fail("weight must lie in [" + num(kMinWeight) + ", " + num(kMaxWeight) + "]");
  }
  if (n > 0) {
    const auto [lo, hi] = std::minmax_element(w.begin(), w.end());
    if (*hi > kMaxWeightRatio * *lo)
      c[static_cast<std::size_t>(hi - w.begin())].fail(
          "weights may differ by a factor of at most 1e10 in one entity; the smallest is " +
          num(*lo) + " (index " + std::to_string(lo - w.begin()) + ")");
  }
  return w;
}

void parse_normal(const JsonCursor& e, Surface& s) {
  if (!e.has("normal")) return;
  const JsonCursor c = e["normal"];
  const std::string n = c.as_string();
  if (n == "inward")
    s.set_normal_sign(-1);
  else if (n != "outward")
    c.fail("normal must be \"outward\" or \"inward\"");
}

/// A length: > 0 and in [kMinLength, kMaxLength].
double parse_positive(const JsonCursor& c) {
  const double x = c.as_number();
  if (!(x > 0.0)) c.fail("must be > 0");
  if (!(x >= kMinLength && x <= kMaxLength))
    c.fail("must lie in [" + num(kMinLength) + ", " + num(kMaxLength) +
           "] (lengths are bounded so that their squares and inverses stay finite)");
  return x;
}

/// Whether the frame ignores this ref_dir (zero or parallel to the axis): then it is not
/// written, and reading it back gives the default that the frame treats the same way.
bool ref_dir_degenerate(const Placement& pl) {
  return !(pl.axis.cross(pl.ref_dir).norm() > 1e-12 * pl.axis.norm() * pl.ref_dir.norm());
}

Placement parse_placement(const JsonCursor& e, bool need_center, bool need_axis) {
  Placement pl;
  if (need_center || e.has("center")) pl.center = parse_vec3(e["center"]);
  if (need_axis || e.has("axis")) {
    const JsonCursor c = e["axis"];
    pl.axis = parse_vec3(c);
    if (!(pl.axis.norm() > 0.0)) c.fail("axis must be a non-zero vector");
  }
  if (e.has("ref_dir")) {
    const JsonCursor c = e["ref_dir"];
    pl.ref_dir = parse_vec3(c);
    if (ref_dir_degenerate(pl)) c.fail("ref_dir must be non-zero and not parallel to the axis");
  }
  return pl;  // without ref_dir: [1, 0, 0], for which the frame falls back when it is parallel
}

Interval parse_interval(const JsonCursor& c) {
  if (!c.json().is_array() || c.json().size() != 2)
    c.fail_type("[lo, hi] (null for an unbounded end)");
  Interval I;
  I.lo = c[0].json().is_null() ? -kInf : parse_coordinate(c[0]);
  I.hi = c[1].json().is_null() ? kInf : parse_coordinate(c[1]);
  if (!(I.lo < I.hi)) c.fail("expected lo < hi");
  return I;
}

Domain2 parse_domain(const JsonCursor& e, Domain2 d) {
  if (!e.has("domain")) return d;
  const JsonCursor c = e["domain"];
  c.expect_object({"u", "v"});
  if (c.has("u")) d.u = parse_interval(c["u"]);
  if (c.has("v")) d.v = parse_interval(c["v"]);
  return d;
}

/// Runs a constructor; any GeometryError it still throws is reported at the entity.
template <class F>
auto build(const JsonCursor& e, F&& make) -> decltype(make()) {
  try {
    return make();
  } catch (const GeometryError& err) {
    e.fail_plain(err.what());
  }
}

NurbsCurve parse_nurbs_curve(const JsonCursor& e) {
  e.expect_object({"type", "degree", "knots", "control_points", "weights"});
  const int p = parse_degree(e["degree"]);
  const JsonCursor cp = e["control_points"];
  cp.expect_array();
  const std::size_t n = cp.size();
  std::vector<double> U = parse_knots(e["knots"], p, static_cast<int>(n));
  const std::vector<Vector3d> P = parse_points(cp, n, "one per basis function");
  const std::vector<double> w = parse_weights(e, n);
  return build(e, [&] { return NurbsCurve(p, std::move(U), P, w); });
}

NurbsSurface parse_nurbs_surface(const JsonCursor& e) {
  e.expect_object({"type", "degree", "knots", "control_points", "weights", "normal"});
  const JsonCursor deg = e["degree"];
  if (!deg.json().is_array() || deg.json().size() != 2)
    deg.fail_type("[degree_u, degree_v], two integers");
  const int p = parse_degree(deg[0]), q = parse_degree(deg[1]);
  const JsonCursor kc = e["knots"];
  kc.expect_object({"u", "v"});
  std::vector<double> Uu = parse_knots(kc["u"], p, -1);
  std::vector<double> Uv = parse_knots(kc["v"], q, -1);
  const std::size_t nu = Uu.size() - static_cast<std::size_t>(p) - 1;
  const std::size_t nv = Uv.size() - static_cast<std::size_t>(q) - 1;
  const std::vector<Vector3d> P =
      parse_points(e["control_points"], nu * nv,
                   "n_u x n_v = " + std::to_string(nu) + " x " + std::to_string(nv) +
                       " from the knots and degrees, u index fastest");
  const std::vector<double> w = parse_weights(e, nu * nv);
  NurbsSurface s = build(e, [&] { return NurbsSurface(p, std::move(Uu), q, std::move(Uv), P, w); });
  parse_normal(e, s);
  return s;
}

/// Normal orientation and the surface itself, with its domain (default: S::default_domain()).
template <class S, class F>
S analytic(const JsonCursor& e, F&& make) {
  const Domain2 d = parse_domain(e, S::default_domain());
  S s = build(e, [&] { return make(d); });
  parse_normal(e, s);
  return s;
}

GeometryEntity parse_analytic(const JsonCursor& e, const std::string& type) {
  if (type == "plane") {
    e.expect_object({"type", "center", "axis", "ref_dir", "domain", "normal"});
    const Placement pl = parse_placement(e, true, true);
    return analytic<Plane>(e, [&](const Domain2& d) { return Plane(pl, d); });
  }
  if (type == "sphere") {
    e.expect_object({"type", "center", "axis", "ref_dir", "radius", "domain", "normal"});
    const Placement pl = parse_placement(e, true, false);
    const double R = parse_positive(e["radius"]);
    return analytic<Sphere>(e, [&](const Domain2& d) { return Sphere(pl, R, d); });
  }
  if (type == "cylinder") {
    e.expect_object({"type", "center", "axis", "ref_dir", "radius", "domain", "normal"});
    const Placement pl = parse_placement(e, true, true);
    const double R = parse_positive(e["radius"]);
    return analytic<Cylinder>(e, [&](const Domain2& d) { return Cylinder(pl, R, d); });
  }
  if (type == "torus") {
    e.expect_object(
        {"type", "center", "axis", "ref_dir", "major_radius", "minor_radius", "domain", "normal"});
    const Placement pl = parse_placement(e, true, true);
    const double R = parse_positive(e["major_radius"]);
    // r >= R: a horn or spindle torus (docs/model_format.md)
    const double r = parse_positive(e["minor_radius"]);
    return analytic<Torus>(e, [&](const Domain2& d) { return Torus(pl, R, r, d); });
  }
  if (type == "cone") {
    e.expect_object({"type", "center", "axis", "ref_dir", "alpha", "domain", "normal"});
    const Placement pl = parse_placement(e, true, true);
    const JsonCursor ac = e["alpha"];
    const double alpha = ac.as_number();
    if (!(alpha > 0.0 && alpha < 0.5 * std::numbers::pi)) ac.fail("must be in (0, pi/2) radians");
    return analytic<Cone>(e, [&](const Domain2& d) { return Cone(pl, alpha, d); });
  }
  if (type == "hyperboloid") {
    e.expect_object({"type", "center", "axis", "ref_dir", "a", "domain", "normal"});
    const Placement pl = parse_placement(e, false, false);
    const double a = parse_coordinate(e["a"]);
    return analytic<Hyperboloid>(e, [&](const Domain2& d) { return Hyperboloid(pl, a, d); });
  }
  // revolution
  e.expect_object({"type", "center", "axis", "ref_dir", "profile", "domain", "normal"});
  const Placement pl = parse_placement(e, false, false);
  const JsonCursor pc = e["profile"];
  pc.expect_array(1);
  std::vector<double> coeffs(pc.size());
  for (std::size_t i = 0; i < coeffs.size(); ++i) coeffs[i] = parse_coordinate(pc[i]);
  return analytic<Revolution>(e, [&](const Domain2& d) { return Revolution(pl, coeffs, d); });
}

PatchGroup parse_patch_group(const JsonCursor& e) {
  e.expect_object({"type", "patches"});
  const JsonCursor c = e["patches"];
  c.expect_array(1);
  PatchGroup g;
  for (std::size_t i = 0; i < c.size(); ++i) g.patches.push_back(c[i].as_string());
  return g;  // the names are checked once the whole section is read
}

// ---- constructions: exact NURBS built at load time ([PT97] Ch. 7-8; constructions.hpp) ----

double optional_number(const JsonCursor& e, const char* key, double fallback) {
  return e.has(key) ? e[key].as_number() : fallback;
}
/// Lengths and coordinates of a construction: the bound of every geometric value
/// (parse_coordinate), so that squares of distances and the homogeneous w P stay finite.
constexpr double kMaxAngleDeg = 1e6;
void check_length(const JsonCursor& c) {
  (void)parse_coordinate(c);
}
void check_point(const JsonCursor& c) {
  for (std::size_t i = 0; i < c.size(); ++i) check_length(c[i]);
}
int parse_count(const JsonCursor& c, int lo, int hi) {
  const int n = c.as_int();
  if (n < lo || n > hi) c.fail("must be in " + std::to_string(lo) + ".." + std::to_string(hi));
  return n;
}
Vector3d parse_direction(const JsonCursor& c) {
  Vector3d d = parse_vec3(c);
  if (!(d.norm() > 0.0)) c.fail("must be a non-zero vector");
  return d;
}

/// A count for both surface directions: n, or [n_u, n_v].
std::array<int, 2> parse_count_pair(const JsonCursor& c, int lo, int hi) {
  if (!c.json().is_array()) {
    const int n = parse_count(c, lo, hi);
    return {n, n};
  }
  if (c.size() != 2) c.fail_type("a count or a pair [u, v]");
  return {parse_count(c[0], lo, hi), parse_count(c[1], lo, hi)};
}

/// Runs a construction; a ConstructionError is reported at the key it names (the model
/// format's key: make_wrap_path's "angle" is "angle_deg"), any other GeometryError at the entity.
template <class F>
auto construct(const JsonCursor& e, F&& make) -> decltype(make()) {
  try {
    return make();
  } catch (const ConstructionError& err) {
    const std::string key = err.key() == "angle" ? "angle_deg" : err.key();
    if (e.has(key)) e[key].fail_plain(err.what());  // the message states the value
    e.fail_plain(key + ": " + err.what());
  } catch (const GeometryError& err) {
    e.fail_plain(err.what());
  }
}

/// Control points in one direction after raising the degree by k and splitting each of the
/// E elements into `parts` ([PT97] A5.9 raises every distinct knot's multiplicity by k; the
/// subdivision inserts parts - 1 simple knots per element).
long refined_count(const KnotVector& K, int k, int parts) {
  const long E = K.num_elements();
  return K.num_basis() + static_cast<long>(k) * E + static_cast<long>(parts - 1) * E;
}

/// "refine": {"elevate": k or [k_u, k_v], "subdivide": n or [n_u, n_v]} of a constructed
/// surface, then "normal". The refined net may hold at most kMaxSurfaceNetPoints points.
NurbsSurface finish_surface(const JsonCursor& e, NurbsSurface s) {
  if (e.has("refine")) {
    const JsonCursor r = e["refine"];
    r.expect_object({"elevate", "subdivide"});
    const std::array<int, 2> k =
        r.has("elevate") ? parse_count_pair(r["elevate"], 0, 5) : std::array{0, 0};
    const std::array<int, 2> n =
        r.has("subdivide") ? parse_count_pair(r["subdivide"], 1, 1024) : std::array{1, 1};
    const long nu = refined_count(s.knots_u(), k[0], n[0]);
    const long nv = refined_count(s.knots_v(), k[1], n[1]);
    if (nu * nv > kMaxSurfaceNetPoints)
      r.fail("makes " + std::to_string(nu) + " x " + std::to_string(nv) + " = " +
             std::to_string(nu * nv) + " control points, above the limit of " +
             std::to_string(kMaxSurfaceNetPoints) + " for a constructed surface");
    s = build(e, [&] {
      NurbsSurface t = k[0] > 0 || k[1] > 0 ? elevate_degree(s, k[0], k[1]) : s;
      return n[0] > 1 || n[1] > 1 ? subdivide(t, n[0], n[1]) : t;
    });
  }
  parse_normal(e, s);
  return s;
}

constexpr double kDeg = std::numbers::pi / 180.0;  // degrees of the model format to radians

// One function per shape of a construction: each checks its keys and values (naming the key at
// fault) and builds the exact NURBS.

NurbsSurface construct_cylinder(const JsonCursor& e) {
  e.expect_object({"type", "shape", "center", "axis", "ref_dir", "radius", "height", "start_deg",
                   "end_deg", "refine", "normal"});
  const Vector3d base = parse_vec3(e["center"]), axis = parse_direction(e["axis"]);
  const Vector3d ref = e.has("ref_dir") ? parse_direction(e["ref_dir"]) : Vector3d::UnitX();
  const double r = parse_positive(e["radius"]), h = parse_positive(e["height"]);
  const double a = optional_number(e, "start_deg", 0.0), b = optional_number(e, "end_deg", 360.0);
  check_length(e["radius"]);
  check_length(e["height"]);
  if (!(std::abs(a) <= kMaxAngleDeg))
    e["start_deg"].fail("must lie in [-" + num(kMaxAngleDeg) + ", " + num(kMaxAngleDeg) + "]");
  if (!(std::abs(b) <= kMaxAngleDeg))
    e["end_deg"].fail("must lie in [-" + num(kMaxAngleDeg) + ", " + num(kMaxAngleDeg) + "]");
  if (!(b > a))
    e[e.has("end_deg") ? "end_deg" : "start_deg"].fail(
        "the angular range needs start_deg < end_deg (start_deg " + num(a) + ", end_deg " + num(b) +
        ")");
  if (b - a > 360.0 * (1.0 + 1e-12))
    e[e.has("end_deg") ? "end_deg" : "start_deg"].fail(
        "the angular range end_deg - start_deg must be <= 360 (start_deg " + num(a) + ", end_deg " +
        num(b) + ")");
  return finish_surface(e, construct(e, [&] {
                          return make_cylinder(base, axis.normalized(), ref, r, h, a * kDeg,
                                               b * kDeg);
                        }));
}

// A [lo, hi] pair of angles in degrees within [min, max], lo < hi.
std::pair<double, double> angle_range(const JsonCursor& c, double min, double max) {
  const std::vector<double> a = c.as_numbers();
  if (a.size() != 2) c.fail("expected [low, high] in degrees");
  if (!(a[0] >= min && a[1] <= max && a[1] > a[0]))
    c.fail("needs " + num(min) + " <= low < high <= " + num(max) + ", got [" + num(a[0]) + ", " +
           num(a[1]) + "]");
  return {a[0], a[1]};
}

NurbsSurface construct_sphere(const JsonCursor& e) {
  e.expect_object({"type", "shape", "center", "radius", "axis", "ref_dir", "lat_deg", "lon_deg",
                   "refine", "normal"});
  const Vector3d c = parse_vec3(e["center"]);
  const double r = parse_positive(e["radius"]);
  check_length(e["radius"]);
  check_point(e["center"]);
  if (!e.has("axis") && !e.has("ref_dir") && !e.has("lat_deg") && !e.has("lon_deg"))
    return finish_surface(e, construct(e, [&] { return make_sphere(c, r); }));
  // A zone: latitudes and longitudes about an axis.
  const Vector3d axis = e.has("axis") ? parse_direction(e["axis"]) : Vector3d::UnitZ();
  const Vector3d ref = e.has("ref_dir") ? parse_direction(e["ref_dir"]) : Vector3d::UnitX();
  if (!(ref.cross(axis).norm() > 1e-6)) e["ref_dir"].fail("must not be parallel to axis");
  const std::pair<double, double> lat =
      e.has("lat_deg") ? angle_range(e["lat_deg"], -90.0, 90.0) : std::pair{-90.0, 90.0};
  const std::pair<double, double> lon = e.has("lon_deg")
                                            ? angle_range(e["lon_deg"], -kMaxAngleDeg, kMaxAngleDeg)
                                            : std::pair{0.0, 360.0};
  if (lon.second - lon.first > 360.0 * (1.0 + 1e-12))
    e["lon_deg"].fail("spans more than 360 degrees");
  return finish_surface(e, construct(e, [&] {
                          return make_sphere_zone(c, axis, ref, r, lat.first * kDeg,
                                                  lat.second * kDeg, lon.first * kDeg,
                                                  lon.second * kDeg);
                        }));
}

NurbsSurface construct_torus(const JsonCursor& e) {
  e.expect_object(
      {"type", "shape", "center", "axis", "major_radius", "minor_radius", "refine", "normal"});
  const Vector3d c = parse_vec3(e["center"]), axis = parse_direction(e["axis"]);
  const double R = parse_positive(e["major_radius"]), r = parse_positive(e["minor_radius"]);
  check_length(e["major_radius"]);
  check_point(e["center"]);
  if (!(r < R)) e["minor_radius"].fail("must be < major_radius " + num(R) + " (a ring torus)");
  return finish_surface(e, construct(e, [&] { return make_torus(c, axis.normalized(), R, r); }));
}

NurbsSurface construct_plane(const JsonCursor& e) {
  e.expect_object({"type", "shape", "origin", "du", "dv", "refine", "normal"});
  const Vector3d o = parse_vec3(e["origin"]), du = parse_direction(e["du"]),
                 dv = parse_direction(e["dv"]);
  check_point(e["origin"]);
  check_point(e["du"]);
  check_point(e["dv"]);
  if (!(du.cross(dv).norm() > 1e-12 * du.norm() * dv.norm()))
    e["dv"].fail("must not be parallel to du (the patch would be a line)");
  return finish_surface(e, construct(e, [&] { return make_plane_patch(o, du, dv); }));
}

NurbsSurface construct_hyperboloid(const JsonCursor& e) {  // [KS15] (11)
  e.expect_object({"type", "shape", "a", "x_range", "y_range", "refine", "normal"});
  const double a = e["a"].as_number();
  const Interval x = parse_interval(e["x_range"]), y = parse_interval(e["y_range"]);
  if (!std::isfinite(x.lo) || !std::isfinite(x.hi)) e["x_range"].fail("must be finite");
  if (!std::isfinite(y.lo) || !std::isfinite(y.hi)) e["y_range"].fail("must be finite");
  if (!(std::max(std::abs(x.lo), std::abs(x.hi)) <= kMaxCoordinate))
    e["x_range"].fail("must lie within +-" + num(kMaxCoordinate));
  if (!(std::max(std::abs(y.lo), std::abs(y.hi)) <= kMaxCoordinate))
    e["y_range"].fail("must lie within +-" + num(kMaxCoordinate));
  if (!(std::abs(a) <= kMaxCoordinate)) e["a"].fail("must lie within +-" + num(kMaxCoordinate));
  return finish_surface(
      e, construct(e, [&] { return make_bilinear_hyperboloid(a, x.lo, x.hi, y.lo, y.hi); }));
}

/// A straight rod: a degree-1 segment elevated and split into elements.
NurbsCurve construct_line(const JsonCursor& e) {
  e.expect_object({"type", "shape", "start", "end", "degree", "elements"});
  const Vector3d a = parse_vec3(e["start"]), b = parse_vec3(e["end"]);
  check_point(e["start"]);
  check_point(e["end"]);
  if (!((b - a).norm() > 0.0)) e["end"].fail("must differ from start");
  const int p = e.has("degree") ? parse_count(e["degree"], 1, kMaxDegree) : 1;
  const int n = e.has("elements") ? parse_count(e["elements"], 1, kMaxCurveElements) : 1;
  return construct(e, [&] {
    NurbsCurve c = make_line(a, b);
    if (p > 1) c = elevate_degree(c, p - 1);
    return n > 1 ? subdivide(c, n) : c;
  });
}

NurbsCurve construct_arc(const JsonCursor& e) {
  e.expect_object({"type", "shape", "center", "x_axis", "normal", "radius", "start_deg", "end_deg",
                   "degree", "elements"});
  const Vector3d c = e.has("center") ? parse_vec3(e["center"]) : Vector3d::Zero();
  if (e.has("center")) check_point(e["center"]);
  const Vector3d x = e.has("x_axis") ? parse_direction(e["x_axis"]) : Vector3d::UnitX();
  const Vector3d nrm = e.has("normal") ? parse_direction(e["normal"]) : Vector3d::UnitZ();
  if (!(x.cross(nrm).norm() > 1e-6)) e["normal"].fail("must not be parallel to x_axis");
  const Vector3d y = nrm.cross(x).normalized();
  const Vector3d xo = y.cross(nrm).normalized();  // x_axis made normal to `normal`
  const double r = parse_positive(e["radius"]);
  check_length(e["radius"]);
  const double a0 = optional_number(e, "start_deg", 0.0), a1 = e["end_deg"].as_number();
  if (!std::isfinite(a0) || std::abs(a0) > 720.0) e["start_deg"].fail("must lie within +-720");
  if (!(a1 > a0 && a1 - a0 <= 360.0)) e["end_deg"].fail("must lie in (start_deg, start_deg + 360]");
  const int p = e.has("degree") ? parse_count(e["degree"], 2, kMaxDegree) : 2;
  const int n = e.has("elements") ? parse_count(e["elements"], 1, kMaxCurveElements) : 1;
  return construct(e, [&] {
    NurbsCurve arc = make_circular_arc(c, xo, y, r, a0 * kDeg, a1 * kDeg);
    if (p > 2) arc = elevate_degree(arc, p - 2);
    return n > 1 ? subdivide(arc, n) : arc;
  });
}

NurbsCurve construct_wrap_path(const JsonCursor& e) {
  e.expect_object({"type", "shape", "center", "axis", "mid_dir", "radius", "angle_deg", "pitch",
                   "span_length", "arc_elements", "span_elements", "degree"});
  WrapPathSpec w;
  if (e.has("center")) w.center = parse_vec3(e["center"]);
  if (e.has("axis")) w.axis = parse_direction(e["axis"]);
  if (e.has("mid_dir")) w.mid_dir = parse_direction(e["mid_dir"]);
  if (e.has("center")) check_point(e["center"]);
  w.radius = parse_positive(e["radius"]);
  check_length(e["radius"]);
  const JsonCursor ac = e["angle_deg"];
  w.angle = ac.as_number() * kDeg;
  if (!(w.angle > 0.0 && w.angle <= 4.0 * std::numbers::pi)) ac.fail("must be in (0, 720]");
  w.pitch = optional_number(e, "pitch", 0.0);
  if (!std::isfinite(w.pitch) || std::abs(w.pitch) > kMaxCoordinate)
    e["pitch"].fail("must lie within +-" + num(kMaxCoordinate));
  w.span_length = parse_positive(e["span_length"]);
  check_length(e["span_length"]);
  w.arc_elements = parse_count(e["arc_elements"], 1, kMaxCurveElements);
  w.span_elements = parse_count(e["span_elements"], 1, kMaxCurveElements);
  if (e.has("degree")) w.degree = parse_count(e["degree"], 3, 5);
  return construct(e, [&] { return make_wrap_path(w).curve; });
}

GeometryEntity parse_construction(const JsonCursor& e) {
  const JsonCursor sc = e["shape"];
  const std::string shape = sc.as_string();
  if (shape == "cylinder") return construct_cylinder(e);
  if (shape == "sphere") return construct_sphere(e);
  if (shape == "torus") return construct_torus(e);
  if (shape == "plane") return construct_plane(e);
  if (shape == "hyperboloid") return construct_hyperboloid(e);
  if (shape == "line") return construct_line(e);
  if (shape == "wrap_path") return construct_wrap_path(e);
  if (shape == "arc") return construct_arc(e);
  sc.fail(
      "unknown shape (expected one of cylinder, sphere, torus, plane, hyperboloid, line, "
      "wrap_path, arc)");
}

constexpr const char* kEntityTypes[] = {
    "nurbs_curve", "nurbs_surface", "plane",      "sphere",      "cylinder",        "torus",
    "cone",        "hyperboloid",   "revolution", "patch_group", "trimmed_surface", "construction"};

GeometryEntity parse_entity(const JsonCursor& e);

/// {"type": "trimmed_surface", "surface": {...}, "loops": [[[u, v], ...], ...],
///  "edges": [{nurbs_curve}, ...], "deflection": d}
TrimmedSurface parse_trimmed(const JsonCursor& e) {
  e.expect_object({"type", "surface", "loops", "edges", "deflection"});
  const JsonCursor sc = e["surface"];
  const GeometryEntity base = parse_entity(sc);
  const Surface* s = as_surface(base);
  if (s == nullptr || std::holds_alternative<TrimmedSurface>(base))
    sc.fail_plain("the base of a trimmed surface must be a NURBS or analytic surface");
  const JsonCursor lc = e["loops"];
  lc.expect_array(1);
  std::vector<TrimmedSurface::Loop> loops(lc.size());
  for (std::size_t k = 0; k < lc.size(); ++k) {
    const JsonCursor L = lc[k];
    L.expect_array(3);
    for (std::size_t i = 0; i < L.size(); ++i) {
      const JsonCursor p = L[i];
      if (!p.json().is_array() || p.json().size() != 2) p.fail_type("[u, v]");
      loops[k].emplace_back(p[0].as_number(), p[1].as_number());
    }
  }
  std::vector<NurbsCurve> edges;
  if (e.has("edges")) {
    const JsonCursor ec = e["edges"];
    ec.expect_array();
    for (std::size_t i = 0; i < ec.size(); ++i) {
      GeometryEntity c = parse_entity(ec[i]);
      if (!std::holds_alternative<NurbsCurve>(c)) ec[i].fail_plain("an edge must be a nurbs_curve");
      edges.push_back(std::get<NurbsCurve>(std::move(c)));
    }
  }
  const double deflection = e.has("deflection") ? e["deflection"].as_number() : 0.0;
  return build(e,
               [&] { return TrimmedSurface(*s, std::move(loops), std::move(edges), deflection); });
}

GeometryEntity parse_entity(const JsonCursor& e) {
  if (!e.json().is_object()) e.fail_type("an object with a \"type\" key");
  const JsonCursor tc = e["type"];
  const std::string type = tc.as_string();
  if (type == "nurbs_curve") return parse_nurbs_curve(e);
  if (type == "nurbs_surface") return parse_nurbs_surface(e);
  if (type == "patch_group") return parse_patch_group(e);
  if (type == "trimmed_surface") return parse_trimmed(e);
  if (type == "construction") return parse_construction(e);
  for (const char* t : kEntityTypes)
    if (type == t) return parse_analytic(e, type);
  std::string list;
  for (const char* t : kEntityTypes) list += std::string(list.empty() ? "" : ", ") + t;
  tc.fail("unknown entity type (expected one of " + list + ")");
}

void check_patch_group(const GeometryModel& m, const PatchGroup& g, const JsonCursor& e) {
  const JsonCursor c = e["patches"];
  for (std::size_t i = 0; i < g.patches.size(); ++i) {
    const std::string& name = g.patches[i];
    const GeometryEntity* member = m.find(name);
    if (member == nullptr)
      c[i].fail_plain("\"" + name + "\" does not name an entity of this geometry section");
    if (as_surface(*member) == nullptr)
      c[i].fail_plain("\"" + name + "\" is a " + entity_type(*member) +
                      "; a patch group takes surfaces only (NURBS or analytic)");
    for (std::size_t k = 0; k < i; ++k)
      if (g.patches[k] == name) c[i].fail_plain("\"" + name + "\" is listed twice");
  }
}

// ---- writing ------------------------------------------------------------------------------

Json vec3_json(const Vector3d& x) {
  return Json::array({x.x(), x.y(), x.z()});
}

/// The Cartesian coordinate x with fl(w * x) == y, so that reading (x, w) back reproduces the
/// stored homogeneous coordinate y = w x bit for bit. fl(y / w) is within an ulp or two of
/// such an x; among the candidates the one with the shortest decimal text is written (1.5
/// rather than 1.5000000000000002 when both multiply back to y).
double exact_coordinate(double y, double w) {
  const double x0 = y / w;
  double best = x0;
  bool found = false;
  std::size_t best_len = 0;
  auto consider = [&](double x) {
    if (w * x != y) return;
    const std::size_t len = num(x).size();
    if (!found || len < best_len) {
      best = x;
      best_len = len;
      found = true;
    }
  };
  consider(x0);
  double up = x0, down = x0;
  for (int k = 0; k < 4; ++k) {
    up = std::nextafter(up, kInf);
    down = std::nextafter(down, -kInf);
    consider(up);
    consider(down);
  }
  return best;
}

Json points_json(const std::vector<Vector4d>& pw) {
  Json a = Json::array();
  for (const Vector4d& q : pw)
    a.push_back(Json::array({exact_coordinate(q.x(), q.w()), exact_coordinate(q.y(), q.w()),
                             exact_coordinate(q.z(), q.w())}));
  return a;
}

Json weights_json(const std::vector<Vector4d>& pw) {
  Json a = Json::array();
  for (const Vector4d& q : pw) a.push_back(q.w());
  return a;
}

Json bound_json(double x) {
  return std::isinf(x) ? Json(nullptr) : Json(x);
}

Json interval_json(const Interval& I) {
  return Json::array({bound_json(I.lo), bound_json(I.hi)});
}

const char* normal_name(const Surface& s) {
  return s.normal_sign() < 0 ? "inward" : "outward";
}

Json analytic_json(const AnalyticSurface& s) {
  Json j;
  j["type"] = s.type_name();
  j["center"] = vec3_json(s.placement().center);
  j["axis"] = vec3_json(s.placement().axis);
  if (!ref_dir_degenerate(s.placement())) j["ref_dir"] = vec3_json(s.placement().ref_dir);
  visit_analytic(s, Overloaded{
                        [](const Plane&) {},
                        [&](const Sphere& sp) { j["radius"] = sp.radius(); },
                        [&](const Cylinder& cy) { j["radius"] = cy.radius(); },
                        [&](const Torus& to) {
                          j["major_radius"] = to.major_radius();
                          j["minor_radius"] = to.minor_radius();
                        },
                        [&](const Cone& co) { j["alpha"] = co.alpha(); },
                        [&](const Hyperboloid& hy) { j["a"] = hy.a(); },
                        [&](const Revolution& re) { j["profile"] = re.coeffs(); },
                    });
  j["domain"] = {{"u", interval_json(s.domain().u)}, {"v", interval_json(s.domain().v)}};
  j["normal"] = normal_name(s);
  return j;
}

}  // namespace

// ---- public API ---------------------------------------------------------------------------

std::string entity_type(const GeometryEntity& e) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, NurbsCurve>)
          return "nurbs_curve";
        else if constexpr (std::is_same_v<T, PatchGroup>)
          return "patch_group";
        else
          return x.type_name();
      },
      e);
}

const Surface* as_surface(const GeometryEntity& e) {
  return std::visit(
      [](const auto& x) -> const Surface* {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_base_of_v<Surface, T>)
          return &x;
        else
          return nullptr;
      },
      e);
}

const GeometryEntity* GeometryModel::find(const std::string& name) const {
  for (const auto& [n, e] : entities)
    if (n == name) return &e;
  return nullptr;
}

const Surface* GeometryModel::surface(const std::string& name) const {
  const GeometryEntity* e = find(name);
  return e != nullptr ? as_surface(*e) : nullptr;
}

const NurbsCurve* GeometryModel::curve(const std::string& name) const {
  const GeometryEntity* e = find(name);
  return e != nullptr ? std::get_if<NurbsCurve>(e) : nullptr;
}

std::vector<const Surface*> GeometryModel::surfaces_of(const std::string& name) const {
  const GeometryEntity* e = find(name);
  if (e == nullptr) throw std::out_of_range("no geometry entity named \"" + name + "\"");
  if (const auto* g = std::get_if<PatchGroup>(e)) {
    std::vector<const Surface*> out;
    for (const std::string& member : g->patches) {
      const Surface* s = surface(member);
      if (s == nullptr)
        throw std::out_of_range("patch group \"" + name + "\": \"" + member +
                                "\" is not a surface of this geometry");
      out.push_back(s);
    }
    return out;
  }
  if (const Surface* s = as_surface(*e)) return {s};
  throw std::out_of_range("geometry entity \"" + name + "\" is a " + entity_type(*e) +
                          ", not a surface");
}

GeometryModel parse_geometry(const Json& j, const std::string& file, const JsonPointer& at,
                             const std::map<std::string, EntityExpander>& expanders) {
  const JsonCursor g(j, file, at);
  if (!j.is_object()) g.fail_type("an object mapping entity names to entities");
  GeometryModel m;
  for (const std::string& name : g.keys()) {
    const JsonCursor e = g[name];
    if (name.empty()) e.fail_plain("entity names must not be empty");
    const auto expander =
        e.json().is_object() && e.json().contains("type") && e.json()["type"].is_string()
            ? expanders.find(e.json()["type"].get<std::string>())
            : expanders.end();
    if (expander == expanders.end()) {
      m.entities.emplace_back(name, parse_entity(e));
      continue;
    }
    for (auto& [member, entity] : expander->second(e, name)) {
      if (m.find(member) != nullptr || (member != name && j.contains(member)))
        e.fail_plain("the entity \"" + member + "\" it makes is already a name of this section");
      m.entities.emplace_back(member, std::move(entity));
    }
  }
  for (const auto& [name, e] : m.entities)
    if (const auto* grp = std::get_if<PatchGroup>(&e);
        grp != nullptr && g.has(name) && g[name].has("patches"))
      check_patch_group(m, *grp, g[name]);  // (an expander's groups are its own to check)
  return m;
}

Json entity_to_json(const GeometryEntity& e) {
  if (const auto* c = std::get_if<NurbsCurve>(&e)) {
    Json j;
    j["type"] = "nurbs_curve";
    j["degree"] = c->degree();
    j["knots"] = c->knots().knots();
    j["control_points"] = points_json(c->homogeneous());
    if (c->is_rational()) j["weights"] = weights_json(c->homogeneous());
    return j;
  }
  if (const auto* s = std::get_if<NurbsSurface>(&e)) {
    Json j;
    j["type"] = "nurbs_surface";
    j["degree"] = Json::array({s->degree_u(), s->degree_v()});
    j["knots"] = {{"u", s->knots_u().knots()}, {"v", s->knots_v().knots()}};
    j["control_points"] = points_json(s->homogeneous());
    if (s->is_rational()) j["weights"] = weights_json(s->homogeneous());
    j["normal"] = normal_name(*s);
    return j;
  }
  if (const auto* g = std::get_if<PatchGroup>(&e)) {
    Json j;
    j["type"] = "patch_group";
    j["patches"] = g->patches;
    return j;
  }
  if (const auto* t = std::get_if<TrimmedSurface>(&e)) {
    Json j;
    j["type"] = "trimmed_surface";
    if (const auto* n = dynamic_cast<const NurbsSurface*>(&t->base()))
      j["surface"] = entity_to_json(GeometryEntity(*n));
    else
      j["surface"] = analytic_json(dynamic_cast<const AnalyticSurface&>(t->base()));
    Json loops = Json::array();
    for (const TrimmedSurface::Loop& L : t->loops()) {
      Json l = Json::array();
      for (const Vector2d& p : L) l.push_back({p[0], p[1]});
      loops.push_back(l);
    }
    j["loops"] = loops;
    Json edges = Json::array();
    for (const NurbsCurve& c : t->edges()) edges.push_back(entity_to_json(GeometryEntity(c)));
    j["edges"] = edges;
    j["deflection"] = t->deflection();
    return j;
  }
  return analytic_json(dynamic_cast<const AnalyticSurface&>(*as_surface(e)));
}

Json geometry_to_json(const GeometryModel& m) {
  Json j = Json::object();
  for (const auto& [name, e] : m.entities) j[name] = entity_to_json(e);
  return j;
}

}  // namespace iga
