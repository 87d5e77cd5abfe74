// The distributed linear solver over PETSc (a build with PETSc); see
// iga/solvers/distributed_solver.hpp.
#include <petscksp.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "iga/parallel/communicator.hpp"
#include "iga/parallel/dof_layout.hpp"
#include "iga/solvers/distributed_solver.hpp"
#include "iga/solvers/with_petsc/mumps_direct.hpp"
#include "iga/solvers/with_petsc/petsc_common.hpp"

namespace iga {

using petsc::call;

struct DistributedLinearSolver::Impl {
  LinearMethod method = LinearMethod::mumps;
  Mat A = nullptr;
  KSP ksp = nullptr;
  Vec b = nullptr, x = nullptr, x_all = nullptr, b_zero = nullptr;
  VecScatter to_all = nullptr, to_zero = nullptr;
  PetscInt n = -1;
  bool symmetric = true;
  /// this rank's part's pattern (column starts, row indices), the pattern's signature
  std::vector<int> outer, inner;
  std::string message;
  int negative = -1;
  bool reused = false;
  bool ready = false;
  Eigen::MatrixXd modes;              ///< the Krylov method's near null space (empty: none)
  const DofLayout* layout = nullptr;  ///< rows by owner, ghosts (null: even split, replicated)
  /// The direct method: MUMPS called directly (mumps_direct.hpp) on this rank's rows of A (else
  /// through PETSc's interface: the PETSc option -iga_mumps_through_petsc, PORD's ordering on
  /// Debian 12), and the values of those rows handed to it (a symmetric matrix's lower triangle).
  std::unique_ptr<petsc::MumpsDirect> mumps;
  bool direct = false;
  std::vector<double> row_values;

  ~Impl() { destroy(); }
  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  Impl(Impl&&) = delete;
  Impl& operator=(Impl&&) = delete;

  void destroy() {
    if (petsc::finalized()) return;
    if (ksp) KSPDestroy(&ksp);
    if (A) MatDestroy(&A);
    if (b) VecDestroy(&b);
    if (x) VecDestroy(&x);
    if (x_all) VecDestroy(&x_all);
    if (b_zero) VecDestroy(&b_zero);
    if (to_all) VecScatterDestroy(&to_all);
    if (to_zero) VecScatterDestroy(&to_zero);
    ksp = nullptr;
    A = nullptr;
    b = x = x_all = b_zero = nullptr;
    to_all = to_zero = nullptr;
  }

