// MUMPS called directly, with METIS's ordering of the whole matrix; see mumps_direct.hpp.
#include "iga/solvers/with_petsc/mumps_direct.hpp"

#include <mpi.h>
#include <petscsys.h>

#include <algorithm>
#include <climits>
#include <cstddef>
#include <string>
#include <vector>

#include <cholmod.h>

namespace iga::petsc {

namespace {

MPI_Comm comm() {
  return PETSC_COMM_WORLD;
}

int rank() {
  int r = 0;
  MPI_Comm_rank(comm(), &r);
  return r;
}

/// Process 0: the elimination position (1-based, MUMPS's PERM_IN) of every unknown in METIS's
/// nested dissection of the pattern whose strictly lower entries are `pairs` (i > j, as
/// i0, j0, i1, j1, ...); empty where CHOLMOD cannot order it.
std::vector<MUMPS_INT> metis_positions(int n, const std::vector<int>& pairs) {
  // the pattern column by column, each column's rows sorted and once
  const std::size_t m = pairs.size() / 2;
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (std::size_t k = 0; k < m; ++k) ++start[static_cast<std::size_t>(pairs[2 * k + 1]) + 1];
  for (int j = 0; j < n; ++j) start[j + 1] += start[j];
  std::vector<int> rows(m), next(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < m; ++k)
    rows[static_cast<std::size_t>(next[pairs[2 * k + 1]]++)] = pairs[2 * k];
  std::vector<int> p(static_cast<std::size_t>(n) + 1, 0);
  std::size_t nnz = 0;
  for (int j = 0; j < n; ++j) {
    const auto first = rows.begin() + start[j], last = rows.begin() + start[j + 1];
    std::sort(first, last);
    const auto end = std::unique(first, last);
    for (auto it = first; it != end; ++it) rows[nnz++] = *it;
    p[j + 1] = static_cast<int>(nnz);
  }
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  std::vector<MUMPS_INT> position;
  cholmod_sparse* A =
      cholmod_allocate_sparse(n, n, std::max<std::size_t>(nnz, 1), 1, 1, -1, CHOLMOD_PATTERN, &c);
  if (A != nullptr) {
    std::copy(p.begin(), p.end(), static_cast<int*>(A->p));
    std::copy(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(nnz),
              static_cast<int*>(A->i));
    std::vector<int> order(static_cast<std::size_t>(n));
    if (cholmod_metis(A, nullptr, 0, 1, order.data(), &c)) {
      position.assign(static_cast<std::size_t>(n), 0);
      for (int k = 0; k < n; ++k) position[static_cast<std::size_t>(order[k])] = k + 1;
    }
    cholmod_free_sparse(&A, &c);
  }
  cholmod_finish(&c);
  return position;
}

/// MUMPS's integer controls and real controls set in PETSc's options (-mat_mumps_icntl_<k>,
/// -mat_mumps_cntl_<k>), as PETSc's own interface reads them.
void petsc_options(DMUMPS_STRUC_C& id) {
  for (int k = 1; k <= 60; ++k) {
    PetscInt v = 0;
    PetscBool set = PETSC_FALSE;
    const std::string name = "-mat_mumps_icntl_" + std::to_string(k);
    if (PetscOptionsGetInt(nullptr, nullptr, name.c_str(), &v, &set) == 0 && set)
      id.icntl[k - 1] = static_cast<MUMPS_INT>(v);
  }
  for (int k = 1; k <= 15; ++k) {
    PetscReal v = 0;
    PetscBool set = PETSC_FALSE;
    const std::string name = "-mat_mumps_cntl_" + std::to_string(k);
    if (PetscOptionsGetReal(nullptr, nullptr, name.c_str(), &v, &set) == 0 && set)
      id.cntl[k - 1] = v;
  }
}

/// MUMPS's errors that more workspace mends (users' guide 5.5, INFO(1)).
bool workspace_error(int info) {
  return info == -8 || info == -9 || info == -14 || info == -15 || info == -17 || info == -20;
}

}  // namespace

MumpsDirect::~MumpsDirect() {
  end();
}

void MumpsDirect::start(bool symmetric) {
  end();
  id_ = DMUMPS_STRUC_C{};
  id_.par = 1;  // process 0 works too
  id_.sym = symmetric ? 2 : 0;
  id_.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm()));
  run(-1);
  live_ = true;
  symmetric_ = symmetric;
  set_controls();
}

void MumpsDirect::end() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (live_ && !finalized) run(-2);
  live_ = false;
  factorized_ = false;
}

