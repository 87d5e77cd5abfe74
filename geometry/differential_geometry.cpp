// Surface frames (metric, curvature tensor, principal curvatures and directions) and curve
// Serret-Frenet frames. References: [KS15] notation of Sect. 2 (a_ij, a^ij, h_ij = rho_ij . n,
// n = rho_1 x rho_2 / |rho_1 x rho_2|), see ../shared/paper/EQUATIONS.md; do Carmo,
// Differential Geometry of Curves and Surfaces, Sects. 1.5 and 3.2-3.3.
#include "geometry/differential_geometry.hpp"
#include "geometry/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "geometry/knot_vector.hpp"  // GeometryError

namespace iga {

namespace {
std::string num(double x) {
  return num_text(x, 6);
}
}  // namespace

SurfaceFrame surface_frame(const SurfaceDerivs& d, int normal_sign) {
  SurfaceFrame f;
  f.a1 = d.Su;
  f.a2 = d.Sv;
  const Vector3d c = f.a1.cross(f.a2);
  f.jacobian = c.norm();
  const double l1 = f.a1.norm();
  // Singular (or numerically degenerate) parametrization: rho_1, rho_2 (nearly) parallel, or
  // one of them vanishing against the other (a pole). Relative to max(|rho_1|, |rho_2|)^2 so
  // that the test is scale-invariant; `!(x > y)` also catches NaN.
  const double lmax = std::max(l1, f.a2.norm());
  if (!(f.jacobian > 1e-14 * lmax * lmax) || !(f.jacobian > 0.0))
    throw GeometryError("surface_frame: singular point, |rho_1 x rho_2| = " + num(f.jacobian) +
                        " (|rho_1| = " + num(l1) + ", |rho_2| = " + num(f.a2.norm()) + ")");
  f.n = (normal_sign < 0 ? -1.0 : 1.0) / f.jacobian * c;

  // Metric a_ij and its inverse; det a = |rho_1 x rho_2|^2 (Lagrange), free of the
  // cancellation in a_11 a_22 - a_12^2.
  const double a12 = f.a1.dot(f.a2);
  f.a << f.a1.squaredNorm(), a12, a12, f.a2.squaredNorm();
  const double det_a = f.jacobian * f.jacobian;
  f.a_inv << f.a(1, 1) / det_a, -a12 / det_a, -a12 / det_a, f.a(0, 0) / det_a;
  // Contravariant basis rho^i = a^ij rho_j (rho^i . rho_j = delta^i_j).
  f.a1_contra = f.a_inv(0, 0) * f.a1 + f.a_inv(0, 1) * f.a2;
  f.a2_contra = f.a_inv(1, 0) * f.a1 + f.a_inv(1, 1) * f.a2;

  if (d.order < 2) return f;

  // Curvature tensor h_ij = rho_ij . n.
  const double h12 = d.Suv.dot(f.n);
  f.h << d.Suu.dot(f.n), h12, h12, d.Svv.dot(f.n);

  // Principal curvatures: the generalized symmetric eigenproblem h x = k a x, i.e. the
  // eigenvalues of the shape operator a^{-1} h. With the Cholesky factor a = L L^T the problem
  // becomes the ordinary symmetric M y = k y, M = L^{-1} h L^{-T}, x = L^{-T} y. The columns
  // of [rho_1 rho_2] L^{-T} are orthonormal (e1 = rho_1/|rho_1|, e2 = the unit part of rho_2
  // normal to it), so the 3-D principal direction x^i rho_i = y^1 e1 + y^2 e2 is a unit vector.
  const double l11 = l1, l21 = a12 / l1, l22 = f.jacobian / l1;
  Matrix2d Linv;
  Linv << 1.0 / l11, 0.0, -l21 / (l11 * l22), 1.0 / l22;
  const Matrix2d M = Linv * f.h * Linv.transpose();
  const Vector3d e1 = f.a1 / l11;
  const Vector3d e2 = (f.a2 - l21 * e1) / l22;

  // Closed-form 2x2 symmetric eigensolution, stable also at umbilic points (M = k I): the
  // rotation angle phi = atan2(2 M12, M11 - M22) / 2 is well defined (atan2(0, 0) = 0) and the
  // eigenvalues m +- r with r = hypot((M11 - M22)/2, M12) never lose their ordering.
  const double m12 = 0.5 * (M(0, 1) + M(1, 0));
  const double mean = 0.5 * (M(0, 0) + M(1, 1));
  const double half_diff = 0.5 * (M(0, 0) - M(1, 1));
  const double rad = std::hypot(half_diff, m12);
  f.k1 = mean + rad;
  f.k2 = mean - rad;
  const double phi = 0.5 * std::atan2(m12, half_diff);
  const double cp = std::cos(phi), sp = std::sin(phi);
  f.dir1 = cp * e1 + sp * e2;
  f.dir2 = -sp * e1 + cp * e2;

  f.mean_curvature = mean;                        // H = tr(a^{-1} h)/2 = tr(M)/2
  f.gauss_curvature = f.h.determinant() / det_a;  // K = det h / det a
  return f;
}

CurveFrame curve_frame(const CurveDerivs& d) {
  if (d.order < 1) throw GeometryError("curve_frame: needs derivatives of order >= 1, got 0");
  CurveFrame f;
  const Vector3d& c1 = d.d[1];
  f.speed = c1.norm();
  if (!(f.speed > 0.0) || !std::isfinite(f.speed))
    throw GeometryError("curve_frame: singular point, |C'| = " + num(f.speed));
  f.tangent = c1 / f.speed;
  if (d.order < 2) return f;

  const Vector3d& c2 = d.d[2];
  const Vector3d b = c1.cross(c2);
  const double lb = b.norm();
  // kappa ~ 0: C'' (numerically) parallel to C'; the principal normal is undefined, so the
  // normal and binormal stay zero and the torsion 0.
  if (!(lb > 1e-12 * f.speed * c2.norm())) return f;

  f.curvature = lb / (f.speed * f.speed * f.speed);  // kappa = |C' x C''| / |C'|^3
  f.binormal = b / lb;                               // beta = C' x C'' / |C' x C''|
  f.normal = f.binormal.cross(f.tangent);            // nu = beta x tau
  if (d.order >= 3) f.torsion = b.dot(d.d[3]) / (lb * lb);
  return f;
}

}  // namespace iga
