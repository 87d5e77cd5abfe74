// Output sinks (iga/output/output_sink.hpp): the registry of formats, the steps table's CSV
// (header, rows, non-finite cells, restart round trip), the field series with their .pvd
// collections in both VTK formats.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "iga/output/output_sink.hpp"
#include "tests/support/files.hpp"
#include "tests/support/vtk_xml_read.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_output_sink {

using namespace iga;
namespace fs = std::filesystem;

namespace {

std::string out_dir(const std::string& name) {
  std::string d = test::fresh_out_dir("output_sink", name);
  fs::create_directories(d);
  return d;
}

MeshOutput polyline(const std::string& series, const std::string& stem, double shift) {
  MeshOutput m{series, stem, "a rope", {}};
  m.mesh.shape = SampledMesh::Shape::kPolyline;
  m.mesh.fields.name({"N"}, {});
  for (int k = 0; k < 3; ++k) {
    m.mesh.points.emplace_back(k + shift, 0.0, 0.0);
    m.mesh.fields.append({10.0 * k}, {});
  }
  return m;
}

}  // namespace

TEST_CASE("output sinks: the built-in formats are registered and an unknown one is named",
          "[iga][output]") {
  const std::vector<std::string> names = output_format_names();
  for (const char* f : {"csv", "summary", "vtk", "vtk_xml"})
    CHECK(std::find(names.begin(), names.end(), f) != names.end());
  CHECK_THROWS_WITH(make_output_sink("hdf5"),
                    Catch::Contains("unknown output format \"hdf5\" (known: csv, summary, "));
  CHECK_THROWS_AS(register_output_format("", [] { return make_output_sink("csv"); }),
                  std::invalid_argument);
}

TEST_CASE(
    "output sinks: steps.csv has the header, one row per step, empty cells for non-finite "
    "values, and goes on after a restart",
    "[iga][output]") {
  const std::string dir = out_dir("csv");
  auto csv = make_output_sink("csv");
  csv->open(dir, {"step", "t", "F"});
  csv->row({1, 0.5, 2.25});
  csv->row({2, 1.0, std::numeric_limits<double>::quiet_NaN()});
  CHECK(test::slurp(fs::path(dir) / "steps.csv") == "step,t,F\n1,0.5,2.25\n2,1,\n");
  // A restart file holds the rows; a new sink that reads them back writes them after the header.
  StateArchive w = StateArchive::writer();
  csv->archive(w);
  const std::string file = (fs::path(dir) / "sink.bin").string();
  w.save(file);
  StateArchive r = StateArchive::reader(file);
  auto again = make_output_sink("csv");
  again->archive(r);
  const std::string dir2 = out_dir("csv_restarted");
  again->open(dir2, {"step", "t", "F"});
  again->row({3, 1.5, -1.0 / 3.0});
  CHECK(test::slurp(fs::path(dir2) / "steps.csv") ==
        "step,t,F\n1,0.5,2.25\n2,1,\n3,1.5,-0.333333333333\n");
}

TEST_CASE(
    "output sinks: a field series writes each snapshot's files and its .pvd, in either VTK "
    "format",
    "[iga][output]") {
  for (const std::string format : {"vtk", "vtk_xml"}) {
    INFO(format);
    const std::string dir = out_dir("series_" + format);
    auto s = make_output_sink(format);
    s->open(dir, {});
    const std::string ext = format == "vtk" ? ".vtk" : ".vtu";
    for (int k = 1; k <= 2; ++k) {
      const auto files = s->snapshot(0.5 * k, {polyline("rope", "step" + std::to_string(k), k),
                                               polyline("", "loose" + std::to_string(k), k)});
      REQUIRE(files.size() == 2);
      CHECK(files[0].file == "step" + std::to_string(k) + ext);
      CHECK(files[0].series == "rope");
      CHECK(files[1].series.empty());
    }
    const std::string pvd = test::slurp(fs::path(dir) / "rope.pvd");
    CHECK_THAT(pvd, Catch::Contains("timestep=\"0.5\" part=\"0\" file=\"step1" + ext + "\""));
    CHECK_THAT(pvd, Catch::Contains("timestep=\"1\" part=\"0\" file=\"step2" + ext + "\""));
    CHECK_THAT(pvd, !Catch::Contains("loose"));  // outside any series
    CHECK(fs::exists(fs::path(dir) / ("loose2" + ext)));
    if (format == "vtk_xml") {  // the points and the field as given
      const test::VtkXmlFile f = test::read_vtk_xml(fs::path(dir) / "step2.vtu");
      CHECK(f.points() == std::vector<double>{2, 0, 0, 3, 0, 0, 4, 0, 0});
      CHECK(f.field("N") == std::vector<double>{0, 10, 20});
    } else {
      CHECK_THAT(test::slurp(fs::path(dir) / "step2.vtk"), Catch::Contains("SCALARS N double"));
    }
    // The series so far in a restart file: a restarted sink's .pvd goes on from them.
    StateArchive w = StateArchive::writer();
    s->archive(w);
    const std::string file = (fs::path(dir) / "sink.bin").string();
    w.save(file);
    StateArchive r = StateArchive::reader(file);
    auto again = make_output_sink(format);
    again->archive(r);
    again->open(dir, {});
    again->snapshot(1.5, {polyline("rope", "step3", 3)});
    const std::string pvd3 = test::slurp(fs::path(dir) / "rope.pvd");
    CHECK_THAT(pvd3, Catch::Contains("file=\"step1" + ext + "\""));
    CHECK_THAT(pvd3, Catch::Contains("timestep=\"1.5\" part=\"0\" file=\"step3" + ext + "\""));
  }
}

TEST_CASE("output sinks: a format registered by name is made by the registry", "[iga][output]") {
  struct Counting : OutputSink {
    int* rows;
    explicit Counting(int* r) : rows(r) {}
    void row(const std::vector<double>& /*values*/) override { ++*rows; }
  };
  static int rows = 0;
  register_output_format("test_counting", [] { return std::make_unique<Counting>(&rows); });
  auto s = make_output_sink("test_counting");
  s->row({1.0});
  s->row({2.0});
  CHECK(rows == 2);
  const std::vector<std::string> names = output_format_names();
  CHECK(std::find(names.begin(), names.end(), "test_counting") != names.end());
}

}  // namespace test_output_sink
