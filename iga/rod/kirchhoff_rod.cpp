// Rotation-free Kirchhoff rod: quadrature data, the energy density with its gradient and Hessian
// in (r', r''), element forces and tangents, assembly; RodProblem (DOF map, BCs, loads).
// References and notation: see kirchhoff_rod.hpp ([PT97], [GC13], [MPW14], [MPW15], [BBP16]).
#include "iga/rod/kirchhoff_rod.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "geometry/differential_geometry.hpp"
#include "geometry/number_text.hpp"
#include "iga/core/quadrature.hpp"
#include "iga/rod/rod_common.hpp"

namespace iga {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Value, gradient and Hessian of the energy density W(a, b), a = r', b = r'' (6 variables:
/// a first). `order` 0: W only; 1: and g; 2: and H. Also the strains for output.
struct Density {
  double W = 0.0;
  Vector6d g = Vector6d::Zero();
  Matrix6d H = Matrix6d::Zero();
  double eps = 0.0;
  double curvature = 0.0;
  Vector2d bending_strain = Vector2d::Zero();
  Vector2d bending_moment = Vector2d::Zero();
};

/// Axial part: eps = (a.a - A) / (2 A) (Green-Lagrange, [BBP16]); W_a = 1/2 EA eps^2,
/// dW_a/da = EA eps a / A, d2W_a/da2 = EA (a a^T / A^2 + eps I / A).
void add_axial(const KirchhoffRod::QuadraturePoint& q, double EA, const Vector3d& a, int order,
               Density& out) {
  const double eps = (a.squaredNorm() - q.A) / (2.0 * q.A);
  out.eps = eps;
  out.W += 0.5 * EA * eps * eps;
  if (order >= 1) out.g.head<3>().noalias() += (EA * eps / q.A) * a;
  if (order >= 2) {
    out.H.topLeftCorner<3, 3>().noalias() += (EA / (q.A * q.A)) * (a * a.transpose());
    out.H.topLeftCorner<3, 3>().diagonal().array() += EA * eps / q.A;
  }
}

/// Bending through k2 = |kappa|^2 = f h, f = |a x b|^2, h = 1 / (A (a.a)^2) ([MPW15] torsion-free
/// rod): W_b = 1/2 EI k2 for a straight isotropic reference, W_b = 1/2 EI (sqrt(k2 + delta^2) -
/// |K|)^2 for the magnitude measure. Derivatives (written out here):
///   grad_a f = 2 b x c, grad_b f = 2 c x a (c = a x b);
///   f_aa = 2 (b.b) I - 2 b b^T, f_bb = 2 (a.a) I - 2 a a^T, f_ab = 4 a b^T - 2 b a^T - 2 (a.b) I;
///   grad_a h = -4 a / (A (a.a)^3), h_aa = -4 I / (A (a.a)^3) + 24 a a^T / (A (a.a)^4).
void add_bending_k2(const KirchhoffRod::QuadraturePoint& q, double EI, bool magnitude,
                    const Vector3d& a, const Vector3d& b, int order, Density& out) {
  const Vector3d c = a.cross(b);
  const double qa = a.squaredNorm();
  const double f = c.squaredNorm();
  const double h = 1.0 / (q.A * qa * qa);
  const double k2 = f * h;
  out.curvature = std::sqrt(k2);

  double dW = 0.5 * EI, d2W = 0.0;  // dW/dk2, d2W/dk2^2
  if (magnitude && q.Kmag > 0.0) {
    const double delta = 1e-6 * q.Kmag;
    const double kap = std::sqrt(k2 + delta * delta);
    const double m = EI * (kap - q.Kmag);
    out.W += 0.5 * EI * (kap - q.Kmag) * (kap - q.Kmag);
    out.bending_strain = Vector2d(kap - q.Kmag, 0.0);
    out.bending_moment = Vector2d(m, 0.0);
    dW = 0.5 * EI * (1.0 - q.Kmag / kap);
    d2W = EI * q.Kmag / (4.0 * kap * kap * kap);
  } else {
    out.W += 0.5 * EI * k2;
    out.bending_strain = Vector2d(out.curvature, 0.0);
    out.bending_moment = Vector2d(EI * out.curvature, 0.0);
  }
  if (order < 1) return;

  const Vector3d fa = 2.0 * b.cross(c);
  const Vector3d fb = 2.0 * c.cross(a);
  const double h3 = h / qa;  // 1 / (A (a.a)^3)
  const Vector3d ha = -4.0 * h3 * a;
  Vector6d dk2;
  dk2.head<3>() = h * fa + f * ha;
  dk2.tail<3>() = h * fb;
  out.g.noalias() += dW * dk2;
  if (order < 2) return;

  const double qb = b.squaredNorm(), ab = a.dot(b);
  const Matrix3d I = Matrix3d::Identity();
  Matrix3d f_aa = 2.0 * qb * I;
  f_aa.noalias() -= 2.0 * (b * b.transpose());
  Matrix3d f_bb = 2.0 * qa * I;
  f_bb.noalias() -= 2.0 * (a * a.transpose());
  Matrix3d f_ab = -2.0 * ab * I;
  f_ab.noalias() += 4.0 * (a * b.transpose());
  f_ab.noalias() -= 2.0 * (b * a.transpose());
  Matrix3d h_aa = -4.0 * h3 * I;
  h_aa.noalias() += (24.0 * h3 / qa) * (a * a.transpose());

  Matrix6d d2k2;
  d2k2.topLeftCorner<3, 3>() = h * f_aa + f * h_aa;
  d2k2.topLeftCorner<3, 3>().noalias() += fa * ha.transpose();
  d2k2.topLeftCorner<3, 3>().noalias() += ha * fa.transpose();
  d2k2.topRightCorner<3, 3>() = h * f_ab;
  d2k2.topRightCorner<3, 3>().noalias() += ha * fb.transpose();
  d2k2.bottomLeftCorner<3, 3>() = d2k2.topRightCorner<3, 3>().transpose();
  d2k2.bottomRightCorner<3, 3>() = h * f_bb;
  out.H.noalias() += dW * d2k2;
  if (d2W != 0.0) out.H.noalias() += d2W * (dk2 * dk2.transpose());
}

/// Bending in the section frame carried by the smallest rotation T -> t ([MPW14]):
///   d_a = D_a - (D_a.t)/(1 + T.t) (T + t), and with kappa.t = 0, kappa = c / (J a.a),
///   kappa_a = kappa.d_a = (c.D_a) phi - (c.T) psi_a,   c = a x b,   J = |R'| = sqrt(A),
///   phi = 1 / (J a.a),  psi_a = (D_a.a) / u,  u = J s (a.a),  s = l + T.a,  l = |a|.
/// Each term is g = (c.V) chi(a) with a constant V; its derivatives are
///   grad_a g = chi (b x V) + (c.V) grad chi,   grad_b g = chi (V x a),
///   g_aa = (b x V) grad chi^T + grad chi (b x V)^T + (c.V) chi_aa,
///   g_ab = -chi [V]x + grad chi (V x a)^T,     g_bb = 0.
/// W_b = 1/2 sum_a EI_a (kappa_a - K_a)^2.
void add_bending_frame(const KirchhoffRod::QuadraturePoint& q, const RodSection& sec,
                       const Vector3d& a, const Vector3d& b, int order, Density& out) {
  const Vector3d c = a.cross(b);
  const double qa = a.squaredNorm();
  const double l = std::sqrt(qa);
  const double J = std::sqrt(q.A);
  const double phi = 1.0 / (J * qa);
  const double s = l + q.T.dot(a);
  const double u = J * s * qa;
  const double cT = c.dot(q.T);
  out.curvature = c.norm() * phi;

  // Derivatives of phi and u (functions of a only):
  //   grad phi = -2 a / (J (a.a)^2),  phi_aa = -2 I / (J (a.a)^2) + 8 a a^T / (J (a.a)^3);
  //   grad s = t + T,  s_aa = (I - t t^T) / l;
  //   grad u = J ((a.a) grad s + 2 s a),  u_aa = J ((a.a) s_aa + 2 grad s a^T + 2 a grad s^T + 2 s
  //   I).
  Vector3d dphi = Vector3d::Zero(), du = Vector3d::Zero();
  Matrix3d d2phi = Matrix3d::Zero(), d2u = Matrix3d::Zero();
  const Matrix3d I = Matrix3d::Identity();
  if (order >= 1) {
    const double phi2 = phi / qa;  // 1 / (J (a.a)^2)
    dphi = -2.0 * phi2 * a;
    const Vector3d t = a / l;
    const Vector3d ds = t + q.T;
    du = J * (qa * ds + 2.0 * s * a);
    if (order >= 2) {
      d2phi = -2.0 * phi2 * I;
      d2phi.noalias() += (8.0 * phi2 / qa) * (a * a.transpose());
      Matrix3d d2s = I / l;
      d2s.noalias() -= (t * t.transpose()) / l;
      d2u = (J * qa) * d2s + (2.0 * J * s) * I;
      d2u.noalias() += (2.0 * J) * (ds * a.transpose() + a * ds.transpose());
    }
  }

  const Vector3d* D[2] = {&q.D1, &q.D2};
  const double K[2] = {q.K1, q.K2};
  const double EI[2] = {sec.EI1, sec.EI2};
  for (int al = 0; al < 2; ++al) {
    const Vector3d& Da = *D[al];
    const double p = Da.dot(a);
    const double cD = c.dot(Da);
    const double psi = p / u;
    const double kappa = cD * phi - cT * psi;  // kappa_a
    const double m = EI[al] * (kappa - K[al]);
    out.W += 0.5 * EI[al] * (kappa - K[al]) * (kappa - K[al]);
    out.bending_strain[al] = kappa - K[al];
    out.bending_moment[al] = m;
    if (order < 1 || EI[al] == 0.0) continue;

    const Vector3d dpsi = Da / u - (p / (u * u)) * du;
    const Vector3d bxD = b.cross(Da), bxT = b.cross(q.T);
    const Vector3d Dxa = Da.cross(a), Txa = q.T.cross(a);
    Vector6d dk;
    dk.head<3>() = phi * bxD + cD * dphi - psi * bxT - cT * dpsi;
    dk.tail<3>() = phi * Dxa - psi * Txa;
    out.g.noalias() += m * dk;
    if (order < 2) continue;

    Matrix3d d2psi = (2.0 * p / (u * u * u)) * (du * du.transpose());
    d2psi.noalias() -= (Da * du.transpose() + du * Da.transpose()) / (u * u);
    d2psi.noalias() -= (p / (u * u)) * d2u;
    Matrix3d k_aa = cD * d2phi - cT * d2psi;
    k_aa.noalias() += bxD * dphi.transpose() + dphi * bxD.transpose();
    k_aa.noalias() -= bxT * dpsi.transpose() + dpsi * bxT.transpose();
    Matrix3d k_ab = psi * skew(q.T) - phi * skew(Da);
    k_ab.noalias() += dphi * Dxa.transpose();
    k_ab.noalias() -= dpsi * Txa.transpose();

    out.H.noalias() += EI[al] * (dk * dk.transpose());
    out.H.topLeftCorner<3, 3>().noalias() += m * k_aa;
    out.H.topRightCorner<3, 3>().noalias() += m * k_ab;
    out.H.bottomLeftCorner<3, 3>().noalias() += m * k_ab.transpose();
  }
}

void density(const KirchhoffRod::QuadraturePoint& q, const RodSection& sec, BendingMeasure measure,
             const Vector3d& a, const Vector3d& b, int order, Density& out) {
  if (q.axial) add_axial(q, sec.EA, a, order, out);
  if (!q.bending) return;
  if (q.frame)
    add_bending_frame(q, sec, a, b, order, out);
  else
    add_bending_k2(q, sec.EI1, measure == BendingMeasure::kCurvatureMagnitude, a, b, order, out);
}

/// r' and r'' at a quadrature point from the element's control points.
void centre_line_derivs(const RationalBasis& B, std::span<const Vector3d> x, Vector3d& a,
                        Vector3d& b) {
  a.setZero();
  b.setZero();
  for (int j = 0; j < B.count; ++j) {
    const Vector3d& xj = x[static_cast<std::size_t>(B.first + j)];
    a.noalias() += B.dN[static_cast<std::size_t>(j)] * xj;
    b.noalias() += B.ddN[static_cast<std::size_t>(j)] * xj;
  }
}

std::string num(double v) {
  return num_text(v, 6);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// RodSection, rational basis

RodSection RodSection::circular(double E, double r) {
  const double A = std::numbers::pi * r * r;
  const double I = std::numbers::pi * r * r * r * r / 4.0;
  return {E * A, E * I, E * I, Vector3d::Zero()};
}

RodSection RodSection::rectangular(double E, double w, double h, const Vector3d& width_direction) {
  return {E * w * h, E * w * h * h * h / 12.0, E * h * w * w * w / 12.0, width_direction};
}

// ---------------------------------------------------------------------------------------------
// KirchhoffRod

KirchhoffRod::KirchhoffRod(NurbsCurve reference, RodSection section, RodOptions options)
    : reference_(std::move(reference)), section_(std::move(section)), options_(options) {
  const int p = reference_.degree();
  if (p < 2)
    throw RodError("KirchhoffRod: the curve must be of degree >= 2 (C1), got " + std::to_string(p));
  detail::check_rod_curve_and_section(reference_, section_, "KirchhoffRod");
  const KnotVector& U = reference_.knots();
  if (options_.bending == BendingMeasure::kCurvatureMagnitude && !section_.isotropic())
    throw RodError("KirchhoffRod: the curvature magnitude measure needs EI1 == EI2, got " +
                   num(section_.EI1) + ", " + num(section_.EI2));
  if (!section_.isotropic() && !(section_.ref_direction.norm() > 0.0))
    throw RodError("KirchhoffRod: a general section (EI1 != EI2) needs a ref_direction");
  if (options_.quadrature_points < 0 || options_.quadrature_points > kMaxGaussPoints)
    throw RodError("KirchhoffRod: quadrature_points must be in [0, 20], got " +
                   std::to_string(options_.quadrature_points));
  if (options_.axial_quadrature_points < 0 || options_.axial_quadrature_points > kMaxGaussPoints)
    throw RodError("KirchhoffRod: axial_quadrature_points must be in [0, 20], got " +
                   std::to_string(options_.axial_quadrature_points));

  const int ng = options_.quadrature_points > 0 ? options_.quadrature_points : p + 1;
  const int na = options_.axial_quadrature_points > 0 ? options_.axial_quadrature_points : ng;
  std::array<double, kMaxGaussPoints> gx{}, gw{}, ax{}, aw{};
  gauss_legendre(ng, gx, gw);
  gauss_legendre(na, ax, aw);

  const std::vector<double>& k = U.knots();
  const int n = reference_.num_control_points();
  for (int i = p; i < n; ++i) {
    const double lo = k[static_cast<std::size_t>(i)], hi = k[static_cast<std::size_t>(i + 1)];
    if (!(hi > lo)) continue;
    Element el;
    el.first = i - p;
    el.range = {lo, hi};
    el.qp_begin = static_cast<int>(qps_.size());
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (int g = 0; g < ng; ++g) {
      const std::size_t gi = static_cast<std::size_t>(g);
      qps_.push_back(make_point(mid + half * gx[gi], half * gw[gi], hi - lo));
      qps_.back().axial = (na == ng);
    }
    if (na != ng)  // separate rule for the axial term
      for (int g = 0; g < na; ++g) {
        const std::size_t gi = static_cast<std::size_t>(g);
        qps_.push_back(make_point(mid + half * ax[gi], half * aw[gi], hi - lo));
        qps_.back().bending = false;
      }
    el.qp_count = static_cast<int>(qps_.size()) - el.qp_begin;
    elements_.push_back(el);
  }
}

KirchhoffRod::QuadraturePoint KirchhoffRod::make_point(double xi, double weight,
                                                       double element_length) const {
  QuadraturePoint q;
  q.xi = xi;
  q.basis = rational_basis(reference_, xi);
  Vector3d R1 = Vector3d::Zero(), R2 = Vector3d::Zero();
  for (int j = 0; j < q.basis.count; ++j) {
    const Vector3d X = reference_.control_point(q.basis.first + j);
    R1.noalias() += q.basis.dN[static_cast<std::size_t>(j)] * X;
    R2.noalias() += q.basis.ddN[static_cast<std::size_t>(j)] * X;
  }
  q.A = R1.squaredNorm();
  const double J = std::sqrt(q.A);
  if (!(J > 0.0))
    throw RodError("KirchhoffRod: the reference curve is singular (|R'| = 0) at xi = " + num(xi));
  q.wJ = weight * J;
  q.T = R1 / J;
  // The stress-free curvature vector: the reference curve's, or 0 for a rod straight when
  // unloaded (RodOptions::straight_stress_free).
  const Vector3d K =
      options_.straight_stress_free ? Vector3d::Zero() : Vector3d(R1.cross(R2) / (q.A * J));
  q.Kmag = K.norm();

  if (options_.bending == BendingMeasure::kCurvatureMagnitude) {
    q.frame = false;
  } else if (section_.isotropic()) {
    // K = 0 (to round-off against the element size): the exact torsion-free form 1/2 EI |kappa|^2
    // ([MPW15]); otherwise any D_1 normal to T gives the same isotropic energy: D_1 = K/|K|.
    q.frame = q.Kmag * element_length * J > 1e-10;
    if (q.frame) {
      q.D1 = K / q.Kmag;
      q.D2 = q.T.cross(q.D1);
      q.K1 = q.Kmag;
      q.K2 = 0.0;
    } else {
      q.Kmag = 0.0;
    }
  } else {
    const Vector3d& D = section_.ref_direction;
    const Vector3d Dp = D - D.dot(q.T) * q.T;
    if (!(Dp.norm() > 1e-8 * D.norm()))
      throw RodError(
          "KirchhoffRod: the section's ref_direction is parallel to the tangent at "
          "xi = " +
          num(xi));
    q.frame = true;
    q.D1 = Dp.normalized();
    q.D2 = q.T.cross(q.D1);
    q.K1 = K.dot(q.D1);
    q.K2 = K.dot(q.D2);
  }
  return q;
}

int KirchhoffRod::num_quadrature_points(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).qp_count;
}
Interval KirchhoffRod::element_range(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).range;
}
int KirchhoffRod::element_first_point(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).first;
}
const KirchhoffRod::QuadraturePoint& KirchhoffRod::quadrature_point(int e, int q) const {
  const Element& el = elements_.at(static_cast<std::size_t>(e));
  return qps_.at(static_cast<std::size_t>(el.qp_begin + q));
}

