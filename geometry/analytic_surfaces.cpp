// Analytic rigid surfaces: placement frames, parameter validation and exact derivatives up to
// order 2. References: [KS15] (8), (11), (13), (15), (A.1), (B.4), (B.10), (B.16), (B.23); see
// ../shared/paper/EQUATIONS.md. Parametrizations and normal orientations: analytic_surfaces.hpp.
#include "geometry/analytic_surfaces.hpp"
#include "geometry/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

#include <Eigen/Geometry>

#include "geometry/knot_vector.hpp"  // GeometryError

namespace iga {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::string num(double x) {
  return num_text(x, 12);
}

// Streams rather than string '+': GCC 12 at -O3 warns falsely (-Wrestrict) on the latter.
std::string vec(const Vector3d& x) {
  std::ostringstream os;
  os.precision(12);
  os << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return os.str();
}

[[noreturn]] void fail(const std::string& msg) {
  throw GeometryError(msg);
}

void check_domain(const std::string& type, const Domain2& d) {
  // !(lo < hi) also rejects NaN bounds.
  if (!(d.u.lo < d.u.hi))
    fail(type + ": domain u must satisfy lo < hi, got [" + num(d.u.lo) + ", " + num(d.u.hi) + "]");
  if (!(d.v.lo < d.v.hi))
    fail(type + ": domain v must satisfy lo < hi, got [" + num(d.v.lo) + ", " + num(d.v.hi) + "]");
}

void check_positive(const std::string& what, double x) {
  if (!(x > 0.0) || !std::isfinite(x)) fail(what + " must be finite and > 0, got " + num(x));
}

/// A direction spans a full turn when its interval is 2 pi long (up to round-off of the bounds).
bool spans_full_turn(const Interval& i) {
  return std::abs((i.hi - i.lo) - kTwoPi) <= 1e-12 * kTwoPi;
}

/// Radial and circumferential unit vectors e_r(phi), e_phi(phi) of the frame E.
void polar(const Matrix3d& E, double phi, Vector3d& er, Vector3d& ephi) {
  const double c = std::cos(phi), s = std::sin(phi);
  er = c * E.col(0) + s * E.col(1);
  ephi = -s * E.col(0) + c * E.col(1);
}

}  // namespace

// ---- Placement ------------------------------------------------------------------------------

Matrix3d Placement::frame() const {
  if (!center.allFinite()) fail("Placement: center must be finite, got " + vec(center));
  const double len = axis.norm();
  if (!(len > 0.0) || !std::isfinite(len))
    fail("Placement: axis must be a finite non-zero vector, got " + vec(axis));
  const Vector3d ez = axis / len;

  // e_x = ref_dir orthogonalized against e_z. When ref_dir is zero, non-finite or parallel to
  // the axis we fall back to the coordinate unit vector least aligned with the axis (so the
  // default ref_dir = e_x works with every axis, including axis = e_x).
  Vector3d ex = Vector3d::Zero();
  bool have_ex = false;
  if (ref_dir.allFinite()) {
    Vector3d perp = ref_dir - ref_dir.dot(ez) * ez;
    if (perp.norm() > 1e-12 * ref_dir.norm()) {
      // A second Gram-Schmidt pass removes the round-off left along e_z when ref_dir is
      // nearly parallel to the axis, so that E is orthonormal to machine precision.
      perp -= perp.dot(ez) * ez;
      ex = perp.normalized();
      have_ex = true;
    }
  }
  if (!have_ex) {
    Eigen::Index i = 0;
    ez.cwiseAbs().minCoeff(&i);
    const Vector3d ref = Vector3d::Unit(i);
    Vector3d perp = ref - ref.dot(ez) * ez;
    perp -= perp.dot(ez) * ez;
    ex = perp.normalized();
  }
  const Vector3d ey = ez.cross(ex);

  Matrix3d E;
  E.col(0) = ex;
  E.col(1) = ey;
  E.col(2) = ez;
  return E;
}

