// Triplets summed into a kept sparse pattern; see sparse_assembly.hpp.
#include "iga/core/sparse_assembly.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace iga {

bool PatternAssembler::same_sequence(const std::vector<Triplet>& triplets, Eigen::Index rows,
                                     Eigen::Index cols) const {
  if (builds_ == 0 || pattern_.rows() != rows || pattern_.cols() != cols ||
      triplets.size() != slot_.size())
    return false;
  // Triplet k still belongs at slot_k: its row is the row index there, and slot_k lies in its
  // column's range (the columns' ranges are disjoint, so the entry is (i_k, j_k)).
  const auto* outer = pattern_.outerIndexPtr();
  const auto* inner = pattern_.innerIndexPtr();
  for (std::size_t k = 0; k < triplets.size(); ++k) {
    const Eigen::Index j = triplets[k].col(), s = slot_[k];
    if (j < 0 || j >= cols || inner[s] != triplets[k].row() || s < outer[j] || s >= outer[j + 1])
      return false;
  }
  return true;
}

void PatternAssembler::build(const std::vector<Triplet>& triplets, Eigen::Index rows,
                             Eigen::Index cols) {
  // The pattern (the entries setFromTriplets makes, explicit zeros kept) and each triplet's
  // place in it, in linear time: the triplets bucketed by column (a counting sort of their
  // indices), then per column its distinct rows (a mark per row), sorted, and each triplet's
  // place from its row's position (before: setFromTriplets on a copy of the triplets and a
  // binary search per triplet, three times the instructions).
  using Index = Matrix::StorageIndex;
  const std::size_t n = triplets.size();
  std::vector<Index> outer(static_cast<std::size_t>(cols) + 1, 0);  // first the bucket starts
  for (const Triplet& t : triplets) {
    if (t.row() < 0 || t.row() >= rows || t.col() < 0 || t.col() >= cols)
      throw std::invalid_argument("PatternAssembler: triplet (" + std::to_string(t.row()) + ", " +
                                  std::to_string(t.col()) + ") outside a " + std::to_string(rows) +
                                  " x " + std::to_string(cols) + " matrix");
    ++outer[static_cast<std::size_t>(t.col()) + 1];
  }
  for (std::size_t j = 0; j < static_cast<std::size_t>(cols); ++j) outer[j + 1] += outer[j];
  std::vector<Index> order(n);  // triplet indices by column, in their order within a column
  {
    std::vector<Index> next(outer.begin(), outer.end() - 1);
    for (std::size_t k = 0; k < n; ++k)
      order[static_cast<std::size_t>(next[static_cast<std::size_t>(triplets[k].col())]++)] =
          static_cast<Index>(k);
  }
  std::vector<Index> mark(static_cast<std::size_t>(rows), -1),
      where(static_cast<std::size_t>(rows));
  std::vector<Index> inner, starts(outer);  // starts: the buckets; outer becomes the pattern's
  inner.reserve(n / 4 + 16);
  outer[0] = 0;
  slot_.resize(n);
  for (std::size_t j = 0; j < static_cast<std::size_t>(cols); ++j) {
    const auto first = static_cast<std::ptrdiff_t>(inner.size());
    const auto b0 = static_cast<std::size_t>(starts[j]),
               b1 = static_cast<std::size_t>(starts[j + 1]);
    for (std::size_t b = b0; b < b1; ++b) {
      const auto r = static_cast<Index>(triplets[static_cast<std::size_t>(order[b])].row());
      if (mark[static_cast<std::size_t>(r)] == static_cast<Index>(j)) continue;
      mark[static_cast<std::size_t>(r)] = static_cast<Index>(j);
      inner.push_back(r);
    }
    std::sort(inner.begin() + first, inner.end());
    for (auto p = static_cast<std::size_t>(first); p < inner.size(); ++p)
      where[static_cast<std::size_t>(inner[p])] = static_cast<Index>(p);
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t k = static_cast<std::size_t>(order[b]);
      slot_[k] = where[static_cast<std::size_t>(triplets[k].row())];
    }
    outer[j + 1] = static_cast<Index>(inner.size());
  }
  const std::vector<double> zeros(inner.size(), 0.0);
  pattern_ = Eigen::Map<const Matrix>(rows, cols, static_cast<Eigen::Index>(inner.size()),
                                      outer.data(), inner.data(), zeros.data());
  ++builds_;
}

void PatternAssembler::assemble(const std::vector<Triplet>& triplets, Eigen::Index rows,
                                Eigen::Index cols, Matrix& K) {
  if (same_sequence(triplets, rows, cols))
    ++reuses_;
  else
    build(triplets, rows, cols);
  double* v = pattern_.valuePtr();
  std::fill(v, v + pattern_.nonZeros(), 0.0);
  for (std::size_t k = 0; k < triplets.size(); ++k) v[slot_[k]] += triplets[k].value();
  K = pattern_;
}

}  // namespace iga
