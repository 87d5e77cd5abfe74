// A build without PETSc (IGA_WITH_PETSC=OFF): no PETSc solvers; see iga/solvers/petsc_engine.hpp.
#include <stdexcept>
#include <string>

#include "iga/solvers/petsc_engine.hpp"

namespace iga {

std::unique_ptr<PetscEngine> make_petsc_engine(LinearMethod method) {
  throw std::runtime_error(std::string("the linear solver \"") + to_string(method) +
                           "\" needs PETSc, and this build has none (IGA_WITH_PETSC=OFF)");
}

}  // namespace iga
