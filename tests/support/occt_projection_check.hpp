// Closest points of an imported CAD face against OpenCASCADE's own projection (issue 34,
// item 4): used by tests/cad/test_cad_occt_faces.cpp and the corpus study
// (tests/support/cad_corpus_study.cpp).
//
// Notation: S(u, v) OCCT's surface of the face (BRep_Tool::Surface), B its UV box
// (BRepTools::UVBounds, clamped into a bounded B-spline's range where the import clamped it), h the
// face's size (diagonal of its 3-D box); x a random point S(u, v) + h/10 w, (u, v) uniform in B, w
// uniform in [-1, 1]^3. Ours: the closest point of x on the imported base surface (a trimmed face's
// base, untrimmed: OCCT's projection knows no trimming), foot y, distance d = |x - y|. OCCT's:
// GeomAPI_ProjectPointOnSurf restricted to B, nearest extremum y_o, d_o = |x - y_o|.
// A point passes when (for an untrimmed face whose UV box is larger than the face, a planar
// rectangle re-framed on its sides, OCCT's foot outside the face is not compared: occt_outside)
//   - y lies on S within B (OCCT's projection of y, restricted to B, is within 1e-9 h), and
//   - OCCT finds no extremum, or d <= d_o + 1e-9 h; where |d - d_o| <= 1e-9 h also
//     |y - y_o| <= 1e-9 h (the same foot). Ours closer (d < d_o - 1e-9 h): OCCT's answer is a
//     local minimum or an interior extremum where the minimum over B is on its boundary
//     (Extrema finds interior extrema only); counted separately.
//   Equal distances with feet apart fail where our foot is interior; where ours is on B's
//   bound (status edge or vertex) they are counted (bound_apart): OCCT's Extrema finds
//   interior extrema only and returns, for a minimum on the bound, a point on the bound that
//   is not converged along it (seen: 1e-5 .. 1e-4 of the distance along the edge, where the
//   distance changes only to second order); ours is the converged 1-D minimum on that edge.
// A face OCCT approximated within a bound b (CadFace::tolerance) is compared with 1e-9 h + 2 b
// in place of 1e-9 h: our surface is within b of OCCT's at equal parameters, so distances
// differ by up to b; 2 b leaves the same margin for the feet, except where the distance is flat
// along the surface: feet apart by more, each a stationary point of its own surface, are
// counted (approx_apart) with the largest gap. Where the foot is ill-conditioned (x near a focal
// point of S, or S_u and S_v nearly parallel) the gradient's round-off fixes it only to a reach
// far above eps |x|: feet of equal distance apart by less, each stationary, are counted
// (ill_posed_apart).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>

#include <BRepBndLib.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Vec.hxx>

#include "contact/rigid_surface.hpp"
#include "geometry/geometry_io.hpp"
#include "geometry/trimmed_surface.hpp"

