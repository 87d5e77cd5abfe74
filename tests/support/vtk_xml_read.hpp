// A small reader of the VTK XML files that iga/output/vtk_xml_writer writes (raw appended data,
// UInt64 block headers; Float64, Int64 and UInt8 arrays), for tests: the XML header and every
// DataArray by name ("Points" for the points, "" for an unnamed array), values as doubles.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <regex>
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

}  // namespace iga::test
