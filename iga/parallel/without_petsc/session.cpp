// A build without PETSc (IGA_WITH_PETSC=OFF): one process always; see
// iga/parallel/communicator.hpp.
#include <cstring>
#include <stdexcept>

#include "iga/parallel/communicator.hpp"

namespace iga {

bool parallel_build() {
  return false;
}

ParallelSession::ParallelSession(int& argc, char**& argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--petsc") == 0)
      throw std::runtime_error(
          "--petsc: this build has no PETSc (configured with IGA_WITH_PETSC=OFF)");
  if (launched_by_mpirun())
    throw std::runtime_error(
        "started by mpirun, but this build has no PETSc and MPI (configured with "
        "IGA_WITH_PETSC=OFF): each rank would run the whole model alone");
}

ParallelSession::~ParallelSession() = default;

void ensure_petsc() {
  throw std::runtime_error("this build has no PETSc (configured with IGA_WITH_PETSC=OFF)");
}

}  // namespace iga
