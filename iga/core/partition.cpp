// A model spread over the processes of a run; see partition.hpp.
#include "iga/core/partition.hpp"

#include <algorithm>
#include <stdexcept>

namespace iga {

namespace {

std::string range(int lo, int hi) {
  return "[" + std::to_string(lo) + ", " +
         (hi == std::numeric_limits<int>::max() ? std::string("end") : std::to_string(hi)) + ")";
}

// [lo, hi) of part k of n items cut into p parts, the first n mod p one larger.
std::array<int, 2> part(int k, int p, int n) {
  const int base = n / p, extra = n % p;
  const int lo = k * base + std::min(k, extra);
  return {lo, lo + base + (k < extra ? 1 : 0)};
}

}  // namespace

std::string ElementBlock::describe() const {
  return "elements " + range(u0, u1) + " x " + range(v0, v1);
}

std::array<int, 2> processor_grid(int processes, int nu, int nv) {
  if (processes < 1 || nu < 1 || nv < 1)
    throw std::invalid_argument("processor_grid: " + std::to_string(processes) +
                                " processes on a grid of " + std::to_string(nu) + " x " +
                                std::to_string(nv) + " elements");
  std::array<int, 2> best{0, 0};
  long best_cut = -1;
  for (int pu = 1; pu <= processes; ++pu) {
    if (processes % pu != 0) continue;
    const int pv = processes / pu;
    if (pu > nu || pv > nv) continue;  // a block of no element
    const long cut = static_cast<long>(pu - 1) * nv + static_cast<long>(pv - 1) * nu;
    if (best_cut < 0 || cut < best_cut) {
      best_cut = cut;
      best = {pu, pv};
    }
  }
  if (best_cut < 0)
    throw std::invalid_argument(
        "a patch of " + std::to_string(nu) + " x " + std::to_string(nv) +
        " elements cannot be cut into " + std::to_string(processes) +
        " blocks of at least one element each (no p_u x p_v = " + std::to_string(processes) +
        " with p_u <= " + std::to_string(nu) + ", p_v <= " + std::to_string(nv) +
        "): run on fewer processes or refine the patch");
  return best;
}

ElementBlock element_block(int rank, int processes, int nu, int nv) {
  if (rank < 0 || rank >= processes)
    throw std::invalid_argument("element_block: rank " + std::to_string(rank) + " of " +
                                std::to_string(processes));
  const std::array<int, 2> g = processor_grid(processes, nu, nv);
  const std::array<int, 2> u = part(rank % g[0], g[0], nu), v = part(rank / g[0], g[1], nv);
  return {u[0], u[1], v[0], v[1]};
}

std::vector<int> assign_whole(const std::vector<double>& work, std::vector<double>& load) {
  if (load.empty()) throw std::invalid_argument("assign_whole: no process");
  std::vector<int> owner;
  for (const double w : work) {
    const auto r = std::min_element(load.begin(), load.end()) - load.begin();
    owner.push_back(static_cast<int>(r));
    load[static_cast<std::size_t>(r)] += w;
  }
  return owner;
}

}  // namespace iga
