// ParaView output of the 80 x 80 saddle (issue 35): the Kirchhoff-Love plate of data/saddle.json
// refined to 80 x 80 elements (quadratic), sampled at its default 4 points per element and
// direction (321 x 321 points, with its fields and the contact pair's), written as legacy ASCII
// VTK (write_vtk, .vtk) and as VTK XML with raw binary appended data (write_vtk_xml, .vts).
// Reported: the write time and the file size (counter "MB").
// Run: build/release/bench/bench_output --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"
#include "iga/output/vtk_writer.hpp"
#include "iga/output/vtk_xml_writer.hpp"

using namespace iga;

namespace {

/// The saddle's plate, refined to 80 x 80 elements, sampled with the contact fields of its pair
/// (each body's samples as write_output takes them).
const SampledMesh& saddle_mesh() {
  static const SampledMesh mesh = [] {
    Json doc = read_json_file(std::string(IGA_SOURCE_DIR) + "/data/saddle.json");
    doc["geometry"]["plate"]["refine"]["subdivide"] = 80;
    Analysis a = Analysis::from_json(doc, "saddle_80.json");
    // A deformed state, u_i = 1e-3 sin(i): fields of full-precision numbers, as in a run (the
    // reference state's zeros would make the ASCII file small).
    VectorXd u(a.problem().num_dofs());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = 1e-3 * std::sin(static_cast<double>(i));
    return a.body(0).sample(u, 0.0, a.body(0).default_samples());
  }();
  return mesh;
}

template <class Write>
void run(benchmark::State& state, const std::string& file, Write&& write) {
  const SampledMesh& m = saddle_mesh();
  const std::string path = (std::filesystem::temp_directory_path() / file).string();
  for (auto _ : state) write(path, m);
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  state.counters["points"] = static_cast<double>(m.points.size());
  std::filesystem::remove(path);
}

void BM_saddle80_legacy_vtk(benchmark::State& state) {
  run(state, "bench_saddle80.vtk",
      [](const std::string& p, const SampledMesh& m) { write_vtk(p, m); });
}

void BM_saddle80_vtk_xml(benchmark::State& state) {
  run(state, "bench_saddle80.vts",
      [](const std::string& p, const SampledMesh& m) { write_vtk_xml(p, m); });
}

}  // namespace

BENCHMARK(BM_saddle80_legacy_vtk)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_saddle80_vtk_xml)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