void MumpsDirect::set_controls() {
  auto icntl = [&](int k) -> MUMPS_INT& { return id_.icntl[k - 1]; };
  icntl(1) = -1;  // no printing unless asked (-mat_mumps_icntl_4)
  icntl(2) = -1;
  icntl(3) = -1;
  icntl(4) = 0;
  icntl(5) = 0;   // assembled entries
  icntl(18) = 3;  // distributed: each process its own
  icntl(28) = 1;  // sequential analysis, on process 0
  icntl(13) = 1;  // the root front without ScaLAPACK: the inertia on any number of processes
  icntl(24) = 1;  // null pivots detected
  icntl(20) = 0;  // the right-hand side dense on process 0
  icntl(21) = 0;  // and the solution there
  petsc_options(id_);
  if (icntl(4) > 0) {  // printing asked for: to standard output
    icntl(1) = 6;
    icntl(2) = 0;
    icntl(3) = 6;
  }
}

void MumpsDirect::run(int job) {
  id_.job = job;
  dmumps_c(&id_);
}

std::string MumpsDirect::error(const char* phase) const {
  return std::string("MUMPS: ") + phase + " failed (INFOG(1) = " + std::to_string(id_.infog[0]) +
         ", INFOG(2) = " + std::to_string(id_.infog[1]) + ")";
}

bool MumpsDirect::analyze(int n, bool symmetric, std::span<const int> rows,
                          std::span<const int> cols, std::string& why) {
  if (!live_ || symmetric != symmetric_) start(symmetric);
  factorized_ = false;
  n_ = n;
  irn_.resize(rows.size());
  jcn_.resize(cols.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    irn_[k] = rows[k] + 1;
    jcn_[k] = cols[k] + 1;
  }
  a_.assign(rows.size(), 0.0);
  id_.n = n;
  id_.nnz_loc = static_cast<MUMPS_INT8>(rows.size());
  id_.irn_loc = irn_.data();
  id_.jcn_loc = jcn_.data();
  id_.a_loc = a_.data();

  // METIS's ordering on process 0 from every process's pattern, unless another was asked for
  if (id_.icntl[6] == 1 || id_.icntl[6] == 7) {
    bool metis = false;
    std::vector<int> mine;
    mine.reserve(2 * rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (rows[k] != cols[k]) {
        mine.push_back(std::max(rows[k], cols[k]));
        mine.push_back(std::min(rows[k], cols[k]));
      }
    int size = 1;
    MPI_Comm_size(comm(), &size);
    const int count = static_cast<int>(std::min<std::size_t>(mine.size(), INT_MAX));
    std::vector<int> counts(static_cast<std::size_t>(size)), offsets(counts.size() + 1, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm());
    long long total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) total += counts[r];
    // the gather's offsets are ints (a count past them was clamped to INT_MAX)
    int fits = rank() != 0 || total < INT_MAX;
    MPI_Bcast(&fits, 1, MPI_INT, 0, comm());
    if (fits) {
      std::vector<int> pairs;
      if (rank() == 0) {
        for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
        pairs.resize(static_cast<std::size_t>(total));
      }
      MPI_Gatherv(mine.data(), count, MPI_INT, pairs.data(), counts.data(), offsets.data(), MPI_INT,
                  0, comm());
      int ordered = 0;
      if (rank() == 0) {
        perm_ = metis_positions(n, pairs);
        ordered = perm_.empty() ? 0 : 1;
      }
      MPI_Bcast(&ordered, 1, MPI_INT, 0, comm());
      metis = ordered == 1;
    }
    id_.icntl[6] = metis ? 1 : 7;  // else MUMPS's own choice
    id_.perm_in = metis && rank() == 0 ? perm_.data() : nullptr;
  }
  run(1);
  if (id_.infog[0] < 0) {
    why = error("analysis");
    return false;
  }
  return true;
}

bool MumpsDirect::factorize(std::span<const double> values, std::string& why) {
  factorized_ = false;
  std::copy(values.begin(), values.end(), a_.begin());
  // more workspace where MUMPS's estimate fell short (ICNTL(14): percent over the estimate)
  for (int attempt = 0; attempt < 4; ++attempt) {
    run(2);
    if (!workspace_error(id_.infog[0])) break;
    id_.icntl[13] = std::max<MUMPS_INT>(2 * id_.icntl[13], 40);
  }
  if (id_.infog[0] < 0) {
    why = id_.infog[0] == -10 ? "MUMPS: the matrix is numerically singular (INFOG(1) = -10)"
                              : error("factorization");
    return false;
  }
  if (id_.infog[27] > 0) {
    why = "MUMPS: " + std::to_string(id_.infog[27]) + " null pivot(s): the matrix is singular";
    return false;
  }
  factorized_ = true;
  return true;
}

bool MumpsDirect::solve(double* rhs, std::string& why) {
  id_.nrhs = 1;
  id_.lrhs = n_;
  id_.rhs = rhs;
  run(3);
  if (id_.infog[0] < 0) {
    why = error("solve");
    return false;
  }
  return true;
}

}  // namespace iga::petsc
