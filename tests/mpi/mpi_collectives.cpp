// Run by the suite under mpirun (tests/CMakeLists.txt): the MPI communicator of
// iga/parallel/communicator.hpp on N ranks. Sums, maxima, the gather of messages to rank 0 and
// the broadcast against their values in closed form; exit 0 on every rank when all hold.
// `mpi_collectives fail`: rank 1 aborts while the others wait in a barrier: the run must end
// with its message and a non-zero status, never hang.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "iga/parallel/communicator.hpp"

int main(int argc, char** argv) {
  const iga::ParallelSession session(argc, argv);
  const iga::Communicator& w = iga::world();
  const int r = w.rank(), n = w.size();
  if (!session.active() || n < 2) {
    std::fprintf(stderr, "mpi_collectives: not under mpirun with 2 or more ranks (%s)\n",
                 w.describe().c_str());
    return 1;
  }
  if (argc > 1 && std::strcmp(argv[1], "fail") == 0) {
    if (r == 1) w.abort(3, "rank 1 failed on purpose");
    w.barrier();  // the others wait here; the abort must end them
    return 0;
  }
  int errors = 0;
  const auto expect = [&](bool ok, const char* what) {
    if (!ok) {
      std::fprintf(stderr, "[rank %d] %s\n", r, what);
      ++errors;
    }
  };
  std::vector<double> v = {double(r), 1.0, -double(r * r)};
  w.sum(std::span<double>(v));
  double squares = 0.0;
  for (int k = 0; k < n; ++k) squares += double(k * k);
  expect(v[0] == n * (n - 1) / 2.0 && v[1] == n && v[2] == -squares, "sum of doubles");
  expect(w.sum(static_cast<long long>(r + 1)) == static_cast<long long>(n) * (n + 1) / 2,
         "sum of integers");
  expect(w.max(double(-r)) == 0.0 && w.max(double(r)) == n - 1.0, "maximum");
  const std::vector<std::string> all =
      w.gather(std::string(static_cast<std::size_t>(r), 'x') + "rank " + std::to_string(r));
  if (r == 0) {
    expect(static_cast<int>(all.size()) == n, "gather: one message per rank");
    for (int k = 0; k < n && k < static_cast<int>(all.size()); ++k)
      expect(all[static_cast<std::size_t>(k)] ==
                 std::string(static_cast<std::size_t>(k), 'x') + "rank " + std::to_string(k),
             "gather: the messages in rank order");
  } else {
    expect(all.empty(), "gather: nothing on the other ranks");
  }
  std::string s = r == n - 1 ? "from the last rank" : "";
  w.broadcast(s, n - 1);
  expect(s == "from the last rank", "broadcast");
  expect(w.describe() == "MPI, " + std::to_string(n) + " ranks", "describe");
  // Rank 0 has nothing to say, ranks 1 and up do: rank 1's message reaches every rank.
  expect(w.first_message(r == 0 ? "" : "from rank " + std::to_string(r)) == "from rank 1",
         "first_message");
  expect(w.first_message("").empty(), "first_message of nothing");
  const long long failed = w.sum(static_cast<long long>(errors));
  if (r == 0) std::printf("mpi_collectives: %d ranks, %lld failures\n", n, failed);
  return failed == 0 ? 0 : 1;
}
