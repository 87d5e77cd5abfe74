// Triplets summed into a kept sparse pattern; see sparse_assembly.hpp.
#include "iga/core/sparse_assembly.hpp"

#include <algorithm>

namespace iga {

bool PatternAssembler::same_sequence(const std::vector<Triplet>& triplets, Eigen::Index rows,
                                     Eigen::Index cols) const {
  if (builds_ == 0 || pattern_.rows() != rows || pattern_.cols() != cols ||
      triplets.size() != rows_.size())
    return false;
  for (std::size_t k = 0; k < triplets.size(); ++k)
    if (triplets[k].row() != rows_[k] || triplets[k].col() != cols_[k]) return false;
  return true;
}

void PatternAssembler::build(const std::vector<Triplet>& triplets, Eigen::Index rows,
                             Eigen::Index cols) {
  // The pattern (the entries setFromTriplets makes, explicit zeros kept), then each triplet's
  // place in it by a search in its column's sorted row indices.
  std::vector<Triplet> zeros;
  zeros.reserve(triplets.size());
  rows_.resize(triplets.size());
  cols_.resize(triplets.size());
  for (std::size_t k = 0; k < triplets.size(); ++k) {
    rows_[k] = static_cast<int>(triplets[k].row());
    cols_[k] = static_cast<int>(triplets[k].col());
    zeros.emplace_back(rows_[k], cols_[k], 0.0);
  }
  pattern_.resize(rows, cols);
  pattern_.setFromTriplets(zeros.begin(), zeros.end());
  pattern_.makeCompressed();
  slot_.resize(triplets.size());
  const auto* outer = pattern_.outerIndexPtr();
  const auto* inner = pattern_.innerIndexPtr();
  for (std::size_t k = 0; k < triplets.size(); ++k) {
    const auto* first = inner + outer[cols_[k]];
    const auto* last = inner + outer[cols_[k] + 1];
    slot_[k] = std::lower_bound(first, last, rows_[k]) - inner;
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
