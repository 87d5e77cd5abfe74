// A trimmed face (issue 15, item 3): a surface restricted to the part of its parameter
// rectangle inside its trimming loops (an outer boundary and holes), as CAD faces are. The
// loops are closed polylines in the base surface's (u, v), within a stated deflection of the
// exact trimming curves; the boundary's 3-D edge curves are kept exactly (NURBS), for the
// closest point on the boundary (point-to-curve projection, the paper's own contact pair).
//
// Notation: rho(u, v) the base surface; L_k the loops (polylines, closed implicitly); E_j the
// edge curves; "inside" by the even-odd rule (a point is inside when a ray from it crosses the
// loops an odd number of times), so the loops' orientation does not matter.
#pragma once

#include <memory>
#include <vector>

#include "geometry/derivatives.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/surface.hpp"

namespace iga {

class TrimmedSurface final : public Surface {
 public:
  using Loop = std::vector<Vector2d>;
  TrimmedSurface() = default;
  /// `base`: a NURBS or analytic surface (copied); `loops`: at least one, each of >= 3 points
  /// inside the base's domain (to 1e-9 of its size); `edges`: the boundary curves in 3-D (may
  /// be empty); `deflection`: how far the polylines may be from the exact loops, in (u, v).
  /// Throws GeometryError otherwise.
  TrimmedSurface(const Surface& base, std::vector<Loop> loops, std::vector<NurbsCurve> edges,
                 double deflection);

  const Surface& base() const { return *base_; }
  const std::vector<Loop>& loops() const { return loops_; }
  const std::vector<NurbsCurve>& edges() const { return edges_; }
  double deflection() const { return deflection_; }
  /// (u, v) inside the loops (even-odd); points on a loop count as inside.
  bool inside(const Vector2d& uv) const;
  /// Distance in (u, v) from uv to the nearest loop segment.
  double distance_to_loops(const Vector2d& uv) const;
  /// Whether the closed rectangle `r` of (u, v) holds a point of the face (inside the loops or
  /// on them): a loop segment crosses r, or r lies wholly inside (its centre is inside).
  bool meets(const Domain2& r) const;

  // Surface interface: the base's geometry and normal sign (set_normal_sign sets both).
  SurfaceDerivs derivs(double u, double v, int order = 2) const override;
  Domain2 domain() const override;  ///< the loops' bounding rectangle
  bool closed_u() const override { return false; }
  bool closed_v() const override { return false; }
  std::string type_name() const override { return "trimmed_surface"; }

  bool operator==(const TrimmedSurface& o) const;

 private:
  void build_bands();

  std::shared_ptr<const Surface> base_;
  std::vector<Loop> loops_;
  std::vector<NurbsCurve> edges_;
  double deflection_ = 0.0;
  Domain2 box_;
  // Segments (loop, index) by horizontal band of v, for the crossing test.
  double v0_ = 0.0, dv_ = 1.0;
  std::vector<std::vector<std::pair<int, int>>> bands_;
};

/// Same concrete type and data (NURBS or analytic surfaces; TrimmedSurface included).
bool same_surface(const Surface& a, const Surface& b);

}  // namespace iga
