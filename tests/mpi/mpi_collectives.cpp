// Run by the suite under mpirun (tests/CMakeLists.txt): the MPI communicator of
// iga/parallel/communicator.hpp on N ranks. Sums, maxima, the gather of messages to rank 0, the
// broadcast and the personalized exchange against their values in closed form; the DofLayout
// of iga/parallel/dof_layout.hpp (owners' rows, residual parts added into the owners, owners'
// values sent to the ghosts, the gather, dot products); exit 0 on every rank when all hold.
// `mpi_collectives fail`: rank 1 aborts while the others wait in a barrier: the run must end
// with its message and a non-zero status, never hang.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "iga/parallel/communicator.hpp"
#include "iga/parallel/dof_layout.hpp"

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
  // exchange: rank r sends rank q the q + 1 values r, q, r + q, ...
  std::vector<std::vector<double>> to(static_cast<std::size_t>(n));
  for (int q = 0; q < n; ++q)
    for (int k = 0; k <= q; ++k) to[static_cast<std::size_t>(q)].push_back(100.0 * r + q + k);
  const std::vector<std::vector<double>> from = w.exchange(to);
  bool exchanged = static_cast<int>(from.size()) == n;
  for (int q = 0; exchanged && q < n; ++q) {
    const std::vector<double>& f = from[static_cast<std::size_t>(q)];
    exchanged = static_cast<int>(f.size()) == r + 1;
    for (int k = 0; exchanged && k <= r; ++k)
      exchanged = f[static_cast<std::size_t>(k)] == 100.0 * q + r + k;
  }
  expect(exchanged, "exchange: what each rank sent here, in order");

  // DofLayout: m unknowns, unknown i owned by (7 i + 3) mod n; rank r reads the unknowns i with
  // i mod 3 == r mod 3 and i mod 5 == r mod 5 (some of them its own).
  const int m = 30 * n;
  std::vector<int> owner(static_cast<std::size_t>(m)), reads;
  for (int i = 0; i < m; ++i) owner[static_cast<std::size_t>(i)] = (7 * i + 3) % n;
  const auto reader = [](int q, int i) { return i % 3 == q % 3 || i % 5 == q % 5; };
  for (int i = m - 1; i >= 0; --i)  // (any order)
    if (reader(r, i)) reads.push_back(i);
  const iga::DofLayout L(w, owner, reads);
  const auto own = [&](int i) { return owner[static_cast<std::size_t>(i)]; };
  // rows: the owners' blocks one after the other, each in the serial order
  bool rows_ok = true;
  for (int i = 0; i < m; ++i)
    for (int j = i + 1; j < m; ++j) {
      const int ri = L.rows()[static_cast<std::size_t>(i)],
                rj = L.rows()[static_cast<std::size_t>(j)];
      if ((own(i) <= own(j)) != (ri < rj)) rows_ok = false;
    }
  int before = 0;
  for (int i = 0; i < m; ++i) before += own(i) < r ? 1 : 0;
  expect(rows_ok && L.first_row() == before, "DofLayout: rows by owner");
  // add_to_owners: rank q adds (q + 1)(i + 1) at what it reads or owns
  Eigen::VectorXd R = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i)
    if (reader(r, i) || own(i) == r) R[i] = (r + 1.0) * (i + 1.0);
  L.add_to_owners(R);
  bool added = true;
  for (const int i : L.owned()) {
    double total = 0.0;
    for (int q = 0; q < n; ++q)
      if (reader(q, i) || own(i) == q) total += (q + 1.0) * (i + 1.0);
    added = added && R[i] == total;
  }
  expect(added && !L.owned().empty(), "DofLayout: parts added into the owners");
  // update_ghosts and gather: the owners' values 1000 i + owner
  Eigen::VectorXd x = Eigen::VectorXd::Constant(m, -1.0);
  for (const int i : L.owned()) x[i] = 1000.0 * i + r;
  L.update_ghosts(x);
  bool ghosts = true;
  for (int i = 0; i < m; ++i) {
    const bool current = own(i) == r || reader(r, i);
    ghosts = ghosts && x[i] == (current ? 1000.0 * i + own(i) : -1.0);
  }
  expect(ghosts && !L.ghosts().empty(), "DofLayout: owners' values at the ghosts, nothing else");
  L.gather(x);
  bool gathered = true;
  for (int i = 0; i < m; ++i) gathered = gathered && x[i] == 1000.0 * i + own(i);
  expect(gathered, "DofLayout: gather");
  // dot over the owners: sum_i i (i + 1) whatever the other entries hold
  Eigen::VectorXd a = Eigen::VectorXd::Constant(m, 1e6), b = a;
  for (int i = 0; i < m; ++i)
    if (own(i) == r) {
      a[i] = i;
      b[i] = i + 1.0;
    }
  expect(L.dot(a, b) == (m - 1.0) * m * (m + 1.0) / 3.0, "DofLayout: dot over the owners");

  const long long failed = w.sum(static_cast<long long>(errors));
  if (r == 0) std::printf("mpi_collectives: %d ranks, %lld failures\n", n, failed);
  return failed == 0 ? 0 : 1;
}
