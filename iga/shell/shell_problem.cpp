// ShellProblem: edge conditions, springs, dead and follower loads of a Kirchhoff-Love shell
// patch. References and notation: see shell_problem.hpp.
#include "iga/shell/shell_problem.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/differential_geometry.hpp"
#include "iga/core/follower_pressure.hpp"
#include "iga/core/partition.hpp"
#include "iga/core/quadrature.hpp"

namespace iga {

namespace {

[[noreturn]] void shell_fail(const std::string& msg) {
  throw ShellError(msg);
}

bool along_u(SurfaceEdge e) {  // the edge runs in u (v fixed)
  return e == SurfaceEdge::kVMin || e == SurfaceEdge::kVMax;
}

}  // namespace

ShellProblem::ShellProblem(KirchhoffLoveShell shell)
    : ControlPointProblem(shell.reference_points(), "ShellProblem", &shell_fail),
      shell_(std::move(shell)) {}

std::vector<int> ShellProblem::edge_points(SurfaceEdge edge, int row) const {
  if (row < 0 || row > 1) shell_fail("ShellProblem::edge_points: row must be 0 or 1");
  return iga::edge_points(shell_.reference(), edge, row);
}

std::vector<Vector3d> ShellProblem::edge_normals(SurfaceEdge edge) const {
  const NurbsSurface& S = shell_.reference();
  const Domain2 dom = S.domain();
  const bool u_run = along_u(edge);
  const std::vector<double> g = u_run ? S.knots_u().greville() : S.knots_v().greville();
  const double fixed = edge == SurfaceEdge::kUMin   ? dom.u.lo
                       : edge == SurfaceEdge::kUMax ? dom.u.hi
                       : edge == SurfaceEdge::kVMin ? dom.v.lo
                                                    : dom.v.hi;
  std::vector<Vector3d> n;
  for (double s : g) {
    const SurfaceDerivs d = u_run ? S.derivs(s, fixed, 1) : S.derivs(fixed, s, 1);
    n.push_back(d.Su.cross(d.Sv).normalized());
  }
  return n;
}

void ShellProblem::simply_support(SurfaceEdge edge, std::initializer_list<int> components) {
  for (int c : components) {
    if (c < 0 || c > 2)
      shell_fail("ShellProblem::simply_support: component must be 0, 1 or 2, got " +
                 std::to_string(c));
    for (int i : edge_points(edge, 0)) dofs_.fix_along(i, Vector3d::Unit(c));
  }
}

void ShellProblem::clamp(SurfaceEdge edge) {
  const std::vector<int> row0 = edge_points(edge, 0), row1 = edge_points(edge, 1);
  const std::vector<Vector3d> n = edge_normals(edge);
  for (std::size_t k = 0; k < row0.size(); ++k) {
    for (int c = 0; c < 3; ++c) dofs_.fix_along(row0[k], Vector3d::Unit(c));
    dofs_.fix_along(row1[k], n[k]);  // (x_1 - x_0).n = 0: the tangent plane is held
  }
}

void ShellProblem::symmetry(SurfaceEdge edge, const Vector3d& plane_normal) {
  if (!(plane_normal.norm() > 0.0))
    shell_fail("ShellProblem::symmetry: the plane normal must be non-zero");
  const Vector3d N = plane_normal.normalized();
  // In-plane directions: the other coordinate axes for a coordinate plane, else the completion
  // DofMap::fix_along uses (so that rows 0 and 1 share one basis).
  Vector3d t1 = N.unitOrthogonal(), t2 = N.cross(t1);
  Matrix3d Q;
  Q << t1, t2, N;
  for (int c = 0; c < 3; ++c)
    if (std::abs(N[c]) > 1.0 - 1e-12) {
      t1 = Vector3d::Unit((c + 1) % 3);
      t2 = Vector3d::Unit((c + 2) % 3);
      Q = Matrix3d::Identity();
    }
  const std::vector<int> row0 = edge_points(edge, 0), row1 = edge_points(edge, 1);
  for (std::size_t k = 0; k < row0.size(); ++k) {
    dofs_.fix_along(row0[k], N);
    const int s = row1[k], m = row0[k];
    if (dofs_.axis_along(s, t1) < 0) dofs_.set_local_basis(s, Q);  // throws if constrained
    for (const Vector3d& t : {t1, t2}) {
      const int cs = dofs_.axis_along(s, t), cm = dofs_.axis_along(m, t);
      if (cs < 0 || cm < 0)
        shell_fail("ShellProblem::symmetry: control points " + std::to_string(s) + " and " +
                   std::to_string(m) + " have local bases without the plane's in-plane axes");
      dofs_.tie(s, cs, m, cm);
    }
  }
}

void ShellProblem::add_spring(int point, double stiffness, LoadCurve curve,
                              std::optional<Vector3d> direction) {
  if (point < 0 || point >= num_control_points())
    shell_fail("ShellProblem::add_spring: control point " + std::to_string(point) +
               " out of range [0, " + std::to_string(num_control_points() - 1) + "]");
  if (!(stiffness >= 0.0) || !std::isfinite(stiffness))
    shell_fail("ShellProblem::add_spring: stiffness must be finite and >= 0, got " +
               std::to_string(stiffness));
  Spring s{point, stiffness, std::move(curve), direction.has_value(), Vector3d::Zero()};
  if (direction) {
    if (!(direction->norm() > 0.0))
      shell_fail("ShellProblem::add_spring: the direction must be non-zero");
    s.d = direction->normalized();
  }
  springs_.push_back(std::move(s));
}

void ShellProblem::add_surface_load(const Vector3d& q, LoadCurve curve) {
  std::vector<Vector3d> f(static_cast<std::size_t>(num_control_points()), Vector3d::Zero());
  SurfaceBasis B;
  for (int e = 0; e < shell_.num_elements(); ++e)
    for (int g = 0; g < shell_.num_quadrature_points(e); ++g) {
      const KirchhoffLoveShell::QuadraturePoint& qp = shell_.quadrature_point(e, g);
      shell_.basis(e, g, B);
      for (int k = 0; k < B.count(); ++k)  // f_I = int R_I q dA
        f[static_cast<std::size_t>(B.global_index(k))] +=
            (qp.wJ * B.R[static_cast<std::size_t>(k)]) * q;
    }
  add_nodal_load(f, std::move(curve), /*split=*/!shell_.options().block.whole());
}

void ShellProblem::add_pressure(double p, LoadCurve curve) {
  pressures_.push_back(Pressure{p, std::move(curve)});
}

void ShellProblem::add_edge_load(SurfaceEdge edge, const Vector3d& q, LoadCurve curve) {
  const NurbsSurface& S = shell_.reference();
  const Domain2 dom = S.domain();
  const bool u_run = along_u(edge);
  const KnotVector& kv = u_run ? S.knots_u() : S.knots_v();
  const double fixed = edge == SurfaceEdge::kUMin   ? dom.u.lo
                       : edge == SurfaceEdge::kUMax ? dom.u.hi
                       : edge == SurfaceEdge::kVMin ? dom.v.lo
                                                    : dom.v.hi;
  const int ng = std::min(kMaxGaussPoints, kv.degree() + 2);
  std::array<double, kMaxGaussPoints> gx{}, gw{};
  gauss_legendre(ng, gx, gw);
  const std::vector<double> br = kv.breaks();
  std::vector<Vector3d> f(static_cast<std::size_t>(num_control_points()), Vector3d::Zero());
  SurfaceBasis B;
  for (std::size_t e = 0; e + 1 < br.size(); ++e) {
    const double mid = 0.5 * (br[e] + br[e + 1]), half = 0.5 * (br[e + 1] - br[e]);
    for (int g = 0; g < ng; ++g) {
      const double s = mid + half * gx[static_cast<std::size_t>(g)];
      if (u_run)
        rational_basis(S, s, fixed, B);
      else
        rational_basis(S, fixed, s, B);
      const Vector3d At = combine(B, u_run ? B.d1 : B.d2, reference_points());
      const double w = half * gw[static_cast<std::size_t>(g)] * At.norm();  // dS = |A_t| ds
      for (int k = 0; k < B.count(); ++k)
        f[static_cast<std::size_t>(B.global_index(k))] +=
            (w * B.R[static_cast<std::size_t>(k)]) * q;
    }
  }
  add_nodal_load(f, std::move(curve));
}

void ShellProblem::add_point_load(double u, double v, const Vector3d& F, LoadCurve curve) {
  SurfaceBasis B;
  rational_basis(shell_.reference(), u, v, B);
  std::vector<std::pair<int, Vector3d>> forces;
  for (int k = 0; k < B.count(); ++k)
    if (B.R[static_cast<std::size_t>(k)] != 0.0)
      forces.emplace_back(B.global_index(k), B.R[static_cast<std::size_t>(k)] * F);  // R_I F
  add_nodal_load(std::move(forces), std::move(curve));
}

void ShellProblem::add_pressure_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                                      std::vector<Triplet>* K) const {
  double p = 0.0;
  for (const Pressure& pr : pressures_) p += pr.p * pr.curve(t);
  if (pressures_.empty() || p == 0.0) return;
  SurfaceBasis B;
  for (int e = 0; e < shell_.num_elements(); ++e)
    for (int q = 0; q < shell_.num_quadrature_points(e); ++q) {
      shell_.basis(e, q, B);
      add_follower_pressure(B, p * shell_.quadrature_point(e, q).w_param, x, g, K);
    }
}

