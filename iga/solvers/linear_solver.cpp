// Sparse direct solvers behind one interface: CHOLMOD LL^T with UMFPACK LU as the general solver
// and the fallback. [CHOLMOD] Chen, Davis, Hager, Rajamanickam, ACM TOMS 35(3), 2008;
// [UMFPACK] Davis, ACM TOMS 30(2), 2004.
#include "iga/solvers/linear_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "iga/parallel/communicator.hpp"
#include "iga/solvers/distributed_solver.hpp"

#include <omp.h>
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

namespace iga {

namespace {

/// While alive, OpenMP regions run on the calling thread alone (max-active-levels 0), the
/// previous setting restored after. CHOLMOD of SuiteSparse 5 (Debian 12) opens regions of a
/// fixed 4 threads (its compile-time CHOLMOD_OMP_NUM_THREADS, whatever OMP_NUM_THREADS says) in
/// the supernodal factorization, several per supernode for loops of a few thousand entries:
/// their start-ups and barriers cost more than the threads share (some 250,000 futex calls and
/// a second core half busy for one factorization of the 160 x 160 plate;
/// bench_linear_solver's LinearSolver against plain CHOLMOD: 1.26 s -> 0.57 s at 160 x 160,
/// 264 -> 94 ms at 80 x 80, 10 -> 2 ms at 20 x 20 on 2 cores). The factorizations run alone,
/// between the element loops, which keep their threads.
class SerialRegions {
 public:
  SerialRegions() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialRegions() { omp_set_max_active_levels(levels_); }
  SerialRegions(const SerialRegions&) = delete;
  SerialRegions& operator=(const SerialRegions&) = delete;

 private:
  int levels_;
};

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// CHOLMOD, supernodal or simplicial as CHOLMOD's flop count decides, but always LL^T: the
/// default simplicial LDL^T (no pivoting) would "succeed" on indefinite matrices, whereas LL^T
/// stops at the first pivot that is not positive, which is what triggers the UMFPACK fallback.
class Cholmod : public Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
 public:
  Cholmod() {
    cholmod().supernodal = CHOLMOD_AUTO;
    cholmod().final_asis = 1;
    cholmod().final_ll = 1;  // simplicial factorizations are LL^T too
    cholmod().print = 0;     // library code does not print (CHOLMOD warns on stdout otherwise)
  }
  /// The column at which the last factorization stopped (n on success).
  long minor_column() const {
    return m_cholmodFactor ? static_cast<long>(m_cholmodFactor->minor) : 0;
  }
  /// CHOLMOD's cheap reciprocal condition estimate, (min L_ii / max L_ii)^2.
  double rcond() { return m_cholmodFactor ? cholmod_rcond(m_cholmodFactor, &cholmod()) : 0.0; }
  /// CHOLMOD's status of the last call (negative: error, positive: warning).
  int library_status() { return cholmod().status; }
};

/// CHOLMOD simplicial LDL^T, for symmetric indefinite matrices: no pivoting, so it factorizes
/// any matrix whose leading minors (after the fill-reducing permutation) are not singular; its
/// solutions are checked (LinearSolver::solve).
class CholmodLdlt : public Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
 public:
  CholmodLdlt() {
    cholmod().supernodal = CHOLMOD_SIMPLICIAL;
    cholmod().final_asis = 1;
    cholmod().final_ll = 0;  // LDL^T
    cholmod().print = 0;
  }
  bool factorized() const {
    return m_cholmodFactor && m_cholmodFactor->minor == m_cholmodFactor->n &&
           m_cholmodFactor->is_ll == 0 && m_cholmodFactor->is_super == 0;
  }
  /// The number of negative entries of D, or -1 if one is zero or not finite.
  int negative_pivots() const {
    const cholmod_factor* L = m_cholmodFactor;
    const auto* p = static_cast<const int*>(L->p);
    const auto* x = static_cast<const double*>(L->x);
    int negative = 0;
    for (std::size_t j = 0; j < L->n; ++j) {
      const double d = x[p[j]];  // the first entry of column j of the unit L holds D_jj
      if (!std::isfinite(d) || d == 0.0) return -1;
      negative += d < 0.0 ? 1 : 0;
    }
    return negative;
  }
  int library_status() { return cholmod().status; }
  /// CHOLMOD's estimate from D, (min |D_jj| / max |D_jj|).
  double rcond() { return m_cholmodFactor ? cholmod_rcond(m_cholmodFactor, &cholmod()) : 0.0; }
};

