// The built-in sinks (steps.csv, summary.json, legacy VTK and VTK XML field series) and the
// registry of formats.
#include "iga/output/output_sink.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "iga/output/output_format.hpp"
#include "iga/output/vtk_writer.hpp"
#include "iga/output/vtk_xml_writer.hpp"

namespace iga {

namespace fs = std::filesystem;

namespace {

/// steps.csv: the header at open (then a restarted run's earlier rows), a row per step, flushed
/// at once so that a run that stops midway keeps its rows.
class CsvTableSink final : public OutputSink {
 public:
  void open(const std::string& dir, const std::vector<std::string>& columns) override {
    path_ = (fs::path(dir) / "steps.csv").string();
    file_.open(path_);
    if (!file_) throw std::runtime_error(path_ + ": cannot write file");
    for (std::size_t i = 0; i < columns.size(); ++i) file_ << (i > 0 ? "," : "") << columns[i];
    file_ << "\n" << rows_ << std::flush;
  }
  void row(const std::vector<double>& values) override {
    std::string line;
    for (std::size_t i = 0; i < values.size(); ++i)
      line += (i > 0 ? "," : "") + csv_number(values[i]);
    line += "\n";
    rows_ += line;
    if (!file_.is_open()) return;
    file_ << line << std::flush;
    if (!file_) throw std::runtime_error(path_ + ": cannot write a row");
  }
  void archive(StateArchive& a) override { a.io(rows_); }

 private:
  std::string path_;
  std::ofstream file_;
  std::string rows_;  // every row so far (a restart's earlier ones first)
};

/// summary.json at the end of the run.
class JsonSummarySink final : public OutputSink {
 public:
  void open(const std::string& dir, const std::vector<std::string>& /*columns*/) override {
    path_ = (fs::path(dir) / "summary.json").string();
  }
  void close(const Json& summary) override {
    if (path_.empty()) return;
    std::ofstream f(path_);
    f << format_json(summary) << "\n";
    if (!f) throw std::runtime_error(path_ + ": cannot write file");
  }

 private:
  std::string path_;
};

/// The pieces' format: the collection's extension and the writers of a piece and of a
/// collection (null: the format keeps no pieces).
struct PieceFormat {
  const char* (*collection_extension)(const SampledMesh& mesh) = nullptr;
  void (*write_piece)(const std::string& path, const SampledMesh& mesh,
                      const MeshPieces& pieces) = nullptr;
  void (*write_collection)(const std::string& path, SampledMesh::Shape shape,
                           const MeshPieces& pieces,
                           const std::function<std::string(int)>& piece_file) = nullptr;
};

/// A field series: each mesh a file <stem><extension>; each series a ParaView collection
/// <series>.pvd rewritten at every snapshot, so that a run that stops midway leaves valid ones.
/// With a piece format (VTK XML): a spread mesh as each process's piece <stem>_p<r><extension>
/// and process 0's collection <stem><collection extension>, which the series lists.
class FieldSeriesSink final : public OutputSink {
 public:
  using Writer = void (*)(const std::string& path, const MeshOutput& m);
  using Extension = const char* (*)(const SampledMesh& mesh);
  FieldSeriesSink(Writer write, Extension extension, PieceFormat pieces = {})
      : write_(write), extension_(extension), pieces_(pieces) {}

  bool writes_pieces() const override { return pieces_.collection_extension != nullptr; }
  void open_part(const std::string& dir) override {
    dir_ = dir;
    root_ = false;
    restored_.clear();  // process 0 keeps the series
  }
  void open(const std::string& dir, const std::vector<std::string>& /*columns*/) override {
    dir_ = dir;
    for (auto& [series, entries] : restored_) {  // a restarted run's series go on
      auto it = pvd_.emplace(series, VtkCollection(pvd_path(series), std::move(entries))).first;
      it->second.write();
    }
    restored_.clear();
  }
  std::vector<OutputFileRef> snapshot(double key, const std::vector<MeshOutput>& meshes) override {
    std::vector<OutputFileRef> files;
    for (const MeshOutput& m : meshes) {
      const bool spread = m.pieces.rank >= 0;
      if (spread && !writes_pieces())
        throw std::logic_error(m.stem + ": a mesh in pieces handed to a format without pieces");
      if (spread && m.pieces.write)
        pieces_.write_piece((fs::path(dir_) / piece_file(m, m.pieces.rank)).string(), m.mesh,
                            m.pieces);
      if (!root_) continue;  // process 0 writes the collections and the meshes written whole
      std::string file;
      if (spread) {
        file = m.stem + pieces_.collection_extension(m.mesh);
        pieces_.write_collection((fs::path(dir_) / file).string(), m.mesh.shape, m.pieces,
                                 [&](int r) { return piece_file(m, r); });
      } else {
        file = m.stem + extension_(m.mesh);
        write_((fs::path(dir_) / file).string(), m);
      }
      files.push_back({m.series, file});
      if (m.series.empty()) continue;
      auto it = pvd_.find(m.series);
      if (it == pvd_.end()) it = pvd_.emplace(m.series, VtkCollection(pvd_path(m.series))).first;
      it->second.add(key, file);
    }
    return files;
  }
  void archive(StateArchive& a) override {
    // written: the series so far; read back: kept until open() goes on with them
    std::vector<std::pair<std::string, VtkCollection::Entries>> series;
    if (!a.loading())
      for (const auto& [name, c] : pvd_) series.emplace_back(name, c.entries());
    a.items(
        series,
        [&](std::pair<std::string, VtkCollection::Entries>& e) {
          a.io(e.first);
          a.items(
              e.second,
              [&](std::pair<double, std::string>& f) {
                a.io(f.first);
                a.io(f.second);
              },
              "series entries");
        },
        "ParaView series");
    if (a.loading()) restored_ = std::move(series);
  }

