/** kl_linear.cpp -- standalone benchmark driver for G+Smo's *linear*
    Kirchhoff-Love shell (gsKLShell module).

    Cases:
      scordelis : Scordelis-Lo roof (R=25, L=50 along y, +-40 deg arc, h=0.25,
                  E=4.32e8, nu=0, self weight 90 per unit area in -z,
                  rigid diaphragms at y=0 and y=50, u_y fixed at one corner).
                  Monitor: -u_z at the mid-point of the free edge
                  (x=25 sin40, y=25, z=25 cos40).
      pinched   : pinched cylinder with rigid diaphragms, one eighth
                  (R=300, y in [0,300], h=3, E=3e6, nu=0.3, P/4=0.25 in -z at
                  (0,300,300)); symmetry at x=0, z=0, y=300, diaphragm at y=0.
                  Monitor: -u_z under the load.

    Usage: kl_linear --case scordelis|pinched --n N --degree p

    Prints a single JSON line.  Linear path: gsThinShellAssembler<3,real_t,true>
    with gsMaterialMatrixLinear<3,real_t> (St. Venant-Kirchhoff, linear),
    assemble() once, solve with gsSparseSolver<>::SimplicialLDLT (Eigen's
    sparse direct LDL^T with AMD ordering), constructDisplacement(), evaluate.
*/

#include <gismo.h>
// Header-only (GISMO_BUILD_LIB off) use of gsKLShell: gsMaterialMatrixXml.h must
// come first, it declares the XML helpers used by the material .hpp files.
#include <gsKLShell/src/gsMaterialMatrixXml.h>

#include <gsKLShell/src/gsMaterialMatrixContainer.h>
#include <gsKLShell/src/gsMaterialMatrixLinear.h>
#include <gsKLShell/src/gsThinShellAssembler.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

using namespace gismo;

namespace {
typedef std::chrono::steady_clock Clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void usage() {
  std::fprintf(stderr, "usage: kl_linear --case scordelis|pinched --n N --degree p\n");
}

/// Tensor NURBS surface: exact rational quadratic circular arc in the x-z
/// plane (parameter u, 3 control points, weights 1,w,1) times a linear
/// segment in y (parameter v, degree 1) from y=0 to y=Ly.
gsTensorNurbs<2, real_t> makeArcSurface(const real_t x[3], const real_t z[3], const real_t w[3],
                                        const real_t Ly) {
  gsKnotVector<real_t> ku(0, 1, 0, 3);  // degree 2, one element
  gsKnotVector<real_t> kv(0, 1, 0, 2);  // degree 1, one element
  gsMatrix<real_t> coefs(6, 3), weights(6, 1);
  for (index_t j = 0; j != 2; ++j)    // v (y) index, slow
    for (index_t i = 0; i != 3; ++i)  // u (arc) index, fast
    {
      const index_t k = i + 3 * j;
      coefs(k, 0) = x[i];
      coefs(k, 1) = j * Ly;
      coefs(k, 2) = z[i];
      weights(k, 0) = w[i];
    }
  return gsTensorNurbs<2, real_t>(ku, kv, give(coefs), give(weights));
}
}  // namespace

