// MUMPS called directly over the run's processes (a build with PETSc: MUMPS is PETSc's), for
// DistributedLinearSolver's direct method, with a nested dissection ordering of the whole
// matrix computed once per pattern on process 0 (METIS through CHOLMOD, cholmod_metis) and
// handed to MUMPS as its PERM_IN.
//
// Why not through PETSc's MUMPS interface: Debian 12's MUMPS is built with PORD as its only
// nested dissection (METIS and SCOTCH asked for fall back to PORD), whose orderings of shell
// tangents cost 27 % more floating-point work than METIS's (20.3 against 15.9 GFlop on the 160 x
// 160 plate; docs/parallel.md), and PETSc passes a user ordering to MUMPS only for a matrix
// centralized on one process. Here each process hands MUMPS the entries of its rows of PETSc's
// matrix (distributed assembled input, ICNTL(18) = 3), the analysis is MUMPS's sequential one on
// process 0 with the ordering given (ICNTL(7) = 1, ICNTL(28) = 1), and the right-hand side and
// the solution are dense on process 0 (the caller gathers and scatters them with PETSc).
//
// Notation: n unknowns; a process's entries (i, j, a_ij), 0-based here, 1-based for MUMPS; for
// a symmetric matrix only i >= j (MUMPS sums what it is given, SYM = 2: LDL^T with the inertia);
// otherwise all (SYM = 0: LU). INFOG(k) as in MUMPS's manual: INFOG(1) < 0 an error (the same
// on every process), INFOG(12) the negative pivots (with ICNTL(13) = 1 on any number of
// processes), INFOG(28) the null pivots (ICNTL(24) = 1).
// References: [MUMPS] Amestoy, Duff, L'Excellent, Koster, SIAM J. Matrix Anal. Appl. 23(1),
// 2001, and its users' guide 5.5; [METIS] Karypis, Kumar, SIAM J. Sci. Comput. 20(1), 1998;
// [CHOLMOD] Chen, Davis, Hager, Rajamanickam, ACM TOMS 35(3), 2008.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <dmumps_c.h>
#include <Eigen/Core>

namespace iga::petsc {

/// One MUMPS instance over PETSC_COMM_WORLD. Every member function is collective, and a
/// failure (false, with the reason in `why`) is the same on every process.
class MumpsDirect {
 public:
  MumpsDirect() = default;
  ~MumpsDirect();
  MumpsDirect(const MumpsDirect&) = delete;
  MumpsDirect& operator=(const MumpsDirect&) = delete;
  MumpsDirect(MumpsDirect&&) = delete;
  MumpsDirect& operator=(MumpsDirect&&) = delete;

  /// The analysis of the pattern of this process's entries (rows[k], cols[k]), 0-based, for
  /// an n x n matrix (symmetric: i >= j only). The arrays are copied.
  bool analyze(int n, bool symmetric, std::span<const int> rows, std::span<const int> cols,
               std::string& why);
  /// The factorization with this process's values, in the order of analyze's entries (read
  /// until the next factorize).
  bool factorize(std::span<const double> values, std::string& why);
  /// x = A^-1 b in place on process 0 (`rhs`: its n entries there; not read elsewhere).
  bool solve(double* rhs, std::string& why);
  /// INFOG(12) after a symmetric factorization, else -1.
  int negative_pivots() const { return symmetric_ && factorized_ ? id_.infog[11] : -1; }

 private:
  void start(bool symmetric);
  void end();
  void set_controls();
  void run(int job);
  std::string error(const char* phase) const;
  DMUMPS_STRUC_C id_{};
  bool live_ = false, symmetric_ = true, factorized_ = false;
  int n_ = 0;
  std::vector<MUMPS_INT> irn_, jcn_, perm_;
  std::vector<double> a_;
};

}  // namespace iga::petsc
