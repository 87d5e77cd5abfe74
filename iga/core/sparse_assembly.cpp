// Triplets summed into a kept sparse pattern; see sparse_assembly.hpp.
#include "iga/core/sparse_assembly.hpp"

#include <algorithm>

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
  // The pattern (the entries setFromTriplets makes, explicit zeros kept), then each triplet's
  // place in it by a search in its column's sorted row indices.
  {
    std::vector<Triplet> zeros;
    zeros.reserve(triplets.size());
    for (const Triplet& t : triplets) zeros.emplace_back(t.row(), t.col(), 0.0);
    pattern_.resize(rows, cols);
    pattern_.setFromTriplets(zeros.begin(), zeros.end());
  }
  pattern_.makeCompressed();
  slot_.resize(triplets.size());
  const auto* outer = pattern_.outerIndexPtr();
  const auto* inner = pattern_.innerIndexPtr();
  for (std::size_t k = 0; k < triplets.size(); ++k) {
    const auto* first = inner + outer[triplets[k].col()];
    const auto* last = inner + outer[triplets[k].col() + 1];
    slot_[k] = static_cast<Matrix::StorageIndex>(
        std::lower_bound(first, last, static_cast<Matrix::StorageIndex>(triplets[k].row())) -
        inner);
  }
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
