// A NURBS patch evaluated through its Bezier elements: the same surface, cut at its knots into
// rational Bezier patches once, then evaluated with Bernstein polynomials on the element that
// holds (u, v) instead of the B-spline basis of a knot span ([PT97] A5.6 for the extraction,
// A4.4 for the rational derivatives). For the many evaluations of a closest point projection:
// no knot span search and no divisions by knot differences.
//
// Notation: element e = (i, j) covers [bu_i, bu_{i+1}] x [bv_j, bv_{j+1}] (the distinct knots
// bu, bv); t = (u - bu_i) / h_u in [0, 1] its local parameter, h_u = bu_{i+1} - bu_i;
// B^p_r(t) = C(p, r) t^r (1 - t)^(p - r) the Bernstein polynomials, d/du = (1 / h_u) d/dt.
#pragma once

#include <string>
#include <vector>

#include "geometry/nurbs_surface.hpp"
#include "geometry/refinement.hpp"

namespace iga {

/// The surface of a NurbsSurface (same domain, closedness and normal orientation), evaluated
/// element by element. A point on an element border belongs to the element above it (as the
/// knot span of NurbsSurface::derivs), the end of the domain to the last element.
class BezierSurface final : public Surface {
 public:
  BezierSurface() = default;
  explicit BezierSurface(const NurbsSurface& s);

  const std::vector<BezierPatch>& elements() const { return elements_; }
  /// Distinct knots in u and v (element borders), the elements' ranges.
  const std::vector<double>& breaks_u() const { return breaks_u_; }
  const std::vector<double>& breaks_v() const { return breaks_v_; }
  /// Index into elements() of the element holding (u, v) (clamped to the domain).
  int element_of(double u, double v) const;

  /// The derivatives of element `e`'s polynomial at (u, v), clamped into its range: on an
  /// element border, that element's side (derivs takes the element above it).
  SurfaceDerivs derivs_on(int e, double u, double v, int order = 2) const;

  // Surface interface
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  Domain2 domain() const override { return domain_; }
  bool closed_u() const override { return closed_u_; }
  bool closed_v() const override { return closed_v_; }
  std::string type_name() const override { return "bezier_surface"; }

 private:
  std::vector<BezierPatch> elements_;
  std::vector<double> breaks_u_, breaks_v_;
  double per_u_ = 0.0,
         per_v_ = 0.0;  // elements per unit of u and v (the first guess of element_of)
  Domain2 domain_;
  bool closed_u_ = false, closed_v_ = false;
};

/// The Bernstein polynomials B^p_r(t), r = 0..p, and their derivatives in t up to `order`
/// (<= 2; rows above are left untouched), t in [0, 1], p <= kMaxDegree.
void bernstein_derivs(int p, double t, int order, BasisDerivs& B);

}  // namespace iga
