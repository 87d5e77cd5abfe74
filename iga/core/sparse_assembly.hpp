// Summing element contributions (triplets) into a sparse matrix with the pattern kept: while the
// sequence of (row, column) pairs of the triplets is that of the last call (the same elements,
// the same active contact points), the compressed pattern and the place of every triplet in it
// are reused and only the values are summed in; a new sequence (an active set that changed)
// builds them again. What is kept per triplet is its place alone (4 bytes): a call checks that
// each triplet's (row, column) is the entry at its place (its row index there, the place inside
// its column), which is what reusing the places needs. The values are those of Eigen's
// setFromTriplets bit for bit: duplicates are summed in the order of the triplets either way.
//
// Notation: t_k = (i_k, j_k, v_k) the triplets; slot_k the index of entry (i_k, j_k) in the
// matrix's value array; K_ij = sum over k with (i_k, j_k) = (i, j) of v_k.
#pragma once

#include <vector>

#include <Eigen/SparseCore>

namespace iga {

class PatternAssembler {
 public:
  using Triplet = Eigen::Triplet<double>;
  using Matrix = Eigen::SparseMatrix<double>;  // column major

  /// K (rows x cols) = the sum of the triplets (K's former contents are replaced).
  void assemble(const std::vector<Triplet>& triplets, Eigen::Index rows, Eigen::Index cols,
                Matrix& K);
  /// Calls that built the pattern, and calls that reused it.
  int builds() const { return builds_; }
  int reuses() const { return reuses_; }

 private:
  bool same_sequence(const std::vector<Triplet>& triplets, Eigen::Index rows,
                     Eigen::Index cols) const;
  void build(const std::vector<Triplet>& triplets, Eigen::Index rows, Eigen::Index cols);
  Matrix pattern_;                          // the last matrix: its pattern, compressed
  std::vector<Matrix::StorageIndex> slot_;  // slot_k
  int builds_ = 0, reuses_ = 0;
};

}  // namespace iga
