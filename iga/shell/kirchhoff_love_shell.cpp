// Rotation-free Kirchhoff-Love shell: rational surface basis, quadrature data, the energy
// density with its gradient and Hessian in y = (a_1, a_2, a_11, a_22, a_12), element forces and
// tangents, assembly, stresses. References and notation: see kirchhoff_love_shell.hpp.
#include "iga/shell/kirchhoff_love_shell.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "geometry/differential_geometry.hpp"
#include "geometry/number_text.hpp"
#include "iga/core/quadrature.hpp"

namespace iga {

namespace {

using Vector15d = Eigen::Matrix<double, 15, 1>;
using Matrix15d = Eigen::Matrix<double, 15, 15>;
using Matrix3x15d = Eigen::Matrix<double, 3, 15>;
using Matrix3x6d = Eigen::Matrix<double, 3, 6>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

std::string num(double v) {
  return num_text(v, 6);
}

[[noreturn]] void fail(const std::string& msg) {
  throw ShellError(msg);
}

/// The kinematic variables y = (a_1, a_2, a_11, a_22, a_12) at a quadrature point: 5 blocks of 3.
struct Kinematics {
  std::array<Vector3d, 5> y;
};

void kinematics(const SurfaceBasis& B, std::span<const Vector3d> x, int first_u, int first_v,
                int num_u, Kinematics& k) {
  for (Vector3d& v : k.y) v.setZero();
  for (int j = 0; j < B.nv; ++j)
    for (int i = 0; i < B.nu; ++i) {
      const std::size_t l = static_cast<std::size_t>(i + B.nu * j);
      const Vector3d& xi = x[static_cast<std::size_t>(first_u + i + num_u * (first_v + j))];
      k.y[0].noalias() += B.d1[l] * xi;
      k.y[1].noalias() += B.d2[l] * xi;
      k.y[2].noalias() += B.d11[l] * xi;
      k.y[3].noalias() += B.d22[l] * xi;
      k.y[4].noalias() += B.d12[l] * xi;
    }
}

/// Voigt (11, 22, 12) forms of the fourth-order tensors M (x) M and Isym(M)^abcd =
/// 1/2 (M^ac M^bd + M^ad M^bc) of a symmetric 2 x 2 M, against strains (E_11, E_22, 2 E_12).
Matrix3d voigt_outer(const Matrix2d& M) {
  const Vector3d v(M(0, 0), M(1, 1), M(0, 1));
  return v * v.transpose();
}
Matrix3d voigt_isym(const Matrix2d& M) {
  const double m11 = M(0, 0), m22 = M(1, 1), m12 = M(0, 1);
  Matrix3d I;
  I << m11 * m11, m12 * m12, m11 * m12,  //
      m12 * m12, m22 * m22, m22 * m12,   //
      m11 * m12, m22 * m12, 0.5 * (m11 * m22 + m12 * m12);
  return I;
}

/// Thickness-integrated resultants of a law: energy per reference area W, n = dW/deps,
/// m = dW/dkap and (Order 2) their tangents. Dnm is zero for St. Venant-Kirchhoff.
struct Resultants {
  double W = 0.0;
  Vector3d nf = Vector3d::Zero(), mf = Vector3d::Zero();
  Matrix3d Dnn = Matrix3d::Zero(), Dnm = Matrix3d::Zero(), Dmm = Matrix3d::Zero();
  bool coupled = false;  ///< Dnm != 0
};

/// [KHB+15] Sect. 3: E(z) = eps + z kap on the mid-surface metric, n = int S dz,
/// m = int z S dz, D_nn, D_nm, D_mm = int (1, z, z^2) D dz, W = int psi dz.
template <int Order>
void neo_hookean_resultants(const KirchhoffLoveShell::QuadraturePoint& q, const ShellMaterial& mat,
                            const ShellThicknessRule& rule, const Vector3d& eps,
                            const Vector3d& kap, Resultants& r) {
  r.coupled = true;
  for (int i = 0; i < rule.n; ++i) {
    const double z = rule.z[static_cast<std::size_t>(i)], w = rule.w[static_cast<std::size_t>(i)];
    const PlaneStressPoint p = neo_hookean_plane_stress(mat.E, mat.nu, q.Aab, eps + z * kap);
    r.W += w * p.psi;
    r.nf.noalias() += w * p.S;
    r.mf.noalias() += (w * z) * p.S;
    if constexpr (Order >= 2) {
      r.Dnn.noalias() += w * p.D;
      r.Dnm.noalias() += (w * z) * p.D;
      r.Dmm.noalias() += (w * z * z) * p.D;
    }
  }
}

/// Value, gradient and Hessian (Order 0, 1, 2) of the energy density W(y) per reference area,
/// and the strains and resultants for output.
struct Density {
  double W = 0.0;
  Vector15d g = Vector15d::Zero();
  Matrix15d H = Matrix15d::Zero();
  Vector3d eps = Vector3d::Zero(), kap = Vector3d::Zero();
  Vector3d nf = Vector3d::Zero(), mf = Vector3d::Zero();
};

/// [KBLW09] Sect. 3-4, written in y:
///  membrane: eps = (1/2 (a1.a1 - A11), 1/2 (a2.a2 - A22), a1.a2 - A12),
///    d eps / d y = B_eps (rows (a1, 0), (0, a2), (a2, a1)); second derivatives: unit blocks;
///  normal: a3~ = a1 x a2, l = |a3~|, n = a3~ / l, P = I - n n^T,
///    d a3~ = J d(a1, a2) with J = [-[a2]x, [a1]x] (3 x 6), d n = P J / l d(a1, a2);
///  curvature b(c) = c . n for c = a_11, a_22, a_12 (the second derivatives of x):
///    d b / d c = n,  d b / d(a1, a2) = J^T P c / l,  d2 b / d c d(a1, a2) = P J / l,
///    d2 b / d(a1, a2)^2 = H_c / l - [J^T (Pc n^T + n (Pc)^T) J + (c.n) J^T P J] / l^2,
///    H_c = [[0, -[Pc]x], [[Pc]x, 0]] (the Hessian of (Pc).(a1 x a2));
///  kap = (B11 - b11, B22 - b22, 2 (B12 - b12)) (Voigt), nf = h D eps, mf = h^3/12 D kap,
///  W = 1/2 eps.nf + 1/2 kap.mf, g = B_eps^T nf + B_kap^T mf,
///  H = B_eps^T h D B_eps + B_kap^T h^3/12 D B_kap + sum_i nf_i eps_i'' + sum_i mf_i kap_i''.
template <int Order>
void density(const KirchhoffLoveShell::QuadraturePoint& q, const ShellMaterial& mat,
             const ShellThicknessRule& rule, const Kinematics& k, Density& d) {
  const Vector3d& a1 = k.y[0];
  const Vector3d& a2 = k.y[1];
  d.eps = Vector3d(0.5 * (a1.squaredNorm() - q.Aab(0, 0)), 0.5 * (a2.squaredNorm() - q.Aab(1, 1)),
                   a1.dot(a2) - q.Aab(0, 1));
  const Vector3d a3t = a1.cross(a2);
  const double l = a3t.norm();
  const Vector3d n = a3t / l;
  const std::array<double, 3> s{1.0, 1.0, 2.0};  // Voigt factors of kap
  for (int i = 0; i < 3; ++i)
    d.kap[i] = s[static_cast<std::size_t>(i)] * (q.Bv[i] - k.y[2 + i].dot(n));
  Resultants r;
  if (mat.law == ShellLaw::kSaintVenantKirchhoff) {
    const double h = mat.thickness, hb = h * h * h / 12.0;
    r.nf.noalias() = h * (q.D * d.eps);
    r.mf.noalias() = hb * (q.D * d.kap);
    r.W = 0.5 * d.eps.dot(r.nf) + 0.5 * d.kap.dot(r.mf);
    if constexpr (Order >= 2) {
      r.Dnn = h * q.D;
      r.Dmm = hb * q.D;
    }
  } else {
    neo_hookean_resultants<Order>(q, mat, rule, d.eps, d.kap, r);
  }
  d.nf = r.nf;
  d.mf = r.mf;
  d.W = r.W;
  if constexpr (Order < 1) return;

  Matrix3x6d J;
  J.leftCols<3>() = -skew(a2);
  J.rightCols<3>() = skew(a1);
  Matrix3d P = Matrix3d::Identity();
  P.noalias() -= n * n.transpose();

  Matrix3x15d Be = Matrix3x15d::Zero(), Bk = Matrix3x15d::Zero();
  Be.block<1, 3>(0, 0) = a1.transpose();
  Be.block<1, 3>(1, 3) = a2.transpose();
  Be.block<1, 3>(2, 0) = a2.transpose();
  Be.block<1, 3>(2, 3) = a1.transpose();
  for (int i = 0; i < 3; ++i) {
    const double si = s[static_cast<std::size_t>(i)];
    const Vector3d Pc = P * k.y[2 + i];
    Bk.block<1, 6>(i, 0) = (-si / l) * (J.transpose() * Pc).transpose();
    Bk.block<1, 3>(i, 6 + 3 * i) = -si * n.transpose();
  }
  d.g.noalias() = Be.transpose() * d.nf;
  d.g.noalias() += Bk.transpose() * d.mf;
  if constexpr (Order < 2) return;

  d.H.noalias() = Be.transpose() * (r.Dnn * Be);
  d.H.noalias() += Bk.transpose() * (r.Dmm * Bk);
  if (r.coupled) {
    const Matrix15d C = Be.transpose() * (r.Dnm * Bk);
    d.H += C;
    d.H += C.transpose();
  }
  // membrane: nf . eps''
  d.H.block<3, 3>(0, 0).diagonal().array() += d.nf[0];
  d.H.block<3, 3>(3, 3).diagonal().array() += d.nf[1];
  d.H.block<3, 3>(0, 3).diagonal().array() += d.nf[2];
  d.H.block<3, 3>(3, 0).diagonal().array() += d.nf[2];
  // bending: mf . kap'' = -sum_i mf_i s_i b_i''; the (a1, a2) block is linear in c, so it is
  // evaluated once for cbar = sum_i mf_i s_i c_i.
  Vector3d cbar = Vector3d::Zero();
  const Matrix3x6d PJl = (P * J) / l;
  for (int i = 0; i < 3; ++i) {
    const double wi = d.mf[i] * s[static_cast<std::size_t>(i)];
    cbar.noalias() += wi * k.y[2 + i];
    d.H.block<3, 6>(6 + 3 * i, 0).noalias() -= wi * PJl;
    d.H.block<6, 3>(0, 6 + 3 * i).noalias() -= wi * PJl.transpose();
  }
  const Vector3d Pc = P * cbar;
  const double cn = cbar.dot(n);
  const Vector6d JPc = J.transpose() * Pc, Jn = J.transpose() * n;
  Matrix6d Hyy = Matrix6d::Zero();
  Hyy.block<3, 3>(0, 3) = -skew(Pc) / l;
  Hyy.block<3, 3>(3, 0) = skew(Pc) / l;
  Matrix6d JPJ = J.transpose() * J;
  JPJ.noalias() -= Jn * Jn.transpose();
  const double l2 = l * l;
  Hyy.noalias() -= (JPc * Jn.transpose() + Jn * JPc.transpose()) / l2;
  Hyy.noalias() -= (cn / l2) * JPJ;
  d.H.topLeftCorner<6, 6>().noalias() -= Hyy;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Neo-Hookean plane stress ([KHB+15] Sect. 3.1-3.2)

PlaneStressPoint neo_hookean_plane_stress(double E, double nu, const Matrix2d& Aab,
                                          const Vector3d& strain) {
  const double mu = E / (2.0 * (1.0 + nu));
  const double lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Matrix2d C = Aab;  // C_ab = A_ab + 2 E_ab
  C(0, 0) += 2.0 * strain[0];
  C(1, 1) += 2.0 * strain[1];
  C(0, 1) += strain[2];
  C(1, 0) += strain[2];
  PlaneStressPoint p;
  const double detC = C.determinant(), detA = Aab.determinant();
  if (!(detC > 0.0) || !std::isfinite(detC)) {
    p.psi = std::numeric_limits<double>::infinity();
    p.S.setConstant(std::numeric_limits<double>::quiet_NaN());
    p.D.setConstant(std::numeric_limits<double>::quiet_NaN());
    return p;
  }
  // S^33 = 0 <=> g(c) = mu (c - 1) + lam (a + 1/2 ln c) = 0 for c = C_33, a = 1/2 ln(det C /
  // det A); g is increasing in c > 0 with g(0+) = -inf, g(inf) = inf: one root, by Newton kept
  // positive (halving a step that would leave c > 0).
  const double a = 0.5 * std::log(detC / detA);
  double c = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double g = mu * (c - 1.0) + lam * (a + 0.5 * std::log(c));
    const double dg = mu + 0.5 * lam / c;
    double dc = -g / dg;
    while (c + dc <= 0.0) dc *= 0.5;
    c += dc;
    if (std::abs(dc) <= 1e-15 * c) break;
  }
  const double lnJ = a + 0.5 * std::log(c);
  const Matrix2d Ainv = Aab.inverse(), Cinv = C.inverse();
  p.C33 = c;
  // psi = mu/2 (tr C - 3) - mu ln J + lam/2 ln^2 J, tr C = A^ab C_ab + C_33.
  p.psi = 0.5 * mu * ((Ainv.cwiseProduct(C)).sum() + c - 3.0) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
  // S^ab = mu (A^ab - C^ab) + lam ln J C^ab (S^33 = 0 makes the C_33 dependence drop out).
  const Matrix2d S = mu * Ainv + (lam * lnJ - mu) * Cinv;
  p.S = Vector3d(S(0, 0), S(1, 1), S(0, 1));
  // 3D: C^ijkl = lam C^ij C^kl + 2 (mu - lam ln J) Isym(C^-1); condensed over C_33 with
  // C^ab33 = lam C^ab / c, C^3333 = (lam + 2 (mu - lam ln J)) / c^2.
  const double m2 = mu - lam * lnJ;
  p.D = (lam - lam * lam / (lam + 2.0 * m2)) * voigt_outer(Cinv) + (2.0 * m2) * voigt_isym(Cinv);
  return p;
}

// ---------------------------------------------------------------------------------------------
// KirchhoffLoveShell

KirchhoffLoveShell::KirchhoffLoveShell(NurbsSurface reference, ShellMaterial material,
                                       ShellOptions options)
    : reference_(std::move(reference)), material_(material), options_(options) {
  const ShellMaterial& m = material_;
  if (!(m.E > 0.0) || !std::isfinite(m.E))
    fail("KirchhoffLoveShell: ShellMaterial.E must be finite and > 0, got " + num(m.E));
  if (!(m.thickness > 0.0) || !std::isfinite(m.thickness))
    fail("KirchhoffLoveShell: ShellMaterial.thickness must be finite and > 0, got " +
         num(m.thickness));
  if (!(m.nu > -1.0 && m.nu < 0.5))
    fail("KirchhoffLoveShell: ShellMaterial.nu must lie in (-1, 0.5), got " + num(m.nu));
  if (options_.quadrature_points < 0 || options_.quadrature_points > kMaxGaussPoints)
    fail("KirchhoffLoveShell: ShellOptions.quadrature_points must be in [0, 20], got " +
         std::to_string(options_.quadrature_points));
  const KnotVector* kv[2] = {&reference_.knots_u(), &reference_.knots_v()};
  const char* dir[2] = {"u", "v"};
  for (int d = 0; d < 2; ++d) {
    const int p = kv[d]->degree();
    if (p < 2 || p > kMaxShellDegree)
      fail(std::string("KirchhoffLoveShell: degree in ") + dir[d] + " must be in [2, " +
           std::to_string(kMaxShellDegree) + "] (C1, fixed-capacity elements), got " +
           std::to_string(p));
    const std::vector<double> br = kv[d]->breaks();
    for (std::size_t i = 1; i + 1 < br.size(); ++i)
      if (kv[d]->multiplicity(br[i]) > p - 1)
        fail(std::string("KirchhoffLoveShell: interior knot ") + dir[d] + " = " + num(br[i]) +
             " has multiplicity " + std::to_string(kv[d]->multiplicity(br[i])) +
             "; a C1 patch needs <= p - 1 = " + std::to_string(p - 1));
  }
  if (m.thickness_points < 2 || m.thickness_points > kMaxGaussPoints)
    fail("KirchhoffLoveShell: ShellMaterial.thickness_points must be in [2, 20], got " +
         std::to_string(m.thickness_points));
  if (m.law == ShellLaw::kNeoHookean) {
    thickness_rule_.n = m.thickness_points;
    gauss_legendre(m.thickness_points, thickness_rule_.z, thickness_rule_.w);
    for (int i = 0; i < m.thickness_points; ++i) {
      thickness_rule_.z[static_cast<std::size_t>(i)] *= 0.5 * m.thickness;
      thickness_rule_.w[static_cast<std::size_t>(i)] *= 0.5 * m.thickness;
    }
  }
  X_ = reference_.control_points();
  build_elements();
}

void KirchhoffLoveShell::build_elements() {
  const int p = reference_.degree_u(), q = reference_.degree_v();
  const int ngu = options_.quadrature_points > 0 ? options_.quadrature_points : p + 1;
  const int ngv = options_.quadrature_points > 0 ? options_.quadrature_points : q + 1;
  ngu_ = ngu;
  std::array<double, kMaxGaussPoints> xu{}, wu{}, xv{}, wv{};
  gauss_legendre(ngu, xu, wu);
  gauss_legendre(ngv, xv, wv);
  const KnotVector& U = reference_.knots_u();
  const KnotVector& V = reference_.knots_v();
  // The Gauss points of every non-empty span, per direction: the basis tables.
  const std::vector<double> tu = span_rule_points(
      U.breaks(), std::span<const double>(xu.data(), static_cast<std::size_t>(ngu)));
  const std::vector<double> tv = span_rule_points(
      V.breaks(), std::span<const double>(xv.data(), static_cast<std::size_t>(ngv)));
  table_u_ = SpanBasisTable(U, p, tu);
  table_v_ = SpanBasisTable(V, q, tv);
  std::size_t n_block = 0;
  for (int jv = q, ev = 0; jv < reference_.num_v(); ++jv) {
    if (!(V[jv + 1] > V[jv])) continue;
    for (int iu = p, eu = 0; iu < reference_.num_u(); ++iu)
      if (U[iu + 1] > U[iu] && options_.block.contains(eu++, ev)) ++n_block;
    ++ev;
  }
  elements_.reserve(n_block);
  qps_.reserve(n_block * static_cast<std::size_t>(ngu * ngv));
  SurfaceBasis B;
  for (int jv = q, ev = 0; jv < reference_.num_v(); ++jv) {
    if (!(V[jv + 1] > V[jv])) continue;
    for (int iu = p, eu = 0; iu < reference_.num_u(); ++iu) {
      if (!(U[iu + 1] > U[iu])) continue;
      ++patch_elements_;
      const int col = eu;
      if (!options_.block.contains(eu++, ev)) continue;
      elements_.push_back({static_cast<int>(qps_.size()),
                           ngu * ngv,
                           iu,
                           jv,
                           col * ngu,
                           ev * ngv,
                           {{U[iu], U[iu + 1]}, {V[jv], V[jv + 1]}}});
      // Tensor-product Gauss rule mapped to the element (u fastest).
      const double hu = 0.5 * (U[iu + 1] - U[iu]), hv = 0.5 * (V[jv + 1] - V[jv]);
      for (int b = 0; b < ngv; ++b)
        for (int a = 0; a < ngu; ++a) {
          const std::size_t ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
          const std::size_t ru = static_cast<std::size_t>(col * ngu + a),
                            rv = static_cast<std::size_t>(ev * ngv + b);
          rational_basis(reference_, table_u_[ru], table_v_[rv], B);
          qps_.push_back(make_point(tu[ru], tv[rv], hu * wu[ia] * hv * wv[ib], B));
        }
    }
    ++ev;
  }
}

void KirchhoffLoveShell::basis(int e, int g, SurfaceBasis& B) const {
  const Element& el = elements_[static_cast<std::size_t>(e)];
  rational_basis(reference_, table_u_[static_cast<std::size_t>(el.row_u + g % ngu_)],
                 table_v_[static_cast<std::size_t>(el.row_v + g / ngu_)], B);
}

KirchhoffLoveShell::QuadraturePoint KirchhoffLoveShell::make_point(double u, double v,
                                                                   double w_param,
                                                                   const SurfaceBasis& B) const {
  QuadraturePoint q;
  q.u = u;
  q.v = v;
  q.w_param = w_param;
  Kinematics k;
  kinematics(B, X_, B.span_u - reference_.degree_u(), B.span_v - reference_.degree_v(),
             reference_.num_u(), k);
  const Vector3d A3t = k.y[0].cross(k.y[1]);
  const double J = A3t.norm();
  if (!(J > 0.0))
    fail("KirchhoffLoveShell: the reference surface is singular (A_1 x A_2 = 0) at (u, v) = (" +
         num(u) + ", " + num(v) + ")");
  const Vector3d A3 = A3t / J;
  q.wJ = w_param * J;
  q.Aab << k.y[0].dot(k.y[0]), k.y[0].dot(k.y[1]), k.y[0].dot(k.y[1]), k.y[1].dot(k.y[1]);
  q.Bv = Vector3d(k.y[2].dot(A3), k.y[3].dot(A3), k.y[4].dot(A3));
  // [KBLW09] Sect. 3: C^abcd = E/(1-nu^2) [nu A^ab A^cd + 1/2 (1-nu)(A^ac A^bd + A^ad A^bc)],
  // Voigt rows (11, 22, 12) against strains (E11, E22, 2 E12).
  const Matrix2d G = q.Aab.inverse();
  const double nu = material_.nu;
  const double c = material_.E / (1.0 - nu * nu);
  const double g11 = G(0, 0), g22 = G(1, 1), g12 = G(0, 1);
  q.D << g11 * g11, nu * g11 * g22 + (1.0 - nu) * g12 * g12, g11 * g12,  //
      nu * g11 * g22 + (1.0 - nu) * g12 * g12, g22 * g22, g22 * g12,     //
      g11 * g12, g22 * g12, 0.5 * (1.0 - nu) * g11 * g22 + 0.5 * (1.0 + nu) * g12 * g12;
  q.D *= c;
  return q;
}

int KirchhoffLoveShell::num_quadrature_points(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).qp_count;
}
Domain2 KirchhoffLoveShell::element_range(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).range;
}
const KirchhoffLoveShell::QuadraturePoint& KirchhoffLoveShell::quadrature_point(int e,
                                                                                int q) const {
  const Element& el = elements_.at(static_cast<std::size_t>(e));
  return qps_.at(static_cast<std::size_t>(el.qp_begin + q));
}
int KirchhoffLoveShell::element_point(int e, int k) const {
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const int nu = reference_.degree_u() + 1;
  return (el.span_u - reference_.degree_u() + k % nu) +
         reference_.num_u() * (el.span_v - reference_.degree_v() + k / nu);
}

