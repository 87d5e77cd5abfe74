// Closest point projection of a point onto a surface patch or a curve ("rigid surface is
// master", [KS15] Sect. 2.4, eqs. 10-18), robust for any start: bound-constrained Newton on
// F(alpha) = 1/2 |r - rho(alpha)|^2 (eq. 12) with gradient (16) and Hessian (17), an active set
// for the patch bounds (Sect. 2.2: surface, then edge, then vertex), Levenberg-Marquardt
// regularization where the Hessian (17) is not positive definite, and an Armijo line search.
// Cold and warm starts on a NURBS patch are certified (ProjectionOptions::certify): a branch
// and bound over the Bezier elements, subdivided where needed, with lower bounds from the
// control nets and interval bounds of the gradient (16) and Hessian (17) of (12) over each
// node (patch_bounds.hpp) proves the answer the global minimum, also on edges and corners.
#pragma once

#include <array>
#include <span>
#include <tuple>
#include <vector>

#include "contact/patch_bounds.hpp"
#include "contact/projection.hpp"
#include "geometry/bezier_surface.hpp"
#include "geometry/nurbs_curve.hpp"
#include "geometry/nurbs_surface.hpp"
#include "geometry/refinement.hpp"

namespace iga {

/// interior, edge or vertex: how many parameters of uv lie on a bound of the surface's domain
/// (closed directions have no bound).
ProjectionStatus boundary_status(const Surface& s, const Vector2d& uv);

/// Local (warm-started) closest point projection onto any Surface, within the parameter box
/// `bounds` (by default the surface's domain; infinite bounds allowed). Directions the surface
/// reports as closed wrap around instead of stopping at the bound (seamless full circles).
ProjectionResult closest_point_local(const Surface& s, const Vector3d& x, const Vector2d& start,
                                     const ProjectionOptions& opt = {});
ProjectionResult closest_point_local(const Surface& s, const Vector3d& x, const Vector2d& start,
                                     const Domain2& bounds, const ProjectionOptions& opt = {});

/// Global closest point projection onto one NURBS patch: precomputes the Bezier elements,
/// their boxes and samples once; then projects any number of points, cold or warm.
class PatchProjector {
 public:
  /// samples_per_dir: samples per element and direction used for seeding (2..8).
  explicit PatchProjector(const NurbsSurface& s, int samples_per_dir = 8);

  const NurbsSurface& surface() const { return s_; }
  /// Box of the whole patch (union of the element boxes).
  const Box3& box() const { return box_; }
  const std::vector<BezierPatch>& elements() const { return bez_.elements(); }
  const std::vector<Box3>& element_boxes() const { return boxes_; }
  /// Nodes of the precomputed subdivision of the certified search (0: none, when the Bezier
  /// elements do not form a full grid).
  std::size_t tree_nodes() const { return tree_.size() + high_tree_.size(); }
  /// The node budget of that subdivision, read when a projector is built: the tree goes as
  /// deep below the elements as n_elements x nodes per element <= budget allows (at most 4
  /// levels; the elements themselves always). Process-wide; default kTreeNodes. A smaller
  /// budget makes a projector cheaper to build, its cold searches and certificates then
  /// subdivide at query time: the same feet, more time per query. Building the default tree
  /// costs seconds under the sanitizers, so the fuzz targets (fuzz/) set a small one.
  static constexpr std::size_t kTreeNodes = 6144;
  static void set_tree_budget(std::size_t nodes);
  static std::size_t tree_budget();
  /// Memory held by the projector's precomputed data, in bytes (approximate: vectors' sizes).
  std::size_t memory_bytes() const;

  /// Cold start: the global minimum (certified branch and bound over the elements).
  ProjectionResult project(const Vector3d& x, const ProjectionOptions& opt = {}) const;
  /// Warm start from a parameter guess (e.g. the previous load step's foot point): the local
  /// Newton, then the certified search bounded by its answer (certify = false: the Newton
  /// alone, the cold search if it does not converge).
  ProjectionResult project(const Vector3d& x, const Vector2d& guess,
                           const ProjectionOptions& opt = {}) const;
  /// Cold search, but only among elements whose box lies within `max_distance` of x; returns
  /// status not_converged with distance = +inf when none does.
  ProjectionResult project_within(const Vector3d& x, double max_distance,
                                  const ProjectionOptions& opt = {}) const;
  /// The same search among the given elements only (indices into elements(), e.g. the
  /// candidates of a contact search broad phase).
  ProjectionResult project_among(const Vector3d& x, std::span<const int> element_ids,
                                 double max_distance, const ProjectionOptions& opt = {}) const;

