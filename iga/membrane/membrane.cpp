// MembraneProblem: the membrane's laws, internal forces and tangent, edge conditions, loads and
// sampled output. References and notation: membrane.hpp.
#include "iga/membrane/membrane.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "iga/core/follower_pressure.hpp"
#include "iga/core/partition.hpp"
#include "iga/core/quadrature.hpp"

namespace iga {

namespace {

[[noreturn]] void membrane_fail(const std::string& msg) {
  throw MembraneError(msg);
}

// Voigt index -> (a, b): 11, 22, 12.
constexpr std::array<std::array<int, 2>, 3> kVoigt{{{0, 0}, {1, 1}, {0, 1}}};

/// D_ij = c1 P^ab P^cd + c2 (P^ac P^bd + P^ad P^bc) with (ab) = Voigt i, (cd) = Voigt j.
Eigen::Matrix3d voigt_tensor(const Matrix2d& P, double c1, double c2) {
  Eigen::Matrix3d D;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const auto [a, b] = kVoigt[static_cast<std::size_t>(i)];
      const auto [c, d] = kVoigt[static_cast<std::size_t>(j)];
      D(i, j) = c1 * P(a, b) * P(c, d) + c2 * (P(a, c) * P(b, d) + P(a, d) * P(b, c));
    }
  return D;
}

Eigen::Vector3d voigt(const Matrix2d& P) {
  return {P(0, 0), P(1, 1), P(0, 1)};
}

Matrix2d metric(const Vector3d& a1, const Vector3d& a2) {
  Matrix2d a;
  a << a1.dot(a1), a1.dot(a2), a1.dot(a2), a2.dot(a2);
  return a;
}

void check_material(const MembraneMaterial& m) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(m.thickness)) membrane_fail("membrane: the thickness must be > 0");
  if (!(std::isfinite(m.prestress) && m.prestress >= 0.0))
    membrane_fail("membrane: the prestress must be finite and >= 0");
  if (m.law == MembraneLaw::kSaintVenantKirchhoff) {
    if (!positive(m.E)) membrane_fail("membrane: E must be > 0");
    if (!(m.nu > -1.0 && m.nu <= 0.5)) membrane_fail("membrane: nu must be in (-1, 0.5]");
  } else if (!positive(m.mu)) {
    membrane_fail("membrane: the shear modulus mu must be > 0");
  }
}

}  // namespace

MembraneResponse membrane_response(const MembraneMaterial& m, const Matrix2d& A,
                                   const Matrix2d& a) {
  MembraneResponse r;
  const double det_a = a.determinant();
  if (!(det_a > 0.0) || !std::isfinite(det_a)) {
    r.W = std::numeric_limits<double>::infinity();
    r.S.setConstant(std::numeric_limits<double>::quiet_NaN());
    r.D.setConstant(std::numeric_limits<double>::quiet_NaN());
    return r;
  }
  const Matrix2d Ainv = A.inverse();
  const Matrix2d E = 0.5 * (a - A);
  const Eigen::Vector3d Ev(E(0, 0), E(1, 1), 2.0 * E(0, 1));
  if (m.law == MembraneLaw::kSaintVenantKirchhoff) {
    const double k = m.thickness * m.E / (1.0 - m.nu * m.nu);
    r.D = voigt_tensor(Ainv, k * m.nu, 0.5 * k * (1.0 - m.nu));
    r.S = r.D * Ev;
    r.W = 0.5 * Ev.dot(r.S);
  } else {
    const double mt = m.mu * m.thickness, ratio = A.determinant() / det_a;  // r = lambda_3^2
    const Matrix2d ainv = a.inverse();
    r.S = mt * (voigt(Ainv) - ratio * voigt(ainv));
    r.D = voigt_tensor(ainv, 2.0 * mt * ratio, mt * ratio);
    r.W = 0.5 * mt * ((Ainv * a).trace() + ratio - 3.0);
  }
  if (m.prestress > 0.0) {  // W_0 = n_0 A^ab E_ab
    r.S += m.prestress * voigt(Ainv);
    r.W += m.prestress * voigt(Ainv).dot(Ev);
  }
  return r;
}