double KirchhoffLoveShell::reference_area() const {
  double A = 0.0;
  for (const QuadraturePoint& q : qps_) A += q.wJ;
  return A;
}

template <int Order>
void KirchhoffLoveShell::element_kernel(int e, std::span<const Vector3d> x, double* energy,
                                        ShellElementVector* f, ShellElementMatrix* K) const {
  if (static_cast<int>(x.size()) != num_control_points())
    throw std::invalid_argument("KirchhoffLoveShell: " + std::to_string(x.size()) +
                                " current points, expected " +
                                std::to_string(num_control_points()));
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const int np = (reference_.degree_u() + 1) * (reference_.degree_v() + 1);
  const int fu = el.span_u - reference_.degree_u(), fv = el.span_v - reference_.degree_v();
  if (energy) *energy = 0.0;
  if (f) f->setZero(3 * np);
  if (K) K->setZero(3 * np, 3 * np);
  Kinematics kin;
  Density d;
  Eigen::Matrix<double, 15, 3> G;
  SurfaceBasis B;
  for (int g = 0; g < el.qp_count; ++g) {
    const QuadraturePoint& q = qps_[static_cast<std::size_t>(el.qp_begin + g)];
    basis(e, g, B);
    kinematics(B, x, fu, fv, reference_.num_u(), kin);
    density<Order>(q, material_, thickness_rule_, kin, d);
    if (energy) *energy += q.wJ * d.W;  // Pi_e = int W dA
    if constexpr (Order < 1) continue;
    const std::array<const double*, 5> dR{B.d1.data(), B.d2.data(), B.d11.data(), B.d22.data(),
                                          B.d12.data()};
    // f_k = int sum_s dR_s[k] dW/dy_s dA
    for (int k = 0; k < np; ++k) {
      Vector3d fk = Vector3d::Zero();
      for (int s = 0; s < 5; ++s)
        fk.noalias() += dR[static_cast<std::size_t>(s)][k] * d.g.segment<3>(3 * s);
      f->segment<3>(3 * k).noalias() += q.wJ * fk;
    }
    if constexpr (Order < 2) continue;
    // K_kl = int sum_s sum_t dR_s[k] H_st dR_t[l] dA: first G_l = sum_t H_(:,t) dR_t[l] (15 x 3),
    // then the 3 x 3 blocks of the upper triangle, mirrored.
    d.H *= q.wJ;
    for (int l = 0; l < np; ++l) {
      G.noalias() = dR[0][l] * d.H.middleCols<3>(0);
      for (int t = 1; t < 5; ++t)
        G.noalias() += dR[static_cast<std::size_t>(t)][l] * d.H.middleCols<3>(3 * t);
      for (int k = 0; k <= l; ++k) {
        Matrix3d Kkl = dR[0][k] * G.middleRows<3>(0);
        for (int s = 1; s < 5; ++s)
          Kkl.noalias() += dR[static_cast<std::size_t>(s)][k] * G.middleRows<3>(3 * s);
        K->block<3, 3>(3 * k, 3 * l) += Kkl;
      }
    }
  }
  if constexpr (Order >= 2)
    for (int l = 0; l < np; ++l)
      for (int k = 0; k < l; ++k)
        K->block<3, 3>(3 * l, 3 * k) = K->block<3, 3>(3 * k, 3 * l).transpose();
}