double KirchhoffRod::reference_length() const {
  double L = 0.0;
  for (const QuadraturePoint& q : qps_)
    if (q.bending) L += q.wJ;
  return L;
}

double KirchhoffRod::element_energy(int e, std::span<const Vector3d> x) const {
  const Element& el = elements_[static_cast<std::size_t>(e)];
  double Pi = 0.0;
  Vector3d a, b;
  for (int g = 0; g < el.qp_count; ++g) {
    const QuadraturePoint& q = qps_[static_cast<std::size_t>(el.qp_begin + g)];
    centre_line_derivs(q.basis, x, a, b);
    Density d;
    density(q, section_, options_.bending, a, b, 0, d);
    Pi += q.wJ * d.W;  // Pi_e = int W dS
  }
  return Pi;
}

double KirchhoffRod::energy(std::span<const Vector3d> x) const {
  double Pi = 0.0;
  for (int e = 0; e < num_elements(); ++e) Pi += element_energy(e, x);
  return Pi;
}

template <bool Tangent>
void KirchhoffRod::element_kernel(int e, std::span<const Vector3d> x, RodElementVector& f,
                                  RodElementMatrix* K) const {
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const int np = degree() + 1;
  f.setZero(3 * np);
  if constexpr (Tangent) K->setZero(3 * np, 3 * np);
  Vector3d a, b;
  for (int g = 0; g < el.qp_count; ++g) {
    const QuadraturePoint& q = qps_[static_cast<std::size_t>(el.qp_begin + g)];
    centre_line_derivs(q.basis, x, a, b);
    Density d;
    density(q, section_, options_.bending, a, b, Tangent ? 2 : 1, d);
    const Vector3d ga = q.wJ * d.g.head<3>(), gb = q.wJ * d.g.tail<3>();
    Matrix3d Haa, Hab, Hba, Hbb;
    if constexpr (Tangent) {
      Haa = q.wJ * d.H.topLeftCorner<3, 3>();
      Hab = q.wJ * d.H.topRightCorner<3, 3>();
      Hba = q.wJ * d.H.bottomLeftCorner<3, 3>();
      Hbb = q.wJ * d.H.bottomRightCorner<3, 3>();
    }
    for (int j = 0; j < np; ++j) {
      const double dNj = q.basis.dN[static_cast<std::size_t>(j)];
      const double ddNj = q.basis.ddN[static_cast<std::size_t>(j)];
      // f_j = int (dW/dr' R_j' + dW/dr'' R_j'') dS
      f.segment<3>(3 * j).noalias() += dNj * ga + ddNj * gb;
      if constexpr (Tangent) {
        // K_jk = (R_j' H_aa + R_j'' H_ba) R_k' + (R_j' H_ab + R_j'' H_bb) R_k''
        const Matrix3d Ga = dNj * Haa + ddNj * Hba;
        const Matrix3d Gb = dNj * Hab + ddNj * Hbb;
        for (int k = 0; k < np; ++k) {
          const double dNk = q.basis.dN[static_cast<std::size_t>(k)];
          const double ddNk = q.basis.ddN[static_cast<std::size_t>(k)];
          K->template block<3, 3>(3 * j, 3 * k).noalias() += dNk * Ga + ddNk * Gb;
        }
      }
    }
  }
}

