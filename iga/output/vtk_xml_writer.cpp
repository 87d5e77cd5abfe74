// VTK XML writer (.vts, .vtu) with raw binary appended data.
#include "iga/output/vtk_xml_writer.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace iga {

namespace {

static_assert(std::endian::native == std::endian::little, "the files declare LittleEndian");

/// One DataArray of the appended section: its XML element (without the offset) and its bytes.
struct Block {
  std::string element;  ///< "<DataArray ... format=\"appended\" offset=\"" is completed later
  std::vector<char> bytes;
};

template <class T>
Block block(const std::string& type, const std::string& name, int components,
            const std::vector<T>& values) {
  Block b;
  std::ostringstream e;
  e << "<DataArray type=\"" << type << "\"";
  if (!name.empty()) e << " Name=\"" << name << "\"";
  e << " NumberOfComponents=\"" << components << "\" format=\"appended\" offset=\"";
  b.element = e.str();
  const auto* p = reinterpret_cast<const char*>(values.data());
  b.bytes.assign(p, p + values.size() * sizeof(T));
  return b;
}

double finite(double x) {
  return std::isfinite(x) ? x : 0.0;
}

std::vector<double> flat(const std::vector<Eigen::Vector3d>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const Eigen::Vector3d& x : v)
    for (int k = 0; k < 3; ++k) out.push_back(finite(x[k]));
  return out;
}

/// The point fields as blocks, and the non_finite flag where some point needs it (or
/// everywhere: `flag`, a piece of a collection whose other pieces have it).
std::vector<Block> point_data(const std::string& path, const SampledMesh& mesh, bool flag_all) {
  const std::size_t n = mesh.points.size();
  std::vector<double> flag(n, 0.0);
  bool flagged = false;
  const auto mark = [&](std::size_t i, bool ok) {
    if (!ok) flag[i] = 1.0, flagged = true;
  };
  for (std::size_t i = 0; i < n; ++i) mark(i, mesh.points[i].allFinite());
  const auto check_length = [&](const std::string& name, std::size_t size) {
    if (size != n)
      throw std::runtime_error(path + ": field '" + name + "' has " + std::to_string(size) +
                               " values for " + std::to_string(n) + " points");
  };
  std::vector<Block> blocks;
  for (const auto& [name, v] : mesh.fields.scalars) {
    check_length(name, v.size());
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i) mark(i, std::isfinite(v[i])), w[i] = finite(v[i]);
    blocks.push_back(block("Float64", name, 1, w));
  }
  for (const auto& [name, v] : mesh.fields.vectors) {
    check_length(name, v.size());
    for (std::size_t i = 0; i < n; ++i) mark(i, v[i].allFinite());
    blocks.push_back(block("Float64", name, 3, flat(v)));
  }
  if (flagged || flag_all) blocks.push_back(block("Float64", "non_finite", 1, flag));
  return blocks;
}

/// Writes the XML elements of `blocks` with their offsets, advancing `offset` past each.
void elements(std::ostream& os, const std::vector<Block>& blocks, std::uint64_t& offset,
              const char* indent) {
  for (const Block& b : blocks) {
    os << indent << b.element << offset << "\"/>\n";
    offset += sizeof(std::uint64_t) + b.bytes.size();
  }
}

void append(std::ostream& os, const std::vector<Block>& blocks) {
  for (const Block& b : blocks) {
    const auto size = static_cast<std::uint64_t>(b.bytes.size());
    os.write(reinterpret_cast<const char*>(&size), sizeof size);
    os.write(b.bytes.data(), static_cast<std::streamsize>(b.bytes.size()));
  }
}

std::string extent(int i0, int nu, int j0, int nv) {
  return std::to_string(i0) + " " + std::to_string(i0 + nu - 1) + " " + std::to_string(j0) + " " +
         std::to_string(j0 + nv - 1) + " 0 0";
}

/// A grid's extents: the whole grid's and this piece's (the same for a mesh written whole).
struct GridExtents {
  std::string whole, piece;
};

