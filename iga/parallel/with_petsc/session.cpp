// The MPI communicator and the PETSc session of a build with PETSc (IGA_WITH_PETSC=ON); see
// iga/parallel/communicator.hpp. The only file, with iga/solvers/with_petsc/, that names MPI or
// PETSc.
#include <petscsys.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "iga/parallel/communicator.hpp"

namespace iga {

namespace {

/// MPI_COMM_WORLD as PETSc sees it.
class MpiCommunicator final : public Communicator {
 public:
  MpiCommunicator() {
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
    MPI_Comm_size(PETSC_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  using Communicator::max;
  using Communicator::sum;
  void sum(std::span<double> v) const override {
    if (!v.empty())
      MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM,
                    PETSC_COMM_WORLD);
  }
  void sum(std::span<long long> v) const override {
    if (!v.empty())
      MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_LONG_LONG, MPI_SUM,
                    PETSC_COMM_WORLD);
  }
  void max(std::span<double> v) const override {
    if (!v.empty())
      MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MAX,
                    PETSC_COMM_WORLD);
  }
  std::vector<std::string> gather(const std::string& s) const override {
    const int n = static_cast<int>(s.size());
    std::vector<int> sizes(static_cast<std::size_t>(size_)), offsets(sizes.size());
    MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD);
    int total = 0;
    for (std::size_t r = 0; r < sizes.size(); ++r) {
      offsets[r] = total;
      total += sizes[r];
    }
    std::string all(static_cast<std::size_t>(rank_ == 0 ? total : 0), '\0');
    MPI_Gatherv(s.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0,
                PETSC_COMM_WORLD);
    std::vector<std::string> out;
    if (rank_ != 0) return out;
    for (std::size_t r = 0; r < sizes.size(); ++r)
      out.push_back(
          all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(sizes[r])));
    return out;
  }
  void broadcast(std::string& s, int from) const override {
    int n = static_cast<int>(s.size());
    MPI_Bcast(&n, 1, MPI_INT, from, PETSC_COMM_WORLD);
    s.resize(static_cast<std::size_t>(n));
    MPI_Bcast(s.data(), n, MPI_CHAR, from, PETSC_COMM_WORLD);
  }
  std::vector<std::vector<double>> exchange(
      const std::vector<std::vector<double>>& to) const override {
    const auto P = static_cast<std::size_t>(size_);
    if (to.size() != P)
      throw std::invalid_argument("Communicator::exchange: " + std::to_string(to.size()) +
                                  " lists for " + std::to_string(size_) + " processes");
    std::vector<int> send_n(P), recv_n(P), send_at(P), recv_at(P);
    std::vector<double> send;
    for (std::size_t q = 0; q < P; ++q) {
      send_n[q] = static_cast<int>(to[q].size());
      send_at[q] = static_cast<int>(send.size());
      send.insert(send.end(), to[q].begin(), to[q].end());
    }
    MPI_Alltoall(send_n.data(), 1, MPI_INT, recv_n.data(), 1, MPI_INT, PETSC_COMM_WORLD);
    int total = 0;
    for (std::size_t q = 0; q < P; ++q) {
      recv_at[q] = total;
      total += recv_n[q];
    }
    std::vector<double> recv(static_cast<std::size_t>(total));
    MPI_Alltoallv(send.data(), send_n.data(), send_at.data(), MPI_DOUBLE, recv.data(),
                  recv_n.data(), recv_at.data(), MPI_DOUBLE, PETSC_COMM_WORLD);
    std::vector<std::vector<double>> from(P);
    for (std::size_t q = 0; q < P; ++q)
      from[q].assign(recv.begin() + recv_at[q], recv.begin() + recv_at[q] + recv_n[q]);
    return from;
  }
  void barrier() const override { MPI_Barrier(PETSC_COMM_WORLD); }
  [[noreturn]] void abort(int code, const std::string& message) const override {
    std::fprintf(stderr, "[rank %d of %d] %s\n", rank_, size_, message.c_str());
    std::fflush(stderr);
    MPI_Abort(PETSC_COMM_WORLD, code);
    std::exit(code);  // MPI_Abort does not return
  }
  std::string describe() const override {
    return "MPI, " + std::to_string(size_) + (size_ == 1 ? " rank" : " ranks");
  }

 private:
  int rank_ = 0, size_ = 1;
};

MpiCommunicator* g_mpi = nullptr;
/// PETSc options of the command line (after --petsc), for a lazy start (ensure_petsc).
std::string g_options;
bool g_lazy = false;  ///< PETSc started by ensure_petsc(), finalized at exit

void finalize_lazy() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (!finalized) PetscFinalize();
}

/// Removes "--petsc" and everything after it from argv; returns them joined by spaces.
std::string take_petsc_options(int& argc, char**& argv) {
  std::string options;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--petsc") != 0) continue;
    for (int j = i + 1; j < argc; ++j)
      options += (options.empty() ? "" : " ") + std::string(argv[j]);
    argc = i;
    argv[argc] = nullptr;
    break;
  }
  return options;
}

}  // namespace

bool parallel_build() {
  return true;
}

ParallelSession::ParallelSession(int& argc, char**& argv) {
  g_options = take_petsc_options(argc, argv);
  if (!launched_by_mpirun()) return;  // serial: PETSc starts lazily if a solver asks for it
  int no_args = 1;
  char** prog = argv;
  if (PetscInitialize(&no_args, &prog, nullptr, nullptr) != 0)
    throw std::runtime_error("could not initialize PETSc and MPI");
  if (!g_options.empty()) PetscOptionsInsertString(nullptr, g_options.c_str());
  g_mpi = new MpiCommunicator();
  detail::set_world(g_mpi);
  active_ = true;
}

ParallelSession::~ParallelSession() {
  if (!active_) {
    g_options.clear();  // the options were this session's
    return;
  }
  detail::set_world(nullptr);
  delete g_mpi;
  g_mpi = nullptr;
  PetscFinalize();
}

void ensure_petsc() {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (initialized) return;
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (finalized) throw std::runtime_error("PETSc was finalized and cannot start again");
  if (PetscInitializeNoArguments() != 0) throw std::runtime_error("could not initialize PETSc");
  if (!g_options.empty()) PetscOptionsInsertString(nullptr, g_options.c_str());
  if (!g_lazy) std::atexit(finalize_lazy);
  g_lazy = true;
}

}  // namespace iga