  /// A new matrix of this rank's pattern (collective), with its solver and vectors.
  bool create(std::string& why) {
    destroy();
    // the part's entries as coordinates, column by column (the order of its value array)
    std::vector<PetscInt> i(inner.begin(), inner.end()), j(inner.size());
    for (std::size_t c = 0; c + 1 < outer.size(); ++c)
      std::fill(j.begin() + outer[c], j.begin() + outer[c + 1], static_cast<PetscInt>(c));
    PetscInt local = PETSC_DECIDE;
    if (layout != nullptr) {  // the owners' rows: the layout's numbering
      const std::vector<int>& row = layout->rows();
      for (PetscInt& k : i) k = row[static_cast<std::size_t>(k)];
      for (PetscInt& k : j) k = row[static_cast<std::size_t>(k)];
      local = static_cast<PetscInt>(layout->owned().size());
    }
    if (!call(MatCreate(PETSC_COMM_WORLD, &A), "MatCreate", why) ||
        !call(MatSetSizes(A, local, local, n, n), "MatSetSizes", why) ||
        !call(MatSetType(A, MATAIJ), "MatSetType", why) ||
        !call(MatSetPreallocationCOO(A, static_cast<PetscCount>(i.size()), i.data(), j.data()),
              "MatSetPreallocationCOO", why) ||
        !call(MatSetOption(A, MAT_SYMMETRIC, symmetric ? PETSC_TRUE : PETSC_FALSE), "MatSetOption",
              why) ||
        !call(MatCreateVecs(A, &x, &b), "MatCreateVecs", why) ||
        (layout == nullptr &&
         !call(VecScatterCreateToAll(x, &to_all, &x_all), "VecScatterCreateToAll", why)))
      return false;
    if (direct)  // b on rank 0 for MUMPS, x back to the rows' owners
      return call(VecScatterCreateToZero(b, &to_zero, &b_zero), "VecScatterCreateToZero", why);
    return call(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate", why) &&
           call(KSPSetOperators(ksp, A, A), "KSPSetOperators", why) &&
           petsc::configure(ksp, method, symmetric, why);
  }

  /// This rank's rows of A (its own unknowns; PETSc's numbering), as MUMPS takes them: the
  /// values, a symmetric matrix's lower triangle only, row by row (the diagonal block's entries,
  /// then the off-diagonal block's), and with `rows`, `cols` their places.
  bool own_rows(std::vector<int>* rows, std::vector<int>* cols, std::string& why) {
    Mat blocks[2] = {A, nullptr};
    const PetscInt* colmap = nullptr;
    PetscBool spread = PETSC_FALSE;
    PetscInt lo = 0, hi = 0;
    if (!call(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &spread),
              "PetscObjectTypeCompare", why) ||
        (spread && !call(MatMPIAIJGetSeqAIJ(A, &blocks[0], &blocks[1], &colmap),
                         "MatMPIAIJGetSeqAIJ", why)) ||
        !call(MatGetOwnershipRange(A, &lo, &hi), "MatGetOwnershipRange", why))
      return false;
    row_values.clear();
    for (int part = 0; part < 2; ++part) {
      Mat B = blocks[part];
      if (B == nullptr) continue;
      const PetscInt *ia = nullptr, *ja = nullptr;
      PetscInt rows_here = 0;
      PetscBool done = PETSC_FALSE;
      const PetscScalar* v = nullptr;
      if (!call(MatGetRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &rows_here, &ia, &ja, &done),
                "MatGetRowIJ", why) ||
          !done || !call(MatSeqAIJGetArrayRead(B, &v), "MatSeqAIJGetArrayRead", why))
        return false;
      for (PetscInt r = 0; r < rows_here; ++r)
        for (PetscInt k = ia[r]; k < ia[r + 1]; ++k) {
          const PetscInt i = lo + r, j = part == 0 ? lo + ja[k] : colmap[ja[k]];
          if (symmetric && i < j) continue;
          row_values.push_back(v[k]);
          if (rows != nullptr) {
            rows->push_back(static_cast<int>(i));
            cols->push_back(static_cast<int>(j));
          }
        }
      MatSeqAIJRestoreArrayRead(B, &v);
      MatRestoreRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &rows_here, &ia, &ja, &done);
    }
    return true;
  }

  /// MUMPS's analysis (a new pattern) and factorization of A's values (collective).
  bool factor_direct(std::string& why) {
    if (!mumps) mumps = std::make_unique<petsc::MumpsDirect>();
    std::vector<int> rows, cols;
    const bool read = reused ? own_rows(nullptr, nullptr, why) : own_rows(&rows, &cols, why);
    if (world().sum(static_cast<long long>(read ? 0 : 1)) != 0) return false;  // before MUMPS
    if (!reused && !mumps->analyze(static_cast<int>(n), symmetric, rows, cols, why)) {
      outer.clear();  // not kept: the next factorize analyses again
      return false;
    }
    if (!mumps->factorize(row_values, why)) return false;
    negative = mumps->negative_pivots();
    return true;
  }

  /// x = A^-1 b by MUMPS (collective): b gathered on rank 0, solved there, x sent back to the
  /// rows' owners.
  bool solve_direct(std::string& why) {
    PetscScalar* host = nullptr;
    bool ok = call(VecScatterBegin(to_zero, b, b_zero, INSERT_VALUES, SCATTER_FORWARD),
                   "VecScatterBegin", why) &&
              call(VecScatterEnd(to_zero, b, b_zero, INSERT_VALUES, SCATTER_FORWARD),
                   "VecScatterEnd", why) &&
              call(VecGetArray(b_zero, &host), "VecGetArray", why);
    // MUMPS's solve is collective: every rank takes part whatever happened here
    std::string mumps_why;
    const bool solved = mumps->solve(host, mumps_why);
    if (host != nullptr) VecRestoreArray(b_zero, &host);
    if (ok && !solved) {
      why = mumps_why;
      ok = false;
    }
    return ok &&
           call(VecScatterBegin(to_zero, b_zero, x, INSERT_VALUES, SCATTER_REVERSE),
                "VecScatterBegin", why) &&
           call(VecScatterEnd(to_zero, b_zero, x, INSERT_VALUES, SCATTER_REVERSE), "VecScatterEnd",
                why);
  }

  bool setup(const double* values, std::string& why) {
    return call(MatSetValuesCOO(A, values, INSERT_VALUES), "MatSetValuesCOO", why) &&
           (method != LinearMethod::krylov || petsc::set_near_null_space(A, modes, why)) &&
           call(KSPSetOperators(ksp, A, A), "KSPSetOperators", why) &&
           call(KSPSetUp(ksp), "KSPSetUp", why) &&
           petsc::check_factorization(ksp, method, symmetric, negative, why);
  }
};