MembraneProblem::MembraneProblem(NurbsSurface reference, MembraneMaterial material,
                                 int quadrature_points, const ElementBlock& block)
    : ControlPointProblem(reference.control_points(), "MembraneProblem", &membrane_fail),
      reference_(std::move(reference)),
      material_(material),
      block_(block) {
  check_material(material_);
  const int p = reference_.degree_u(), q = reference_.degree_v();
  if (p < 1 || q < 1 || p > kMaxSurfaceBasisDegree || q > kMaxSurfaceBasisDegree)
    membrane_fail("membrane: the degree must be in 1.." + std::to_string(kMaxSurfaceBasisDegree) +
                  " in each direction");
  if (quadrature_points < 0 || quadrature_points > kMaxGaussPoints)
    membrane_fail("membrane: quadrature_points must be in 0..20 (0: p + 1)");
  const int ngu = quadrature_points > 0 ? quadrature_points : p + 1;
  const int ngv = quadrature_points > 0 ? quadrature_points : q + 1;
  points_per_element_ = ngu * ngv;
  std::array<double, kMaxGaussPoints> xu{}, wu{}, xv{}, wv{};
  gauss_legendre(ngu, xu, wu);
  gauss_legendre(ngv, xv, wv);
  const std::vector<double> bu = reference_.knots_u().breaks(), bv = reference_.knots_v().breaks();
  const std::vector<Vector3d> X = reference_.control_points();
  // The Gauss points of every span per direction and their B-spline basis.
  const std::vector<double> tu =
      span_rule_points(bu, std::span<const double>(xu.data(), static_cast<std::size_t>(ngu)));
  const std::vector<double> tv =
      span_rule_points(bv, std::span<const double>(xv.data(), static_cast<std::size_t>(ngv)));
  table_u_ = SpanBasisTable(reference_.knots_u(), p, tu);
  table_v_ = SpanBasisTable(reference_.knots_v(), q, tv);
  SurfaceBasis B;
  for (std::size_t j = 0; j + 1 < bv.size(); ++j)
    for (std::size_t i = 0; i + 1 < bu.size(); ++i) {
      if (!block_.contains(static_cast<int>(i), static_cast<int>(j))) continue;  // another's
      ++elements_;
      const double hu = 0.5 * (bu[i + 1] - bu[i]), hv = 0.5 * (bv[j + 1] - bv[j]);
      for (int b = 0; b < ngv; ++b)
        for (int a = 0; a < ngu; ++a) {
          Point pt;
          pt.row_u = static_cast<int>(i) * ngu + a;
          pt.row_v = static_cast<int>(j) * ngv + b;
          const double u = tu[static_cast<std::size_t>(pt.row_u)];
          const double v = tv[static_cast<std::size_t>(pt.row_v)];
          basis(pt, B);
          pt.w_param = hu * wu[static_cast<std::size_t>(a)] * hv * wv[static_cast<std::size_t>(b)];
          const auto [A1, A2] = base(B, X);
          const double J = A1.cross(A2).norm();
          if (!(J > 0.0))
            membrane_fail("membrane: the reference surface is singular at (u, v) = (" +
                          std::to_string(u) + ", " + std::to_string(v) + ")");
          pt.wJ = pt.w_param * J;
          pt.A = metric(A1, A2);
          points_.push_back(pt);
        }
    }
}

std::pair<Vector3d, Vector3d> MembraneProblem::base(const SurfaceBasis& B,
                                                    std::span<const Vector3d> x) const {
  return {combine(B, B.d1, x), combine(B, B.d2, x)};
}

double MembraneProblem::energy(std::span<const Vector3d> x) const {
  double W = 0.0;
  SurfaceBasis B;
  for (const Point& pt : points_) {
    basis(pt, B);
    const auto [a1, a2] = base(B, x);
    W += membrane_response(material_, pt.A, metric(a1, a2)).W * pt.wJ;
  }
  return W;
}

void MembraneProblem::support(SurfaceEdge edge, const std::vector<int>& components) {
  for (int c : components) {
    if (c < 0 || c > 2)
      membrane_fail("MembraneProblem::support: component must be 0, 1 or 2, got " +
                    std::to_string(c));
    for (int i : edge_points(reference_, edge)) dofs_.fix_along(i, Vector3d::Unit(c));
  }
}

