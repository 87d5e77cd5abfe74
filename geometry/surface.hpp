// The interface every rigid or deformable surface offers: NURBS patches and analytic surfaces
// alike. Differential geometry and contact algorithms work on this interface only.
#pragma once

#include <string>

#include "geometry/derivatives.hpp"

namespace iga {

/// A regular parametric surface rho(u, v) on a rectangle, with a chosen normal orientation.
/// The unit normal is n = s * (rho_1 x rho_2)/|rho_1 x rho_2|, s = normal_sign() = +1 or -1.
class Surface {
 public:
  virtual ~Surface() = default;

  /// Point and derivatives up to `order` (0, 1 or 2) at (u, v). No heap allocation.
  virtual SurfaceDerivs derivs(double u, double v, int order = 2) const = 0;
  /// Parameter rectangle; may be unbounded for analytic surfaces (plane, hyperboloid).
  virtual Domain2 domain() const = 0;
  /// Whether rho(u_lo, v) == rho(u_hi, v) (a closed direction such as a full circle).
  virtual bool closed_u() const { return false; }
  virtual bool closed_v() const { return false; }
  /// A short type name for messages and output ("nurbs_surface", "cylinder", ...).
  virtual std::string type_name() const = 0;

  Vector3d point(double u, double v) const { return derivs(u, v, 0).S; }
  int normal_sign() const { return normal_sign_; }
  void set_normal_sign(int s) { normal_sign_ = s < 0 ? -1 : 1; }

 protected:
  Surface() = default;
  Surface(const Surface&) = default;
  Surface& operator=(const Surface&) = default;

 private:
  int normal_sign_ = 1;
};

}  // namespace iga