/// UMFPACK with access to its status code and statistics.
class UmfPack : public Eigen::UmfPackLU<SparseMatrix> {
 public:
  int code() const { return static_cast<int>(m_fact_errorCode); }
  /// UMFPACK's reciprocal condition estimate, min |U_ii| / max |U_ii| (Info[UMFPACK_RCOND]).
  double rcond() const { return m_umfpackInfo(UMFPACK_RCOND); }
};

/// Equal sparsity patterns (both compressed).
bool same_pattern(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const Eigen::Index n = a.outerSize();
  const Eigen::Index nnz = a.nonZeros();
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + n + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + nnz, b.innerIndexPtr());
}

/// "(i, j) = nan" for the first non-finite entry of a compressed matrix, or "" if none.
std::string first_non_finite(const SparseMatrix& a) {
  const double* v = a.valuePtr();
  const Eigen::Index nnz = a.nonZeros();
  for (Eigen::Index k = 0; k < nnz; ++k) {
    if (std::isfinite(v[k])) continue;
    const int* outer = a.outerIndexPtr();
    const Eigen::Index col = std::upper_bound(outer, outer + a.outerSize() + 1, k) - outer - 1;
    std::ostringstream s;
    s << "matrix entry (" << a.innerIndexPtr()[k] << ", " << col << ") is " << v[k];
    return s.str();
  }
  return {};
}

}  // namespace

const char* to_string(LinearBackend b) {
  switch (b) {
    case LinearBackend::none:
      return "none";
    case LinearBackend::cholmod:
      return "cholmod";
    case LinearBackend::ldlt:
      return "ldlt";
    case LinearBackend::umfpack:
      return "umfpack";
    case LinearBackend::mumps:
      return "mumps";
    case LinearBackend::krylov:
      return "krylov";
  }
  return "?";
}

const char* to_string(LinearMethod m) {
  switch (m) {
    case LinearMethod::suitesparse:
      return "suitesparse";
    case LinearMethod::mumps:
      return "mumps";
    case LinearMethod::krylov:
      return "krylov";
  }
  return "?";
}

const char* to_string(LinearSolveStatus s) {
  switch (s) {
    case LinearSolveStatus::success:
      return "success";
    case LinearSolveStatus::singular:
      return "singular";
    case LinearSolveStatus::invalid_input:
      return "invalid_input";
    case LinearSolveStatus::not_factorized:
      return "not_factorized";
  }
  return "?";
}

struct LinearSolver::Impl {
  bool symmetric = true;
  SparseMatrix A;  // compressed copy of the last matrix; its pattern is the signature
  bool has_pattern = false;
  Cholmod llt;
  bool llt_analyzed = false;  // llt holds the analysis of A's pattern
  CholmodLdlt ldl;
  bool ldl_analyzed = false;
  bool prefer_ldlt = false;  // the last LDL^T had negative pivots: try it first
  int negative = 0;          // negative pivots of the current factorization (-1: unknown)
  double ldl_a_norm = 0.0;   // |A| (max norm) of the LDL^T factorization's matrix
  UmfPack lu;
  bool lu_analyzed = false;
  LinearBackend backend = LinearBackend::none;
  LinearMethod method = LinearMethod::suitesparse;
  std::unique_ptr<PetscEngine> engine;            ///< PETSc's solvers (method mumps or krylov)
  std::unique_ptr<DistributedLinearSolver> dist;  ///< the same over the ranks (distributed)
  const DofLayout* layout = nullptr;              ///< dist's ownership of the unknowns, or null
  Eigen::MatrixXd modes;  ///< the Krylov method's near null space (set_near_null_space)
  LinearSolveStatus status = LinearSolveStatus::not_factorized;
  std::string message;
  bool fell_back = false;
  bool reused = false;
  LinearSolverStats stats;

