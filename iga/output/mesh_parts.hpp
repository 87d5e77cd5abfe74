// The output meshes of a run spread over several processes: each process samples its share of
// the bodies (a shell's block of elements, the rods it owns, its contact points), packs its
// meshes into bytes (pack_meshes), process 0 gathers and unpacks them (unpack_meshes) and joins
// each mesh's parts into the whole (join_parts), which it writes as a run on one process does.
//
// Notation: part r is process r's piece of one mesh (possibly empty: a rod another process
// owns, a pair without contact there); a grid part sits at (i0, j0) of the whole grid
// (SampledMesh).
#pragma once

#include <string>
#include <vector>

#include "iga/output/output_sink.hpp"

namespace iga {

/// The meshes as bytes (unpack_meshes reads them back, on any process of the run).
std::string pack_meshes(const std::vector<MeshOutput>& meshes);
/// The meshes of pack_meshes; std::runtime_error if the bytes are not such meshes.
std::vector<MeshOutput> unpack_meshes(const std::string& bytes);

/// One mesh from its parts, in rank order (series, stem and title of the first):
///  - points: the parts' points one after the other, in rank order;
///  - a polyline: the one part that has points (a rod goes whole to one process);
///  - a grid: each part placed at its (i0, j0); where parts overlap (the samples on a border
///    of two blocks) the lower rank's value stands, as in a grid sampled whole (a border
///    sample belongs to the span before it).
/// Parts with points must have the same fields, in the same order (empty parts need none).
/// std::runtime_error naming the mesh otherwise, or for a polyline in several parts.
MeshOutput join_parts(std::vector<MeshOutput> parts);

}  // namespace iga