AnalyticSurface::AnalyticSurface(const Placement& pl, const Domain2& d)
    : place_(pl), E_(pl.frame()), domain_(d) {
  // Normalize the stored axis only when it is not unit already, so that constructing again
  // from the stored placement reproduces it bit for bit (JSON round trips compare with ==).
  if (std::abs(place_.axis.squaredNorm() - 1.0) > 4.0 * std::numeric_limits<double>::epsilon())
    place_.axis = E_.col(2);
}

// ---- Plane (8) ------------------------------------------------------------------------------

Plane::Plane(const Placement& pl, const Domain2& d) : AnalyticKind(pl, d) {
  check_domain("Plane", d);
}

Domain2 Plane::default_domain() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{-inf, inf}, {-inf, inf}};
}

SurfaceDerivs Plane::derivs(double u, double v, int order) const {
  SurfaceDerivs r;
  r.order = std::clamp(order, 0, 2);
  r.S = place_.center + u * E_.col(0) + v * E_.col(1);
  if (r.order >= 1) {
    r.Su = E_.col(0);
    r.Sv = E_.col(1);
  }
  return r;  // second derivatives vanish
}

bool Plane::operator==(const Plane& o) const {
  return place_ == o.place_ && domain_ == o.domain_ && normal_sign() == o.normal_sign();
}

// ---- Sphere (B.4) ---------------------------------------------------------------------------

Sphere::Sphere(const Placement& pl, double radius, const Domain2& d)
    : AnalyticKind(pl, d), R_(radius) {
  check_positive("Sphere: radius", radius);
  check_domain("Sphere", d);
}

Domain2 Sphere::default_domain() {
  return {{0.0, kTwoPi}, {-0.5 * std::numbers::pi, 0.5 * std::numbers::pi}};
}

SurfaceDerivs Sphere::derivs(double u, double v, int order) const {
  // rho = c + R (cos v e_r(u) + sin v e_z): rho_u x rho_v = R^2 cos v (cos v e_r + sin v e_z).
  SurfaceDerivs r;
  r.order = std::clamp(order, 0, 2);
  Vector3d er, eu;
  polar(E_, u, er, eu);
  const Vector3d& ez = E_.col(2);
  const double cv = std::cos(v), sv = std::sin(v);
  r.S = place_.center + R_ * (cv * er + sv * ez);
  if (r.order >= 1) {
    r.Su = R_ * cv * eu;
    r.Sv = R_ * (-sv * er + cv * ez);
  }
  if (r.order >= 2) {
    r.Suu = -R_ * cv * er;
    r.Suv = -R_ * sv * eu;
    r.Svv = -R_ * (cv * er + sv * ez);
  }
  return r;
}

bool Sphere::closed_u() const {
  return spans_full_turn(domain_.u);
}

bool Sphere::operator==(const Sphere& o) const {
  return place_ == o.place_ && R_ == o.R_ && domain_ == o.domain_ &&
         normal_sign() == o.normal_sign();
}

// ---- Cylinder (B.10) ------------------------------------------------------------------------

Cylinder::Cylinder(const Placement& pl, double radius, const Domain2& d)
    : AnalyticKind(pl, d), R_(radius) {
  check_positive("Cylinder: radius", radius);
  check_domain("Cylinder", d);
}

Domain2 Cylinder::default_domain() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{0.0, kTwoPi}, {-inf, inf}};
}

SurfaceDerivs Cylinder::derivs(double u, double v, int order) const {
  // rho = c + R e_r(u) + v e_z: rho_u x rho_v = R e_r (outward).
  SurfaceDerivs r;
  r.order = std::clamp(order, 0, 2);
  Vector3d er, eu;
  polar(E_, u, er, eu);
  r.S = place_.center + R_ * er + v * E_.col(2);
  if (r.order >= 1) {
    r.Su = R_ * eu;
    r.Sv = E_.col(2);
  }
  if (r.order >= 2) r.Suu = -R_ * er;
  return r;
}