DistributedLinearSolver::DistributedLinearSolver(LinearMethod method)
    : impl_(std::make_unique<Impl>()) {
  if (method == LinearMethod::suitesparse)
    throw std::invalid_argument("DistributedLinearSolver: suitesparse runs on one process only");
  ensure_petsc();
  impl_->method = method;
  PetscBool through_petsc = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-iga_mumps_through_petsc", &through_petsc);
  impl_->direct = method == LinearMethod::mumps && !through_petsc;
}

DistributedLinearSolver::~DistributedLinearSolver() = default;

LinearSolveStatus DistributedLinearSolver::factorize(const Eigen::SparseMatrix<double>& local,
                                                     bool symmetric) {
  if (local.rows() != local.cols() || !local.isCompressed())
    throw std::invalid_argument(
        "DistributedLinearSolver::factorize: the part must be square and "
        "compressed, got " +
        std::to_string(local.rows()) + " x " + std::to_string(local.cols()));
  Impl& m = *impl_;
  const Communicator& w = world();
  const auto n = static_cast<PetscInt>(local.rows());
  if (m.layout != nullptr && m.layout->size() != n)
    throw std::invalid_argument("DistributedLinearSolver::factorize: a part of " +
                                std::to_string(n) + " unknowns for a layout of " +
                                std::to_string(m.layout->size()));
  const int* outer = local.outerIndexPtr();
  const int* inner = local.innerIndexPtr();
  const auto nnz = static_cast<std::size_t>(local.nonZeros());
  const bool same = m.A != nullptr && n == m.n && symmetric == m.symmetric &&
                    m.outer.size() == static_cast<std::size_t>(n) + 1 && m.inner.size() == nnz &&
                    std::equal(m.outer.begin(), m.outer.end(), outer) &&
                    std::equal(m.inner.begin(), m.inner.end(), inner);
  m.reused = w.sum(static_cast<long long>(same ? 0 : 1)) == 0;  // every rank's unchanged
  std::string why;
  bool ok = true;
  if (!m.reused) {
    m.n = n;
    m.symmetric = symmetric;
    m.outer.assign(outer, outer + n + 1);
    m.inner.assign(inner, inner + nnz);
    ok = m.create(why);
  }
  if (m.direct) {
    // A's values summed from the parts, then MUMPS; a failure before MUMPS is agreed on first
    // (MUMPS's calls are collective)
    ok = ok && call(MatSetValuesCOO(m.A, local.valuePtr(), INSERT_VALUES), "MatSetValuesCOO", why);
    if (w.sum(static_cast<long long>(ok ? 0 : 1)) == 0)
      ok = m.factor_direct(why);
    else
      ok = false;
  } else {
    ok = ok && m.setup(local.valuePtr(), why);
  }
  // A failure on one rank is every rank's (their next steps must agree).
  m.ready = w.sum(static_cast<long long>(ok ? 0 : 1)) == 0;
  if (m.ready) {
    m.message.clear();
    return LinearSolveStatus::success;
  }
  m.message = w.first_message(why);
  return LinearSolveStatus::singular;
}

LinearSolveStatus DistributedLinearSolver::factorize(
    int n, const std::vector<Eigen::Triplet<double>>& local, bool symmetric) {
  Eigen::SparseMatrix<double> part(n, n);
  part.setFromTriplets(local.begin(), local.end());
  part.makeCompressed();
  return factorize(part, symmetric);
}

namespace {

/// A solve's outcome, the same on every rank: a success where every rank's solve succeeded and
/// its x is finite (with a layout a rank holds only its part of x), else the first rank's reason.
LinearSolveStatus agree_on_solution(bool ok, std::string why, const Eigen::VectorXd& x,
                                    std::string& message) {
  if (ok && !x.allFinite()) {
    why = "the solution is not finite";
    ok = false;
  }
  const Communicator& w = world();
  if (w.sum(static_cast<long long>(ok ? 0 : 1)) == 0) return LinearSolveStatus::success;
  message = w.first_message(why);
  if (message.empty()) message = "the solution is not finite";
  return LinearSolveStatus::singular;
}

}  // namespace

