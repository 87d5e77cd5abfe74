// CTRS penalty contact with Coulomb friction at one point, [KS15] (34)-(36), (52), (54),
// (66)-(67), with the consistent linearization (Sect. 5; checked against finite differences
// in tests/contact/test_contact_law.cpp).
#include "contact/contact_law.hpp"

#include <cmath>

#include <Eigen/LU>

namespace iga {

namespace {
using Matrix32 = Eigen::Matrix<double, 3, 2>;
using Matrix23 = Eigen::Matrix<double, 2, 3>;

// Parameter increment xi - xi_prev, the short way round in closed directions.
double increment(double now, double before, bool closed, const Interval& I) {
  double d = now - before;
  if (closed) {
    const double period = I.hi - I.lo;
    d = std::remainder(d, period);
  }
  return d;
}
}  // namespace

ContactPoint evaluate_contact(const Surface& s, const ProjectionResult& foot, const Vector3d& r,
                              const ContactParameters& p, const ContactHistory& history,
                              double lambda_n) {
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
  c.gap = dvec.dot(n) - p.radius;  // (52)
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

  // Tangential part (66), (35)-(36); none in the step of first contact (see the header).
  if (!(p.mu > 0.0 && p.eps_t > 0.0) || history.patch < 0 || !history.active) return c;
  Vector2d dxi, T_prev;
  if (history.patch == foot.patch) {
    dxi << increment(foot.uv[0], history.xi[0], s.closed_u(), dom.u),
        increment(foot.uv[1], history.xi[1], s.closed_v(), dom.v);  // (54)
    T_prev = history.T;
  } else {
    // Another patch: carry the increment and the force through space (contravariant basis
    // rho^i = a^ij rho_j), to first order as in (28).
    const Matrix23 contra = a_inv * J.transpose();
    dxi = contra * (d.S - history.foot);
    T_prev = contra * history.T_vector;
  }
  const Vector2d t = T_prev - p.eps_t * dxi;  // (66): trial force
  const Matrix23 dt_dr = -p.eps_t * dxi_dr;
  const double m = std::sqrt(t.dot(a * t));  // |T_tr| (35)
  const double absN = -c.N;
  c.phi = m - p.mu * absN;
  Matrix23 dT_dr;
  if (m - p.mu * absN <= 0.0 || m == 0.0) {  // stick (36)
    c.T = t;
    dT_dr = dt_dr;
  } else {  // slip (36): T = mu |N| t / |t|
    c.slip = true;
    c.T = p.mu * absN * t / m;
    // dm/dr = ((a t)^T dt/dr + 1/2 sum_k t^T (da/dxi^k) t dxi^k/dr) / m,
    // da_ij/dxi^k = rho_ik.rho_j + rho_i.rho_jk.
    Eigen::RowVector3d dm_dr = (a * t).transpose() * dt_dr;
    for (int k = 0; k < 2; ++k) {
      Matrix2d da;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          da(i, j) = rho2[i][k]->dot(J.col(j)) + J.col(i).dot(*rho2[j][k]);
      dm_dr += 0.5 * t.dot(da * t) * dxi_dr.row(k);
    }
    dm_dr /= m;
    const Eigen::RowVector3d dabsN_dr = -p.eps_n * n.transpose();
    const Matrix23 du_dr = dt_dr / m - t * dm_dr / (m * m);
    dT_dr = p.mu * (t / m) * dabsN_dr + p.mu * absN * du_dr;
  }
  // f_T = T^i rho_i, K_T = rho_i dT^i/dr + T^i rho_ik dxi^k/dr.
  c.T_vector = J * c.T;
  Matrix32 T_rho2;
  T_rho2.col(0) = c.T[0] * d.Suu + c.T[1] * d.Suv;
  T_rho2.col(1) = c.T[0] * d.Suv + c.T[1] * d.Svv;
  c.force += c.T_vector;
  c.stiffness += J * dT_dr + T_rho2 * dxi_dr;
  return c;
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

}  // namespace iga
