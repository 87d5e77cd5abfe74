// A rigid body's surface made of pieces: NURBS patches and analytic surfaces from one model,
// acting as one surface for projections ([KS15] Sect. 2.2: the global proximity domain is the
// union of the pieces' domains; Remark 5: one rigid surface for all deformable elements).
// Shared edges between patches are detected, so a foot point on them counts as interior;
// closed patches (full circles) are seamless; warm starts continue from the previous patch.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "contact/closest_point.hpp"
#include "contact/contact_search.hpp"
#include "contact/projection.hpp"
#include "geometry/analytic_surfaces.hpp"
#include "geometry/geometry_io.hpp"

namespace iga {

class RigidSurface {
 public:
  RigidSurface() = default;
  /// The surface or patch group `name` of a geometry model. Throws std::invalid_argument if
  /// the name is unknown or a curve.
  static RigidSurface from_geometry(const GeometryModel& g, const std::string& name);

  /// Adds a patch; returns its index. Shared edges are recomputed.
  int add(const NurbsSurface& s);
  /// Adds a NURBS, analytic or trimmed surface as the overloads below; std::invalid_argument
  /// for another kind.
  int add(const Surface& s);
  int add(const AnalyticSurface& s);
  /// A trimmed face (issue 15, item 3): its closest point is the base surface's foot when that
  /// lies inside the trimming loops, else the closest point on the face's edge curves (status
  /// edge; uv found on the base); its ray hits count only inside the loops. Trimmed pieces are
  /// searched like analytic ones (always candidates, pruned by the face's box). Certified: a
  /// foot inside the loops when the base's is; a boundary foot only on a planar face (elsewhere
  /// an interior local minimum of the distance inside the loops could be closer: not searched).
  int add(const TrimmedSurface& s);
  /// A rigid surface of piece i alone (sharing its projector): a contact pair per face.
  RigidSurface piece(int i) const;
  /// The trimmed face of piece i, or nullptr.
  const TrimmedSurface* trimmed(int i) const {
    return pieces_[static_cast<std::size_t>(i)].trim.get();
  }
  /// Ray x + xi3 N onto piece i alone (trimming respected); any piece type.
  ProjectionResult ray_piece(int i, const Vector3d& x, const Vector3d& N,
                             const ProjectionOptions& opt = {}) const;

  int num_patches() const { return static_cast<int>(pieces_.size()); }
  const Surface& patch(int i) const { return *pieces_[static_cast<std::size_t>(i)].surface; }
  /// The NURBS projector of patch i, or nullptr for an analytic piece.
  const PatchProjector* nurbs(int i) const {
    return pieces_[static_cast<std::size_t>(i)].nurbs.get();
  }
  /// Bounding box of all pieces (infinite for unbounded analytic surfaces).
  const Box3& box() const { return box_; }

  /// Cold closest point: the global minimum over all pieces (patch boxes prune).
  ProjectionResult closest_point(const Vector3d& x, const ProjectionOptions& opt = {}) const;
  /// Closest point within `max_distance` only (status far if none is).
  ProjectionResult closest_point_within(const Vector3d& x, double max_distance,
                                        const ProjectionOptions& opt = {}) const;
  /// Warm start from a previous result (its patch and uv): a local Newton on that patch; if
  /// the foot point reaches one of the patch's edges, the search continues over all pieces.
  ProjectionResult closest_point(const Vector3d& x, const ProjectionResult& previous,
                                 const ProjectionOptions& opt = {}) const;
  /// Closest points of many query points within `search_distance` (status far beyond it):
  /// a broad phase over all Bezier elements of all NURBS pieces and the boxes of the trimmed
  /// faces (element_index: the uniform grid of contact_search.hpp, built once per distance; or
  /// CGAL's box_intersection_d with use_cgal, which rebuilds its tree on every call), then the
  /// projection among each point's candidate elements (a trimmed face: the face) only.
  /// Untrimmed analytic pieces are always candidates, pruned by their box.
  std::vector<ProjectionResult> closest_points(const std::vector<Vector3d>& points,
                                               double search_distance, bool use_cgal = false,
                                               const ProjectionOptions& opt = {}) const;
  /// The Bezier elements of all NURBS pieces indexed for the broad phase with boxes enlarged
  /// by `distance`: built at the first call for that distance and kept (a rigid tool never
  /// deforms; a moving one is queried in its own frame), shared by copies, safe to call from
  /// several threads. Box b of the index is element tag(b).second of piece tag(b).first, or a
  /// box of trimmed piece tag(b).first when tag(b).second is -1 (the cells of its base that
  /// meet the face: issue 15, item 3).
  const RigidBoxIndex& element_index(double distance) const;
  const std::pair<int, int>& element_tag(int box) const;
  /// The element boxes of the NURBS pieces and the boxes of the trimmed ones, in the index's
  /// order.
  const std::vector<Box3>& element_boxes() const;

  /// Ray x + xi3 N: the hit with the smallest |xi3| over all pieces (miss / tangent if none).
  ProjectionResult ray(const Vector3d& x, const Vector3d& N,
                       const ProjectionOptions& opt = {}) const;

  /// Sides of patch i: 0: u = lo, 1: u = hi, 2: v = lo, 3: v = hi. True when the side
  /// coincides with a side of another patch (or with the opposite side: a closed direction).
  bool side_shared(int patch, int side) const;

 private:
  struct Piece {
    std::shared_ptr<const Surface> surface;
    std::shared_ptr<const PatchProjector> nurbs;  // NURBS pieces only
    Box3 box;
    bool shared[4] = {};
    // Trimmed pieces: the face, its base's projector if NURBS, and points of its loops in 3-D
    // with their (u, v) (the start of the Newton that finds a boundary foot's uv).
    std::shared_ptr<const TrimmedSurface> trim;
    std::shared_ptr<const PatchProjector> base_nurbs;
    std::vector<std::pair<Vector3d, Vector2d>> rim;
    // Trimmed pieces' boxes for the broad phase: the base's cells (Bezier elements of a NURBS
    // base, an 8 x 8 grid over the loops' rectangle of an analytic one) that meet the face.
    std::vector<Box3> boxes;
  };
  ProjectionResult project_trimmed(const Piece& p, const Vector3d& x,
                                   const ProjectionOptions& opt) const;
  static Box3 sampled_box(const Surface& s, const Domain2& d, int n);
  int push(Piece p);  ///< adds the piece, updates box, shared sides and index; its index
  ProjectionResult project_piece(int i, const Vector3d& x, double max_distance,
                                 const ProjectionOptions& opt) const;
  /// Status with respect to the union: sides shared with a neighbour are not edges.
  void union_status(ProjectionResult& r) const;
  void detect_shared_sides();

  // The element boxes and their indices per search distance (element_index).
  struct ElementIndex {
    std::vector<Box3> boxes;
    std::vector<std::pair<int, int>> tags;  // (piece, element)
    std::mutex mutex;
    std::vector<std::pair<double, std::unique_ptr<const RigidBoxIndex>>> by_distance;
  };
  void reset_index();

  std::vector<Piece> pieces_;
  Box3 box_;
  std::shared_ptr<ElementIndex> index_ = std::make_shared<ElementIndex>();
};

}  // namespace iga