void KirchhoffRod::element_forces(int e, std::span<const Vector3d> x, RodElementVector& f) const {
  element_kernel<false>(e, x, f, nullptr);
}

void KirchhoffRod::element_tangent(int e, std::span<const Vector3d> x, RodElementVector& f,
                                   RodElementMatrix& K) const {
  element_kernel<true>(e, x, f, &K);
}

void KirchhoffRod::assemble(std::span<const Vector3d> x, Eigen::VectorXd& f_int,
                            std::vector<Triplet>* K) const {
  if (static_cast<int>(x.size()) != num_control_points())
    throw std::invalid_argument("KirchhoffRod::assemble: " + std::to_string(x.size()) +
                                " current points, expected " +
                                std::to_string(num_control_points()));
  // Elements in parallel (OpenMP), each writing its own slots: its forces into fe_all and its
  // triplets into the block of K reserved for it; the forces are added in element order by one
  // thread, so f_int and K are the same bit for bit for any number of threads.
  const int nel = num_elements();
  const int ne = 3 * (degree() + 1);
  const std::size_t per_element = static_cast<std::size_t>(ne * ne);
  const std::size_t base = K ? K->size() : 0;
  if (K) K->resize(base + static_cast<std::size_t>(nel) * per_element);
  std::vector<RodElementVector> fe_all(static_cast<std::size_t>(nel));
#pragma omp parallel for schedule(static) if (nel >= kParallelRodElements)
  for (int e = 0; e < nel; ++e) {
    RodElementVector& fe = fe_all[static_cast<std::size_t>(e)];
    if (!K) {
      element_forces(e, x, fe);
      continue;
    }
    RodElementMatrix Ke;
    element_tangent(e, x, fe, Ke);
    const int first = 3 * elements_[static_cast<std::size_t>(e)].first;
    Triplet* out = K->data() + base + static_cast<std::size_t>(e) * per_element;
    for (int c = 0; c < ne; ++c)
      for (int r = 0; r < ne; ++r) *out++ = Triplet(first + r, first + c, Ke(r, c));
  }
  f_int.setZero(num_dofs());
  for (int e = 0; e < nel; ++e)
    f_int.segment(3 * elements_[static_cast<std::size_t>(e)].first, ne) +=
        fe_all[static_cast<std::size_t>(e)];
}

