// CTRS penalty contact with Coulomb friction at one point, [KS15] (34)-(36), (52), (54),
// (66)-(67), with the consistent linearization (Sect. 5; checked against finite differences
// in tests/contact/test_contact_law.cpp).
#include "contact/contact_law.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

namespace iga {

namespace {
using Matrix32 = Eigen::Matrix<double, 3, 2>;
using Matrix23 = Eigen::Matrix<double, 2, 3>;

}  // namespace

void ContactParameters::check(const std::string& who) const {
  const auto fail = [&](const char* what, double v) {
    throw std::invalid_argument(who + ": " + what + ", got " + std::to_string(v));
  };
  if (!(eps_n > 0.0) || !std::isfinite(eps_n)) fail("eps_n must be > 0 and finite", eps_n);
  if (!(eps_t >= 0.0) || !std::isfinite(eps_t)) fail("eps_t must be >= 0 and finite", eps_t);
  if (!(mu >= 0.0) || !std::isfinite(mu)) fail("mu must be >= 0 and finite", mu);
}

void ContactEnforcement::check(const std::string& who) const {
  if (augmented && !(penetration_tol > 0.0 && std::isfinite(penetration_tol)))
    throw std::invalid_argument(who + ": penetration_tol must be > 0 and finite, got " +
                                std::to_string(penetration_tol));
  if (slip_tol != 0.0 && !(augmented && slip_tol > 0.0 && std::isfinite(slip_tol)))
    throw std::invalid_argument(
        who + ": slip_tol must be > 0 and finite, with the augmented Lagrangian, got " +
        std::to_string(slip_tol));
  if (augmented && max_augmentations < 1)
    throw std::invalid_argument(who + ": max_augmentations must be >= 1, got " +
                                std::to_string(max_augmentations));
}

ContactPoint evaluate_contact(const Surface& s, const ProjectionResult& foot, const Vector3d& r,
                              const ContactParameters& p, const ContactHistory& history,
                              double lambda_n, const Vector3d* lambda_t, const Vector3d* roll,
                              double radius) {
  ContactPoint c;
  c.xi = foot.uv;
  const SurfaceDerivs d = s.derivs(foot.uv[0], foot.uv[1], 2);
  Matrix32 J;
  J << d.Su, d.Sv;
  const Matrix2d a = J.transpose() * J;
  const Matrix2d a_inv = a.inverse();
  const Vector3d cr = d.Su.cross(d.Sv);
  const Vector3d n = s.normal_sign() * cr / cr.norm();
  const Vector3d dvec = r - d.S;
  c.foot = d.S;
  c.normal = n;
  c.gap = dvec.dot(n) - radius;  // (52)
  // (34), augmented: N = min(0, lambda_N + eps_N xi^3); lambda_N = 0 is the penalty law.
  if (lambda_n == 0.0 ? c.gap > 0.0 : lambda_n + p.eps_n * c.gap > 0.0) return c;  // no force
  c.active = true;
  c.N = p.eps_n * c.gap + lambda_n;  // (34), N <= 0

  // Derivatives of the foot parameters and of the normal with respect to r.
  const Vector3d* rho2[2][2] = {{&d.Suu, &d.Suv}, {&d.Suv, &d.Svv}};
  Matrix2d A, h;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      A(i, j) = a(i, j) - rho2[i][j]->dot(dvec);  // (17)
      h(i, j) = rho2[i][j]->dot(n);
    }
  Matrix23 dxi_dr = A.inverse() * J.transpose();
  // Parameters held at a patch bound do not move with r.
  const Domain2 dom = s.domain();
  if (!s.closed_u() && (foot.uv[0] <= dom.u.lo || foot.uv[0] >= dom.u.hi)) dxi_dr.row(0).setZero();
  if (!s.closed_v() && (foot.uv[1] <= dom.v.lo || foot.uv[1] >= dom.v.hi)) dxi_dr.row(1).setZero();
  const Matrix32 dn_dxi = -J * (a_inv * h);  // Weingarten: dn/dxi^k = -h_kj a^jl rho_l
  const Matrix3d dn_dr = dn_dxi * dxi_dr;

  // Normal part: f_N = -N n, K_N = -eps_N n n^T - N dn/dr.
  c.force = -c.N * n;
  c.stiffness = -p.eps_n * n * n.transpose() - c.N * dn_dr;