 private:
  /// The file of process r's piece of a spread mesh (beside its collection).
  std::string piece_file(const MeshOutput& m, int r) const {
    std::string file = m.stem;  // (appended: GCC 12 warns falsely of + chains, -Wrestrict)
    file += "_p";
    file += std::to_string(r);
    file += extension_(m.mesh);
    return file;
  }
  std::string pvd_path(const std::string& series) const {
    return (fs::path(dir_) / (series + ".pvd")).string();
  }
  Writer write_;
  Extension extension_;
  PieceFormat pieces_;
  bool root_ = true;  // process 0 (or the one process): it writes the collections and series
  std::string dir_;
  std::map<std::string, VtkCollection> pvd_;
  std::vector<std::pair<std::string, VtkCollection::Entries>> restored_;
};

void write_legacy(const std::string& path, const MeshOutput& m) {
  write_vtk(path, m.mesh, m.title.empty() ? "iga" : m.title);
}
const char* legacy_extension(const SampledMesh& /*mesh*/) {
  return ".vtk";
}
void write_xml(const std::string& path, const MeshOutput& m) {
  write_vtk_xml(path, m.mesh);
}

struct Registry {
  std::mutex mutex;
  std::map<std::string, OutputSinkFactory> formats{
      {"csv", [] { return std::make_unique<CsvTableSink>(); }},
      {"summary", [] { return std::make_unique<JsonSummarySink>(); }},
      {"vtk", [] { return std::make_unique<FieldSeriesSink>(write_legacy, legacy_extension); }},
      {"vtk_xml",
       [] {
         return std::make_unique<FieldSeriesSink>(
             write_xml, vtk_xml_extension,
             PieceFormat{vtk_xml_collection_extension, write_vtk_xml_piece,
                         write_vtk_xml_collection});
       }},
  };
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

void register_output_format(const std::string& name, OutputSinkFactory factory) {
  if (name.empty() || !factory)
    throw std::invalid_argument("register_output_format: a name and a factory are needed");
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.formats[name] = std::move(factory);
}

std::vector<std::string> output_format_names() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [name, f] : r.formats) names.push_back(name);
  return names;
}

std::unique_ptr<OutputSink> make_output_sink(const std::string& name) {
  OutputSinkFactory factory;
  {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    const auto it = r.formats.find(name);
    if (it != r.formats.end()) factory = it->second;
  }
  if (!factory) {
    std::string known;
    for (const std::string& n : output_format_names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown output format \"" + name + "\" (known: " + known + ")");
  }
  std::unique_ptr<OutputSink> sink = factory();
  if (!sink) throw std::runtime_error("output format \"" + name + "\" made no sink");
  return sink;
}

std::vector<OutputFileRef> write_meshes(const std::string& format, const std::string& dir,
                                        std::vector<MeshOutput> meshes) {
  const std::unique_ptr<OutputSink> sink = make_output_sink(format);
  sink->open(dir, {});
  std::vector<std::string> series;  // each mesh's, reported; written outside any (no .pvd)
  series.reserve(meshes.size());
  for (MeshOutput& m : meshes) series.push_back(std::exchange(m.series, {}));
  std::vector<OutputFileRef> files = sink->snapshot(0.0, meshes);
  for (std::size_t i = 0; i < files.size() && i < series.size(); ++i)
    files[i].series = std::move(series[i]);
  return files;
}

}  // namespace iga