 private:
  struct Sample {
    Vector2d uv;
    Vector3d x;
    Vector3d xu, xv;  // S_u, S_v there (a Gauss-Newton step from the sample: seed_from)
  };
  // A start for the Newton from sample s of element e: one Gauss-Newton step from s towards
  // the foot of x, (J^T J) d = J^T (x - S), J = [S_u S_v], where that step stays within the
  // element's width in each parameter and inside the patch (else s itself; s itself also on a
  // patch with creases, kinks_). Near the surface it saves the Newton about one iteration,
  // without an evaluation.
  Vector2d seed_from(const Sample& s, int e, const Vector3d& x) const;
  // The certified search among the elements ids[0 .. n_ids) (ids = nullptr: all), or with
  // `pieces`, among those nodes of the tree (the rest of the patch proven by the caller).
  // box_d2: with all elements, their boxes' squared distances from x if the caller has them
  // (box_distances2).
  ProjectionResult search(const Vector3d& x, const int* ids, std::size_t n_ids, double max_distance,
                          const ProjectionOptions& opt, const ProjectionResult* start = nullptr,
                          bool pieces = false, const double* box_d2 = nullptr) const;
  static constexpr int kMaxSamples = 64;  // 8 x 8
  NurbsSurface s_;
  BezierSurface bez_;  // the same patch by its Bezier elements: what the Newtons evaluate
  int samples_per_dir_ = 8;
  std::vector<Box3> boxes_;
  std::vector<std::vector<Sample>> samples_;  // per element
  std::vector<Vector3d> hull_;                // control points of all elements (lower bounds)
  std::vector<std::size_t> hull_offset_;      // element e: hull_[offset[e] .. offset[e+1])
  Box3 box_;
  // The same boxes and samples as arrays of coordinates, for scans whose distances vectorize:
  // box_coords_[c * n + e] = element e's lo (c = 0..2) and hi (c = 3..5) in x, y, z
  // (n elements); sample_coords_[(3 e + c) * n_s + k] = coordinate c of sample k of element e
  // (n_s = samples_per_dir^2).
  std::vector<double> box_coords_, sample_coords_;
  // Element boxes' squared distances from x, d2[e], all elements (box_coords_).
  void box_distances2(const Vector3d& x, double* d2) const;
  // The sample of element e nearest to x (its index in samples_[e]).
  int nearest_sample(int e, const Vector3d& x) const;
  // Inner element borders of multiplicity >= the degree (the patch C0 there), sorted, per
  // direction: the certified search does not leave a minimum on them to the other side.
  std::vector<double> kinks_[2];
  // The subdivision of the certified search, precomputed to a fixed depth (kTreeNodes at most):
  // nodes 0 .. n_elements - 1 are the elements, each node's four children are consecutive.
  // Patches of degree 5 at most hold their nodes in tree_, the others (up to kMaxDegree) in
  // high_tree_: the same nodes on bigger nets (at most one of the two is not empty).
  template <int D>
  struct NodeOf {
    detail::NetOf<D> net;
    std::array<Vector3d, detail::NetOf<D>::kPoints> points;  // projected
    Box3 box;
    detail::PatchBounds bounds;  // in the tangent frame at the centre
    SurfaceDerivs centre;        // S, S_u, S_v at the centre of net.range
    int child = -1;              // the tree's: first of the four children (-1: none)
    int element = 0, level = 0;  // the element holding it, its depth below the element
  };
  using Node = NodeOf<detail::kMaxNetDegree>;
  using HighNode = NodeOf<detail::kMaxHighNetDegree>;
  // What the certificate of a foot reads of tree node k, in cert_[k]: apart from the search's
  // nodes and small, so that a certificate touches few cache lines (a warm start's time is
  // mostly the memory it reads). Each node has a region, the node and those of its level
  // around it (across element borders where the surface is C1), with the boxes of the
  // derivatives over it: a foot that satisfies the optimality conditions and passes the chord
  // test on a region proves the whole region in one test, instead of a subdivision of the nodes
  // around the foot.
  struct Cert {
    Domain2 range;  // the node's
    Domain2 region;
    int child = -1;
    int n_near = 0;
    double gap =
        0.0;  // lower bound of the distance from the node's points to those outside its region
    double rest_gap = 0.0;
    Box3 box;                        // the node's points, axis-aligned
    detail::FrameBox frame_box;      // and in the node's tangent frame
    detail::ChordData region_chord;  // the region's bounds, as the chord test needs them
    // The pieces of the tree outside the region nearest to the node: the coarsest nodes apart
    // from it, by a lower bound of their distance to the node's points (rounded down to
    // float), nearest first (kNear at most); every piece not listed is at least rest_gap from
    // the node's points.
    static constexpr int kNear = 32;
    struct Near {
      float gap;
      int node;
    };
    std::array<Near, kNear> near{};
  };
  std::vector<Node> tree_;
  std::vector<HighNode> high_tree_;
  std::vector<Cert> cert_;
  bool has_tree() const { return !tree_.empty() || !high_tree_.empty(); }
  template <class N>
  void build_tree(std::vector<N>& tree);
  template <class N>
  ProjectionResult search_in(const std::vector<N>& tree, const Vector3d& x, const int* ids,
                             std::size_t n_ids, double max_distance, const ProjectionOptions& opt,
                             const ProjectionResult* start, bool pieces,
                             const double* box_d2) const;
  // The leaves of the tree that a certificate's ball test could not clear (by their boxes
  // within the ball's radius of x): a search among them alone completes the proof, as the rest
  // of the patch is the region or clear.
  struct Uncleared {
    static constexpr int kMax = 16;
    std::array<int, kMax> nodes{};
    int n = 0;
    bool overflow = false;  // more than kMax, or no region: not usable
  };
  // The certificate of a foot r that satisfies the optimality conditions of the patch, without
  // a search: the chord test on the coarsest region holding it that passes, and x no farther
  // from the foot than half the region's gap, or every piece outside the region farther from x
  // than the foot (the pieces that are not go to `left`).
  bool proves_global(const Vector3d& x, const ProjectionResult& r, Uncleared* left = nullptr) const;
  // r certified by proves_global, or else the search among the leaves left uncleared, or else
  // the whole search, started from r.
  ProjectionResult certify(const Vector3d& x, ProjectionResult r,
                           const ProjectionOptions& opt) const;
  // The coarsest node of the tree whose region holds uv and passes the chord test with r_star
  // (the foot's r* = x - S*); nullptr when none does.
  const Cert* chord_region(const Vector2d& uv, const Vector3d& r_star) const;
  // Whether every piece of the tree outside `region` is at least `radius` from x (boxes,
  // axis-aligned and in the pieces' tangent frames); the leaves that are not go to `left`.
  // A ball about x, radius^2 = r2.
  struct Ball {
    Vector3d x;
    double r2;
  };
  bool ball_clear(const Ball& ball, const Domain2& region, Uncleared* left) const;
  // The same for the region of node n holding the foot, d = |x - foot|: only the pieces of n's
  // near list closer than d + radius to n are examined (all of them when the list ends before
  // that distance).
  bool ball_clear_near(const Cert& n, const Vector3d& x, const Vector3d& foot, double radius,
                       Uncleared* left) const;
  bool clear_of(const Cert& m, const Ball& ball, const Domain2& region, Uncleared* left) const;
  int element_of(const Vector2d& uv) const;
};

/// Closest point on a NURBS curve: warm (local Newton from u0, clamped to the domain, ends are
/// "vertex") and cold (global, over Bezier segments with box bounds) versions. uv(0) = u.
ProjectionResult closest_point_local(const NurbsCurve& c, const Vector3d& x, double u0,
                                     const ProjectionOptions& opt = {});
ProjectionResult closest_point(const NurbsCurve& c, const Vector3d& x,
                               const ProjectionOptions& opt = {});

}  // namespace iga