Vector3d KirchhoffRod::point(double xi, std::span<const Vector3d> x) const {
  const RationalBasis B = rational_basis(reference_, xi);
  Vector3d r = Vector3d::Zero();
  for (int j = 0; j < B.count; ++j)
    r.noalias() += B.N[static_cast<std::size_t>(j)] * x[static_cast<std::size_t>(B.first + j)];
  return r;
}

RodStrains KirchhoffRod::strains(double xi, std::span<const Vector3d> x) const {
  const Interval dom = reference_.domain();
  xi = std::clamp(xi, dom.lo, dom.hi);
  const int span = reference_.knots().find_span(xi);
  const double h = reference_.knots()[span + 1] - reference_.knots()[span];
  const QuadraturePoint q = make_point(xi, 0.0, h);
  Vector3d a, b;
  centre_line_derivs(q.basis, x, a, b);
  Density d;
  density(q, section_, options_.bending, a, b, 0, d);
  RodStrains s;
  s.eps = d.eps;
  s.axial_force = section_.EA * d.eps;
  s.curvature = d.curvature;
  s.bending_strain = d.bending_strain;
  s.bending_moment = d.bending_moment;
  s.energy_density = d.W;
  return s;
}

// ---------------------------------------------------------------------------------------------
// RodProblem