void write_file(const std::string& path, const SampledMesh& mesh, const GridExtents& ext,
                bool flag_all) {
  const std::size_t n = mesh.points.size();
  const bool grid = mesh.shape == SampledMesh::Shape::kGrid;
  if (grid && (mesh.nu < 2 || mesh.nv < 2 ||
               n != static_cast<std::size_t>(mesh.nu) * static_cast<std::size_t>(mesh.nv)))
    throw std::runtime_error(path + ": a grid of " + std::to_string(mesh.nu) + " x " +
                             std::to_string(mesh.nv) + " needs that many points, got " +
                             std::to_string(n));
  const std::vector<Block> fields = point_data(path, mesh, flag_all);
  const std::vector<Block> points{block("Float64", "Points", 3, flat(mesh.points))};
  // Cells of an unstructured grid: one vertex per point, or one poly-line through them all.
  std::vector<Block> cells;
  std::size_t num_cells = 0;
  if (!grid) {
    std::vector<std::int64_t> connectivity(n), offsets;
    std::vector<std::uint8_t> types;
    for (std::size_t i = 0; i < n; ++i) connectivity[i] = static_cast<std::int64_t>(i);
    if (mesh.shape == SampledMesh::Shape::kPolyline && n >= 2) {
      offsets.push_back(static_cast<std::int64_t>(n));
      types.push_back(4);  // VTK_POLY_LINE
    } else {
      for (std::size_t i = 0; i < n; ++i) offsets.push_back(static_cast<std::int64_t>(i + 1));
      types.assign(n, 1);  // VTK_VERTEX
    }
    num_cells = types.size();
    cells = {block("Int64", "connectivity", 1, connectivity), block("Int64", "offsets", 1, offsets),
             block("UInt8", "types", 1, types)};
  }

  std::ofstream os(path, std::ios::binary);
  if (!os) throw std::runtime_error("cannot write " + path);
  const char* type = grid ? "StructuredGrid" : "UnstructuredGrid";
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"" << type
     << "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  std::uint64_t offset = 0;
  if (grid) {
    os << "  <StructuredGrid WholeExtent=\"" << ext.whole << "\">\n    <Piece Extent=\""
       << ext.piece << "\">\n";
  } else {
    os << "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\""
       << num_cells << "\">\n";
  }
  os << "      <PointData>\n";
  elements(os, fields, offset, "        ");
  os << "      </PointData>\n      <Points>\n";
  elements(os, points, offset, "        ");
  os << "      </Points>\n";
  if (!grid) {
    os << "      <Cells>\n";
    elements(os, cells, offset, "        ");
    os << "      </Cells>\n";
  }
  os << "    </Piece>\n  </" << type << ">\n  <AppendedData encoding=\"raw\">\n   _";
  append(os, fields);
  append(os, points);
  append(os, cells);
  os << "\n  </AppendedData>\n</VTKFile>\n";
  if (!os) throw std::runtime_error("error while writing " + path);
}

/// The PDataArray elements of the collection's point fields and points.
void collection_arrays(std::ostream& os, const MeshPieces& pieces) {
  os << "    <PPointData>\n";
  const auto array = [&os](const std::string& name, int components) {
    os << "      <PDataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\""
       << components << "\"/>\n";
  };
  for (const auto& f : pieces.fields.scalars) array(f.first, 1);
  for (const auto& f : pieces.fields.vectors) array(f.first, 3);
  if (pieces.non_finite) array("non_finite", 1);
  os << "    </PPointData>\n    <PPoints>\n"
     << "      <PDataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
     << "    </PPoints>\n";
}

}  // namespace

void write_vtk_xml(const std::string& path, const SampledMesh& mesh) {
  const std::string e = extent(0, mesh.nu, 0, mesh.nv);
  write_file(path, mesh, {e, e}, false);
}

void write_vtk_xml_piece(const std::string& path, const SampledMesh& mesh,
                         const MeshPieces& pieces) {
  write_file(path, mesh,
             {extent(0, pieces.nu, 0, pieces.nv), extent(mesh.i0, mesh.nu, mesh.j0, mesh.nv)},
             pieces.non_finite);
}

const char* vtk_xml_extension(const SampledMesh& mesh) {
  return mesh.shape == SampledMesh::Shape::kGrid ? ".vts" : ".vtu";
}

const char* vtk_xml_collection_extension(const SampledMesh& mesh) {
  return mesh.shape == SampledMesh::Shape::kGrid ? ".pvts" : ".pvtu";
}

void write_vtk_xml_collection(const std::string& path, SampledMesh::Shape shape,
                              const MeshPieces& pieces,
                              const std::function<std::string(int)>& piece_file) {
  const bool grid = shape == SampledMesh::Shape::kGrid;
  if (pieces.listed.empty()) throw std::runtime_error(path + ": a collection of no pieces");
  if (grid)
    for (const MeshPieces::Piece& p : pieces.listed)
      if (p.nu < 2 || p.nv < 2 || p.i0 < 0 || p.j0 < 0 || p.i0 + p.nu > pieces.nu ||
          p.j0 + p.nv > pieces.nv)
        throw std::runtime_error(path + ": the piece of process " + std::to_string(p.rank) +
                                 " does not fit the grid of " + std::to_string(pieces.nu) + " x " +
                                 std::to_string(pieces.nv));
  std::ofstream os(path);
  if (!os) throw std::runtime_error("cannot write " + path);
  const char* type = grid ? "PStructuredGrid" : "PUnstructuredGrid";
  os << "<?xml version=\"1.0\"?>\n<VTKFile type=\"" << type
     << "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <" << type;
  if (grid) os << " WholeExtent=\"" << extent(0, pieces.nu, 0, pieces.nv) << "\"";
  os << " GhostLevel=\"0\">\n";
  collection_arrays(os, pieces);
  if (!grid)
    os << "    <PCells>\n"
       << "      <PDataArray type=\"Int64\" Name=\"connectivity\" NumberOfComponents=\"1\"/>\n"
       << "      <PDataArray type=\"Int64\" Name=\"offsets\" NumberOfComponents=\"1\"/>\n"
       << "      <PDataArray type=\"UInt8\" Name=\"types\" NumberOfComponents=\"1\"/>\n"
       << "    </PCells>\n";
  for (const MeshPieces::Piece& p : pieces.listed) {
    os << "    <Piece";
    if (grid) os << " Extent=\"" << extent(p.i0, p.nu, p.j0, p.nv) << "\"";
    os << " Source=\"" << piece_file(p.rank) << "\"/>\n";
  }
  os << "  </" << type << ">\n</VTKFile>\n";
  if (!os) throw std::runtime_error("error while writing " + path);
}

}  // namespace iga