  /// PETSc's MUMPS or Krylov solver on A (engine), timed and counted; the pattern's reuse is
  /// the engine's.
  LinearSolveStatus factorize_petsc() {
    const Clock::time_point t0 = Clock::now();
    std::string why;
    if (method == LinearMethod::krylov) engine->set_near_null_space(modes);
    const bool ok = engine->factorize(A, symmetric, why);
    return petsc_factorized(t0, ok ? LinearSolveStatus::success : LinearSolveStatus::singular, why,
                            engine->reused_analysis(), engine->negative_pivots());
  }

  /// The bookkeeping of a PETSc factorization (one process or distributed) begun at t0.
  LinearSolveStatus petsc_factorized(Clock::time_point t0, LinearSolveStatus s,
                                     const std::string& why, bool reused_pattern, int negatives) {
    stats.time_factorize += seconds_since(t0);
    ++stats.factorizations;
    reused = reused_pattern;
    if (!reused) ++stats.analyses;
    if (s != LinearSolveStatus::success) return fail(s, why);
    backend = method == LinearMethod::mumps ? LinearBackend::mumps : LinearBackend::krylov;
    negative = negatives;
    status = LinearSolveStatus::success;
    return status;
  }

  /// This rank's part A of the matrix, summed over the ranks and factorized by `dist`
  /// (collective; `bad`: this rank's non-finite entry, if any, which fails every rank).
  LinearSolveStatus factorize_distributed(const SparseMatrix& A_local, const std::string& bad) {
    const Communicator& w = world();
    if (w.sum(static_cast<long long>(bad.empty() ? 0 : 1)) > 0) {
      reused = false;
      return fail(LinearSolveStatus::invalid_input, w.first_message(bad));
    }
    const Clock::time_point t0 = Clock::now();
    if (method == LinearMethod::krylov) dist->set_near_null_space(modes);
    const LinearSolveStatus s = dist->factorize(A_local, symmetric);  // A_local is compressed
    return petsc_factorized(t0, s, dist->message(), dist->reused_analysis(),
                            dist->negative_pivots());
  }

  LinearSolveStatus fail(LinearSolveStatus s, std::string why) {
    backend = LinearBackend::none;
    status = s;
    message = std::move(why);
    return s;
  }

  /// The symbolic analysis of A's pattern by a CHOLMOD factorization `d` (LL^T or LDL^T), unless
  /// it has it (`analyzed`); then its numeric factorization of A, timed and counted. false
  /// (with the reason in `why`) if the analysis failed.
  template <class Decomposition>
  bool cholmod_factorize(Decomposition& d, bool& analyzed, const char* name, std::string& why) {
    const SerialRegions serial;
    if (!analyzed) {
      const Clock::time_point t0 = Clock::now();
      d.analyzePattern(A);
      stats.time_analyze += seconds_since(t0);
      ++stats.analyses;
      if (d.library_status() < CHOLMOD_OK) {
        why = std::string(name) + " analysis failed (status " + std::to_string(d.library_status()) +
              ")";
        return false;
      }
      analyzed = true;
    }
    const Clock::time_point t0 = Clock::now();
    d.factorize(A);
    stats.time_factorize += seconds_since(t0);
    ++stats.factorizations;
    return true;
  }

  /// CHOLMOD LL^T of A; false (with the reason in `why`) if it is not positive definite.
  bool factorize_cholmod(std::string& why) {
    if (!cholmod_factorize(llt, llt_analyzed, "CHOLMOD", why)) return false;
    if (llt.info() == Eigen::Success) return true;
    ++stats.cholesky_failures;
    if (llt.library_status() < CHOLMOD_OK) {
      why = "CHOLMOD factorization failed (status " + std::to_string(llt.library_status()) + ")";
      llt_analyzed = false;  // start afresh next time
    } else {
      why = "CHOLMOD: not positive definite (pivot " + std::to_string(llt.minor_column() + 1) +
            " of " + std::to_string(A.rows()) + ")";
    }
    return false;
  }