double KirchhoffLoveShell::element_energy(int e, std::span<const Vector3d> x) const {
  double Pi = 0.0;
  element_kernel<0>(e, x, &Pi, nullptr, nullptr);
  return Pi;
}

double KirchhoffLoveShell::energy(std::span<const Vector3d> x) const {
  double Pi = 0.0;
  for (int e = 0; e < num_elements(); ++e) Pi += element_energy(e, x);
  return Pi;
}

void KirchhoffLoveShell::element_forces(int e, std::span<const Vector3d> x,
                                        ShellElementVector& f) const {
  element_kernel<1>(e, x, nullptr, &f, nullptr);
}

void KirchhoffLoveShell::element_tangent(int e, std::span<const Vector3d> x, ShellElementVector& f,
                                         ShellElementMatrix& K) const {
  element_kernel<2>(e, x, nullptr, &f, &K);
}

void KirchhoffLoveShell::assemble(std::span<const Vector3d> x, Eigen::VectorXd& f_int,
                                  std::vector<Triplet>* K) const {
  // Elements in parallel (OpenMP), each writing its own slots: its force vector into fe_all and
  // its triplets into the block of K reserved for it, in element order. The forces are then
  // added in element order by one thread, so f_int and K are the same, bit for bit, for any
  // number of threads.
  const int ne = num_elements();
  const int np = (reference_.degree_u() + 1) * (reference_.degree_v() + 1);
  const std::size_t per_element = static_cast<std::size_t>(9 * np * np);
  const std::size_t base = K ? K->size() : 0;
  if (K) {
    // An eighth more room for what the caller appends (springs, contact), so that the list,
    // most of an assembly's memory, does not double for a few more triplets.
    const std::size_t n = static_cast<std::size_t>(ne) * per_element;
    if (K->capacity() < base + n) K->reserve(base + n + n / 8);
    K->resize(base + n);
  }
  std::vector<ShellElementVector> fe_all(static_cast<std::size_t>(ne));
  // Small meshes stay on one thread (the pool's start costs more than they do).
#pragma omp parallel for schedule(static) if (ne >= kParallelElements)
  for (int e = 0; e < ne; ++e) {
    ShellElementVector& fe = fe_all[static_cast<std::size_t>(e)];
    if (!K) {
      element_forces(e, x, fe);
      continue;
    }
    ShellElementMatrix Ke;
    element_tangent(e, x, fe, Ke);
    std::array<int, kMaxShellElementPoints> idx{};
    for (int k = 0; k < np; ++k) idx[static_cast<std::size_t>(k)] = 3 * element_point(e, k);
    Triplet* out = K->data() + base + static_cast<std::size_t>(e) * per_element;
    for (int l = 0; l < np; ++l)
      for (int b = 0; b < 3; ++b)
        for (int k = 0; k < np; ++k)
          for (int a = 0; a < 3; ++a)
            *out++ = Triplet(idx[static_cast<std::size_t>(k)] + a,
                             idx[static_cast<std::size_t>(l)] + b, Ke(3 * k + a, 3 * l + b));
  }
  f_int.setZero(num_dofs());
  for (int e = 0; e < ne; ++e)
    for (int k = 0; k < np; ++k)
      f_int.segment<3>(3 * element_point(e, k)) +=
          fe_all[static_cast<std::size_t>(e)].segment<3>(3 * k);
}