void ShellProblem::assemble_model(std::span<const Vector3d> x, std::span<const double> /*s: none*/,
                                  double t, VectorXd& g, std::vector<Triplet>* K) {
  shell_.assemble(x, g, K);  // g = f_int
  add_pressure_terms(x, t, g, K);
  add_spring_terms(x, t, g, K);
}

bool ShellProblem::add_load_terms(std::span<const Vector3d> x, std::span<const double> /*s*/,
                                  double t, VectorXd& g) const {
  add_pressure_terms(x, t, g, nullptr);
  add_spring_terms(x, t, g, nullptr);
  return true;
}

void ShellProblem::add_spring_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                                    std::vector<Triplet>* K) const {
  const std::vector<Vector3d>& X = reference_points();
  for (const Spring& s : springs_) {
    if (!adds_point_terms(s.point)) continue;  // added by another process
    const double k = s.k * s.curve(t);
    const std::size_t i = static_cast<std::size_t>(s.point);
    const Vector3d u = x[i] - X[i];
    const Matrix3d Ks =
        s.directional ? Matrix3d(k * s.d * s.d.transpose()) : Matrix3d(k * Matrix3d::Identity());
    g.segment<3>(3 * s.point) += Ks * u;  // force -k u acts on the point: g = f_int - f_ext
    if (K)
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a)
          if (Ks(a, b) != 0.0) K->emplace_back(3 * s.point + a, 3 * s.point + b, Ks(a, b));
  }
}

NurbsSurface ShellProblem::current_surface(const VectorXd& u, double t) const {
  const NurbsSurface& S = shell_.reference();
  return NurbsSurface(S.degree_u(), S.knots_u().knots(), S.degree_v(), S.knots_v().knots(),
                      current_points(u, t), S.weights());
}

Vector3d ShellProblem::displacement(double u, double v, const VectorXd& state, double t) const {
  const std::vector<Vector3d> x = current_points(state, t);
  return shell_.point(u, v, x) - shell_.point(u, v, reference_points());
}

void ShellProblem::point_partition(int rank, int processes, std::vector<int>& owner,
                                   std::vector<char>& reads) const {
  patch_point_partition(shell_.reference().knots_u(), shell_.reference().knots_v(), rank, processes,
                        owner, reads);
}

}  // namespace iga
