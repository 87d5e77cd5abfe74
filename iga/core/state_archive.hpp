// The state of a run for a restart: one routine per class lists its state, and the same
// routine writes it (a writer archive) and reads it back (a reader archive), so that the two
// directions cannot disagree. The file is binary (doubles bit for bit: a restarted run repeats
// the uninterrupted one), made of named sections whose names and sizes are checked on reading:
// a restart file of another model (other bodies, pairs or numbers of unknowns or contact
// points) is refused with a message naming the file, the section and what differs.
//
// Notation: a "section" is a named part (e.g. "body 0", "pair 1"); io(x) writes x or reads
// into x; items(v, f) the size of v, then f(item) for each (a reader resizes v first, or
// checks the size against v's when `resize` is false).
#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace iga {

/// A restart file that cannot be read or does not fit the model.
class RestartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateArchive {
 public:
  /// An empty archive to write into (in memory, until save()).
  static StateArchive writer();
  /// An archive that writes as it goes into `path`.part, renamed to `path` by save(path): the
  /// state is never held whole in memory (a shell's contact points are hundreds of bytes each).
  /// RestartError if the file cannot be opened.
  static StateArchive file_writer(const std::string& path);
  /// The archive of a file, to read from; RestartError if it cannot be read or is not a
  /// restart file of this version.
  static StateArchive reader(const std::string& path);

  bool loading() const { return loading_; }
  /// The file it was read from (empty for a writer).
  const std::string& file() const { return file_; }

  /// Writes the name, or checks that the next section has it.
  void section(const std::string& name);
  void io(double& x);
  void io(int& x);
  void io(bool& x);
  void io(std::string& x);
  template <int R, int C>
  void io(Eigen::Matrix<double, R, C>& x) {
    static_assert(R > 0 && C > 0, "fixed sizes only (VectorXd has its own)");
    for (int j = 0; j < C; ++j)
      for (int i = 0; i < R; ++i) io(x(i, j));
  }
  void io(Eigen::VectorXd& x);
  void io(std::vector<double>& x);
  /// The size of v, then each item by f(item&). resize false: a reader checks that the file
  /// has v.size() items (the model fixes the count, e.g. contact points) instead of resizing.
  template <class T, class F>
  void items(std::vector<T>& v, F&& f, const char* what, bool resize = true) {
    int n = static_cast<int>(v.size());
    io(n);
    if (loading_) {
      if (n < 0) fail(std::string("a negative number of ") + what);
      if (resize)
        v.resize(static_cast<std::size_t>(n));
      else if (static_cast<std::size_t>(n) != v.size())
        fail(std::string("the file has ") + std::to_string(n) + " " + what + ", the model " +
             std::to_string(v.size()));
    }
    for (T& item : v) f(item);
  }
  /// A reader: checks that everything was read (else the model reads less than was written).
  void finish() const;
  /// A writer: writes the file (through a temporary file renamed at the end: a run killed while
  /// it writes leaves the previous restart file whole). RestartError if it cannot, or if a
  /// file_writer is saved under another path than its own.
  void save(const std::string& path);

  /// RestartError naming the file and the section being read.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  void raw(void* p, std::size_t n);
  bool loading_ = false;
  std::string file_;
  std::string current_;  // the section being read or written
  std::vector<char> data_;
  std::size_t pos_ = 0;                 // reader: next byte
  std::unique_ptr<std::ofstream> out_;  // file_writer: the temporary file written into
  std::string out_path_;                // file_writer: the path save() renames it to
};

}  // namespace iga
