// Analytic rigid surfaces of the reference paper, with exact parametrizations.
// References: [KS15] Konyukhov & Schweizerhof (see ../shared/paper/EQUATIONS.md): plane (8),
// hyperboloid z = a x y (11, 13, 15), surface of revolution r_s(r, phi) = (r cos phi,
// r sin phi, f(r)) (A.1), sphere (B.4), cylinder (B.10), torus (B.16), cone (B.23).
//
// Every surface is placed by a local frame: an origin `center` and a unit `axis` (e_z); e_x is
// `ref_dir` orthogonalized against the axis (default: any vector normal to the axis).
// Parametrizations (u, v) and the orientation of rho_u x rho_v ("outward" normal):
//   Plane        rho = c + u e_x + v e_y                          n = +e_z (axis)
//   Sphere       rho = c + R (cos v cos u e_x + cos v sin u e_y + sin v e_z),
//                u = longitude in [0, 2pi], v = latitude in [-pi/2, pi/2]      n outward
//   Cylinder     rho = c + R (cos u e_x + sin u e_y) + v e_z                   n outward
//   Torus        rho = c + (R + r cos v)(cos u e_x + sin u e_y) + r sin v e_z n outward
//                (ring r < R; horn r = R and spindle r > R too: there rho_u x rho_v =
//                r (R + r cos v)(cos v e_r + sin v e_z) turns over where R + r cos v < 0,
//                the inner part seen from the meridian half-plane u + pi, and vanishes on
//                the axis, R + r cos v = 0: singular points)
//   Cone         rho = c + v (cos u e_x + sin u e_y) + v tan(alpha) e_z, v > 0 = radius s,
//                alpha = angle of the generator to the plane normal to the axis (B.23),
//                outward n = (sin alpha e_r - cos alpha e_z)  so that p = s sin a - z cos a
//   Hyperboloid  rho = c + u e_x + v e_y + a u v e_z   (11)                    n along +e_z side
//   Revolution   rho = c + u (cos v e_x + sin v e_y) + f(u) e_z, f(r) = sum_k coeffs[k] r^k (A.1),
//                n = (e_z - f'(u) e_r)/norm ("upward")
// "inward" flips the normal (normal_sign = -1).
// Default domains: angles [0, 2pi] (sphere latitude [-pi/2, pi/2]); plane, hyperboloid and the
// cylinder's v unbounded; cone v and revolution u (radii) in [0, inf). closed_u/closed_v:
// the angular interval is 2pi long (to 1e-12 relative). Constructors throw GeometryError for
// radius <= 0, alpha outside (0, pi/2), non-finite parameters and
// domains without lo < hi; the message names the value.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "geometry/surface.hpp"

namespace iga {

/// Local frame of an analytic surface (origin + orthonormal e_x, e_y, e_z).
struct Placement {
  Vector3d center = Vector3d::Zero();
  Vector3d axis = Vector3d::UnitZ();     ///< e_z, normalized on construction
  Vector3d ref_dir = Vector3d::UnitX();  ///< projected to give e_x
  bool operator==(const Placement&) const = default;
  /// Orthonormal right-handed (e_x, e_y, e_z) as columns, e_z = axis/|axis|, e_x = ref_dir
  /// orthogonalized against e_z. Throws GeometryError if axis is zero or center/axis are not
  /// finite. If ref_dir is zero or parallel to the axis (|ref_perp| <= 1e-12 |ref_dir|), e_x
  /// is instead built from the coordinate unit vector least aligned with the axis (so the
  /// default ref_dir works with any axis); this choice is deterministic.
  Matrix3d frame() const;
};

class Plane;
class Sphere;
class Cylinder;
class Torus;
class Cone;
class Hyperboloid;
class Revolution;

/// The analytic surface types, visited: a new type is one class deriving from
/// AnalyticKind<itself> plus its visit() here, and every visitor (the projections' view, the
/// JSON output) then fails to compile until it handles the new type.
class AnalyticVisitor {
 public:
  virtual ~AnalyticVisitor() = default;
  virtual void visit(const Plane& s) = 0;
  virtual void visit(const Sphere& s) = 0;
  virtual void visit(const Cylinder& s) = 0;
  virtual void visit(const Torus& s) = 0;
  virtual void visit(const Cone& s) = 0;
  virtual void visit(const Hyperboloid& s) = 0;
  virtual void visit(const Revolution& s) = 0;
};

class AnalyticSurface : public Surface {
 public:
  /// Calls v.visit with the surface's own type.
  virtual void accept(AnalyticVisitor& v) const = 0;
  /// A copy of the concrete type.
  virtual std::unique_ptr<AnalyticSurface> clone() const = 0;
  const Placement& placement() const { return place_; }
  /// Parameter bounds used for display, sampling and patch limits (may be infinite).
  void set_domain(const Domain2& d) { domain_ = d; }
  Domain2 domain() const override { return domain_; }

