// Output sinks: where a run's results go, apart from any file format. The driver
// (iga/model/analysis) hands every sink of a run the same things, through one interface: the
// columns of the steps table, the row of each converged step, snapshots of sampled meshes (the
// field series: bodies, contact points, tools) and the summary at the end. Each sink writes what
// it keeps in its own format: the steps table as CSV (steps.csv), the summary as JSON
// (summary.json), the field series as legacy VTK (.vtk) or VTK XML (.vts/.vtu), each series with
// a ParaView collection (.pvd). Formats are registered by name (register_output_format), so a
// new one is a new sink and a registration; the driver does not change.
//
// Notation: a row is one step's values in the table's columns; a snapshot is the meshes of one
// state, each in a series (empty: a file outside any series) under a file stem; its key is its
// place in the series (the pseudo-time t, or under arc length the step number).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry/json_reader.hpp"
#include "iga/core/sampled_mesh.hpp"
#include "iga/core/state_archive.hpp"

namespace iga {

/// A mesh of a run spread over several processes, written as one piece per process and a
/// collection that lists them (a format that keeps pieces, OutputSink::writes_pieces: VTK XML's
/// .pvts over .vts pieces for a grid, .pvtu over .vtu pieces otherwise). The piece of process r
/// is the file <stem>_p<r>, the collection <stem> with the format's parallel extension.
struct MeshPieces {
  /// A piece the collection lists: its process and, for a grid, its size and place in the whole
  /// grid (SampledMesh nu, nv, i0, j0; neighbouring pieces share their border samples).
  struct Piece {
    int rank = 0, nu = 0, nv = 0, i0 = 0, j0 = 0;
  };
  int rank = -1;  ///< this process's piece; -1: the mesh is whole (written by process 0 alone)
  /// Whether this process writes its piece: it has points, or no piece has and it is process
  /// 0's (a collection lists at least one piece).
  bool write = false;
  /// Some piece holds a non-finite value: every piece writes the non_finite flag field, so that
  /// all pieces have the same fields.
  bool non_finite = false;
  int nu = 0, nv = 0;  ///< the whole grid's size (grids)
  /// Process 0 (empty elsewhere): the pieces the collection lists, in rank order, and their
  /// fields' names (values empty).
  std::vector<Piece> listed;
  PointFields fields;
};

/// One mesh of a snapshot: its series (empty: not in a series), the file stem it is written
/// under (relative to the output folder, no extension), a title (formats that keep one), the
/// mesh with its fields and, spread over several processes, this process's piece of it.
struct MeshOutput {
  std::string series, stem, title;
  SampledMesh mesh;
  MeshPieces pieces;
};

/// A file a sink wrote (relative to the output folder) and its series (empty: none).
struct OutputFileRef {
  std::string series, file;
};

/// Where a run's results go. Every call has a default that ignores what the sink does not keep.
/// A sink throws std::runtime_error naming the file when it cannot write; the driver ends the run
/// with the error, keeping what was written before.
class OutputSink {
 public:
  virtual ~OutputSink() = default;
  /// The run starts writing into `dir` (which exists): the table's columns, in order. A
  /// restarted run's sink has read back its earlier rows and series (archive) before.
  virtual void open(const std::string& dir, const std::vector<std::string>& columns) {
    (void)dir;
    (void)columns;
  }
  /// A process other than 0 of a run spread over several: instead of open(), it writes its
  /// pieces of the meshes into `dir` (a sink that writes_pieces); nothing else.
  virtual void open_part(const std::string& dir) { (void)dir; }
  /// Whether the sink writes a spread mesh as pieces (MeshOutput::pieces, on every process)
  /// rather than whole from process 0 (then the parts are joined before snapshot()).
  virtual bool writes_pieces() const { return false; }
  /// The row of a converged step, in the columns' order (counts as whole numbers; any value may
  /// be non-finite: no file may hold one).
  virtual void row(const std::vector<double>& values) { (void)values; }
  /// The meshes of one state, with their series' key; returns the files written, in the order of
  /// the meshes (none: the sink keeps no fields). A spread mesh's file is its collection, on
  /// process 0.
  virtual std::vector<OutputFileRef> snapshot(double key, const std::vector<MeshOutput>& meshes) {
    (void)key;
    (void)meshes;
    return {};
  }
  /// The run's summary, at its end whatever the outcome.
  virtual void close(const Json& summary) { (void)summary; }
  /// The sink's part of a restart file, written or read back (StateArchive): what a restarted
  /// run needs to go on with the same files (rows so far, series so far).
  virtual void archive(StateArchive& a) { (void)a; }
};

/// Makes a sink of a format.
using OutputSinkFactory = std::function<std::unique_ptr<OutputSink>()>;

/// Registers a format under a name (replacing one of the name). Built in:
///   "csv"      the steps table as steps.csv (12 significant digits; a non-finite value is an
///              empty cell), one row written and flushed per converged step;
///   "summary"  the summary as summary.json (indented; non-finite numbers are null);
///   "vtk"      the field series as legacy ASCII VTK files (.vtk) and .pvd collections;
///   "vtk_xml"  the field series as VTK XML files with raw binary appended data (.vts for
///              grids, .vtu for points and polylines) and .pvd collections; a spread mesh as
///              pieces and their parallel collection (.pvts, .pvtu).
void register_output_format(const std::string& name, OutputSinkFactory factory);

/// A sink of the named format; std::invalid_argument naming the known formats if there is none.
std::unique_ptr<OutputSink> make_output_sink(const std::string& name);

/// The names of the registered formats, sorted.
std::vector<std::string> output_format_names();

/// Writes each mesh as one file of the field format `format` ("vtk", "vtk_xml", or a registered
/// one) into dir, outside any series; returns the files in the meshes' order, each with its
/// mesh's series. (By value: callers hand over the meshes they made, nothing is copied.)
std::vector<OutputFileRef> write_meshes(const std::string& format, const std::string& dir,
                                        std::vector<MeshOutput> meshes);

}  // namespace iga