LinearSolveStatus DistributedLinearSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Impl& m = *impl_;
  if (!m.ready) {
    m.message = "solve() without a successful factorization";
    return LinearSolveStatus::not_factorized;
  }
  if (b.size() != m.n)
    throw std::invalid_argument("DistributedLinearSolver::solve: right-hand side of size " +
                                std::to_string(b.size()) + " for " + std::to_string(m.n) +
                                " unknowns");
  std::string why;
  PetscInt lo = 0, hi = 0;
  PetscScalar* bl = nullptr;
  bool ok = call(VecGetOwnershipRange(m.b, &lo, &hi), "VecGetOwnershipRange", why) &&
            call(VecGetArray(m.b, &bl), "VecGetArray", why);
  if (ok) {
    if (m.layout != nullptr) {  // this rank's own entries, complete here
      const std::vector<int>& own = m.layout->owned();
      for (std::size_t k = 0; k < own.size(); ++k) bl[k] = b[own[k]];
    } else {
      std::copy(b.data() + lo, b.data() + hi, bl);
    }
    ok = call(VecRestoreArray(m.b, &bl), "VecRestoreArray", why);
  }
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  if (m.direct) {
    // MUMPS's solve is collective: a failure before it is agreed on first
    ok = world().sum(static_cast<long long>(ok ? 0 : 1)) == 0 && m.solve_direct(why);
  } else {
    ok = ok && call(KSPSolve(m.ksp, m.b, m.x), "KSPSolve", why) &&
         call(KSPGetConvergedReason(m.ksp, &reason), "KSPGetConvergedReason", why);
  }
  if (ok && reason < 0) {
    why = std::string("PETSc KSP did not converge: ") + KSPConvergedReasons[reason];
    ok = false;
  }
  if (m.layout != nullptr) {
    // the owners' entries, then the ghosts' from their owners (collective whatever happened)
    x.setZero(m.n);
    const PetscScalar* xl = nullptr;
    ok = ok && call(VecGetArrayRead(m.x, &xl), "VecGetArrayRead", why);
    if (ok) {
      const std::vector<int>& own = m.layout->owned();
      for (std::size_t k = 0; k < own.size(); ++k) x[own[k]] = xl[k];
      VecRestoreArrayRead(m.x, &xl);
    }
    m.layout->update_ghosts(x);
  } else {
    ok = ok &&
         call(VecScatterBegin(m.to_all, m.x, m.x_all, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterBegin", why) &&
         call(VecScatterEnd(m.to_all, m.x, m.x_all, INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterEnd", why);
    if (ok) {
      const PetscScalar* xa = nullptr;
      ok = call(VecGetArrayRead(m.x_all, &xa), "VecGetArrayRead", why);
      if (ok) {
        x = Eigen::Map<const Eigen::VectorXd>(xa, m.n);
        VecRestoreArrayRead(m.x_all, &xa);
      }
    }
  }
  return agree_on_solution(ok, why, x, m.message);
}

void DistributedLinearSolver::set_near_null_space(const Eigen::MatrixXd& Z) {
  const DofLayout* l = impl_->layout;
  if (l == nullptr || Z.cols() == 0) {
    impl_->modes = Z;
    return;
  }
  // the rows in the matrix's numbering (the owners')
  impl_->modes.resize(Z.rows(), Z.cols());
  for (Eigen::Index i = 0; i < Z.rows(); ++i)
    impl_->modes.row(l->rows()[static_cast<std::size_t>(i)]) = Z.row(i);
}

void DistributedLinearSolver::set_layout(const DofLayout* layout) {
  if (layout == impl_->layout) return;
  impl_->layout = layout;
  impl_->outer.clear();  // a new matrix at the next factorize()
  impl_->inner.clear();
  impl_->ready = false;
}

const std::string& DistributedLinearSolver::message() const {
  return impl_->message;
}
int DistributedLinearSolver::negative_pivots() const {
  return impl_->negative;
}
bool DistributedLinearSolver::reused_analysis() const {
  return impl_->reused;
}
std::pair<int, int> DistributedLinearSolver::owned_rows() const {
  PetscInt lo = 0, hi = 0;
  if (impl_->A) MatGetOwnershipRange(impl_->A, &lo, &hi);
  return {static_cast<int>(lo), static_cast<int>(hi)};
}

}  // namespace iga