  /// CHOLMOD simplicial LDL^T of A; false (with the reason in `why`) on a zero pivot or a
  /// pivot that is not finite.
  bool factorize_ldlt(std::string& why) {
    if (!cholmod_factorize(ldl, ldl_analyzed, "CHOLMOD LDL^T", why)) return false;
    ++stats.ldlt_factorizations;
    negative = ldl.factorized() ? ldl.negative_pivots() : -1;
    if (negative >= 0) {
      ldl_a_norm = 0.0;  // max column sum = max row sum (symmetric), for solve_ldlt's test
      for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
        double col = 0.0;
        for (SparseMatrix::InnerIterator it(A, j); it; ++it) col += std::abs(it.value());
        ldl_a_norm = std::max(ldl_a_norm, col);
      }
      return true;
    }
    ++stats.ldlt_rejected;
    if (ldl.library_status() < CHOLMOD_OK) ldl_analyzed = false;
    why = "CHOLMOD LDL^T: a zero pivot";
    return false;
  }

  /// UMFPACK LU of A.
  LinearSolveStatus factorize_umfpack(const std::string& prefix) {
    if (!lu_analyzed) {
      const Clock::time_point t0 = Clock::now();
      lu.analyzePattern(A);
      stats.time_analyze += seconds_since(t0);
      ++stats.analyses;
      if (lu.info() != Eigen::Success)
        return fail(
            LinearSolveStatus::invalid_input,
            prefix + "UMFPACK symbolic analysis failed (status " + std::to_string(lu.code()) + ")");
      lu_analyzed = true;
    }
    const Clock::time_point t0 = Clock::now();
    lu.factorize(A);
    stats.time_factorize += seconds_since(t0);
    ++stats.factorizations;
    if (lu.info() != Eigen::Success) {
      if (lu.code() == UMFPACK_WARNING_singular_matrix)
        return fail(LinearSolveStatus::singular, prefix + "UMFPACK: singular matrix (zero pivot)");
      lu_analyzed = false;
      return fail(
          LinearSolveStatus::invalid_input,
          prefix + "UMFPACK factorization failed (status " + std::to_string(lu.code()) + ")");
    }
    backend = LinearBackend::umfpack;
    negative = -1;
    status = LinearSolveStatus::success;
    return status;
  }

  /// The LDL^T solution of A x = b, refined once where its residual is above round-off;
  /// false if it stays above 1e-10 (|A| |x| + |b|) (max norms): the factorization without
  /// pivoting has grown, UMFPACK must do it.
  bool solve_ldlt(const VectorXd& b, VectorXd& x) {
    x = ldl.solve(b);
    if (ldl.info() != Eigen::Success || !x.allFinite()) return false;
    for (int pass = 0; pass < 2; ++pass) {
      const VectorXd r = b - A * x;
      const double scale = ldl_a_norm * x.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff();
      if (r.cwiseAbs().maxCoeff() <= 1e-14 * scale) return true;
      if (pass == 1) return r.cwiseAbs().maxCoeff() <= 1e-10 * scale;
      x += ldl.solve(r);  // one step of iterative refinement
      if (!x.allFinite()) return false;
    }
    return true;
  }
};

LinearSolver::LinearSolver(bool symmetric) : impl_(std::make_unique<Impl>()) {
  impl_->symmetric = symmetric;
}
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::set_symmetric(bool symmetric) {
  impl_->symmetric = symmetric;
}
bool LinearSolver::symmetric() const {
  return impl_->symmetric;
}
LinearSolveStatus LinearSolver::status() const {
  return impl_->status;
}
const std::string& LinearSolver::message() const {
  return impl_->message;
}
LinearBackend LinearSolver::backend() const {
  return impl_->backend;
}
bool LinearSolver::fell_back() const {
  return impl_->fell_back;
}
int LinearSolver::negative_pivots() const {
  return impl_->negative;
}
bool LinearSolver::reused_analysis() const {
  return impl_->reused;
}
const LinearSolverStats& LinearSolver::stats() const {
  return impl_->stats;
}

double LinearSolver::rcond() const {
  Impl& m = *impl_;
  if (m.backend == LinearBackend::none) return 0.0;
  if (m.A.rows() == 0 || m.engine) return 1.0;  // PETSc's solvers: not estimated
  if (m.backend == LinearBackend::ldlt) return m.ldl.rcond();
  return m.backend == LinearBackend::cholmod ? m.llt.rcond() : m.lu.rcond();
}

