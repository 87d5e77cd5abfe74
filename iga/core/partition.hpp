// How a model is spread over the processes of a run (docs/parallel.md): a shell patch is cut
// into blocks of elements, one per process, on a processor grid chosen to keep the cut short
// (as PetIGA does); bodies that are not cut (rods, membranes) go whole to the least loaded
// process. Every process builds the same partition from the model alone: no communication.
//
// Notation: the element grid of a patch is its n_u x n_v non-empty knot spans, element
// (e_u, e_v) with e_u fastest; P processes on a p_u x p_v grid, process r = i + p_u j holds
// element columns [u0, u1) and rows [v0, v1); the cut is the length of the blocks' inner
// borders, (p_u - 1) n_v + (p_v - 1) n_u element edges.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "geometry/knot_vector.hpp"

namespace iga {

/// A block of a patch's elements: columns [u0, u1), rows [v0, v1) of the element grid. The
/// default block holds every element.
struct ElementBlock {
  int u0 = 0, u1 = std::numeric_limits<int>::max();
  int v0 = 0, v1 = std::numeric_limits<int>::max();
  bool contains(int eu, int ev) const { return eu >= u0 && eu < u1 && ev >= v0 && ev < v1; }
  bool whole() const {
    return u0 == 0 && v0 == 0 && u1 == std::numeric_limits<int>::max() &&
           v1 == std::numeric_limits<int>::max();
  }
  /// "elements [0, 10) x [5, 10)".
  std::string describe() const;
};

/// The processor grid {p_u, p_v} (p_u p_v = P) of P processes over an n_u x n_v element grid
/// with the shortest cut, each block at least one element wide (p_u <= n_u, p_v <= n_v); ties
/// go to the smaller p_u. Throws std::invalid_argument naming the sizes when no grid fits
/// (e.g. 7 processes on a 4 x 4 patch).
std::array<int, 2> processor_grid(int processes, int nu, int nv);

/// The block of process `rank` among P on the grid of processor_grid: columns and rows split
/// as evenly as whole elements allow (the first n mod p blocks one element larger).
ElementBlock element_block(int rank, int processes, int nu, int nv);

/// The control points of a patch (U, V; point i + n_u j) cut over P processes as element_block
/// does (DofLayout, docs/parallel.md): owner[i + n_u j] the process whose block holds the element
/// of the point's Greville abscissae (an element of the point's support, so that the owner is one
/// of the processes that read it); reads[...] whether the block of process `rank` has an element
/// in the point's support.
void patch_point_partition(const KnotVector& U, const KnotVector& V, int rank, int processes,
                           std::vector<int>& owner, std::vector<char>& reads);

/// The process of each body that is not cut, the bodies given by their work (e.g. control
/// points) in the model's order: each goes whole to the process with the least work so far
/// (ties: the lowest rank), starting from `load`, the work each process already has (the cut
/// bodies' share). `load` has one entry per process and is updated.
std::vector<int> assign_whole(const std::vector<double>& work, std::vector<double>& load);

}  // namespace iga
