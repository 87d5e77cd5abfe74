// The processes of a run and what they tell each other: a communicator with the few collective
// operations the framework needs (sums and maxima over ranks, messages gathered to rank 0, a
// string broadcast, an abort that ends every rank), a serial one (one process, every operation
// the identity) and the run's world. Under mpirun the world is MPI_COMM_WORLD through PETSc
// (ParallelSession); without it, or in a build without PETSc (IGA_WITH_PETSC=OFF), the serial
// communicator. No code outside iga/parallel/with_petsc names MPI or PETSc.
//
// Notation: rank r in [0, size); rank 0 the root, which writes the run's tables and messages.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace iga {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool root() const { return rank() == 0; }
  /// In place: each entry becomes its sum over the ranks (the same on every rank).
  virtual void sum(std::span<double> values) const = 0;
  virtual void sum(std::span<long long> values) const = 0;
  /// In place: each entry becomes its maximum over the ranks.
  virtual void max(std::span<double> values) const = 0;
  double sum(double v) const {
    sum(std::span<double>(&v, 1));
    return v;
  }
  long long sum(long long v) const {
    sum(std::span<long long>(&v, 1));
    return v;
  }
  double max(double v) const {
    max(std::span<double>(&v, 1));
    return v;
  }
  /// Every rank's string, in rank order, on rank 0 (empty on the others).
  virtual std::vector<std::string> gather(const std::string& s) const = 0;
  /// s of rank `from` on every rank.
  virtual void broadcast(std::string& s, int from = 0) const = 0;
  /// Personalized all-to-all: to[q] (size() lists) goes to rank q; returns what each rank q sent
  /// here, from[q] (MPI_Alltoallv). Integers up to 2^53 travel exactly as doubles.
  virtual std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& to) const = 0;
  virtual void barrier() const = 0;
  /// The first non-empty of the ranks' strings, in rank order, on every rank (empty if all
  /// are): a failure's reason that every rank reports alike.
  std::string first_message(const std::string& s) const;
  /// Ends every rank of the run with `code` after printing `message` (a rank that failed while
  /// the others wait in a collective: never a hang). Serial: prints and exits.
  [[noreturn]] virtual void abort(int code, const std::string& message) const = 0;
  /// "MPI, 4 ranks" or "serial".
  virtual std::string describe() const = 0;
};

/// One process on its own: every collective operation is the identity. By default the one
/// process of a serial run. SerialCommunicator(r, P) is process r of P standing alone: a model
/// built on it is that process's share of a run over P, which one process can assemble and
/// check (its sums are its own part; tests).
class SerialCommunicator final : public Communicator {
 public:
  SerialCommunicator() = default;
  SerialCommunicator(int rank, int size);
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  using Communicator::max;
  using Communicator::sum;
  void sum(std::span<double>) const override {}
  void sum(std::span<long long>) const override {}
  void max(std::span<double>) const override {}
  std::vector<std::string> gather(const std::string& s) const override { return {s}; }
  void broadcast(std::string&, int) const override {}
  /// What this process sends itself; nothing from the others (they are not there).
  std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& to) const override;
  void barrier() const override {}
  [[noreturn]] void abort(int code, const std::string& message) const override;
  /// "serial", or "process 1 of 3, alone".
  std::string describe() const override;

 private:
  int rank_ = 0, size_ = 1;
};

/// The serial communicator (one instance for the program).
const Communicator& serial_communicator();

/// The processes of this run: MPI_COMM_WORLD while a ParallelSession over MPI is alive, else
/// the serial communicator.
const Communicator& world();

/// Whether this build has PETSc and MPI (the CMake option IGA_WITH_PETSC).
bool parallel_build();

/// Whether the process was started by mpirun or mpiexec (OpenMPI's OMPI_COMM_WORLD_SIZE, or a
/// PMI launcher's PMI_SIZE / PMIX_RANK in the environment).
bool launched_by_mpirun();

/// MPI and PETSc for the life of a program. Started by mpirun (launched_by_mpirun()), it
/// initializes PETSc (and MPI) with the command line's PETSc options, which it removes from
/// argc / argv, and makes world() the MPI communicator; otherwise, and in a build without PETSc,
/// it does nothing and world() stays serial, so that a run without mpirun is the serial run.
/// Under mpirun in a build without PETSc it fails (std::runtime_error): each rank would run the
/// whole model on its own.
class ParallelSession {
 public:
  ParallelSession(int& argc, char**& argv);
  // (Out of line: the PETSc build's finalizes PETSc; the one without has nothing to do.)
  ~ParallelSession();  // NOLINT(performance-trivially-destructible)
  ParallelSession(const ParallelSession&) = delete;
  ParallelSession& operator=(const ParallelSession&) = delete;
  /// Whether this session runs over MPI.
  bool active() const { return active_; }

 private:
  bool active_ = false;
};

/// PETSc initialized for a library user without a ParallelSession (a test, the Python module):
/// on first use, without command-line options, finalized at exit; nothing if it already is.
/// Throws std::runtime_error in a build without PETSc.
void ensure_petsc();

namespace detail {
/// Set by the MPI session (with_petsc): the world while it is alive (null: serial).
void set_world(const Communicator* w);
}  // namespace detail

}  // namespace iga