void LinearSolver::reset() {
  const bool symmetric = impl_->symmetric, distributed = impl_->dist != nullptr;
  const LinearMethod method = impl_->method;
  const DofLayout* layout = impl_->layout;
  impl_ = std::make_unique<Impl>();
  impl_->symmetric = symmetric;
  if (method != LinearMethod::suitesparse) set_method(method);
  set_distributed(distributed, layout);
}

void LinearSolver::set_method(LinearMethod method) {
  Impl& m = *impl_;
  if (m.dist && method == LinearMethod::suitesparse)
    throw std::invalid_argument("LinearSolver: a distributed solver needs a PETSc method");
  m.engine = method == LinearMethod::suitesparse ? nullptr : make_petsc_engine(method);
  if (m.dist) {
    m.dist = std::make_unique<DistributedLinearSolver>(method);
    m.dist->set_layout(m.layout);
  }
  m.method = method;
  m.backend = LinearBackend::none;
  m.status = LinearSolveStatus::not_factorized;
}

LinearMethod LinearSolver::method() const {
  return impl_->method;
}

void LinearSolver::set_distributed(bool distributed, const DofLayout* layout) {
  Impl& m = *impl_;
  if (!distributed) layout = nullptr;
  if (distributed == (m.dist != nullptr) && layout == m.layout) return;
  if (distributed && m.method == LinearMethod::suitesparse)
    throw std::invalid_argument(
        "LinearSolver: a problem spread over the ranks needs a PETSc solver (\"linear_solver\": "
        "\"mumps\" or \"krylov\")");
  m.layout = layout;
  if (!distributed) {
    m.dist = nullptr;
  } else if (!m.dist) {
    m.dist = std::make_unique<DistributedLinearSolver>(m.method);
  }
  if (m.dist) m.dist->set_layout(layout);
  m.backend = LinearBackend::none;
  m.status = LinearSolveStatus::not_factorized;
}

void LinearSolver::set_near_null_space(const Eigen::MatrixXd& Z) {
  impl_->modes = Z;
}

bool LinearSolver::distributed() const {
  return impl_->dist != nullptr;
}

LinearSolveStatus LinearSolver::factorize(const SparseMatrix& A) {
  if (A.rows() != A.cols())
    throw std::invalid_argument("LinearSolver::factorize: the matrix must be square, got " +
                                std::to_string(A.rows()) + " x " + std::to_string(A.cols()));
  if (!A.isCompressed()) {
    SparseMatrix compressed = A;
    compressed.makeCompressed();
    return factorize(compressed);
  }
  Impl& m = *impl_;
  m.backend = LinearBackend::none;
  m.fell_back = false;
  m.message.clear();
  const int analyses_before = m.stats.analyses;

  const std::string bad = first_non_finite(A);
  if (m.dist) return m.factorize_distributed(A, bad);
  if (!bad.empty()) {
    m.reused = false;
    return m.fail(LinearSolveStatus::invalid_input, bad);
  }

  // Pattern signature: reuse the analyses while it is unchanged, copying the values only.
  if (m.has_pattern && same_pattern(m.A, A)) {
    std::copy(A.valuePtr(), A.valuePtr() + A.nonZeros(), m.A.valuePtr());
  } else {
    m.A = A;
    m.has_pattern = true;
    m.llt_analyzed = false;
    m.ldl_analyzed = false;
    m.lu_analyzed = false;
  }

  if (m.engine && m.A.rows() > 0) return m.factorize_petsc();
  if (m.A.rows() == 0) {  // nothing to factorize; solve() returns an empty vector
    m.reused = true;
    m.backend = m.symmetric ? LinearBackend::cholmod : LinearBackend::umfpack;
    m.status = LinearSolveStatus::success;
    return m.status;
  }

  std::string prefix;
  if (m.symmetric) {
    std::string why;
    if (!m.prefer_ldlt) {
      if (m.factorize_cholmod(why)) {
        m.reused = m.stats.analyses == analyses_before;
        m.backend = LinearBackend::cholmod;
        m.negative = 0;
        m.status = LinearSolveStatus::success;
        return m.status;
      }
      m.fell_back = true;
      prefix = why + "; ";
    }
    if (m.factorize_ldlt(why)) {
      m.reused = m.stats.analyses == analyses_before;
      m.backend = LinearBackend::ldlt;
      m.prefer_ldlt = m.negative > 0;
      m.status = LinearSolveStatus::success;
      if (m.fell_back) m.message = prefix + "factorized by LDL^T";
      return m.status;
    }
    m.prefer_ldlt = false;
    prefix += why + "; ";
  }
  const LinearSolveStatus s = m.factorize_umfpack(prefix);
  m.reused = m.stats.analyses == analyses_before;
  if (s == LinearSolveStatus::success && m.fell_back) m.message = prefix + "factorized by UMFPACK";
  return s;
}

