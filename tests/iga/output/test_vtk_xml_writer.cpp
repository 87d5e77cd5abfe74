// The VTK XML writer: files parsed back by a small reader of the format
// (tests/support/vtk_xml_read.hpp: the XML elements' types, names, components and offsets; the
// raw appended blocks with their UInt64 byte counts) give back the points, cells and fields
// written, bit for bit (no formatting in between).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <regex>
#include <string>

#include "iga/output/vtk_xml_writer.hpp"
#include "tests/support/files.hpp"
#include "tests/support/vtk_xml_read.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_vtk_xml_writer {

using namespace iga;
namespace fs = std::filesystem;

namespace {

/// The DataArrays of a file by name (tests/support/vtk_xml_read.hpp), its header, and its end.
std::map<std::string, test::VtkXmlArray> read_back(const fs::path& file, std::string& header) {
  const test::VtkXmlFile f = test::read_vtk_xml(file);
  header = f.header;
  CHECK(f.tail == "\n  </AppendedData>\n</VTKFile>\n");
  return f.arrays;
}

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("iga_vtk_xml_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("write_vtk_xml: a grid as a structured grid (.vts) with its fields", "[iga][output]") {
  SampledMesh m;
  m.shape = SampledMesh::Shape::kGrid;
  m.nu = 3;
  m.nv = 2;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i)
      m.points.emplace_back(0.1 * i, 1.0 / 3.0 * j, std::sqrt(2.0) * i * j);
  m.fields.name({"pressure"}, {"displacement"});
  for (int k = 0; k < 6; ++k)
    m.fields.append({1e-300 * k + k / 7.0}, {Eigen::Vector3d(k, -k, 0.5)});
  REQUIRE(std::string(vtk_xml_extension(m)) == ".vts");
  const fs::path file = temp_dir() / "shell.vts";
  write_vtk_xml(file.string(), m);
  std::string header;
  const auto a = read_back(file, header);
  CHECK_THAT(header, Catch::Contains("<VTKFile type=\"StructuredGrid\" version=\"1.0\" "
                                     "byte_order=\"LittleEndian\" header_type=\"UInt64\">"));
  CHECK_THAT(header, Catch::Contains("<StructuredGrid WholeExtent=\"0 2 0 1 0 0\">"));
  CHECK_THAT(header, Catch::Contains("<Piece Extent=\"0 2 0 1 0 0\">"));
  REQUIRE(a.size() == 3);
  REQUIRE(a.at("Points").components == 3);
  REQUIRE(a.at("Points").values.size() == 18);
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) {
      CHECK(a.at("Points").values[static_cast<std::size_t>(3 * k + c)] ==
            m.points[static_cast<std::size_t>(k)][c]);
      CHECK(a.at("displacement").values[static_cast<std::size_t>(3 * k + c)] ==
            m.fields.vectors[0].second[static_cast<std::size_t>(k)][c]);
    }
  CHECK(a.at("pressure").values == m.fields.scalars[0].second);
  CHECK(a.count("non_finite") == 0);
}

TEST_CASE("write_vtk_xml: points and a polyline as unstructured grids (.vtu)", "[iga][output]") {
  SampledMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {1, 2, 3}};
  m.fields.name({"gap"}, {});
  for (double g : {0.0, -1e-3, 2.5, 1e10}) m.fields.append({g}, {});
  const fs::path dir = temp_dir();
  REQUIRE(std::string(vtk_xml_extension(m)) == ".vtu");
  write_vtk_xml((dir / "cloud.vtu").string(), m);
  std::string header;
  auto a = read_back(dir / "cloud.vtu", header);
  CHECK_THAT(header, Catch::Contains("<Piece NumberOfPoints=\"4\" NumberOfCells=\"4\">"));
  CHECK(a.at("connectivity").values == std::vector<double>{0, 1, 2, 3});
  CHECK(a.at("offsets").values == std::vector<double>{1, 2, 3, 4});
  CHECK(a.at("types").values == std::vector<double>{1, 1, 1, 1});  // VTK_VERTEX
  CHECK(a.at("gap").values == m.fields.scalars[0].second);

  m.shape = SampledMesh::Shape::kPolyline;
  write_vtk_xml((dir / "rope.vtu").string(), m);
  a = read_back(dir / "rope.vtu", header);
  CHECK_THAT(header, Catch::Contains("<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">"));
  CHECK(a.at("connectivity").values == std::vector<double>{0, 1, 2, 3});
  CHECK(a.at("offsets").values == std::vector<double>{4});
  CHECK(a.at("types").values == std::vector<double>{4});  // VTK_POLY_LINE

  m.points.clear();  // no contact points: a valid empty file
  m.fields.name({"gap"}, {});
  write_vtk_xml((dir / "empty.vtu").string(), m);
  a = read_back(dir / "empty.vtu", header);
  CHECK_THAT(header, Catch::Contains("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"));
  CHECK(a.at("Points").values.empty());
}

TEST_CASE("write_vtk_xml: no non-finite number reaches the file, and bad meshes are refused",
          "[iga][output]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SampledMesh m;
  m.points = {{0, 0, 0}, {1, nan, 0}, {2, 0, 0}};
  m.fields.name({"pressure"}, {"traction"});
  m.fields.append({1.0}, {Eigen::Vector3d(0, 0, 0)});
  m.fields.append({2.0}, {Eigen::Vector3d(0, 0, 0)});
  m.fields.append({std::numeric_limits<double>::infinity()}, {Eigen::Vector3d(0, 0, 1)});
  const fs::path dir = temp_dir();
  write_vtk_xml((dir / "bad.vtu").string(), m);
  std::string header;
  const auto a = read_back(dir / "bad.vtu", header);
  CHECK(a.at("non_finite").values == std::vector<double>{0, 1, 1});
  CHECK(a.at("Points").values[4] == 0.0);
  CHECK(a.at("pressure").values == std::vector<double>{1, 2, 0});
  for (const auto& [name, arr] : a)
    for (double v : arr.values) CHECK(std::isfinite(v));

  m.fields.scalars[0].second.pop_back();
  CHECK_THROWS_WITH(write_vtk_xml((dir / "x.vtu").string(), m),
                    Catch::Contains("field 'pressure' has 2 values for 3 points"));
  SampledMesh g;
  g.shape = SampledMesh::Shape::kGrid;
  g.nu = 2;
  g.nv = 2;
  g.points.resize(3);
  CHECK_THROWS_WITH(write_vtk_xml((dir / "g.vts").string(), g),
                    Catch::Contains("a grid of 2 x 2 needs that many points, got 3"));
  CHECK_THROWS_WITH(write_vtk_xml((dir / "no_such_dir" / "x.vtu").string(), SampledMesh{}),
                    Catch::Contains("cannot write"));
}

}  // namespace test_vtk_xml_writer
