// Sound bounds over a rational Bezier patch for the certified closest point search
// (contact/closest_point.cpp): boxes that contain the patch's points and its first and second
// derivatives over the whole element, from its control net (convex hull property of the net
// and of its hodographs), and from them interval bounds on the gradient (16) and Hessian (17)
// of F = 1/2 |x - rho|^2 (12) for one point x. Internal header of contact/.
//
// Notation ([KS15] -> code):
//   rho(alpha) -> S,  rho_i = d rho / d alpha^i -> Su, Sv,  rho_ij -> Suu, Suv, Svv;
//   r = x - rho;  F = 1/2 |r|^2 (12);  F_,i = -rho_i . r (16) -> gu, gv;
//   F_,ij = rho_i . rho_j - rho_ij . r (17) -> H11, H12, H22.
//   Homogeneous control points (w P, w) -> (A, w), so that rho = A / w.
//
// The bounds come from the homogeneous form A = w rho: A_u = w_u rho + w rho_u and
// A_uu = w_uu rho + 2 w_u rho_u + w rho_uu (and alike), solved for the derivatives of rho
// with interval arithmetic; the derivatives of the polynomials A and w are bounded by their
// hodographs' control points. Interval arithmetic here rounds to nearest: the bounds are
// sound up to round-off, which the callers cover with relative margins.
#pragma once

#include <algorithm>
#include <array>

#include "geometry/bspline_basis.hpp"
#include "geometry/derivatives.hpp"
#include "geometry/refinement.hpp"