namespace iga::test {

struct OcctComparison {
  int points = 0;        ///< points compared
  int same = 0;          ///< same foot as OCCT's
  int ours_closer = 0;   ///< ours nearer than OCCT's extremum
  int occt_none = 0;     ///< OCCT found no extremum in B (ours still checked on S)
  int occt_outside = 0;  ///< untrimmed: OCCT's foot outside the face (B larger than the face)
  int bound_apart = 0;   ///< equal distances, our foot on B's bound, OCCT's apart along it
  /// equal distances, feet apart, ours stationary (first-order condition by OCCT's derivatives)
  /// and OCCT's not: OCCT's extremum not converged (e.g. along a C0 crease)
  int occt_unconverged = 0;
  /// an approximated face: equal distances, feet apart, each stationary on its own surface
  int approx_apart = 0;
  double approx_apart_worst = 0.0;  ///< largest |y - y_o| / h among those
  /// equal distances, feet apart within the round-off reach of an ill-conditioned foot (x near a
  /// focal point of S, or S_u and S_v nearly parallel), each stationary on S
  int ill_posed_apart = 0;
  double ill_posed_reach = 0.0;  ///< the largest reach / h among those
  /// our projection ended without a foot (a status such as not_converged, never a wrong foot)
  int ours_failed = 0;
  std::string ours_failed_first;  ///< the first of those, described
  double worst = 0.0;             ///< largest |y - y_o| / h over the same feet
  std::string failure;            ///< empty: every point passed; else the first failure, described
};

/// OCCT's UV box of the face, clamped into a non-periodic B-spline's range where the import
/// clamped it (`ours`: the imported base surface, whose parameters are OCCT's in a non-periodic
/// direction of a B-spline); where the import extended the surface by its end polynomials (its
/// domain reaches past the range), the face's box (OCCT evaluates its B-spline there by the same
/// polynomials).
inline void occt_box(const TopoDS_Face& face, const Handle(Geom_Surface) & s, const Surface& ours,
                     double& u0, double& u1, double& v0, double& v1) {
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(s);
  if (bs.IsNull()) return;
  double a0 = 0, a1 = 0, b0 = 0, b1 = 0;
  bs->Bounds(a0, a1, b0, b1);
  const Domain2 d = ours.domain();
  const double eu = 1e-12 * (a1 - a0), ev = 1e-12 * (b1 - b0);
  const bool extended_u = d.u.lo < a0 - eu || d.u.hi > a1 + eu;
  const bool extended_v = d.v.lo < b0 - ev || d.v.hi > b1 + ev;
  if (!bs->IsUPeriodic() && !extended_u) u0 = std::max(u0, a0), u1 = std::min(u1, a1);
  if (!bs->IsVPeriodic() && !extended_v) v0 = std::max(v0, b0), v1 = std::min(v1, b1);
}

/// True if `a` is a C0 parameter of a B-spline's direction: an inner knot of multiplicity >= the
/// degree (a crease, where the derivative is one-sided), or within `eps` of the bound `lo`/`hi`.
inline bool c0_at(double a, double lo, double hi, const TColStd_Array1OfReal& knots,
                  const TColStd_Array1OfInteger& mult, int degree, double eps) {
  if (std::abs(a - lo) <= eps || std::abs(a - hi) <= eps) return true;
  for (int i = knots.Lower(); i <= knots.Upper(); ++i)
    if (mult(i) >= degree && std::abs(a - knots(i)) <= eps) return true;
  return false;
}

/// First-order residual of the distance from x at parameters (a, b) of S, in each direction
/// where S is C1 there (not a crease or B's bound: a minimum there may be one-sided): the
/// largest |(x - S) . S_w| / (|x - S| |S_w|). 0 where no direction qualifies or |x - S| = 0.
inline double stationarity(const Handle(Geom_Surface) & s, const gp_Pnt& x, double a, double b,
                           double u0, double u1, double v0, double v1) {
  gp_Pnt p;
  gp_Vec su, sv;
  s->D1(a, b, p, su, sv);
  const gp_Vec r(p, x);
  if (r.Magnitude() == 0.0) return 0.0;
  // Near a crease (within 1e-6 of the range: OCCT's parameters of a foot on one are that far
  // off it, seen 1e-9 .. 1e-7) its direction is left out.
  const double eu = 1e-6 * (u1 - u0), ev = 1e-6 * (v1 - v0);
  bool cu = std::abs(a - u0) <= eu || std::abs(a - u1) <= eu;
  bool cv = std::abs(b - v0) <= ev || std::abs(b - v1) <= ev;
  if (const Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(s);
      !bs.IsNull()) {
    cu = cu || c0_at(a, u0, u1, bs->UKnots(), bs->UMultiplicities(), bs->UDegree(), eu);
    cv = cv || c0_at(b, v0, v1, bs->VKnots(), bs->VMultiplicities(), bs->VDegree(), ev);
  }
  double worst = 0.0;
  if (!cu && su.Magnitude() > 0.0)
    worst = std::max(worst, std::abs(r.Dot(su)) / (r.Magnitude() * su.Magnitude()));
  if (!cv && sv.Magnitude() > 0.0)
    worst = std::max(worst, std::abs(r.Dot(sv)) / (r.Magnitude() * sv.Magnitude()));
  return worst;
}

/// The same first-order residual on our surface, by our derivatives, at our parameters uv, in
/// each direction where uv is not on the domain's bound.
inline double own_stationarity(const Surface& surf, const Vector3d& x, const Vector2d& uv) {
  const SurfaceDerivs d = surf.derivs(uv.x(), uv.y(), 1);
  const Vector3d r = x - d.S;
  if (r.norm() == 0.0) return 0.0;
  const Domain2 dm = surf.domain();
  const bool on_u = uv.x() <= dm.u.lo || uv.x() >= dm.u.hi;
  const bool on_v = uv.y() <= dm.v.lo || uv.y() >= dm.v.hi;
  double worst = 0.0;
  if (!on_u && d.Su.norm() > 0.0)
    worst = std::max(worst, std::abs(r.dot(d.Su)) / (r.norm() * d.Su.norm()));
  if (!on_v && d.Sv.norm() > 0.0)
    worst = std::max(worst, std::abs(r.dot(d.Sv)) / (r.norm() * d.Sv.norm()));
  return worst;
}

/// `approximation`: the face's stated bound (CadFace::tolerance; 0 if exact): the distances
/// and feet may differ by that much more.
inline OcctComparison compare_with_occt(const TopoDS_Face& face, const GeometryEntity& e,
                                        double approximation = 0.0, int n = 200,
                                        unsigned seed = 11) {
  OcctComparison out;
  const Surface* surf = as_surface(e);
  if (surf == nullptr) {
    out.failure = "not a surface";
    return out;
  }
  const auto* trim = dynamic_cast<const TrimmedSurface*>(surf);
  const bool trimmed = trim != nullptr;
  if (trimmed) surf = &trim->base();
  RigidSurface rs;
  if (const auto* nu = dynamic_cast<const NurbsSurface*>(surf))
    rs.add(*nu);
  else if (const auto* an = dynamic_cast<const AnalyticSurface*>(surf))
    rs.add(*an);
  else {
    out.failure = "base is neither NURBS nor analytic";
    return out;
  }
  const Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  occt_box(face, s, *surf, u0, u1, v0, v1);
  Bnd_Box box;
  BRepBndLib::AddOptimal(face, box, false, false);
  const double h = box.IsVoid() ? 1.0 : box.CornerMin().Distance(box.CornerMax());
  const double tol = 1e-9 * h + 2.0 * approximation;
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0), W(-1.0, 1.0);
  for (int k = 0; k < n; ++k) {
    const double u = u0 + (u1 - u0) * U(g), v = v0 + (v1 - v0) * U(g);
    const gp_Pnt P = s->Value(u, v);
    const Vector3d x = Vector3d(P.X(), P.Y(), P.Z()) + 0.1 * h * Vector3d(W(g), W(g), W(g));
    const gp_Pnt X(x.x(), x.y(), x.z());
    std::ostringstream why;
    why.precision(17);
    why << "x = (" << x.transpose() << "): ";
    const ProjectionResult ours = rs.closest_point(x);
    if (!found(ours.status)) {
      why << "our projection failed: " << to_string(ours.status);
      if (out.ours_failed++ == 0) out.ours_failed_first = why.str();
      continue;
    }
    const double d = (x - ours.point).norm();
    try {
      const gp_Pnt Y(ours.point.x(), ours.point.y(), ours.point.z());
      GeomAPI_ProjectPointOnSurf on(Y, s, u0, u1, v0, v1);
      // Our foot on OCCT's surface within B: OCCT's projection restricted to B, or (a foot on
      // B's bound or at a degenerate side, where Extrema finds no interior extremum)
      // ShapeAnalysis_Surface's projection (with its boundary search) landing inside B, or
      // within 1e-9 of B's size outside it; else (e.g. at a pole, where the parameter of the
      // foot is any) the distance of our foot from S at that parameter clamped into B.
      double off = on.NbPoints() > 0 ? on.LowerDistance() : 1e300;
      // OCCT's parameters of our foot, where known (for the first-order check below)
      bool known_uv = off <= tol;
      double yu = ours.uv.x(), yv = ours.uv.y();
      if (known_uv) on.LowerDistanceParameters(yu, yv);
      // Our own parameters: where they are OCCT's (a B-spline face imported in its own
      // parameters), S(uv) is our foot. This also places a foot on a crease next to a zero
      // derivative, where neither of OCCT's projections below converges (seen: OCC17026-1.igs,
      // a foot 0.011 off by both, exactly on S at our parameters).
      if (off > tol && ours.uv.x() >= u0 && ours.uv.x() <= u1 && ours.uv.y() >= v0 &&
          ours.uv.y() <= v1) {
        const double at_ours = Y.Distance(s->Value(ours.uv.x(), ours.uv.y()));
        if (at_ours <= tol) known_uv = true;
        off = std::min(off, at_ours);
      }
      if (off > tol) {
        ShapeAnalysis_Surface sas(s);
        const gp_Pnt2d q = sas.ValueOfUV(Y, 1e-3 * tol);
        const double pu = 1e-9 * (u1 - u0), pv = 1e-9 * (v1 - v0);
        double qu = q.X(), qv = q.Y();
        if (s->IsUPeriodic())
          qu = u0 + std::remainder(qu - u0 - 0.5 * (u1 - u0), s->UPeriod()) + 0.5 * (u1 - u0);
        if (s->IsVPeriodic())
          qv = v0 + std::remainder(qv - v0 - 0.5 * (v1 - v0), s->VPeriod()) + 0.5 * (v1 - v0);
        if (qu >= u0 - pu && qu <= u1 + pu && qv >= v0 - pv && qv <= v1 + pv)
          off = std::min(off, sas.Gap());
        else
          off = std::min(off, Y.Distance(s->Value(std::clamp(qu, u0, u1), std::clamp(qv, v0, v1))));
      }
      if (off > tol) {
        why << "our foot (" << ours.point.transpose() << ") is " << off / h
            << " h off OCCT's surface within the face's UV box";
        out.failure = why.str();
        return out;
      }
      GeomAPI_ProjectPointOnSurf proj(X, s, u0, u1, v0, v1);
      ++out.points;
      if (proj.NbPoints() == 0) {
        ++out.occt_none;
        continue;
      }
      const double dO = proj.LowerDistance();
      const gp_Pnt yO = proj.NearestPoint();
      if (!trimmed) {
        // Our untrimmed surface is the face itself (its natural rectangle, or a planar
        // rectangle re-framed on its sides whose UV box B is larger): OCCT's foot outside the
        // face is not a point of it.
        double fu = 0, fv = 0;
        proj.LowerDistanceParameters(fu, fv);
        const BRepClass_FaceClassifier in(face, gp_Pnt2d(fu, fv), 1e-9 * h);
        if (in.State() == TopAbs_OUT) {
          ++out.occt_outside;
          continue;
        }
      }
      if (d > dO + tol) {
        why << "ours " << d << " farther than OCCT's " << dO << " (h = " << h << ")";
        out.failure = why.str();
        return out;
      }
      if (d < dO - tol) {
        ++out.ours_closer;
        continue;
      }
      const double dy = Vector3d(yO.X(), yO.Y(), yO.Z()).operator-(ours.point).norm();
      if (dy > tol && ours.status == ProjectionStatus::interior && known_uv) {
        // Equal distances, feet apart: the one that satisfies the first-order condition (by
        // OCCT's derivatives, in each direction where S is C1 at the foot) is the minimum. Near a
        // minimum the distance changes to second order along S, so 1e-9 h of distance can hide
        // feet 1e-5 h apart; the first-order residual tells them apart (seen on creases of
        // OCC17026-1.igs: ours 1e-15, OCCT's 1e-8).
        double ou = 0, ov = 0;
        proj.LowerDistanceParameters(ou, ov);
        const double r_ours = stationarity(s, X, yu, yv, u0, u1, v0, v1);
        const double r_occt = stationarity(s, X, ou, ov, u0, u1, v0, v1);
        if (r_ours <= 1e-10 && r_occt > 100.0 * r_ours && r_occt > 1e-10) {
          ++out.occt_unconverged;
          continue;
        }
        why << "(first-order residuals: ours " << r_ours << " at (" << yu << ", " << yv
            << "), OCCT's " << r_occt << " at (" << ou << ", " << ov << ")) ";
      }
      if (dy > tol && ours.status == ProjectionStatus::interior && approximation > 0.0) {
        // An approximated face: our surface is within b of OCCT's, not OCCT's, so feet of equal
        // distance (within 1e-9 h + 2 b) may lie farther apart than 2 b where the distance is
        // flat along the surface (the foot moves by about b / (1 - d kappa) and with the
        // approximation's slope). Counted (approx_apart) where each foot is a stationary point
        // of its own surface: ours by our derivatives, OCCT's by OCCT's.
        const double r_own = own_stationarity(*surf, x, ours.uv);
        double ou = 0, ov = 0;
        proj.LowerDistanceParameters(ou, ov);
        const double r_occt = stationarity(s, X, ou, ov, u0, u1, v0, v1);
        if (r_own <= 1e-10 && r_occt <= 1e-10) {
          ++out.approx_apart;
          out.approx_apart_worst = std::max(out.approx_apart_worst, dy / h);
          continue;
        }
        why << "(approximated; first-order residuals on each own surface: ours " << r_own
            << ", OCCT's " << r_occt << ") ";
      }
      if (dy > tol && ours.status == ProjectionStatus::interior && approximation == 0.0) {
        // An ill-conditioned foot. The gradient (16) is computed with a round-off of about
        // eps |x| |S_w| in each parameter w, which moves the Newton's foot by
        // J H^-1 (eps |x| |S_u|, eps |x| |S_v|) (J = [S_u, S_v], H the Hessian (17)): about
        // eps |x| where the foot is well posed, far more where x is near a focal point of S (H
        // nearly singular along S) or S_u and S_v are nearly parallel (seen: trj6_b1-ec-214.stp
        // face 86, a degree-8 face whose tangents meet at 1e-4 rad there, feet 3.5e-9 h apart).
        // Feet apart by less than 64 times that reach, each stationary on S, are counted
        // (ill_posed_apart), with the largest reach.
        const SurfaceDerivs dd = surf->derivs(ours.uv.x(), ours.uv.y(), 2);
        const Vector3d rr = x - dd.S;
        Eigen::Matrix<double, 3, 2> J;
        J << dd.Su, dd.Sv;
        Eigen::Matrix2d H = J.transpose() * J;
        H(0, 0) -= dd.Suu.dot(rr);
        H(0, 1) -= dd.Suv.dot(rr);
        H(1, 0) -= dd.Suv.dot(rr);
        H(1, 1) -= dd.Svv.dot(rr);
        const Eigen::LDLT<Eigen::Matrix2d> ldlt(H);
        double reach = 0.0;
        if (ldlt.info() == Eigen::Success && ldlt.isPositive() && H.determinant() > 0.0) {
          const double noise =
              64.0 * std::numeric_limits<double>::epsilon() * (x.cwiseAbs().maxCoeff() + h);
          for (const double su : {-1.0, 1.0})
            reach = std::max(
                reach,
                noise * (J * ldlt.solve(Eigen::Vector2d(su * dd.Su.norm(), dd.Sv.norm()))).norm());
        }
        const double r_own = own_stationarity(*surf, x, ours.uv);
        double ou = 0, ov = 0;
        proj.LowerDistanceParameters(ou, ov);
        const double r_occt = stationarity(s, X, ou, ov, u0, u1, v0, v1);
        if (dy <= reach && r_own <= 1e-9 && r_occt <= 1e-9) {
          ++out.ill_posed_apart;
          out.ill_posed_reach = std::max(out.ill_posed_reach, reach / h);
          continue;
        }
        why << "(round-off reach of the foot " << reach / h << " h) ";
      }
      if (dy > tol && ours.status == ProjectionStatus::interior) {
        why << "same distance " << d << " but feet " << dy / h << " h apart: ours ("
            << ours.point.transpose() << "), OCCT's (" << yO.X() << " " << yO.Y() << " " << yO.Z()
            << ")";
        out.failure = why.str();
        return out;
      }
      if (dy > tol) {  // on the box's bound: OCCT's extremum there is not converged along it
        ++out.bound_apart;
        continue;
      }
      out.worst = std::max(out.worst, dy / h);
      ++out.same;
    } catch (const Standard_Failure& f) {
      why << "OpenCASCADE's projection failed: " << f.GetMessageString();
      out.failure = why.str();
      return out;
    }
  }
  return out;
}

}  // namespace iga::test
