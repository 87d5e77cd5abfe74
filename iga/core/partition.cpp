// A model spread over the processes of a run; see partition.hpp.
#include "iga/core/partition.hpp"

#include <algorithm>
#include <stdexcept>

namespace iga {

namespace {

std::string range(int lo, int hi) {
  // (appended piece by piece: a chain of + draws a false -Wrestrict from GCC 12)
  std::string s = "[";
  s += std::to_string(lo);
  s += ", ";
  s += hi == std::numeric_limits<int>::max() ? std::string("end") : std::to_string(hi);
  s += ")";
  return s;
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

namespace {

/// Per basis function of U: the elements of its support [first, last] and the element of its
/// Greville abscissa.
struct BasisElements {
  std::vector<int> first, last, greville;
};

BasisElements basis_elements(const KnotVector& U) {
  const std::vector<double> b = U.breaks();
  const int ne = static_cast<int>(b.size()) - 1, p = U.degree();
  const auto element_at = [&](double x) {  // the element [b_e, b_e+1) holding x, clamped
    const auto e = static_cast<int>(std::upper_bound(b.begin(), b.end(), x) - b.begin()) - 1;
    return std::clamp(e, 0, ne - 1);
  };
  const auto break_index = [&](double x) {
    return static_cast<int>(std::lower_bound(b.begin(), b.end(), x) - b.begin());
  };
  BasisElements E;
  const std::vector<double> g = U.greville();
  for (int i = 0; i < U.num_basis(); ++i) {
    E.first.push_back(std::min(break_index(U[i]), ne - 1));
    E.last.push_back(std::max(break_index(U[i + p + 1]) - 1, E.first.back()));
    E.greville.push_back(element_at(g[static_cast<std::size_t>(i)]));
  }
  return E;
}

}  // namespace

void patch_point_partition(const KnotVector& U, const KnotVector& V, int rank, int processes,
                           std::vector<int>& owner, std::vector<char>& reads) {
  const int nu = U.num_elements(), nv = V.num_elements();
  const std::array<int, 2> grid = processor_grid(processes, nu, nv);
  // the block column of each element column, the block row of each element row
  std::vector<int> col(static_cast<std::size_t>(nu)), row(static_cast<std::size_t>(nv));
  for (int i = 0; i < grid[0]; ++i) {
    const ElementBlock b = element_block(i, processes, nu, nv);
    std::fill(col.begin() + b.u0, col.begin() + b.u1, i);
  }
  for (int j = 0; j < grid[1]; ++j) {
    const ElementBlock b = element_block(j * grid[0], processes, nu, nv);
    std::fill(row.begin() + b.v0, row.begin() + b.v1, j);
  }
  const ElementBlock mine = element_block(rank, processes, nu, nv);
  const BasisElements Eu = basis_elements(U), Ev = basis_elements(V);
  const int mu = U.num_basis(), mv = V.num_basis();
  owner.assign(static_cast<std::size_t>(mu) * static_cast<std::size_t>(mv), 0);
  reads.assign(owner.size(), 0);
  for (int j = 0; j < mv; ++j)
    for (int i = 0; i < mu; ++i) {
      const auto k = static_cast<std::size_t>(i) + static_cast<std::size_t>(mu) * j;
      const auto ui = static_cast<std::size_t>(i), vj = static_cast<std::size_t>(j);
      owner[k] = col[static_cast<std::size_t>(Eu.greville[ui])] +
                 grid[0] * row[static_cast<std::size_t>(Ev.greville[vj])];
      reads[k] = Eu.first[ui] < mine.u1 && Eu.last[ui] >= mine.u0 && Ev.first[vj] < mine.v1 &&
                 Ev.last[vj] >= mine.v0;
    }
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