namespace {
[[noreturn]] void rod_fail(const std::string& msg) {
  throw RodError(msg);
}
}  // namespace

RodProblem::RodProblem(KirchhoffRod rod)
    : ControlPointProblem(rod.reference().control_points(), "RodProblem", &rod_fail),
      rod_(std::move(rod)) {}

void RodProblem::symmetry(RodEnd end, const Vector3d& normal) {
  const int last = num_control_points() - 1;
  end_symmetry(end == RodEnd::kStart ? 0 : last, end == RodEnd::kStart ? 1 : last - 1, normal,
               "RodProblem::symmetry", &rod_fail);
}

void RodProblem::clamp(RodEnd end) {
  const int n = num_control_points();
  const int i0 = end == RodEnd::kStart ? 0 : n - 1;
  const int i1 = end == RodEnd::kStart ? 1 : n - 2;
  if (dofs_.rotated(i1) || dofs_.constrained(i1, 0) || dofs_.constrained(i1, 1) ||
      dofs_.constrained(i1, 2))
    throw RodError("RodProblem::clamp: control point " + std::to_string(i1) +
                   " (neighbour of the clamped end) already has a local basis or constraints");
  // Open knots: r'(end) = (p / knot span) (w_1 / w_0) (x_1 - x_0), so holding x_0 and the
  // components of x_1 normal to the end tangent holds the tangent direction.
  const Interval dom = rod_.reference().domain();
  const RationalBasis B = rational_basis(rod_.reference(), end == RodEnd::kStart ? dom.lo : dom.hi);
  Vector3d R1 = Vector3d::Zero();
  for (int j = 0; j < B.count; ++j)
    R1.noalias() += B.dN[static_cast<std::size_t>(j)] * rod_.reference().control_point(B.first + j);
  const Vector3d T = R1.normalized();
  Matrix3d Q;
  Q.col(0) = T;
  Q.col(1) = T.unitOrthogonal();
  Q.col(2) = T.cross(Q.col(1));
  fix(i0);
  set_local_basis(i1, Q);
  fix(i1, 1);
  fix(i1, 2);
}