void MembraneProblem::symmetry(SurfaceEdge edge, const Vector3d& plane_normal) {
  if (!(plane_normal.norm() > 0.0))
    membrane_fail("MembraneProblem::symmetry: the plane normal must be non-zero");
  for (int i : edge_points(reference_, edge)) dofs_.fix_along(i, plane_normal.normalized());
}

void MembraneProblem::add_surface_load(const Vector3d& q, LoadCurve curve) {
  std::vector<Vector3d> f(static_cast<std::size_t>(num_control_points()), Vector3d::Zero());
  SurfaceBasis B;
  for (const Point& pt : points_) {
    basis(pt, B);
    for (int k = 0; k < B.count(); ++k)
      f[static_cast<std::size_t>(B.global_index(k))] +=
          B.R[static_cast<std::size_t>(k)] * pt.wJ * q;
  }
  add_nodal_load(f, std::move(curve), /*split=*/!block_.whole());
}

void MembraneProblem::add_pressure(double p, LoadCurve curve) {
  if (!std::isfinite(p)) membrane_fail("MembraneProblem::add_pressure: p must be finite");
  pressures_.push_back({p, std::move(curve)});
}

void MembraneProblem::assemble_model(std::span<const Vector3d> x,
                                     std::span<const double> /*s: none*/, double t, VectorXd& g,
                                     std::vector<Triplet>* K) {
  // Element by element: f_I = int B_I^T S dA, K_IJ = int (B_I^T D B_J + S^ab R_I,a R_J,b 1) dA.
  const int n_el = points_per_element_;
  g.setZero(3 * num_control_points());
  Eigen::MatrixXd Ke;
  SurfaceBasis B;
  for (int e = 0; e < elements_; ++e) {
    const int np = (reference_.degree_u() + 1) * (reference_.degree_v() + 1);
    if (K) Ke.setZero(3 * np, 3 * np);
    for (int q = 0; q < n_el; ++q) {
      const Point& pt = points_[static_cast<std::size_t>(e * n_el + q)];
      basis(pt, B);
      const auto [a1, a2] = base(B, x);
      const MembraneResponse r = membrane_response(material_, pt.A, metric(a1, a2));
      std::array<Eigen::Matrix3d, kMaxSurfaceBasisPoints> BI;
      for (int k = 0; k < np; ++k) {
        const double r1 = B.d1[static_cast<std::size_t>(k)], r2 = B.d2[static_cast<std::size_t>(k)];
        Eigen::Matrix3d& b = BI[static_cast<std::size_t>(k)];
        b.row(0) = r1 * a1.transpose();
        b.row(1) = r2 * a2.transpose();
        b.row(2) = (r1 * a2 + r2 * a1).transpose();
        g.segment<3>(3 * B.global_index(k)) += pt.wJ * b.transpose() * r.S;
      }
      if (!K) continue;
      for (int k = 0; k < np; ++k) {
        const Eigen::Matrix<double, 3, 3> BtD =
            pt.wJ * BI[static_cast<std::size_t>(k)].transpose() * r.D;
        const double rk1 = B.d1[static_cast<std::size_t>(k)],
                     rk2 = B.d2[static_cast<std::size_t>(k)];
        for (int l = 0; l < np; ++l) {
          const double rl1 = B.d1[static_cast<std::size_t>(l)],
                       rl2 = B.d2[static_cast<std::size_t>(l)];
          const double geo =
              r.S[0] * rk1 * rl1 + r.S[1] * rk2 * rl2 + r.S[2] * (rk1 * rl2 + rk2 * rl1);
          Ke.block<3, 3>(3 * k, 3 * l) += BtD * BI[static_cast<std::size_t>(l)];
          Ke.block<3, 3>(3 * k, 3 * l).diagonal().array() += pt.wJ * geo;
        }
      }
    }
    if (!K) continue;
    for (int k = 0; k < np; ++k)
      for (int l = 0; l < np; ++l)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            K->emplace_back(3 * B.global_index(k) + a, 3 * B.global_index(l) + b,
                            Ke(3 * k + a, 3 * l + b));
  }
  add_pressure_terms(x, t, g, K);
}

