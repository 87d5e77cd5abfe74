// Tests of PatternAssembler (iga/core/sparse_assembly.hpp): the matrix of setFromTriplets bit for
// bit, the pattern reused while the triplets' sequence is unchanged and built again when it
// changes.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "iga/core/sparse_assembly.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_sparse_assembly {

using namespace iga;
using Triplet = Eigen::Triplet<double>;
using Matrix = Eigen::SparseMatrix<double>;

namespace {

std::vector<Triplet> random_triplets(int n, int count, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Triplet> t;
  for (int k = 0; k < count; ++k) t.emplace_back(index(gen), index(gen), value(gen));
  for (int k = 0; k < count / 4; ++k) t.push_back(t[static_cast<std::size_t>(k)]);  // duplicates
  return t;
}

void check_same(const Matrix& a, const Matrix& b) {
  REQUIRE(a.rows() == b.rows());
  REQUIRE(a.cols() == b.cols());
  REQUIRE(a.nonZeros() == b.nonZeros());
  for (Eigen::Index j = 0; j <= a.outerSize(); ++j)
    REQUIRE(a.outerIndexPtr()[j] == b.outerIndexPtr()[j]);
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k) {
    REQUIRE(a.innerIndexPtr()[k] == b.innerIndexPtr()[k]);
    REQUIRE(a.valuePtr()[k] == b.valuePtr()[k]);  // the same sums in the same order
  }
}

}  // namespace

TEST_CASE("PatternAssembler: setFromTriplets' matrix, the pattern kept while the sequence is",
          "[iga][core][sparse]") {
  PatternAssembler assembler;
  std::vector<Triplet> t = random_triplets(50, 400, 3u);
  Matrix K, ref;
  ref.resize(50, 50);
  ref.setFromTriplets(t.begin(), t.end());
  assembler.assemble(t, 50, 50, K);
  check_same(K, ref);
  CHECK(assembler.builds() == 1);

  // new values, same sequence: reused
  std::mt19937 gen(9u);
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  for (Triplet& x : t) x = Triplet(x.row(), x.col(), value(gen));
  ref.setFromTriplets(t.begin(), t.end());
  assembler.assemble(t, 50, 50, K);
  check_same(K, ref);
  CHECK(assembler.builds() == 1);
  CHECK(assembler.reuses() == 1);

  // one triplet more (a contact point became active): built again
  t.emplace_back(7, 44, 0.5);
  ref.setFromTriplets(t.begin(), t.end());
  assembler.assemble(t, 50, 50, K);
  check_same(K, ref);
  CHECK(assembler.builds() == 2);

  // the same count in another order: built again (the places differ)
  std::swap(t.front(), t.back());
  ref.setFromTriplets(t.begin(), t.end());
  assembler.assemble(t, 50, 50, K);
  check_same(K, ref);
  CHECK(assembler.builds() == 3);

  // a triplet moved to another column, its row kept: the row index at its place still matches,
  // its column's range does not: built again
  t[5] = Triplet(t[5].row(), (t[5].col() + 1) % 50, t[5].value());
  ref.setFromTriplets(t.begin(), t.end());
  assembler.assemble(t, 50, 50, K);
  check_same(K, ref);
  CHECK(assembler.builds() == 4);
  // ... and moved within its column: built again
  t[6] = Triplet((t[6].row() + 1) % 50, t[6].col(), t[6].value());
  ref.setFromTriplets(t.begin(), t.end());
  assembler.assemble(t, 50, 50, K);
  check_same(K, ref);
  CHECK(assembler.builds() == 5);

  // another size: built again; no triplets: an empty matrix of that size
  assembler.assemble({}, 7, 7, K);
  CHECK(K.rows() == 7);
  CHECK(K.nonZeros() == 0);
  CHECK(assembler.builds() == 6);
}

}  // namespace test_sparse_assembly