  // Tangential part (66), (35)-(36) in space, independent of the parametrization (see the
  // header); none in the step of first contact.
  if (!(p.mu > 0.0 && p.eps_t > 0.0) || history.patch < 0) return c;
  // The tangential projector P = I - n n^T of the current foot and, for a fixed vector w,
  // d(P w)/dr = -(n.w) dn/dr - n (w^T dn/dr).
  const Matrix3d P = Matrix3d::Identity() - n * n.transpose();
  const Matrix3d drho_dr = J * dxi_dr;  // the foot moves with r through xi (17)
  // The committed force T_(n) (or the tangential multiplier lambda_T), carried into the current
  // tangent plane with its length kept: q = P T_(n), carried = |T_(n)| q / |q|.
  const Vector3d& Tn = lambda_t ? *lambda_t : history.T_vector;
  const Vector3d q = P * Tn;
  const double Tn_norm = Tn.norm(), q_norm = q.norm();
  Vector3d carried = Vector3d::Zero();
  Matrix3d dcarried_dr = Matrix3d::Zero();
  if (q_norm > 0.0) {
    const Vector3d qh = q / q_norm;
    const Matrix3d dq_dr = -n.dot(Tn) * dn_dr - n * (Tn.transpose() * dn_dr);
    carried = Tn_norm * qh;
    dcarried_dr = (Tn_norm / q_norm) * (Matrix3d::Identity() - qh * qh.transpose()) * dq_dr;
  }
  // The slip since the anchor rho_(n), in the current tangent plane: g_T = P (rho - rho_(n)),
  // the spatial form of Delta xi^i rho_i (54) (equal to first order, exact on a plane).
  // With a rolling displacement s the body's material point at the contact has moved by the
  // foot's motion plus s.
  const Vector3d chord = d.S - history.foot + (roll ? *roll : Vector3d::Zero());
  const Vector3d gT = P * chord;
  c.slip_distance = gT.norm();
  const Matrix3d dgT_dr = drho_dr - n.dot(chord) * dn_dr - n * (chord.transpose() * dn_dr);
  const Vector3d t = carried - p.eps_t * gT;  // (66): trial force, a tangent vector
  const Matrix3d dt_dr = dcarried_dr - p.eps_t * dgT_dr;
  const double m = t.norm();  // |T_tr| (35): sqrt(T^i a_ij T^j) of a tangent vector
  const double absN = -c.N;
  c.phi = m - p.mu * absN;
  const Matrix3d dt_ds = -p.eps_t * P;  // dg_T/ds = P
  Matrix3d dT_dr, dT_ds;
  if (m - p.mu * absN <= 0.0 || m == 0.0) {  // stick (36)
    c.T_vector = t;
    dT_dr = dt_dr;
    dT_ds = dt_ds;
  } else {  // slip (36): T = mu |N| t / |t|
    c.slip = true;
    const Vector3d u = t / m;
    c.T_vector = p.mu * absN * u;
    const Eigen::RowVector3d dabsN_dr = -p.eps_n * n.transpose();
    const Matrix3d dir = (p.mu * absN / m) * (Matrix3d::Identity() - u * u.transpose());
    dT_dr = p.mu * u * dabsN_dr + dir * dt_dr;
    dT_ds = dir * dt_ds;
  }
  if (roll) c.stiffness_roll = dT_ds;
  c.stiffness_tangential = dT_dr;
  c.T = a_inv * (J.transpose() * c.T_vector);  // contravariant components T^i (output)
  c.force += c.T_vector;
  c.stiffness += dT_dr;
  return c;
}

ContactHistory anchor_at(const ProjectionResult& foot) {
  ContactHistory h;
  h.patch = foot.patch;
  h.xi = foot.uv;
  h.foot = foot.point;
  return h;
}

ContactHistory commit_contact(const ContactPoint& c, int patch) {
  ContactHistory h;
  h.active = c.active;
  h.patch = patch;
  h.xi = c.xi;
  h.foot = c.foot;
  h.T = c.active ? c.T : Vector2d::Zero();
  h.T_vector = c.active ? c.T_vector : Vector3d::Zero();
  return h;
}

bool beyond_open_edge(const ProjectionResult& foot, const Vector3d& x) {
  if (foot.status != ProjectionStatus::edge && foot.status != ProjectionStatus::vertex)
    return false;
  const Vector3d d = x - foot.point;
  return (d - d.dot(foot.normal) * foot.normal).norm() > 1e-8 * (1.0 + d.norm());
}

}  // namespace iga