 protected:
  AnalyticSurface(const Placement& pl, const Domain2& d);
  Placement place_;
  Matrix3d E_;  ///< frame columns e_x, e_y, e_z
  Domain2 domain_;
};

/// accept() and clone() of the concrete type T (T derives from AnalyticKind<T>).
template <class T>
class AnalyticKind : public AnalyticSurface {
 public:
  void accept(AnalyticVisitor& v) const override { v.visit(static_cast<const T&>(*this)); }
  std::unique_ptr<AnalyticSurface> clone() const override {
    return std::make_unique<T>(static_cast<const T&>(*this));
  }

 protected:
  using AnalyticSurface::AnalyticSurface;
};

/// Calls f with the surface's own type: f must take every type (an overload set such as
/// Overloaded{[](const Plane&) {...}, ...}), else the call does not compile.
template <class F>
void visit_analytic(const AnalyticSurface& s, F&& f) {
  struct Adapter final : AnalyticVisitor {
    F& f;
    explicit Adapter(F& g) : f(g) {}
    void visit(const Plane& x) override { f(x); }
    void visit(const Sphere& x) override { f(x); }
    void visit(const Cylinder& x) override { f(x); }
    void visit(const Torus& x) override { f(x); }
    void visit(const Cone& x) override { f(x); }
    void visit(const Hyperboloid& x) override { f(x); }
    void visit(const Revolution& x) override { f(x); }
  } adapter(f);
  s.accept(adapter);
}

/// An overload set of lambdas (for visit_analytic).
template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

class Plane final : public AnalyticKind<Plane> {
 public:
  explicit Plane(const Placement& pl = {}, const Domain2& d = default_domain());
  static Domain2 default_domain();
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  std::string type_name() const override { return "plane"; }
  bool operator==(const Plane& o) const;
};

class Sphere final : public AnalyticKind<Sphere> {
 public:
  Sphere(const Placement& pl, double radius, const Domain2& d = default_domain());
  static Domain2 default_domain();
  double radius() const { return R_; }
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  bool closed_u() const override;
  std::string type_name() const override { return "sphere"; }
  bool operator==(const Sphere& o) const;

 private:
  double R_;
};

class Cylinder final : public AnalyticKind<Cylinder> {
 public:
  Cylinder(const Placement& pl, double radius, const Domain2& d = default_domain());
  static Domain2 default_domain();
  double radius() const { return R_; }
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  bool closed_u() const override;
  std::string type_name() const override { return "cylinder"; }
  bool operator==(const Cylinder& o) const;

 private:
  double R_;
};

class Torus final : public AnalyticKind<Torus> {
 public:
  Torus(const Placement& pl, double major_radius, double minor_radius,
        const Domain2& d = default_domain());
  static Domain2 default_domain();
  double major_radius() const { return R_; }
  double minor_radius() const { return r_; }
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  bool closed_u() const override;
  bool closed_v() const override;
  std::string type_name() const override { return "torus"; }
  bool operator==(const Torus& o) const;

 private:
  double R_, r_;
};

class Cone final : public AnalyticKind<Cone> {
 public:
  /// alpha in (0, pi/2): angle between the generator and the plane normal to the axis.
  Cone(const Placement& pl, double alpha, const Domain2& d = default_domain());
  static Domain2 default_domain();
  double alpha() const { return alpha_; }
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  bool closed_u() const override;
  std::string type_name() const override { return "cone"; }
  bool operator==(const Cone& o) const;

 private:
  double alpha_;
};

class Hyperboloid final : public AnalyticKind<Hyperboloid> {
 public:
  Hyperboloid(const Placement& pl, double a, const Domain2& d = default_domain());
  static Domain2 default_domain();
  double a() const { return a_; }
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  std::string type_name() const override { return "hyperboloid"; }
  bool operator==(const Hyperboloid& o) const;

 private:
  double a_;
};

class Revolution final : public AnalyticKind<Revolution> {
 public:
  /// f(r) = sum_k coeffs[k] r^k; u = r >= 0, v = polar angle.
  Revolution(const Placement& pl, std::vector<double> coeffs, const Domain2& d = default_domain());
  static Domain2 default_domain();
  const std::vector<double>& coeffs() const { return c_; }
  /// f(r), f'(r), f''(r)
  void profile(double r, double& f, double& df, double& ddf) const;
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  bool closed_v() const override;
  std::string type_name() const override { return "revolution"; }
  bool operator==(const Revolution& o) const;

 private:
  std::vector<double> c_;
};

}  // namespace iga
