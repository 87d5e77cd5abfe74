// ParaView output in VTK's XML formats with binary appended data: a sampled surface (a grid) as
// a structured grid (.vts), points and polylines (contact points, a rod's centre line) as an
// unstructured grid (.vtu) of vertices or one poly-line cell. The numbers are stored raw
// (little-endian Float64 / Int64 / UInt8, each block preceded by its byte count as UInt64) after
// the XML header: 8 bytes a number at full precision, written without formatting one (the legacy
// ASCII writer prints 12 digits; bench/bench_output.cpp compares size and time).
// Reference: VTK User's Guide, "VTK File Formats" (XML formats: StructuredGrid,
// UnstructuredGrid, AppendedData with encoding="raw", header_type="UInt64").
//
// Notation: n points, nu x nv the grid (u fastest: point i + nu j), a "block" one DataArray's
// bytes in the appended section.
#pragma once

#include <string>

#include "iga/core/sampled_mesh.hpp"

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

}  // namespace iga