void RodProblem::add_point_load(double xi, const Vector3d& F, LoadCurve curve) {
  add_nodal_load(detail::rod_point_load(rod_.reference(), xi, F), std::move(curve));
}

void detail::check_rod_curve_and_section(const NurbsCurve& reference, const RodSection& section,
                                         const std::string& who) {
  const int p = reference.degree();
  const KnotVector& U = reference.knots();
  const Interval dom = reference.domain();
  for (double k : U.breaks())
    if (k > dom.lo && k < dom.hi && U.multiplicity(k) > p - 1)
      throw RodError(who + ": interior knot " + num(k) + " has multiplicity " +
                     std::to_string(U.multiplicity(k)) +
                     "; a C1 curve needs <= p - 1 = " + std::to_string(p - 1));
  if (!(section.EA > 0.0) || !std::isfinite(section.EA))
    throw RodError(who + ": EA must be finite and > 0, got " + num(section.EA));
  if (!(section.EI1 >= 0.0) || !(section.EI2 >= 0.0) || !std::isfinite(section.EI1) ||
      !std::isfinite(section.EI2))
    throw RodError(who + ": EI1, EI2 must be finite and >= 0, got " + num(section.EI1) + ", " +
                   num(section.EI2));
}

std::vector<std::pair<int, Vector3d>> detail::rod_point_load(const NurbsCurve& reference, double xi,
                                                             const Vector3d& F) {
  const RationalBasis B = rational_basis(reference, xi);
  std::vector<std::pair<int, Vector3d>> forces;
  for (int j = 0; j < B.count; ++j)
    if (B.N[static_cast<std::size_t>(j)] != 0.0)
      forces.emplace_back(B.first + j, B.N[static_cast<std::size_t>(j)] * F);  // f_i = R_i F
  return forces;
}

