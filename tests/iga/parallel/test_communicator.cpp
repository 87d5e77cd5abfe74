// Tests of the serial side of iga/parallel/communicator.hpp: the serial communicator's
// collectives are the identity, the world is serial outside mpirun, a session outside mpirun
// starts nothing and takes PETSc's options (after --petsc) off the command line, or refuses
// them in a build without PETSc. (The MPI side runs under mpirun: tests/mpi/.)
#include <catch2/catch.hpp>

#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "iga/parallel/communicator.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_communicator {

using namespace iga;

TEST_CASE("Communicator: one process, every collective the identity", "[iga][parallel]") {
  const Communicator& s = serial_communicator();
  CHECK(s.rank() == 0);
  CHECK(s.size() == 1);
  CHECK(s.root());
  std::vector<double> v = {1.5, -2.0};
  s.sum(std::span<double>(v));
  s.max(std::span<double>(v));
  CHECK(v == std::vector<double>{1.5, -2.0});
  CHECK(s.sum(3.25) == 3.25);
  CHECK(s.sum(7LL) == 7LL);
  CHECK(s.gather("only") == std::vector<std::string>{"only"});
  std::string b = "kept";
  s.broadcast(b, 0);
  CHECK(b == "kept");
  CHECK(s.describe() == "serial");
  CHECK(s.first_message("why") == "why");
  CHECK(s.first_message("").empty());
  if (!launched_by_mpirun()) CHECK(&world() == &s);
}

TEST_CASE("ParallelSession outside mpirun: serial, PETSc's options taken off the command line",
          "[iga][parallel]") {
  if (launched_by_mpirun()) return;  // (the suite does not run this file under mpirun)
  std::string a0 = "iga", a1 = "run", a2 = "m.json", a3 = "--petsc", a4 = "-pc_type", a5 = "hypre";
  std::vector<char*> args = {a0.data(), a1.data(), a2.data(), a3.data(),
                             a4.data(), a5.data(), nullptr};
  int argc = 6;
  char** argv = args.data();
  if (!parallel_build()) {
    CHECK_THROWS_WITH(ParallelSession(argc, argv), Catch::Contains("IGA_WITH_PETSC=OFF"));
    CHECK_THROWS_WITH(ensure_petsc(), Catch::Contains("IGA_WITH_PETSC=OFF"));
    return;
  }
  const ParallelSession session(argc, argv);
  CHECK_FALSE(session.active());
  CHECK(world().size() == 1);
  REQUIRE(argc == 3);  // "--petsc" and what follows, for PETSc
  CHECK(std::strcmp(argv[2], "m.json") == 0);
  CHECK(argv[3] == nullptr);
}

}  // namespace test_communicator
