// ParaView output in VTK's XML formats with binary appended data: a sampled surface (a grid) as
// a structured grid (.vts), points and polylines (contact points, a rod's centre line) as an
// unstructured grid (.vtu) of vertices or one poly-line cell. The numbers are stored raw
// (little-endian Float64 / Int64 / UInt8, each block preceded by its byte count as UInt64) after
// the XML header: 8 bytes a number at full precision, written without formatting one (the legacy
// ASCII writer prints 12 digits; bench/bench_output.cpp compares size and time).
// A mesh spread over several processes is written as one piece per process and a parallel
// collection that lists the pieces (.pvts: PStructuredGrid, each piece's Extent its place in
// the whole grid; .pvtu: PUnstructuredGrid).
// Reference: VTK User's Guide, "VTK File Formats" (XML formats: StructuredGrid,
// UnstructuredGrid, AppendedData with encoding="raw", header_type="UInt64"; Parallel File
// Formats: PStructuredGrid, PUnstructuredGrid, PPointData, PPoints, Piece Source).
//
// Notation: n points, nu x nv the grid (u fastest: point i + nu j), a "block" one DataArray's
// bytes in the appended section.
#pragma once

#include <functional>
#include <string>

#include "iga/core/sampled_mesh.hpp"
#include "iga/output/output_sink.hpp"

namespace iga {

/// The file extension write_vtk_xml uses for the mesh: ".vts" for a grid, ".vtu" otherwise.
const char* vtk_xml_extension(const SampledMesh& mesh);

/// Writes the mesh with its point fields (scalars, 3-vectors) in VTK's XML format with raw
/// binary appended data; `path` should end in vtk_xml_extension(mesh). As the legacy writer:
/// no file holds a non-finite number (such a value is written as 0 and its point gets the field
/// non_finite = 1, present only when some point needs it). Throws std::runtime_error if the file
/// cannot be written, a field's length differs from the number of points, or a grid's size is
/// not nu nv (nu, nv >= 2).
void write_vtk_xml(const std::string& path, const SampledMesh& mesh);

/// Writes process r's piece of a mesh spread over several (pieces.rank = r): as write_vtk_xml,
/// a grid piece with its extent in the whole grid (i0, j0 of pieces.nu x pieces.nv), and the
/// non_finite field wherever some piece needs it (pieces.non_finite).
void write_vtk_xml_piece(const std::string& path, const SampledMesh& mesh,
                         const MeshPieces& pieces);

/// The parallel extension of a mesh's collection: ".pvts" for a grid, ".pvtu" otherwise.
const char* vtk_xml_collection_extension(const SampledMesh& mesh);

/// Writes the collection (.pvts or .pvtu) of a spread mesh of this shape: the pieces listed
/// (pieces.listed: each the file piece_file(rank), relative to the collection's folder) with
/// their fields (pieces.fields, and non_finite where pieces.non_finite). Throws
/// std::runtime_error if the file cannot be written or a grid's pieces do not fit its size.
void write_vtk_xml_collection(const std::string& path, SampledMesh::Shape shape,
                              const MeshPieces& pieces,
                              const std::function<std::string(int)>& piece_file);

}  // namespace iga