void MembraneProblem::add_pressure_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                                         std::vector<Triplet>* K) const {
  double p = 0.0;
  for (const Pressure& pr : pressures_) p += pr.p * pr.curve(t);
  if (p == 0.0) return;
  SurfaceBasis B;
  for (const Point& pt : points_) {
    basis(pt, B);
    add_follower_pressure(B, p * pt.w_param, x, g, K);
  }
}

NurbsSurface MembraneProblem::current_surface(const VectorXd& u, double t) const {
  const NurbsSurface& S = reference_;
  return NurbsSurface(S.degree_u(), S.knots_u().knots(), S.degree_v(), S.knots_v().knots(),
                      current_points(u, t), S.weights());
}

Vector3d MembraneProblem::displacement(double u, double v, const VectorXd& state, double t) const {
  return current_surface(state, t).point(u, v) - reference_.point(u, v);
}

std::string MembraneProblem::describe() const {
  return "membrane of " + std::to_string(elements_) + " elements (degree " +
         std::to_string(reference_.degree_u()) + " x " + std::to_string(reference_.degree_v()) +
         ", " + std::to_string(num_control_points()) + " control points, " +
         (material_.law == MembraneLaw::kNeoHookean ? "neo-Hookean" : "St. Venant-Kirchhoff") +
         (material_.prestress > 0.0 ? ", prestressed)" : ")");
}

SampledMesh MembraneProblem::sample_model(const VectorXd& u, double t, int samples) const {
  const NurbsSurface current = current_surface(u, t);
  const NurbsSurface& S = reference_;
  SampledMesh m = element_grid(S.knots_u().breaks(), S.knots_v().breaks(), samples, block_);
  m.fields.name({"stretch_1", "stretch_2", "singular"},
                {"displacement", "normal", "membrane_force_N11_N22_N12"});
  for (const auto& [pu, pv] : m.params) {
    const SurfaceDerivs R = S.derivs(pu, pv, 1), C = current.derivs(pu, pv, 1);
    m.points.push_back(C.S);
    const Vector3d A1 = R.Su, A2 = R.Sv, a1 = C.Su, a2 = C.Sv;
    const Matrix2d A = metric(A1, A2), a = metric(a1, a2);
    const MembraneResponse r = membrane_response(material_, A, a);
    // Principal stretches: the square roots of the eigenvalues of A^-1 a; forces S^ab A_a A_b
    // in the frame e_1 = A_1/|A_1|, e_2 = A_3 x e_1.
    const Matrix2d M = A.inverse() * a;  // eigenvalues: the squared principal stretches
    const double tr = M.trace(), disc = std::sqrt(std::max(0.0, tr * tr - 4.0 * M.determinant()));
    const Vector3d e1 = A1.normalized(), e2 = A1.cross(A2).normalized().cross(e1);
    const Matrix3d sigma = r.S[0] * A1 * A1.transpose() + r.S[1] * A2 * A2.transpose() +
                           r.S[2] * (A1 * A2.transpose() + A2 * A1.transpose());
    const Vector3d n = a1.cross(a2).normalized();
    const Vector3d N(e1.dot(sigma * e1), e2.dot(sigma * e2), e1.dot(sigma * e2));
    const double s1 = std::sqrt(0.5 * (tr + disc)), s2 = std::sqrt(0.5 * (tr - disc));
    const bool ok = n.allFinite() && N.allFinite() && std::isfinite(s1) && std::isfinite(s2);
    m.fields.append({ok ? s1 : 0.0, ok ? s2 : 0.0, ok ? 0.0 : 1.0},
                    {C.S - R.S, ok ? n : Vector3d::Zero(), ok ? N : Vector3d::Zero()});
  }
  return m;
}

void MembraneProblem::point_partition(int rank, int processes, std::vector<int>& owner,
                                      std::vector<char>& reads) const {
  patch_point_partition(reference_.knots_u(), reference_.knots_v(), rank, processes, owner, reads);
}

}  // namespace iga