void RodProblem::add_line_load(const Vector3d& q, LoadCurve curve) {
  add_line_load(q, rod_.reference().domain(), std::move(curve));
}

std::vector<Vector3d> rod_line_load(const NurbsCurve& reference, const Vector3d& q,
                                    Interval range) {
  // f_i = int_range R_i q dS, Gauss-Legendre on each knot span's part of the range.
  std::vector<Vector3d> f(static_cast<std::size_t>(reference.num_control_points()),
                          Vector3d::Zero());
  std::array<double, kMaxGaussPoints> gx{}, gw{};
  const int ng = std::min(kMaxGaussPoints, reference.degree() + 2);
  gauss_legendre(ng, gx, gw);
  const std::vector<double> breaks = reference.knots().breaks();
  for (std::size_t e = 0; e + 1 < breaks.size(); ++e) {
    const double lo = std::max(breaks[e], range.lo), hi = std::min(breaks[e + 1], range.hi);
    if (!(hi > lo)) continue;
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (int g = 0; g < ng; ++g) {
      const RationalBasis B =
          rational_basis(reference, mid + half * gx[static_cast<std::size_t>(g)]);
      Vector3d R1 = Vector3d::Zero();
      for (int j = 0; j < B.count; ++j)
        R1.noalias() += B.dN[static_cast<std::size_t>(j)] * reference.control_point(B.first + j);
      const double w = half * gw[static_cast<std::size_t>(g)] * R1.norm();
      for (int j = 0; j < B.count; ++j)
        f[static_cast<std::size_t>(B.first + j)] += (w * B.N[static_cast<std::size_t>(j)]) * q;
    }
  }
  return f;
}