int main(int argc, char* argv[]) {
  std::string testCase;
  index_t N = -1, p = -1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--case") && i + 1 < argc)
      testCase = argv[++i];
    else if (!std::strcmp(argv[i], "--n") && i + 1 < argc)
      N = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--degree") && i + 1 < argc)
      p = std::atoi(argv[++i]);
    else {
      usage();
      return 2;
    }
  }
  if ((testCase != "scordelis" && testCase != "pinched") || N < 1 || p < 2) {
    usage();
    return 2;
  }

  const bool scordelis = (testCase == "scordelis");

  // ------------------------------------------------------------------
  // Geometry (not timed): exact NURBS, degree elevation, h-refinement
  // ------------------------------------------------------------------
  real_t thickness, E_modulus, poisson;
  gsMatrix<real_t> monitorPoint(2, 1);
  gsVector<real_t> monitorXYZ(3);
  gsMultiPatch<real_t> mp;
  if (scordelis) {
    const real_t R = 25, L = 50, th = 40.0 * EIGEN_PI / 180.0;
    const real_t s = math::sin(th), c = math::cos(th);
    const real_t x[3] = {-R * s, 0, R * s};
    const real_t z[3] = {R * c, R / c, R * c};
    const real_t w[3] = {1, c, 1};
    mp.addPatch(makeArcSurface(x, z, w, L));
    thickness = 0.25;
    E_modulus = 4.32e8;
    poisson = 0.0;
    monitorPoint << 1.0, 0.5;  // free edge x = +R sin40, mid-length y = 25
    monitorXYZ << R * s, L / 2, R * c;
  } else {
    const real_t R = 300, L2 = 300;
    const real_t x[3] = {0, R, R};
    const real_t z[3] = {R, R, 0};
    const real_t w[3] = {1, 1.0 / math::sqrt(2.0), 1};
    mp.addPatch(makeArcSurface(x, z, w, L2));
    thickness = 3.0;
    E_modulus = 3e6;
    poisson = 0.3;
    monitorPoint << 0.0, 1.0;  // top (x=0, z=R) of the mid-section y = 300
    monitorXYZ << 0, L2, R;
  }
  mp.computeTopology();
  // degree elevation to p in both directions (arc: 2 -> p, straight: 1 -> p)
  mp.patch(0).degreeElevate(p - 2, 0);
  mp.patch(0).degreeElevate(p - 1, 1);
  // uniform h-refinement to N x N elements (N-1 interior knots per direction)
  if (N > 1) mp.patch(0).uniformRefine(N - 1);

  {  // sanity check of the monitor location
    gsMatrix<real_t> X = mp.patch(0).eval(monitorPoint);
    GISMO_ENSURE((X.col(0) - monitorXYZ).norm() < 1e-9,
                 "monitor point mismatch: " << X.transpose());
  }

  // ------------------------------------------------------------------
  // Setup: basis, BCs, material, assembler (dof mapper, Dirichlet data)
  // ------------------------------------------------------------------
  const Clock::time_point t0 = Clock::now();

  gsMultiBasis<real_t> bases(mp);
  gsBoundaryConditions<real_t> bc;
  bc.setGeoMap(mp);
  gsPointLoads<real_t> pLoads;
  gsVector<real_t> fvec(3);

  // Parametrisation: u (west=0 / east=1) along the arc, v (south=0 / north=1) along y.
  if (scordelis) {
    // rigid diaphragms at y=0 (south) and y=50 (north): u_x = u_z = 0
    bc.addCondition(boundary::south, condition_type::dirichlet, 0, 0, false, 0);
    bc.addCondition(boundary::south, condition_type::dirichlet, 0, 0, false, 2);
    bc.addCondition(boundary::north, condition_type::dirichlet, 0, 0, false, 0);
    bc.addCondition(boundary::north, condition_type::dirichlet, 0, 0, false, 2);
    // u_y fixed at one corner (u=0, v=0)
    bc.addCornerValue(boundary::southwest, 0.0, 0, 1);  // (corner, value, patch, component)
    // straight edges (west, east) free
    fvec << 0, 0, -90;  // self weight per unit area (surface load)
  } else {
    // x = 0 (west, crown line): symmetry -> u_x = 0, clamped u_y, u_z
    bc.addCondition(boundary::west, condition_type::dirichlet, 0, 0, false, 0);
    bc.addCondition(boundary::west, condition_type::clamped, 0, 0, false, 1);
    bc.addCondition(boundary::west, condition_type::clamped, 0, 0, false, 2);
    // z = 0 (east): symmetry -> u_z = 0, clamped u_x, u_y
    bc.addCondition(boundary::east, condition_type::dirichlet, 0, 0, false, 2);
    bc.addCondition(boundary::east, condition_type::clamped, 0, 0, false, 0);
    bc.addCondition(boundary::east, condition_type::clamped, 0, 0, false, 1);
    // y = 0 (south): rigid diaphragm -> u_x = u_z = 0
    bc.addCondition(boundary::south, condition_type::dirichlet, 0, 0, false, 0);
    bc.addCondition(boundary::south, condition_type::dirichlet, 0, 0, false, 2);
    // y = 300 (north): symmetry -> u_y = 0, clamped u_x, u_z
    bc.addCondition(boundary::north, condition_type::dirichlet, 0, 0, false, 1);
    bc.addCondition(boundary::north, condition_type::clamped, 0, 0, false, 0);
    bc.addCondition(boundary::north, condition_type::clamped, 0, 0, false, 2);
    fvec << 0, 0, 0;
    gsVector<real_t> load(3);
    load << 0, 0, -0.25;  // P/4
    gsVector<real_t> pt = monitorPoint.col(0);
    pLoads.addLoad(pt, load, 0);  // parametric location
  }
  gsConstantFunction<real_t> force(fvec, 3);
  gsConstantFunction<real_t> t(thickness, 3);
  gsConstantFunction<real_t> E(E_modulus, 3);
  gsConstantFunction<real_t> nu(poisson, 3);

  gsMaterialMatrixLinear<3, real_t> material(mp, t, E, nu);
  gsThinShellAssembler<3, real_t, true> assembler(mp, bases, bc, force, &material);
  assembler.setPointLoads(pLoads);

  const Clock::time_point t1 = Clock::now();

  // ------------------------------------------------------------------
  // Assembly (once, linear)
  // ------------------------------------------------------------------
  ThinShellAssemblerStatus status = assembler.assemble();
  GISMO_ENSURE(status == ThinShellAssemblerStatus::Success, "Assembly failed");
  const gsSparseMatrix<real_t>& K = assembler.matrix();
  const gsMatrix<real_t>& f = assembler.rhs();

  const Clock::time_point t2 = Clock::now();

  // ------------------------------------------------------------------
  // Sparse direct solve: factorization + solve
  // ------------------------------------------------------------------
  gsSparseSolver<real_t>::SimplicialLDLT solver;
  solver.compute(K);
  GISMO_ENSURE(solver.info() == gsEigen::Success, "LDLT factorization failed");
  gsMatrix<real_t> u = solver.solve(f);

  const Clock::time_point t3 = Clock::now();

  // ------------------------------------------------------------------
  // Construct the displacement field and evaluate the monitor
  // ------------------------------------------------------------------
  gsMultiPatch<real_t> displ = assembler.constructDisplacement(u);
  gsMatrix<real_t> val = displ.patch(0).eval(monitorPoint);
  const real_t monitor = -val(2, 0);

  const Clock::time_point t4 = Clock::now();

  std::printf(
      "{\"case\": \"%s\", \"n\": %d, \"degree\": %d, \"dofs\": %d, "
      "\"time_setup_s\": %.6f, \"time_assembly_s\": %.6f, "
      "\"time_solve_s\": %.6f, \"time_total_s\": %.6f, "
      "\"monitor\": %.10g, \"solver\": \"SimplicialLDLT\"}\n",
      testCase.c_str(), (int)N, (int)p, (int)assembler.numDofs(), seconds(t0, t1), seconds(t1, t2),
      seconds(t2, t3), seconds(t0, t4), monitor);
  return 0;
}