bool Cylinder::closed_u() const {
  return spans_full_turn(domain_.u);
}

bool Cylinder::operator==(const Cylinder& o) const {
  return place_ == o.place_ && R_ == o.R_ && domain_ == o.domain_ &&
         normal_sign() == o.normal_sign();
}

// ---- Torus (B.16) ---------------------------------------------------------------------------

Torus::Torus(const Placement& pl, double major_radius, double minor_radius, const Domain2& d)
    : AnalyticKind(pl, d), R_(major_radius), r_(minor_radius) {
  check_positive("Torus: major radius", major_radius);
  check_positive("Torus: minor radius", minor_radius);
  // r >= R (horn r = R, spindle r > R) is accepted: the same (B.16) parametrization, passing
  // through the axis where R + r cos v = 0 (singular points, as the sphere's poles).
  check_domain("Torus", d);
}

Domain2 Torus::default_domain() {
  return {{0.0, kTwoPi}, {0.0, kTwoPi}};
}

SurfaceDerivs Torus::derivs(double u, double v, int order) const {
  // rho = c + (R + r cos v) e_r(u) + r sin v e_z:
  // rho_u x rho_v = r (R + r cos v)(cos v e_r + sin v e_z), outward from the tube.
  SurfaceDerivs d;
  d.order = std::clamp(order, 0, 2);
  Vector3d er, eu;
  polar(E_, u, er, eu);
  const Vector3d& ez = E_.col(2);
  const double cv = std::cos(v), sv = std::sin(v);
  const double s = R_ + r_ * cv;  // distance from the axis
  d.S = place_.center + s * er + r_ * sv * ez;
  if (d.order >= 1) {
    d.Su = s * eu;
    d.Sv = r_ * (-sv * er + cv * ez);
  }
  if (d.order >= 2) {
    d.Suu = -s * er;
    d.Suv = -r_ * sv * eu;
    d.Svv = -r_ * (cv * er + sv * ez);
  }
  return d;
}

bool Torus::closed_u() const {
  return spans_full_turn(domain_.u);
}
bool Torus::closed_v() const {
  return spans_full_turn(domain_.v);
}

bool Torus::operator==(const Torus& o) const {
  return place_ == o.place_ && R_ == o.R_ && r_ == o.r_ && domain_ == o.domain_ &&
         normal_sign() == o.normal_sign();
}

// ---- Cone (B.23) ----------------------------------------------------------------------------

Cone::Cone(const Placement& pl, double alpha, const Domain2& d)
    : AnalyticKind(pl, d), alpha_(alpha) {
  if (!(alpha > 0.0 && alpha < 0.5 * std::numbers::pi))
    fail("Cone: alpha must lie in (0, pi/2), got " + num(alpha));
  check_domain("Cone", d);
}

Domain2 Cone::default_domain() {
  return {{0.0, kTwoPi}, {0.0, std::numeric_limits<double>::infinity()}};
}

SurfaceDerivs Cone::derivs(double u, double v, int order) const {
  // rho = c + v e_r(u) + v tan(alpha) e_z: rho_u x rho_v = v (tan(alpha) e_r - e_z)
  //     = (v / cos alpha)(sin alpha e_r - cos alpha e_z), the (B.23) normal for v > 0.
  SurfaceDerivs d;
  d.order = std::clamp(order, 0, 2);
  Vector3d er, eu;
  polar(E_, u, er, eu);
  const Vector3d& ez = E_.col(2);
  const double t = std::tan(alpha_);
  d.S = place_.center + v * (er + t * ez);
  if (d.order >= 1) {
    d.Su = v * eu;
    d.Sv = er + t * ez;
  }
  if (d.order >= 2) {
    d.Suu = -v * er;
    d.Suv = eu;
  }
  return d;
}