LinearSolveStatus LinearSolver::solve(const VectorXd& b, VectorXd& x) {
  if (&b == &x) {
    const VectorXd copy = b;  // NOLINT(performance-unnecessary-copy-initialization): b is x
    return solve(copy, x);
  }
  Impl& m = *impl_;
  if (m.backend == LinearBackend::none) {
    m.status = LinearSolveStatus::not_factorized;
    m.message = "solve() without a successful factorization";
    return m.status;
  }
  if (m.dist) {  // collective; the size is checked by the distributed solver
    const Clock::time_point t0 = Clock::now();
    const LinearSolveStatus st = m.dist->solve(b, x);
    m.stats.time_solve += seconds_since(t0);
    ++m.stats.solves;
    m.status = st;
    m.message = st == LinearSolveStatus::success ? std::string() : m.dist->message();
    return m.status;
  }
  if (b.size() != m.A.rows())
    throw std::invalid_argument("LinearSolver::solve: right-hand side of size " +
                                std::to_string(b.size()) + " for a matrix of size " +
                                std::to_string(m.A.rows()));
  if (b.size() == 0) {
    x.resize(0);
    m.status = LinearSolveStatus::success;
    return m.status;
  }
  const Clock::time_point t0 = Clock::now();
  bool ok = true;
  if (m.backend == LinearBackend::ldlt && !m.solve_ldlt(b, x)) {
    // The unpivoted factorization grew: UMFPACK, for this and later solves of this matrix.
    ++m.stats.ldlt_rejected;
    m.prefer_ldlt = false;
    m.stats.time_solve += seconds_since(t0);
    if (m.factorize_umfpack("CHOLMOD LDL^T: residual above round-off; ") !=
        LinearSolveStatus::success)
      return m.status;
    m.message = "CHOLMOD LDL^T: residual above round-off; factorized by UMFPACK";
    return solve(b, x);
  }
  if (m.engine) {
    std::string why;
    ok = m.engine->solve(b, x, why);
    if (!ok) {
      m.stats.time_solve += seconds_since(t0);
      ++m.stats.solves;
      m.status = LinearSolveStatus::singular;
      m.message = why;
      return m.status;
    }
  } else if (m.backend == LinearBackend::cholmod) {
    const SerialRegions serial;
    x = m.llt.solve(b);
    ok = m.llt.info() == Eigen::Success;
  } else if (m.backend == LinearBackend::umfpack) {
    x = m.lu.solve(b);
  }
  m.stats.time_solve += seconds_since(t0);
  ++m.stats.solves;
  if (!ok) {
    m.status = LinearSolveStatus::singular;
    m.message = "CHOLMOD solve failed";
    return m.status;
  }
  if (!x.allFinite()) {
    m.status = LinearSolveStatus::singular;
    m.message = std::string(to_string(m.backend)) +
                ": the solution is not finite (singular or badly scaled matrix)";
    return m.status;
  }
  m.status = LinearSolveStatus::success;
  return m.status;
}

LinearSolveStatus LinearSolver::solve(const SparseMatrix& A, const VectorXd& b, VectorXd& x) {
  const LinearSolveStatus s = factorize(A);
  if (s != LinearSolveStatus::success) return s;
  return solve(b, x);
}

}  // namespace iga