namespace iga::detail {

/// A closed interval [lo, hi].
struct Iv {
  double lo = 0.0, hi = 0.0;
};
inline Iv operator+(Iv a, Iv b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
inline Iv operator-(Iv a, Iv b) {
  return {a.lo - b.hi, a.hi - b.lo};
}
inline Iv operator*(Iv a, Iv b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {std::min({p[0], p[1], p[2], p[3]}), std::max({p[0], p[1], p[2], p[3]})};
}
inline Iv operator*(double s, Iv a) {
  return s >= 0 ? Iv{s * a.lo, s * a.hi} : Iv{s * a.hi, s * a.lo};
}
/// a^2 (tighter than a * a when a contains 0).
inline Iv sq(Iv a) {
  const double l = a.lo * a.lo, h = a.hi * a.hi;
  if (a.lo <= 0.0 && a.hi >= 0.0) return {0.0, std::max(l, h)};
  return {std::min(l, h), std::max(l, h)};
}
/// a / w for an interval w with w.lo > 0.
inline Iv div_pos(Iv a, Iv w) {
  return a * Iv{1.0 / w.hi, 1.0 / w.lo};
}

/// An axis-aligned box as three intervals.
struct IVec3 {
  Iv c[3];
};
inline IVec3 to_ivec(const Box3& b) {
  return {{{b.lo.x(), b.hi.x()}, {b.lo.y(), b.hi.y()}, {b.lo.z(), b.hi.z()}}};
}
inline Iv dot(const IVec3& a, const IVec3& b) {
  return a.c[0] * b.c[0] + a.c[1] * b.c[1] + a.c[2] * b.c[2];
}
inline Iv norm2(const IVec3& a) {
  return sq(a.c[0]) + sq(a.c[1]) + sq(a.c[2]);
}

/// A Bezier patch of degree at most D in each direction, on the stack: the nodes of the
/// subdivision in the certified search. Two capacities: Net for the patches of most models and
/// CAD files (degree 5 at most), HighNet for the rest up to the basis' limit (kMaxDegree), so
/// that a bicubic patch's nodes hold no room for degree 10.
template <int D>
struct NetOf {
  static constexpr int kCapacity = D;
  static constexpr std::size_t kPoints = static_cast<std::size_t>((D + 1) * (D + 1));
  Domain2 range;
  int p = 0, q = 0;                  ///< degrees in u and v
  std::array<Vector4d, kPoints> pw;  ///< (w P, w), u fastest
  const Vector4d& at(int i, int j) const { return pw[static_cast<std::size_t>(i + (p + 1) * j)]; }
  int size() const { return (p + 1) * (q + 1); }
};
constexpr int kMaxNetDegree = 5;
constexpr int kMaxHighNetDegree = kMaxDegree;
using Net = NetOf<kMaxNetDegree>;
using HighNet = NetOf<kMaxHighNetDegree>;
/// The element as a net; false when its degree is above D.
template <int D>
bool to_net(const BezierPatch& b, NetOf<D>& out);

/// Boxes over one Bezier patch, in the coordinates y = frame (X - centre), `centre` the centre
/// of the box of its points and `frame` a rotation (rows: an orthonormal basis): S and the
/// derivatives of S with respect to the patch's parameters. Dot products do not depend on the
/// frame, but the boxes do: aligned with the tangents at the patch's centre, boxes of tangent
/// vectors that turn across the patch stay tight (in world axes a tangent turning by 90
/// degrees has a box reaching the origin).
struct PatchBounds {
  Vector3d centre = Vector3d::Zero();
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  IVec3 S, Su, Sv, Suu, Suv, Svv;
};
/// The box of a patch's points in a frame (PatchBounds' centre, frame and S alone).
struct FrameBox {
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  Vector3d centre = Vector3d::Zero();
  IVec3 S;
};
inline FrameBox frame_box(const PatchBounds& b) {
  return {b.frame, b.centre, b.S};
}
/// Squared distance from x to the box S in the frame about centre.
inline double frame_box_distance2(const Eigen::Matrix3d& frame, const Vector3d& centre,
                                  const IVec3& S, const Vector3d& x) {
  const Vector3d y = frame * (x - centre);
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double g = std::max({S.c[k].lo - y[k], y[k] - S.c[k].hi, 0.0});
    d2 += g * g;
  }
  return d2;
}
inline double frame_box_distance2(const FrameBox& b, const Vector3d& x) {
  return frame_box_distance2(b.frame, b.centre, b.S, x);
}
/// The frame with rows S_u, the part of S_v normal to it, and their normal (normalized), from
/// the derivatives at a point of the patch; the identity where they are degenerate.
Eigen::Matrix3d tangent_frame(const SurfaceDerivs& d);
PatchBounds patch_bounds(const Vector4d* pw, int p, int q, const Domain2& range,
                         const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity());
template <int D>
PatchBounds patch_bounds(const NetOf<D>& b,
                         const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity()) {
  return patch_bounds(b.pw.data(), b.p, b.q, b.range, frame);
}
PatchBounds patch_bounds(const BezierPatch& b,
                         const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity());
/// The bounds of a piece of a patch (a node split off by de Casteljau) whose bounds `whole`
/// are known, in whole's frame: S from the piece's points, the derivatives by the quotient rule
/// intersected with whole's (the piece's values are among the patch's). Without the products of
/// rational numerators and denominators that patch_bounds forms for a rational patch: a
/// fraction of its cost, for the pieces below the projector's tree.
PatchBounds patch_bounds_within(const Vector4d* pw, int p, int q, const Domain2& range,
                                const PatchBounds& whole);
template <int D>
PatchBounds patch_bounds_within(const NetOf<D>& piece, const PatchBounds& whole) {
  return patch_bounds_within(piece.pw.data(), piece.p, piece.q, piece.range, whole);
}
/// Widens `a` to hold `b` too (both in the same frame): the boxes of a region made of the two
/// patches. The chord test on the union holds for points of a convex parameter region covered
/// by the patches where the surface is C1 (the chord's Taylor remainder needs a continuous
/// first derivative along it).
void unite(PatchBounds& a, const PatchBounds& b);

/// Interval bounds on the gradient (16) and Hessian (17) of F over the patch, for the point x.
struct DistanceBounds {
  Iv gu, gv, H11, H12, H22;
};
DistanceBounds distance_bounds(const PatchBounds& b, const Vector3d& x);

/// Tightens the gradient bounds of `d` with the mean value form about the node's centre c,
/// where the exact first derivatives `dc` are known (a, bw: the node's half-widths):
/// grad F(U) in grad F(c) + H(U) (U - c), intersected with the direct bound. Returns a lower
/// bound of F over the node: F(c) + grad F(c).t + 1/2 t.H(U).t minimized over the box.
double refine_about_centre(DistanceBounds& d, const SurfaceDerivs& dc, const Vector3d& x, double a,
                           double bw);

/// The chord test: for a point S* = S(u*) of the patch at which F satisfies the optimality
/// conditions (r* = x - S*), true when no point of the patch is closer to x than S*. With
/// D = S(u) - S* and d = u - u*,
///   F(u) - F(u*) = 1/2 |D|^2 - r*.D,
///   D = Jm d with Jm = int_0^1 [S_u, S_v](u* + t d) dt (a matrix in the hull of the patch's),
///   r*.D = grad(r*.S)(u*).d + 1/2 d.[r*.S_ij](xi).d, and grad(r*.S)(u*).d = -grad F(u*).d <= 0
///     for every d into the patch (optimality),
/// so F(u) - F(u*) >= 1/2 d.(G - Phi).d with G = [S_i.S_j] and Phi = [r*.S_ij] over the patch;
/// G - Phi positive definite proves it. Unlike the Hessian (17), r* is fixed: near the surface
/// Phi is small and the test holds on whole elements.
bool chord_test(const PatchBounds& b, const Vector3d& r_star);
/// What the chord test needs of a patch's bounds, with the parts that do not depend on r*
/// computed once (G = [S_i.S_j] and the Jacobian floor sigma): the same answers as
/// chord_test(b, r*), bit for bit, at a fraction of the cost (a warm start's certificate).
struct ChordData {
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  IVec3 Suu, Suv, Svv;
  Iv G11, G22, G12;
  double sigma = 0.0;  ///< Jacobian floor (convex_weyl)
};
ChordData chord_data(const PatchBounds& b);
bool chord_test(const ChordData& c, const Vector3d& r_star);

/// True when the Hessian (17) is positive definite at every point of the patch: F is strictly
/// convex there, so any point satisfying the bound-constrained optimality conditions on the
/// patch is its minimum over the patch.
inline bool convex_gram(const DistanceBounds& d) {
  const double off = std::max(d.H12.lo * d.H12.lo, d.H12.hi * d.H12.hi);
  return d.H11.lo > 0.0 && d.H22.lo > 0.0 && d.H11.lo * d.H22.lo > off * (1.0 + 1e-9);
}

/// The same from a second bound: |J t| >= sigma |t| for the 3x2 Jacobian J = [S_u, S_v] over
/// the patch, sigma = sigma_min of the tangential 2x2 block's centre less its radius (Weyl;
/// boxes in the patch's tangent frame keep the block close to the true Jacobian), so
/// H = J^T J - [S_ij . r] >= sigma^2 - lambda_max([S_ij . r]) (Gershgorin on the intervals).
bool convex_weyl(const PatchBounds& b, const Vector3d& x);
inline bool convex(const DistanceBounds& d, const PatchBounds& b, const Vector3d& x) {
  return convex_gram(d) || convex_weyl(b, x);
}

/// de Casteljau halving of a Bezier patch in u (dir 0) or v (dir 1).
template <int D>
void split_half(const NetOf<D>& b, int dir, NetOf<D>& low, NetOf<D>& high);
/// de Casteljau split at the parameter t of the patch's range.
template <int D>
void split_at(const NetOf<D>& b, int dir, double t, NetOf<D>& low, NetOf<D>& high);

}  // namespace iga::detail