bool Cone::closed_u() const {
  return spans_full_turn(domain_.u);
}

bool Cone::operator==(const Cone& o) const {
  return place_ == o.place_ && alpha_ == o.alpha_ && domain_ == o.domain_ &&
         normal_sign() == o.normal_sign();
}

// ---- Hyperboloid (11), (13), (15) -----------------------------------------------------------

Hyperboloid::Hyperboloid(const Placement& pl, double a, const Domain2& d)
    : AnalyticKind(pl, d), a_(a) {
  if (!std::isfinite(a)) fail("Hyperboloid: a must be finite, got " + num(a));
  check_domain("Hyperboloid", d);
}

Domain2 Hyperboloid::default_domain() {
  return Plane::default_domain();
}

SurfaceDerivs Hyperboloid::derivs(double u, double v, int order) const {
  SurfaceDerivs d;
  d.order = std::clamp(order, 0, 2);
  const Vector3d& ex = E_.col(0);
  const Vector3d& ey = E_.col(1);
  const Vector3d& ez = E_.col(2);
  d.S = place_.center + u * ex + v * ey + (a_ * u * v) * ez;  // (11)
  if (d.order >= 1) {
    d.Su = ex + (a_ * v) * ez;  // (13)
    d.Sv = ey + (a_ * u) * ez;
  }
  if (d.order >= 2) d.Suv = a_ * ez;  // (15): rho_11 = rho_22 = 0
  return d;
}

bool Hyperboloid::operator==(const Hyperboloid& o) const {
  return place_ == o.place_ && a_ == o.a_ && domain_ == o.domain_ &&
         normal_sign() == o.normal_sign();
}

// ---- Revolution (A.1) -----------------------------------------------------------------------

Revolution::Revolution(const Placement& pl, std::vector<double> coeffs, const Domain2& d)
    : AnalyticKind(pl, d), c_(std::move(coeffs)) {
  for (std::size_t k = 0; k < c_.size(); ++k)
    if (!std::isfinite(c_[k]))
      fail("Revolution: coeffs[" + std::to_string(k) + "] must be finite, got " + num(c_[k]));
  check_domain("Revolution", d);
}

Domain2 Revolution::default_domain() {
  return {{0.0, std::numeric_limits<double>::infinity()}, {0.0, kTwoPi}};
}

void Revolution::profile(double r, double& f, double& df, double& ddf) const {
  // Horner's scheme for the polynomial and its first two derivatives (empty coeffs: f = 0).
  f = df = ddf = 0.0;
  for (std::size_t k = c_.size(); k-- > 0;) {
    ddf = ddf * r + 2.0 * df;
    df = df * r + f;
    f = f * r + c_[k];
  }
}

SurfaceDerivs Revolution::derivs(double u, double v, int order) const {
  // (A.1): rho = c + u e_r(v) + f(u) e_z: rho_u x rho_v = u (e_z - f'(u) e_r).
  SurfaceDerivs d;
  d.order = std::clamp(order, 0, 2);
  Vector3d er, ev;
  polar(E_, v, er, ev);
  const Vector3d& ez = E_.col(2);
  double f = 0.0, df = 0.0, ddf = 0.0;
  profile(u, f, df, ddf);
  d.S = place_.center + u * er + f * ez;
  if (d.order >= 1) {
    d.Su = er + df * ez;
    d.Sv = u * ev;
  }
  if (d.order >= 2) {
    d.Suu = ddf * ez;
    d.Suv = ev;
    d.Svv = -u * er;
  }
  return d;
}

bool Revolution::closed_v() const {
  return spans_full_turn(domain_.v);
}

bool Revolution::operator==(const Revolution& o) const {
  return place_ == o.place_ && c_ == o.c_ && domain_ == o.domain_ &&
         normal_sign() == o.normal_sign();
}

}  // namespace iga
