// Output sinks (iga/output/output_sink.hpp): the registry of formats, the steps table's CSV
// (header, rows, non-finite cells, restart round trip), the field series with their .pvd
// collections in both VTK formats, a mesh spread over processes as pieces and a collection.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "iga/core/partition.hpp"
#include "iga/output/output_sink.hpp"
#include "iga/output/vtk_xml_writer.hpp"
#include "tests/support/files.hpp"
#include "tests/support/vtk_xml_read.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_output_sink {

using namespace iga;
using Eigen::Vector3d;
namespace fs = std::filesystem;

namespace {

std::string out_dir(const std::string& name) {
  std::string d = test::fresh_out_dir("output_sink", name);
  fs::create_directories(d);
  return d;
}

MeshOutput polyline(const std::string& series, const std::string& stem, double shift) {
  MeshOutput m{series, stem, "a rope", {}, {}};
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

namespace {

/// A patch's grid (5 x 3 elements, 3 samples a span) sampled whole or in the block of process r
/// of P, with fields that are functions of the sample; a NaN at (u, v) = (1, 1) with `nan`.
MeshOutput shell_grid(const ElementBlock& block, bool nan = false) {
  const std::vector<double> bu{0, 0.1, 0.35, 0.5, 0.8, 1}, bv{0, 0.25, 0.5, 1};
  MeshOutput o{"shell", "last_shell", "a shell", element_grid(bu, bv, 3, block), {}};
  o.mesh.fields.name({"element"}, {"x"});
  for (std::size_t i = 0; i < o.mesh.params.size(); ++i) {
    const auto [u, v] = o.mesh.params[i];
    o.mesh.points.emplace_back(u, v, u * v);
    const double e = nan && u == 1.0 && v == 1.0 ? std::nan("") : o.mesh.elements[i];
    o.mesh.fields.append({e}, {Vector3d(u, v, 1.0)});
  }
  return o;
}

/// The pieces of a mesh spread over the processes, as Analysis::output_meshes makes them (its
/// collective make_pieces): every process's piece, the listed ones on process 0 (here every
/// process's with points).
void as_pieces(std::vector<MeshOutput>& parts) {
  MeshPieces all;
  bool non_finite = false;
  for (int r = 0; r < static_cast<int>(parts.size()); ++r) {
    const SampledMesh& m = parts[static_cast<std::size_t>(r)].mesh;
    for (const auto& f : m.fields.scalars)
      non_finite = non_finite || std::any_of(f.second.begin(), f.second.end(),
                                             [](double x) { return !std::isfinite(x); });
    if (m.points.empty()) continue;
    all.listed.push_back({r, m.nu, m.nv, m.i0, m.j0});
    all.nu = std::max(all.nu, m.i0 + m.nu);
    all.nv = std::max(all.nv, m.j0 + m.nv);
    if (all.fields.scalars.empty() && all.fields.vectors.empty()) {
      for (const auto& f : m.fields.scalars)
        all.fields.scalars.emplace_back(f.first, std::vector<double>{});
      for (const auto& f : m.fields.vectors)
        all.fields.vectors.emplace_back(f.first, std::vector<Vector3d>{});
    }
  }
  for (int r = 0; r < static_cast<int>(parts.size()); ++r) {
    MeshPieces& p = parts[static_cast<std::size_t>(r)].pieces;
    p.rank = r;
    p.write = !parts[static_cast<std::size_t>(r)].mesh.points.empty();
    p.non_finite = non_finite;
    p.nu = all.nu;
    p.nv = all.nv;
    if (r == 0) {
      p.listed = all.listed;
      p.fields = all.fields;
    }
  }
}

}  // namespace

TEST_CASE(
    "output sinks: a mesh spread over processes is written as pieces and a collection (.pvts, "
    ".pvtu) that join into the mesh written whole",
    "[iga][output]") {
  for (int P : {2, 3, 4}) {
    CAPTURE(P);
    for (bool nan : {false, true}) {
      CAPTURE(nan);
      const std::string dir = out_dir("pieces_" + std::to_string(P) + (nan ? "_nan" : ""));
      // one sink a process: process 0 opens the series, the others write their pieces only
      std::vector<std::unique_ptr<OutputSink>> sinks;
      for (int r = 0; r < P; ++r) {
        sinks.push_back(make_output_sink("vtk_xml"));
        CHECK(sinks.back()->writes_pieces());
        if (r == 0)
          sinks.back()->open(dir, {});
        else
          sinks.back()->open_part(dir);
      }
      std::vector<MeshOutput> grids, points;
      for (int r = 0; r < P; ++r) {
        grids.push_back(shell_grid(element_block(r, P, 5, 3), nan));
        // contact points on the odd processes only; a rope on the last one
        MeshOutput c = polyline("contact", "last_contact", r);
        c.mesh.shape = SampledMesh::Shape::kPoints;
        if (r % 2 == 0) c.mesh = SampledMesh{};
        points.push_back(c);
      }
      as_pieces(grids);
      as_pieces(points);
      std::vector<OutputFileRef> files;
      for (int r = P - 1; r >= 0; --r) {  // process 0's collection lists pieces written or not
        const auto f = sinks[static_cast<std::size_t>(r)]->snapshot(
            1.0, {grids[static_cast<std::size_t>(r)], points[static_cast<std::size_t>(r)]});
        if (r == 0) files = f;
        if (r > 0) CHECK(f.empty());
      }
      REQUIRE(files.size() == 2);
      CHECK(files[0].file == "last_shell.pvts");
      CHECK(files[1].file == "last_contact.pvtu");
      CHECK_THAT(test::slurp(fs::path(dir) / "shell.pvd"), Catch::Contains("last_shell.pvts"));
      for (int r = 0; r < P; ++r) {
        CHECK(fs::exists(fs::path(dir) / ("last_shell_p" + std::to_string(r) + ".vts")));
        CHECK(fs::exists(fs::path(dir) / ("last_contact_p" + std::to_string(r) + ".vtu")) ==
              (r % 2 == 1));
      }
      // joined, the pieces are the grid written whole (border samples: the lower block's)
      const std::string whole = (fs::path(dir) / "whole.vts").string();
      write_vtk_xml(whole, shell_grid({}, nan).mesh);
      const test::VtkXmlFile w = test::read_vtk_xml(whole);
      int pieces = 0;
      const test::VtkXmlFile j =
          test::read_vtk_xml_collection(fs::path(dir) / "last_shell.pvts", &pieces);
      CHECK(pieces == P);
      CHECK(w.arrays.count("non_finite") == (nan ? 1U : 0U));
      REQUIRE(j.arrays.size() == w.arrays.size());
      for (const auto& [name, a] : w.arrays) {
        INFO(name);
        CHECK(j.field(name) == a.values);
      }
      const test::VtkXmlFile c =
          test::read_vtk_xml_collection(fs::path(dir) / "last_contact.pvtu", &pieces);
      CHECK(pieces == P / 2);
      std::vector<double> x;  // the odd processes' points in rank order
      for (int r = 1; r < P; r += 2)
        for (int k = 0; k < 3; ++k) x.insert(x.end(), {k + 1.0 * r, 0.0, 0.0});
      CHECK(c.points() == x);
      CHECK(c.field("connectivity").size() == x.size() / 3);
      CHECK(c.field("connectivity").back() == static_cast<double>(x.size() / 3 - 1));
    }
  }
  // A format without pieces refuses them; a collection of no pieces is refused.
  auto legacy = make_output_sink("vtk");
  CHECK_FALSE(legacy->writes_pieces());
  const std::string dir = out_dir("pieces_refused");
  legacy->open(dir, {});
  std::vector<MeshOutput> one{shell_grid(element_block(0, 2, 5, 3))};
  one[0].pieces.rank = 0;
  CHECK_THROWS_AS(legacy->snapshot(0.0, one), std::logic_error);
  auto xml = make_output_sink("vtk_xml");
  xml->open(dir, {});
  CHECK_THROWS_WITH(xml->snapshot(0.0, one), Catch::Contains("no pieces"));
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