void RodProblem::add_line_load(const Vector3d& q, Interval range, LoadCurve curve) {
  add_nodal_load(rod_line_load(rod_.reference(), q, range), std::move(curve));
}

void RodProblem::add_moment(double xi, const Vector3d& M, LoadCurve curve) {
  moments_.push_back(Moment{rational_basis(rod_.reference(), xi), M, std::move(curve)});
}

NurbsCurve RodProblem::current_curve(const VectorXd& u, double t) const {
  const std::vector<Vector3d> x = current_points(u, t);
  return NurbsCurve(rod_.reference().degree(), rod_.reference().knots().knots(), x,
                    rod_.reference().weights());
}

void RodProblem::add_moment_terms(std::span<const Vector3d> x, double t, VectorXd& g,
                                  std::vector<Triplet>* K) const {
  for (const Moment& mo : moments_) {
    const double lam = mo.curve(t);
    if (lam == 0.0) continue;
    const RationalBasis& B = mo.basis;
    Vector3d r1 = Vector3d::Zero();
    for (int j = 0; j < B.count; ++j)
      r1.noalias() += B.dN[static_cast<std::size_t>(j)] * x[static_cast<std::size_t>(B.first + j)];
    const double q = r1.squaredNorm();
    const Vector3d M = lam * mo.M;
    // f_ext,i = R_i' (M x r') / |r'|^2 : the work of M on the tangent rotation t x delta t.
    const Vector3d fm = M.cross(r1) / q;
    for (int j = 0; j < B.count; ++j)
      g.segment<3>(3 * (B.first + j)) -= B.dN[static_cast<std::size_t>(j)] * fm;
    if (!K) continue;
    // d fm / d r' = [M]x / |r'|^2 - 2 (M x r') r'^T / |r'|^4; tangent contribution -R_j' R_k' (...)
    Matrix3d dfm = skew(M) / q;
    dfm.noalias() -= (2.0 / (q * q)) * (M.cross(r1) * r1.transpose());
    for (int j = 0; j < B.count; ++j)
      for (int k = 0; k < B.count; ++k) {
        const double s = -B.dN[static_cast<std::size_t>(j)] * B.dN[static_cast<std::size_t>(k)];
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r)
            K->emplace_back(3 * (B.first + j) + r, 3 * (B.first + k) + c, s * dfm(r, c));
      }
  }
}

void RodProblem::assemble_model(std::span<const Vector3d> x, std::span<const double> /*s: none*/,
                                double t, VectorXd& g, std::vector<Triplet>* K) {
  rod_.assemble(x, g, K);  // g = f_int
  add_moment_terms(x, t, g, K);
}

}  // namespace iga
