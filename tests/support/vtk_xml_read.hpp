// A small reader of the VTK XML files that iga/output/vtk_xml_writer writes (raw appended data,
// UInt64 block headers; Float64, Int64 and UInt8 arrays), for tests: the XML header and every
// DataArray by name ("Points" for the points, "" for an unnamed array), values as doubles; and
// a parallel collection (.pvts, .pvtu) joined from its pieces.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/files.hpp"

namespace iga::test {

/// One DataArray read back: its type, components and values.
struct VtkXmlArray {
  std::string type;
  int components = 1;
  std::vector<double> values;
};

struct VtkXmlFile {
  std::string header;  ///< the XML before the appended data
  std::string tail;    ///< what follows the last block (the closing tags)
  std::map<std::string, VtkXmlArray> arrays;
  /// The values of the named array; empty if there is none.
  std::vector<double> field(const std::string& name) const {
    const auto it = arrays.find(name);
    return it == arrays.end() ? std::vector<double>{} : it->second.values;
  }
  std::vector<double> points() const { return field("Points"); }
  /// Whether every value of every array is finite (no file may hold a non-finite number).
  bool all_finite() const {
    for (const auto& [name, a] : arrays)
      for (double v : a.values)
        if (!std::isfinite(v)) return false;
    return true;
  }
};

/// The file's arrays, read through their offsets; std::runtime_error naming the file if it is
/// not such a file or a block runs past its end.
inline VtkXmlFile read_vtk_xml(const std::filesystem::path& file) {
  const std::string s = slurp(file);
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(file.string() + ": " + what);
  };
  const std::size_t start = s.find("<AppendedData encoding=\"raw\">");
  if (start == std::string::npos) fail("no raw appended data");
  const std::size_t data = s.find('_', start) + 1;
  VtkXmlFile out;
  out.header = s.substr(0, start);
  const std::regex element(
      "<DataArray type=\"(\\w+)\"(?: Name=\"(\\w+)\")? NumberOfComponents=\"(\\d+)\" "
      "format=\"appended\" offset=\"(\\d+)\"/>");
  std::size_t end = data;
  for (auto it = std::sregex_iterator(out.header.begin(), out.header.end(), element);
       it != std::sregex_iterator(); ++it) {
    VtkXmlArray a;
    a.type = (*it)[1];
    a.components = std::stoi((*it)[3]);
    const std::size_t at = data + std::stoull((*it)[4]);
    std::uint64_t bytes = 0;
    if (at + sizeof bytes > s.size()) fail("a block header past the end");
    std::memcpy(&bytes, s.data() + at, sizeof bytes);
    if (bytes > s.size() - at - sizeof bytes) fail("a block past the end");
    const char* p = s.data() + at + sizeof bytes;
    end = std::max<std::size_t>(end, at + sizeof bytes + bytes);
    // (An empty block has no bytes to copy: memcpy must not get the null data() of an empty
    // vector.)
    if (a.type == "Float64") {
      a.values.resize(bytes / 8);
      if (bytes > 0) std::memcpy(a.values.data(), p, bytes);
    } else if (a.type == "Int64") {
      std::vector<std::int64_t> v(bytes / 8);
      if (bytes > 0) std::memcpy(v.data(), p, bytes);
      a.values.assign(v.begin(), v.end());
    } else if (a.type == "UInt8") {
      for (std::uint64_t k = 0; k < bytes; ++k)
        a.values.push_back(static_cast<unsigned char>(p[k]));
    } else {
      fail("an array of type " + a.type);
    }
    out.arrays[(*it)[2].matched ? std::string((*it)[2]) : std::string()] = a;
  }
  out.tail = s.substr(end);
  return out;
}