Vector3d KirchhoffLoveShell::point(double u, double v, std::span<const Vector3d> x) const {
  SurfaceBasis B;
  rational_basis(reference_, u, v, B);
  Vector3d r = Vector3d::Zero();
  for (int k = 0; k < B.count(); ++k)
    r.noalias() +=
        B.R[static_cast<std::size_t>(k)] * x[static_cast<std::size_t>(B.global_index(k))];
  return r;
}

Vector3d KirchhoffLoveShell::normal(double u, double v, std::span<const Vector3d> x) const {
  SurfaceBasis B;
  rational_basis(reference_, u, v, B);
  Kinematics k;
  kinematics(B, x, B.span_u - reference_.degree_u(), B.span_v - reference_.degree_v(),
             reference_.num_u(), k);
  return k.y[0].cross(k.y[1]).normalized();
}

ShellStresses KirchhoffLoveShell::stresses(double u, double v, std::span<const Vector3d> x) const {
  SurfaceBasis B;
  rational_basis(reference_, u, v, B);
  const QuadraturePoint q = make_point(u, v, 0.0, B);
  Kinematics k;
  kinematics(B, x, B.span_u - reference_.degree_u(), B.span_v - reference_.degree_v(),
             reference_.num_u(), k);
  Density d;
  density<0>(q, material_, thickness_rule_, k, d);
  ShellStresses s;
  s.membrane_strain = d.eps;
  s.bending_strain = d.kap;
  s.membrane_force = d.nf;
  s.moment = d.mf;
  s.energy_density = d.W;
  // Local frame of the reference: e1 = A1/|A1|, e2 = A3 x e1; N_ij = (e_i.A_a)(e_j.A_b) n^ab.
  Kinematics K0;
  kinematics(B, X_, B.span_u - reference_.degree_u(), B.span_v - reference_.degree_v(),
             reference_.num_u(), K0);
  const Vector3d e1 = K0.y[0].normalized();
  const Vector3d e2 = K0.y[0].cross(K0.y[1]).normalized().cross(e1);
  Matrix2d T;
  T << e1.dot(K0.y[0]), e1.dot(K0.y[1]), e2.dot(K0.y[0]), e2.dot(K0.y[1]);
  auto to_local = [&T](const Vector3d& c) {
    Matrix2d t;
    t << c[0], c[2], c[2], c[1];
    const Matrix2d L = T * t * T.transpose();
    return Vector3d(L(0, 0), L(1, 1), L(0, 1));
  };
  s.membrane_force_local = to_local(d.nf);
  s.moment_local = to_local(d.mf);
  const double h = material_.thickness;
  for (double side : {-1.0, 1.0}) {
    const Vector3d sig = s.membrane_force_local / h + side * 6.0 / (h * h) * s.moment_local;
    const double vm = std::sqrt(
        std::max(0.0, sig[0] * sig[0] - sig[0] * sig[1] + sig[1] * sig[1] + 3.0 * sig[2] * sig[2]));
    s.von_mises = std::max(s.von_mises, vm);
  }
  return s;
}

}  // namespace iga
