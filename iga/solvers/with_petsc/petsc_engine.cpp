// MUMPS and PETSc's Krylov solvers behind LinearSolver (a build with PETSc); see
// iga/solvers/petsc_engine.hpp.
#include <petscksp.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "iga/parallel/communicator.hpp"
#include "iga/solvers/petsc_engine.hpp"
#include "iga/solvers/with_petsc/petsc_common.hpp"

namespace iga {

namespace {

using petsc::call;

/// A matrix in PETSc (sequential AIJ over this engine's arrays, which keep its pattern) and the
/// solver of one process.
class SeqEngine final : public PetscEngine {
 public:
  explicit SeqEngine(LinearMethod method) : method_(method) { ensure_petsc(); }
  ~SeqEngine() override { destroy(); }
  SeqEngine(const SeqEngine&) = delete;
  SeqEngine& operator=(const SeqEngine&) = delete;
  SeqEngine(SeqEngine&&) = delete;
  SeqEngine& operator=(SeqEngine&&) = delete;

  bool factorize(const Eigen::SparseMatrix<double>& A, bool symmetric, std::string& why) override {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> csr = A;  // PETSc's AIJ: rows
    const auto n = static_cast<PetscInt>(csr.rows());
    const auto nnz = static_cast<std::size_t>(csr.nonZeros());
    reused_ = mat_ != nullptr && n == n_ && symmetric == symmetric_ && values_.size() == nnz &&
              std::equal(rows_.begin(), rows_.end(), csr.outerIndexPtr()) &&
              std::equal(cols_.begin(), cols_.end(), csr.innerIndexPtr());
    if (!reused_) {
      destroy();
      n_ = n;
      symmetric_ = symmetric;
      rows_.assign(csr.outerIndexPtr(), csr.outerIndexPtr() + n + 1);
      cols_.assign(csr.innerIndexPtr(), csr.innerIndexPtr() + nnz);
      values_.assign(csr.valuePtr(), csr.valuePtr() + nnz);
      if (!call(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, n, n, rows_.data(), cols_.data(),
                                          values_.data(), &mat_),
                "MatCreateSeqAIJWithArrays", why) ||
          !call(MatSetOption(mat_, MAT_SYMMETRIC, symmetric ? PETSC_TRUE : PETSC_FALSE),
                "MatSetOption", why) ||
          !setup_ksp(why))
        return false;
    } else {
      // New values through PETSc's accessor, which marks the matrix changed: the preconditioner
      // factorizes again (numerically only: the pattern is the same).
      PetscScalar* v = nullptr;
      if (!call(MatSeqAIJGetArray(mat_, &v), "MatSeqAIJGetArray", why)) return false;
      std::copy(csr.valuePtr(), csr.valuePtr() + nnz, v);
      if (!call(MatSeqAIJRestoreArray(mat_, &v), "MatSeqAIJRestoreArray", why) ||
          !call(KSPSetOperators(ksp_, mat_, mat_), "KSPSetOperators", why))
        return false;
    }
    if (method_ == LinearMethod::krylov && !petsc::set_near_null_space(mat_, modes_, why))
      return false;
    return call(KSPSetUp(ksp_), "KSPSetUp", why) &&
           petsc::check_factorization(ksp_, method_, symmetric, negative_, why);
  }

  void set_near_null_space(const Eigen::MatrixXd& Z) override { modes_ = Z; }

  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, std::string& why) override {
    x.resize(b.size());
    Vec vb = nullptr, vx = nullptr;
    const auto n = static_cast<PetscInt>(b.size());
    bool ok = call(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, b.data(), &vb), "VecCreate", why) &&
              call(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, x.data(), &vx), "VecCreate", why) &&
              call(KSPSolve(ksp_, vb, vx), "KSPSolve", why);
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    PetscInt its = 0;
    if (ok)
      ok = call(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason", why) &&
           call(KSPGetIterationNumber(ksp_, &its), "KSPGetIterationNumber", why);
    VecDestroy(&vb);
    VecDestroy(&vx);
    if (ok && reason < 0) {
      why = std::string("PETSc KSP did not converge: ") + KSPConvergedReasons[reason] + " after " +
            std::to_string(its) + " iterations";
      ok = false;
    }
    return ok;
  }

  int negative_pivots() const override { return negative_; }
  bool reused_analysis() const override { return reused_; }

 private:
  bool setup_ksp(std::string& why) {
    return call(KSPCreate(PETSC_COMM_SELF, &ksp_), "KSPCreate", why) &&
           call(KSPSetOperators(ksp_, mat_, mat_), "KSPSetOperators", why) &&
           petsc::configure(ksp_, method_, symmetric_, why);
  }

  void destroy() {
    if (petsc::finalized()) return;  // at exit, after PETSc: its objects went with it
    if (ksp_) KSPDestroy(&ksp_);
    if (mat_) MatDestroy(&mat_);
    ksp_ = nullptr;
    mat_ = nullptr;
  }

  LinearMethod method_;
  Mat mat_ = nullptr;
  KSP ksp_ = nullptr;
  PetscInt n_ = -1;
  bool symmetric_ = true;
  std::vector<PetscInt> rows_, cols_;
  std::vector<PetscScalar> values_;  ///< the matrix's values, which PETSc reads in place
  int negative_ = -1;
  bool reused_ = false;
  Eigen::MatrixXd modes_;  ///< the Krylov method's near null space (empty: none)
};

}  // namespace

std::unique_ptr<PetscEngine> make_petsc_engine(LinearMethod method) {
  if (method == LinearMethod::suitesparse)
    throw std::invalid_argument("make_petsc_engine: suitesparse is not a PETSc solver");
  return std::make_unique<SeqEngine>(method);
}

}  // namespace iga
