// What the PETSc solvers of a build with PETSc share (petsc_engine.cpp: one process,
// distributed_solver.cpp: the ranks of the run): error codes as messages, the solver's set-up
// (MUMPS with its inertia and null-pivot detection, or GMRES with GAMG and a tight tolerance,
// both open to PETSc's options), and the check of a factorization.
#pragma once

#include <petscksp.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include "iga/solvers/petsc_engine.hpp"

namespace iga::petsc {

inline bool finalized() {
  PetscBool done = PETSC_FALSE;
  PetscFinalized(&done);
  return done == PETSC_TRUE;
}

/// true if e is 0; else false with PETSc's message for `what` in `why`.
inline bool call(PetscErrorCode e, const char* what, std::string& why) {
  if (e == 0) return true;
  const char* text = nullptr;
  PetscErrorMessage(e, &text, nullptr);
  why = std::string("PETSc: ") + what + " failed (" + (text ? text : "error") + ")";
  return false;
}

/// The solver of `ksp` (its operators set): MUMPS's LDL^T (symmetric) or LU with the inertia
/// computed on any number of ranks (ICNTL(13) = 1) and null pivots detected (ICNTL(24) = 1);
/// or GMRES with GAMG to a relative 1e-10 (Newton needs its corrections to about the
/// residual's round-off). PETSc's options may change either.
inline bool configure(KSP ksp, LinearMethod method, bool symmetric, std::string& why) {
  PC pc = nullptr;
  if (!call(KSPGetPC(ksp, &pc), "KSPGetPC", why)) return false;
  if (method == LinearMethod::mumps) {
    Mat F = nullptr;
    if (!call(KSPSetType(ksp, KSPPREONLY), "KSPSetType", why) ||
        !call(PCSetType(pc, symmetric ? PCCHOLESKY : PCLU), "PCSetType", why) ||
        !call(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType", why) ||
        !call(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType", why) ||
        !call(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix", why) ||
        !call(MatMumpsSetIcntl(F, 13, 1), "MatMumpsSetIcntl", why) ||
        !call(MatMumpsSetIcntl(F, 24, 1), "MatMumpsSetIcntl", why))
      return false;
  } else if (!call(KSPSetType(ksp, KSPGMRES), "KSPSetType", why) ||
             !call(PCSetType(pc, PCGAMG), "PCSetType", why) ||
             !call(KSPSetTolerances(ksp, 1e-10, 1e-300, PETSC_DEFAULT, 2000), "KSPSetTolerances",
                   why)) {
    return false;
  }
  return call(KSPSetFromOptions(ksp), "KSPSetFromOptions", why);
}

/// The near null space of A for an algebraic multigrid preconditioner (GAMG reads it:
/// MatSetNearNullSpace): the columns of Z (A's rows; the same Z on every rank of A's
/// communicator), orthonormalized by modified Gram-Schmidt, columns that add less than 1e-10
/// of their norm left out. Nothing for an empty Z.
inline bool set_near_null_space(Mat A, const Eigen::MatrixXd& Z, std::string& why) {
  if (Z.cols() == 0) return true;
  Eigen::MatrixXd Q(Z.rows(), 0);
  for (Eigen::Index c = 0; c < Z.cols(); ++c) {
    Eigen::VectorXd v = Z.col(c);
    const double before = v.norm();
    for (Eigen::Index k = 0; k < Q.cols(); ++k) v -= Q.col(k).dot(v) * Q.col(k);
    if (!(v.norm() > 1e-10 * before)) continue;
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = v / v.norm();
  }
  PetscInt lo = 0, hi = 0;
  if (!call(MatGetOwnershipRange(A, &lo, &hi), "MatGetOwnershipRange", why)) return false;
  std::vector<Vec> vecs(static_cast<std::size_t>(Q.cols()), nullptr);
  bool ok = true;
  for (std::size_t k = 0; ok && k < vecs.size(); ++k) {
    PetscScalar* a = nullptr;
    ok = call(MatCreateVecs(A, &vecs[k], nullptr), "MatCreateVecs", why) &&
         call(VecGetArray(vecs[k], &a), "VecGetArray", why);
    if (!ok) break;
    for (PetscInt i = lo; i < hi; ++i) a[i - lo] = Q(i, static_cast<Eigen::Index>(k));
    ok = call(VecRestoreArray(vecs[k], &a), "VecRestoreArray", why);
  }
  MatNullSpace space = nullptr;
  ok = ok &&
       call(MatNullSpaceCreate(PetscObjectComm(reinterpret_cast<PetscObject>(A)), PETSC_FALSE,
                               static_cast<PetscInt>(vecs.size()), vecs.data(), &space),
            "MatNullSpaceCreate", why) &&
       call(MatSetNearNullSpace(A, space), "MatSetNearNullSpace", why);
  if (space) MatNullSpaceDestroy(&space);
  for (Vec& v : vecs)
    if (v) VecDestroy(&v);
  return ok;
}

/// After KSPSetUp: the preconditioner's failure, MUMPS's null pivots (INFOG(28)) as a singular
/// matrix, and the inertia's negative count of a symmetric MUMPS factorization (else -1).
inline bool check_factorization(KSP ksp, LinearMethod method, bool symmetric, int& negative,
                                std::string& why) {
  PC pc = nullptr;
  PCFailedReason failed = PC_NOERROR;
  negative = -1;
  if (!call(KSPGetPC(ksp, &pc), "KSPGetPC", why) || !call(PCSetUp(pc), "PCSetUp", why) ||
      !call(PCGetFailedReason(pc, &failed), "PCGetFailedReason", why))
    return false;
  if (failed != PC_NOERROR) {
    why = std::string(method == LinearMethod::mumps ? "MUMPS" : "PETSc preconditioner") +
          ": factorization failed (" + PCFailedReasons[failed] + ")";
    return false;
  }
  if (method != LinearMethod::mumps) return true;
  Mat F = nullptr;
  PetscInt null_pivots = 0;
  if (!call(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix", why) ||
      !call(MatMumpsGetInfog(F, 28, &null_pivots), "MatMumpsGetInfog", why))
    return false;
  if (null_pivots > 0) {
    why = "MUMPS: " + std::to_string(null_pivots) + " null pivot(s): the matrix is singular";
    return false;
  }
  if (!symmetric) return true;
  PetscInt neg = 0, zero = 0, pos = 0;
  if (!call(MatGetInertia(F, &neg, &zero, &pos), "MatGetInertia", why)) return false;
  negative = static_cast<int>(neg);
  return true;
}

}  // namespace iga::petsc