/// A parallel collection (.pvts, .pvtu) read with its pieces and joined into one file's arrays,
/// as write_vtk_xml writes the mesh whole: a structured grid's pieces placed by their Extent in
/// the WholeExtent (a sample two pieces share takes the first piece's value, as a grid sampled
/// whole gives a border sample to the span before it), an unstructured grid's pieces one after
/// the other (connectivity and offsets renumbered). `pieces` gets the number of pieces listed.
/// Every array the collection declares (PDataArray) must be in every piece, and no other.
inline VtkXmlFile read_vtk_xml_collection(const std::filesystem::path& file,
                                          int* pieces = nullptr) {
  const std::string s = slurp(file);
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(file.string() + ": " + what);
  };
  const bool grid = s.find("type=\"PStructuredGrid\"") != std::string::npos;
  if (!grid && s.find("type=\"PUnstructuredGrid\"") == std::string::npos)
    fail("not a PStructuredGrid or PUnstructuredGrid");
  const auto extent = [&](const std::string& e) {
    std::array<int, 6> x{};
    std::istringstream in(e);
    for (int& v : x) in >> v;
    if (!in) fail("an extent \"" + e + "\"");
    return x;
  };
  std::set<std::string> declared;
  const std::regex parray("<PDataArray type=\"\\w+\" Name=\"(\\w+)\"");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), parray); it != std::sregex_iterator();
       ++it)
    declared.insert((*it)[1]);
  for (const char* cells : {"connectivity", "offsets", "types"}) declared.erase(cells);
  std::array<int, 6> whole{};
  if (grid) {
    std::smatch m;
    if (!std::regex_search(s, m, std::regex("WholeExtent=\"([-0-9 ]+)\""))) fail("no WholeExtent");
    whole = extent(m[1]);
  }
  const std::regex piece(grid ? "<Piece Extent=\"([-0-9 ]+)\" Source=\"([^\"]+)\"/>"
                              : "<Piece Source=\"([^\"]+)\"/>");
  VtkXmlFile out;
  const std::size_t nu = static_cast<std::size_t>(whole[1] - whole[0] + 1),
                    nv = static_cast<std::size_t>(whole[3] - whole[2] + 1);
  std::map<std::string, std::vector<char>> set;  // grids: which samples a piece has written
  int count = 0;
  double points_before = 0.0, connectivity_before = 0.0;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), piece); it != std::sregex_iterator();
       ++it, ++count) {
    const std::string source = (*it)[grid ? 2 : 1];
    const VtkXmlFile p = read_vtk_xml(file.parent_path() / source);
    std::set<std::string> has;
    for (const auto& [name, a] : p.arrays)
      if (name != "connectivity" && name != "offsets" && name != "types") has.insert(name);
    if (has != declared) fail(source + ": other arrays than the collection declares");
    if (!grid) {
      const double n = static_cast<double>(p.field("Points").size() / 3);
      for (const auto& [name, a] : p.arrays) {
        VtkXmlArray& o = out.arrays[name];
        o.type = a.type;
        o.components = a.components;
        const double shift = name == "connectivity" ? points_before
                             : name == "offsets"    ? connectivity_before
                                                    : 0.0;
        for (double v : a.values) o.values.push_back(v + shift);
      }
      points_before += n;
      connectivity_before += static_cast<double>(p.field("connectivity").size());
      continue;
    }
    const std::array<int, 6> e = extent((*it)[1]);
    std::smatch own;  // the piece's own extents: the whole grid's, and its place in it
    if (!std::regex_search(
            p.header, own,
            std::regex("WholeExtent=\"([-0-9 ]+)\">\\s*<Piece Extent=\"([-0-9 ]+)\"")) ||
        extent(own[1]) != whole || extent(own[2]) != e)
      fail(source + ": its WholeExtent and Extent are not the collection's");
    const std::size_t pu = static_cast<std::size_t>(e[1] - e[0] + 1);
    for (const auto& [name, a] : p.arrays) {
      VtkXmlArray& o = out.arrays[name];
      const auto c = static_cast<std::size_t>(a.components);
      if (o.values.empty()) {
        o.type = a.type;
        o.components = a.components;
        o.values.assign(nu * nv * c, 0.0);
        set[name].assign(nu * nv, 0);
      }
      std::vector<char>& done = set[name];
      for (std::size_t k = 0; k < a.values.size() / c; ++k) {
        const std::size_t i = static_cast<std::size_t>(e[0]) + k % pu,
                          j = static_cast<std::size_t>(e[2]) + k / pu, at = i + nu * j;
        if (i >= nu || j >= nv) fail(source + ": a sample outside the whole grid");
        if (done[at]) continue;  // the earlier piece's (the lower rank's) value stands
        for (std::size_t q = 0; q < c; ++q) o.values[c * at + q] = a.values[c * k + q];
        done[at] = 1;
      }
    }
  }
  if (count == 0) fail("no pieces");
  for (const auto& [name, done] : set)
    if (std::find(done.begin(), done.end(), 0) != done.end())
      fail(name + ": the pieces leave samples of the whole grid out");
  if (pieces) *pieces = count;
  return out;
}

}  // namespace iga::test
