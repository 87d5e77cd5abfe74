// STAS contact integral ([KS15] Sects. 2-3: (2)-(5), (10)-(18), (27)-(28), (33)-(39)); see
// surface_contact.hpp for the strategies, the sign conventions and the search.
#include "iga/contact_integrals/surface_contact.hpp"

#include "geometry/rational_basis.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <omp.h>
#include <Eigen/LU>

#include "contact/analytic_projection.hpp"
#include "contact/contact_search.hpp"
#include "contact/ray_projection.hpp"
#include "geometry/differential_geometry.hpp"
#include "iga/contact_integrals/contact_state.hpp"
#include "iga/contact_integrals/pass_through.hpp"
#include "iga/core/quadrature.hpp"

namespace iga {

namespace {

using Matrix39 = Eigen::Matrix<double, 3, 9>;
using Matrix29 = Eigen::Matrix<double, 2, 9>;
using Matrix99 = Eigen::Matrix<double, 9, 9>;
using Matrix32 = Eigen::Matrix<double, 3, 2>;
using RowVector9 = Eigen::Matrix<double, 1, 9>;

// The shell's geometry at a contact point: G = (rho, a1, a2), the normal and its derivatives,
// the contact point x_c = rho + c n and dx_c/dG.
struct PointGeometry {
  Vector3d rho, a1, a2, n;
  double j = 0.0;           // |a1 x a2|
  Matrix3d C1, C2;          // d(a1 x a2)/da1 = -[a2]x, d(a1 x a2)/da2 = [a1]x
  Matrix3d dn_da1, dn_da2;  // (I - n n^T) C_i / j
  Vector3d x;               // x_c
  Matrix39 Xg;              // dx_c/dG = [I, c dn/da1, c dn/da2]
  Matrix39 Ng;              // dn/dG = [0, dn/da1, dn/da2]
};

void point_geometry(const double* B, int nen, const int* cps, std::span<const Vector3d> x, double c,
                    PointGeometry& g) {
  g.rho.setZero();
  g.a1.setZero();
  g.a2.setZero();
  for (int k = 0; k < nen; ++k) {
    const Vector3d& X = x[static_cast<std::size_t>(cps[k])];
    g.rho += B[3 * k] * X;
    g.a1 += B[3 * k + 1] * X;
    g.a2 += B[3 * k + 2] * X;
  }
  const Vector3d cr = g.a1.cross(g.a2);
  g.j = cr.norm();
  g.n = cr / g.j;
  g.C1 = -skew(g.a2);
  g.C2 = skew(g.a1);
  const Matrix3d P = Matrix3d::Identity() - g.n * g.n.transpose();
  g.dn_da1.noalias() = P * g.C1 / g.j;
  g.dn_da2.noalias() = P * g.C2 / g.j;
  g.x = g.rho + c * g.n;
  g.Xg << Matrix3d::Identity(), c * g.dn_da1, c * g.dn_da2;
  g.Ng << Matrix3d::Zero(), g.dn_da1, g.dn_da2;
}

// d^2 (f.n)/d(a1, a2)^2 for a fixed vector f (6 x 6): with phi(c) = f.c/|c|, c = a1 x a2,
// grad phi = P f/j, Hess phi = (-f n^T - n f^T - (f.n)(I - 3 n n^T))/j^2, and c bilinear:
// d^2 (g.c)/da1 da2 = -[g]x.
Eigen::Matrix<double, 6, 6> normal_hessian(const PointGeometry& g, const Vector3d& f) {
  const double fn = f.dot(g.n);
  const Vector3d grad = (f - fn * g.n) / g.j;
  const Matrix3d Hc = (-f * g.n.transpose() - g.n * f.transpose() -
                       fn * (Matrix3d::Identity() - 3.0 * g.n * g.n.transpose())) /
                      (g.j * g.j);
  Eigen::Matrix<double, 6, 6> H;
  const Matrix3d H12 = g.C1.transpose() * Hc * g.C2 - skew(grad);
  H.topLeftCorner<3, 3>() = g.C1.transpose() * Hc * g.C1;
  H.topRightCorner<3, 3>() = H12;
  H.bottomLeftCorner<3, 3>() = H12.transpose();
  H.bottomRightCorner<3, 3>() = g.C2.transpose() * Hc * g.C2;
  return H;
}

// (da u) as a 2 x 9 matrix in dG, da_ij = da_i.a_j + a_i.da_j, for a fixed 2-vector u.
Matrix29 metric_times(const Vector3d& a1, const Vector3d& a2, const Vector2d& u) {
  const Vector3d v = u[0] * a1 + u[1] * a2;
  Matrix29 D;
  D << Eigen::RowVector3d::Zero(), v.transpose() + u[0] * a1.transpose(), u[1] * a1.transpose(),
      Eigen::RowVector3d::Zero(), u[0] * a2.transpose(), v.transpose() + u[1] * a2.transpose();
  return D;
}

double shell_face_sign(ShellFace f) {
  return f == ShellFace::kLower ? -1.0 : f == ShellFace::kUpper ? 1.0 : 0.0;
}

// The control points of an element (first non-zero basis functions first_u, first_v), in the
// order of the basis values: k = a + (p+1) b.
void element_dofs(const NurbsSurface& ref, int first_u, int first_v, std::vector<int>& dofs) {
  const int p = ref.degree_u(), q = ref.degree_v();
  for (int b = 0, k = 0; b <= q; ++b)
    for (int a = 0; a <= p; ++a, ++k)
      dofs[static_cast<std::size_t>(k)] = ref.index(first_u + a, first_v + b);
}

// A point's law state before its evaluation: not in contact.
void clear_law_state(SurfaceContactPoint& cp) {
  cp.active = cp.slip = false;
  cp.gap = cp.N = cp.phi = cp.slip_distance = 0.0;
  cp.T.setZero();
  cp.T_vector.setZero();
}

// The laws' inputs of an assembly: the penalties (raised where augmentation updates stalled),
// the Coulomb coefficient, whether friction is on at all (mu, eps_T > 0 as given) and whether
// the tangential multiplier replaces the committed force (augmented stick).
struct LawInputs {
  double eps_n = 0.0, eps_t = 0.0, mu = 0.0;
  bool friction = false;
  bool tangential = false;
};

// Master strategy: (10)-(18), (34)-(36) by the CTRS point law with R = 0 at x_c; df/dG =
// df/dx_c dx_c/dG. False: not in contact.
bool master_law(const Surface& rigid_patch, const PointGeometry& g,
                const ContactParameters& law_params, bool tangential, SurfaceContactPoint& cp,
                Vector3d& f, Matrix39& df) {
  // Beyond an open edge of the rigid body (a trimmed face's boundary, a patch's free side):
  // not in contact, as for rods.
  if (beyond_open_edge(cp.foot, g.x)) {
    cp.gap = 0.0;
    cp.slip_distance = 0.0;
    return false;
  }
  const ContactPoint law = evaluate_contact(rigid_patch, cp.foot, g.x, law_params, cp.history,
                                            cp.lambda_n, tangential ? &cp.lambda_t : nullptr);
  cp.gap = law.gap;
  cp.slip_distance = law.slip_distance;
  if (!law.active) return false;
  cp.N = law.N;
  cp.T = law.T;
  cp.T_vector = law.T_vector;
  cp.phi = law.phi;
  cp.slip = law.slip;
  f = law.force;
  df.noalias() = law.stiffness * g.Xg;
  return true;
}

// The ray hit of the slave strategy as friction needs it: xi3, sigma = sign(n . n_r), dxi3/dG
// and |N|.
struct RayHit {
  double xi3 = 0.0, sigma = 0.0, absN = 0.0;
  RowVector9 dxi3;
};

// Slave strategy, friction in the shell's convected coordinates (28), (35)-(36): adds f_T and
// its derivative to f and df.
void add_slave_friction(const PointGeometry& g, const RayHit& hit, const LawInputs& in,
                        SurfaceContactPoint& cp, Vector3d& f, Matrix39& df) {
  const ContactHistory& h = cp.history;
  const double xi3 = hit.xi3;
  const RowVector9& dxi3 = hit.dxi3;
  const double absN = hit.absN;
  Matrix32 A;
  A << g.a1, g.a2;
  const Matrix2d a = A.transpose() * A;
  const Matrix2d a_inv = a.inverse();
  // (28) with the chord d; (35): T_tr_i = T_i^(k) + eps_T d.rho_i
  const Vector3d d = cp.foot.point - h.foot;
  Matrix39 dd;
  dd.noalias() = g.Xg + g.n * dxi3 + xi3 * g.Ng;  // d r/dG, r = x_c + xi3 n
  cp.slip_distance = d.norm();
  // the committed T_i, or the tangential multiplier (augmented stick)
  const Vector2d Tc = in.tangential ? Vector2d(cp.lambda_t.head<2>()) : h.T;
  const Vector2d t = Tc + in.eps_t * A.transpose() * d;
  Matrix29 dt;
  dt.noalias() = in.eps_t * A.transpose() * dd;
  dt.block<1, 3>(0, 3) += in.eps_t * d.transpose();
  dt.block<1, 3>(1, 6) += in.eps_t * d.transpose();
  const Vector2d t_up = a_inv * t;
  const double m = std::sqrt(t.dot(t_up));  // |T_tr| (35)
  cp.phi = m - in.mu * absN;
  Matrix29 dT;
  if (cp.phi <= 0.0 || m == 0.0) {  // stick (36)
    cp.T = t;
    dT = dt;
  } else {  // slip (36): T = mu |N| T_tr/|T_tr|
    cp.slip = true;
    cp.T = in.mu * absN * t / m;
    const RowVector9 dm =
        (t_up.transpose() * dt - 0.5 * t_up.transpose() * metric_times(g.a1, g.a2, t_up)) / m;
    const RowVector9 dabsN = in.eps_n * hit.sigma * dxi3;
    dT.noalias() = in.mu * (t / m) * dabsN + (in.mu * absN / m) * (dt - t * dm / m);
  }
  // f_T = -T_i rho^i = -A a^-1 T
  const Vector2d u = a_inv * cp.T;
  cp.T_vector = -A * u;
  f += cp.T_vector;
  Matrix29 du;
  du.noalias() = a_inv * (dT - metric_times(g.a1, g.a2, u));
  df.noalias() -= A * du;
  df.block<3, 3>(0, 3) -= u[0] * Matrix3d::Identity();
  df.block<3, 3>(0, 6) -= u[1] * Matrix3d::Identity();
}

// Slave strategy: (2)-(5), the hit r = x_c + xi3 n with its rigid basis r_1, r_2; the normal
// force (34) along nu = sigma n, then friction. False: not in contact.
bool slave_law(const Surface& rigid_patch, const PointGeometry& g, const LawInputs& in,
               SurfaceContactPoint& cp, Vector3d& f, Matrix39& df) {
  const double eps_n = in.eps_n;
  const SurfaceDerivs rd = rigid_patch.derivs(cp.foot.uv[0], cp.foot.uv[1], 1);
  RayHit hit;
  hit.xi3 = cp.foot.distance;
  hit.sigma = g.n.dot(cp.foot.normal) >= 0.0 ? 1.0 : -1.0;
  const double xi3 = hit.xi3, sigma = hit.sigma;
  cp.gap = -sigma * xi3;
  // (34), augmented: N = min(0, lambda_N + eps_N gap); lambda_N = 0 is the penalty law.
  const double lambda = cp.lambda_n;
  if (lambda == 0.0 ? cp.gap > 0.0 : lambda + eps_n * cp.gap > 0.0) return false;
  Matrix3d J;  // (4)
  J << rd.Su, rd.Sv, -g.n;
  const Matrix3d J_inv = J.inverse();
  // implicit function theorem on F = r(alpha) - x_c - xi3 n = 0 (3)
  Matrix39 dy;
  dy.noalias() = J_inv * (g.Xg + xi3 * g.Ng);
  hit.dxi3 = dy.row(2);
  const RowVector9& dxi3 = hit.dxi3;
  cp.N = eps_n * cp.gap + lambda;  // (34), <= 0
  hit.absN = -cp.N;
  // f_N = -N nu = eps_N xi3 n - lambda_N sigma n
  f = eps_n * xi3 * g.n;
  df.noalias() = eps_n * (g.n * dxi3 + xi3 * g.Ng);
  if (lambda != 0.0) {
    f -= lambda * sigma * g.n;
    df.noalias() -= lambda * sigma * g.Ng;
  }
  // no tangential force in the step of first contact (contact/contact_law.hpp)
  const ContactHistory& h = cp.history;
  if (in.friction && h.patch >= 0 && h.active) add_slave_friction(g, hit, in, cp, f, df);
  return true;
}

// R_a -= w (dx_c/dX_a)^T f at an active point with basis values B (nen rows (R, R_,1, R_,2)):
// with x_c = sum_a (R_a rho-part) ..., r_G = Xg^T f; into the element's residual Re (3 nen,
// node a at 3 a).
void add_point_residual(const double* B, int nen, double weight, const PointGeometry& g,
                        const Vector3d& f, double* Re) {
  const Eigen::Matrix<double, 9, 1> rG = g.Xg.transpose() * f;
  for (int k = 0; k < nen; ++k) {
    const double* Bk = B + 3 * k;
    Eigen::Map<Vector3d>(Re + 3 * k) -=
        weight * (Bk[0] * rG.segment<3>(0) + Bk[1] * rG.segment<3>(3) + Bk[2] * rG.segment<3>(6));
  }
}

// An active point's share of its element's tangent, collected as the n_active-th point into
// Nall and Z (see below).
void collect_point_tangent(const double* B, int nen, const PointGeometry& g, const Vector3d& f,
                           const Matrix39& df, double c, double weight, int n_active,
                           Eigen::MatrixXd& Nall, Eigen::MatrixXd& Z) {
  // d r_G/dG = Xg^T df + c d^2(f.n)/dG^2; K_e -= w B^T M B, B = (R, R_,1, R_,2) x I3.
  Matrix99 M;
  M.noalias() = g.Xg.transpose() * df;
  if (c != 0.0) M.bottomRightCorner<6, 6>() += c * normal_hessian(g, f);
  M *= -weight;
  // Collected per element: Nall = [.. Nm_p ..] (nen x 3 n_active), Z_kl = [.. Nm_p M_p^kl ..],
  // M_p^kl(I, J) = M(3 I + k, 3 J + l), the Z_kl stacked; then K_e^kl = Z_kl Nall^T, one
  // product per element for all nine component pairs (k, l).
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> Nm(B, nen, 3);
  Nall.middleCols<3>(3 * n_active) = Nm;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      Matrix3d Mkl;
      for (int I = 0; I < 3; ++I)
        for (int Jj = 0; Jj < 3; ++Jj) Mkl(I, Jj) = M(3 * I + k, 3 * Jj + l);
      Z.block(nen * (3 * k + l), 3 * n_active, nen, 3).noalias() = Nm.lazyProduct(Mkl);
    }
}

// K_e = Z Nall^T over the element's n_active points, emitted as triplets.
void add_element_tangent(const Eigen::MatrixXd& Z, const Eigen::MatrixXd& Nall, int n_active,
                         int nen, const std::vector<int>& dofs, const Matrix3d& turn,
                         Eigen::MatrixXd& Ke, std::vector<Eigen::Triplet<double>>& K) {
  Ke.noalias() = Z.leftCols(3 * n_active) * Nall.leftCols(3 * n_active).transpose();
  if (!turn.isIdentity(
          0.0))  // each 3 x 3 block (aa, bb), entry (k, l) at Ke(nen (3k + l) + aa, bb)
    for (int bb = 0; bb < nen; ++bb)
      for (int aa = 0; aa < nen; ++aa) {
        Matrix3d B;
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) B(k, l) = Ke(nen * (3 * k + l) + aa, bb);
        const Matrix3d T = turn * B * turn.transpose();
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) Ke(nen * (3 * k + l) + aa, bb) = T(k, l);
      }
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      const int row0 = nen * (3 * k + l);
      for (int bb = 0; bb < nen; ++bb)
        for (int aa = 0; aa < nen; ++aa)
          K.emplace_back(3 * dofs[static_cast<std::size_t>(aa)] + k,
                         3 * dofs[static_cast<std::size_t>(bb)] + l, Ke(row0 + aa, bb));
    }
}

}  // namespace

SurfaceContact::SurfaceContact(const NurbsSurface& reference, const RigidSurface& rigid,
                               const SurfaceContactParameters& params, const ElementBlock& block)
    : ref_(reference), rigid_(&rigid), params_(params) {
  check(params);
  const int np = params.points_per_direction;
  const int p = ref_.degree_u(), q = ref_.degree_v();
  nen_ = (p + 1) * (q + 1);
  if (p > kMaxSurfaceBasisDegree || q > kMaxSurfaceBasisDegree)
    throw GeometryError("SurfaceContact: surface degree " + std::to_string(p) + " x " +
                        std::to_string(q) + " above the supported " +
                        std::to_string(kMaxSurfaceBasisDegree));
  std::array<double, kMaxGaussPoints> gx{}, gw{};
  gauss_legendre(np, gx, gw);
  const std::vector<double> bu = ref_.knots_u().breaks(), bv = ref_.knots_v().breaks();
  const std::vector<Vector3d> X = ref_.control_points();
  // The Gauss points of every span per direction, and their B-spline basis (the points keep
  // none of their own: element_basis forms it).
  const auto rule_points = [&](const std::vector<double>& b) {
    std::vector<double> t;
    for (std::size_t e = 0; e + 1 < b.size(); ++e) {
      const double h = 0.5 * (b[e + 1] - b[e]);
      for (int i = 0; i < np; ++i) t.push_back(b[e] + h * (1.0 + gx[static_cast<std::size_t>(i)]));
    }
    return t;
  };
  const std::vector<double> tu = rule_points(bu), tv = rule_points(bv);
  table_u_ = SpanBasisTable(ref_.knots_u(), p, tu);
  table_v_ = SpanBasisTable(ref_.knots_v(), q, tv);
  std::size_t n_block = 0;
  for (std::size_t ev = 0; ev + 1 < bv.size(); ++ev)
    for (std::size_t eu = 0; eu + 1 < bu.size(); ++eu)
      if (block.contains(static_cast<int>(eu), static_cast<int>(ev))) ++n_block;
  elements_.reserve(n_block);
  points_.reserve(n_block * static_cast<std::size_t>(np * np));
  std::vector<int> cps(static_cast<std::size_t>(nen_));
  std::vector<double> rows(static_cast<std::size_t>(np * np * 3 * nen_));
  for (std::size_t ev = 0; ev + 1 < bv.size(); ++ev)
    for (std::size_t eu = 0; eu + 1 < bu.size(); ++eu) {
      if (!block.contains(static_cast<int>(eu), static_cast<int>(ev))) continue;
      const double hu = 0.5 * (bu[eu + 1] - bu[eu]), hv = 0.5 * (bv[ev + 1] - bv[ev]);
      Element el;
      el.row_u = static_cast<int>(eu) * np;
      el.row_v = static_cast<int>(ev) * np;
      el.first_u = table_u_[static_cast<std::size_t>(el.row_u)].span - p;
      el.first_v = table_v_[static_cast<std::size_t>(el.row_v)].span - q;
      elements_.push_back(el);
      element_basis(elements_.back(), rows.data());
      for (int b = 0, k = 0; b <= q; ++b)
        for (int a = 0; a <= p; ++a, ++k)
          cps[static_cast<std::size_t>(k)] = ref_.index(el.first_u + a, el.first_v + b);
      const int e = static_cast<int>(eu + (bu.size() - 1) * ev);  // over the whole patch
      for (int jv = 0, i = 0; jv < np; ++jv)
        for (int iu = 0; iu < np; ++iu, ++i) {
          SurfaceContactPoint cp;
          cp.element = e;
          cp.uv = Vector2d(tu[static_cast<std::size_t>(el.row_u + iu)],
                           tv[static_cast<std::size_t>(el.row_v + jv)]);
          cp.foot.patch = -1;
          cp.foot.status = ProjectionStatus::far;
          PointGeometry g;  // reference area element |A1 x A2|
          point_geometry(rows.data() + static_cast<std::size_t>(i) * 3 * nen_, nen_, cps.data(), X,
                         0.0, g);
          cp.weight =
              gw[static_cast<std::size_t>(iu)] * gw[static_cast<std::size_t>(jv)] * hu * hv * g.j;
          points_.push_back(cp);
        }
    }
  dofs_.resize(static_cast<std::size_t>(nen_));
  cold_.reserve(points_.size());
  cold_x_.reserve(points_.size());
}

void SurfaceContact::element_basis(const Element& el, double* rows) const {
  // (R_k, R_k,u, R_k,v) for k = a + (p+1) b, control point (first_u + a, first_v + b), per
  // point of the element (u fastest).
  const int np = params_.points_per_direction;
  const int p = ref_.degree_u(), q = ref_.degree_v();
  std::array<double, kMaxSurfaceBasisPoints> w{};
  for (int b = 0, k = 0; b <= q; ++b)
    for (int a = 0; a <= p; ++a, ++k)
      w[static_cast<std::size_t>(k)] = ref_.weight(el.first_u + a, el.first_v + b);
  for (int jv = 0; jv < np; ++jv)
    for (int iu = 0; iu < np; ++iu, rows += 3 * nen_)
      rational_basis_first(table_u_[static_cast<std::size_t>(el.row_u + iu)],
                           table_v_[static_cast<std::size_t>(el.row_v + jv)], p, q, w.data(), rows);
}

std::size_t SurfaceContact::elements_with_foot() const {
  const std::size_t per_element = static_cast<std::size_t>(params_.points_per_direction) *
                                  static_cast<std::size_t>(params_.points_per_direction);
  std::size_t n = 0;
  for (std::size_t i0 = 0; i0 < points_.size(); i0 += per_element)
    n += std::any_of(points_.begin() + static_cast<std::ptrdiff_t>(i0),
                     points_.begin() + static_cast<std::ptrdiff_t>(i0 + per_element),
                     [](const SurfaceContactPoint& cp) { return found(cp.foot.status); });
  return n;
}

void SurfaceContact::check(const SurfaceContactParameters& p) const {
  auto fail = [](const std::string& what, double v) {
    throw std::invalid_argument("SurfaceContactParameters: " + what + ", got " + std::to_string(v));
  };
  p.law.check("SurfaceContactParameters");
  if (!(p.thickness >= 0.0) || !std::isfinite(p.thickness))
    fail("thickness must be >= 0 and finite", p.thickness);
  if (!(p.search_distance > 0.0) || !std::isfinite(p.search_distance))
    fail("search_distance must be > 0 and finite", p.search_distance);
  if (p.points_per_direction < 1 || p.points_per_direction > kMaxGaussPoints)
    fail("points_per_direction must be in 1..20", p.points_per_direction);
}

void SurfaceContact::set_enforcement(const ContactEnforcement& e) {
  e.check("SurfaceContact");
  enforcement_ = e;
}

void SurfaceContact::set_parameters(const SurfaceContactParameters& p) {
  check(p);
  if (p.points_per_direction != params_.points_per_direction)
    throw std::invalid_argument(
        "SurfaceContact::set_parameters: points_per_direction cannot change (" +
        std::to_string(params_.points_per_direction) + " -> " +
        std::to_string(p.points_per_direction) + ")");
  params_ = p;
}

bool SurfaceContact::warm_project(SurfaceContactPoint& cp) const {
  const ProjectionResult& prev = cp.foot;
  if (prev.patch < 0 || !found(prev.status)) return false;
  if (rigid_->trimmed(prev.patch) != nullptr) return false;  // the rigid surface's own search
  const Surface& s = rigid_->patch(prev.patch);
  const auto* analytic =
      rigid_->nurbs(prev.patch) ? nullptr : static_cast<const AnalyticSurface*>(&s);
  ProjectionResult r;
  if (params_.strategy == SurfaceContactStrategy::kRigidMaster)  // (18) from the last foot
    r = analytic ? closest_point_analytic(*analytic, cp.x) : closest_point_local(s, cp.x, prev.uv);
  else  // (5) from the last hit
    r = analytic ? ray_project_analytic(*analytic, cp.x, cp.normal)
                 : ray_project_local(s, cp.x, cp.normal, prev.uv, prev.distance);
  if (r.status != ProjectionStatus::interior || !(std::abs(r.distance) <= params_.search_distance))
    return false;
  r.patch = prev.patch;
  cp.foot = r;
  return true;
}

void SurfaceContact::polish(ProjectionResult& foot, const Vector3d& x, const Vector3d& n) const {
  // The projections stop at a scaled residual of 1e-13 (projection.hpp), i.e. a foot error of
  // ~1e-13 times the patch size: enough for the gap, but the friction force eps_T Delta alpha
  // sees it directly. One more Newton step ((18) or (5)) brings it to round-off, so that the
  // residual is the smooth function of x that the tangent differentiates.
  if (foot.status != ProjectionStatus::interior || !rigid_->nurbs(foot.patch)) return;
  const Surface& s = rigid_->patch(foot.patch);
  const SurfaceDerivs d = s.derivs(foot.uv[0], foot.uv[1], 2);
  Vector2d uv = foot.uv;
  double xi3 = foot.distance;
  if (params_.strategy == SurfaceContactStrategy::kRigidMaster) {
    const Vector3d r = x - d.S;
    Matrix2d H;  // (17)
    H << d.Su.squaredNorm() - d.Suu.dot(r), d.Su.dot(d.Sv) - d.Suv.dot(r),
        d.Su.dot(d.Sv) - d.Suv.dot(r), d.Sv.squaredNorm() - d.Svv.dot(r);
    uv += H.inverse() * Vector2d(d.Su.dot(r), d.Sv.dot(r));  // (18) with (16)
  } else {
    Matrix3d J;  // (4)
    J << d.Su, d.Sv, -n;
    const Vector3d step = -J.inverse() * (d.S - x - xi3 * n);  // (5) with (3)
    uv += step.head<2>();
    xi3 += step[2];
  }
  const Domain2 dom = s.domain();
  if (!uv.allFinite() || uv[0] <= dom.u.lo || uv[0] >= dom.u.hi || uv[1] <= dom.v.lo ||
      uv[1] >= dom.v.hi || (uv - foot.uv).norm() > 1e-6 * (1.0 + foot.uv.norm()))
    return;  // not a polish: keep the projection's answer
  const SurfaceDerivs e = s.derivs(uv[0], uv[1], 1);
  const Vector3d cr = e.Su.cross(e.Sv);
  foot.uv = uv;
  foot.point = e.S;
  foot.normal = s.normal_sign() * cr / cr.norm();
  foot.distance = params_.strategy == SurfaceContactStrategy::kRigidMaster
                      ? std::copysign((x - e.S).norm(), (x - e.S).dot(foot.normal))
                      : xi3;
}

void SurfaceContact::cold_project() {
  if (cold_.empty()) return;
  const double d = params_.search_distance;
  if (params_.strategy == SurfaceContactStrategy::kRigidMaster) {
    // Broad phase over all rigid Bezier elements (the tool's index, built once), closest point
    // among the candidates.
    const std::vector<ProjectionResult> r = rigid_->closest_points(cold_x_, d);
    for (std::size_t k = 0; k < cold_.size(); ++k)
      points_[static_cast<std::size_t>(cold_[k])].foot = r[k];
    return;
  }
  // Slave: the same broad phase gives the candidate patches; a ray hit within distance d lies
  // in an element box enlarged by d around the point, so no hit is missed.
  const std::vector<SearchPair> pairs = rigid_->element_boxes().empty()
                                            ? std::vector<SearchPair>{}
                                            : rigid_->element_index(d).query(cold_x_);
  const std::vector<std::size_t> first = first_pair_of_query(pairs, cold_.size());
  const auto n_cold = static_cast<std::ptrdiff_t>(cold_.size());
#pragma omp parallel for schedule(dynamic, 64) if (n_cold >= kParallelQueries)
  for (std::ptrdiff_t qi = 0; qi < n_cold; ++qi) {
    const auto q = static_cast<std::size_t>(qi);
    std::size_t k = first[q];
    SurfaceContactPoint& cp = points_[static_cast<std::size_t>(cold_[q])];
    ProjectionResult best;
    best.status = ProjectionStatus::far;
    best.patch = -1;
    bool tangent = false;
    auto consider = [&](ProjectionResult r, int piece) {
      r.patch = piece;
      tangent = tangent || r.status == ProjectionStatus::tangent;
      if (!found(r.status) || std::abs(r.distance) > d) return;
      if (!found(best.status) || std::abs(r.distance) < std::abs(best.distance)) best = r;
    };
    int last_piece = -1;
    for (; k < pairs.size() && pairs[k].query == static_cast<int>(q); ++k) {
      const int piece = rigid_->element_tag(pairs[k].box).first;
      if (piece == last_piece) continue;  // pairs are sorted: one ray projection per piece
      last_piece = piece;
      consider(rigid_->ray_piece(piece, cp.x, cp.normal), piece);  // NURBS or trimmed piece
    }
    for (int i = 0; i < rigid_->num_patches(); ++i)
      if (!rigid_->nurbs(i) && !rigid_->trimmed(i))
        consider(rigid_->ray_piece(i, cp.x, cp.normal), i);
    if (!found(best.status) && tangent) best.status = ProjectionStatus::tangent;
    cp.foot = best;
  }
}

void SurfaceContact::assemble(std::span<const Vector3d> x, Eigen::VectorXd& R,
                              std::vector<Eigen::Triplet<double>>* K) {
  const int n_cp = ref_.num_u() * ref_.num_v();
  if (static_cast<int>(x.size()) != n_cp || R.size() != 3 * static_cast<Eigen::Index>(x.size()))
    throw std::invalid_argument("SurfaceContact::assemble: expected " + std::to_string(n_cp) +
                                " control points and a residual of size " +
                                std::to_string(3 * n_cp) + ", got " + std::to_string(x.size()) +
                                " and " + std::to_string(R.size()));
  const double c = shell_face_sign(params_.face) * 0.5 * params_.thickness;
  locate(x, c);
  evaluate(x, c, R, K);
}

SurfaceContact::Layout SurfaceContact::layout() const {
  return {params_.strategy == SurfaceContactStrategy::kRigidMaster,
          params_.points_per_direction * params_.points_per_direction,
          3 * static_cast<std::size_t>(nen_), static_cast<int>(elements_.size()),
          static_cast<int>(points_.size()) >= kParallelContactPoints};
}

// Elements in parallel (OpenMP, static schedule: thread t takes the t-th run of elements),
// each writing only its own points, its residual slot and its thread's triplet list; the
// residuals are added and the lists joined in element order by one thread, so R and K are the
// same, bit for bit, for any number of threads (K's triplets in the serial order).
void SurfaceContact::locate(std::span<const Vector3d> x, double c) {
  const Layout lay = layout();  // plain locals: clang's OpenMP takes no structured bindings
  const bool master = lay.master, parallel = lay.parallel;
  const int per_element = lay.per_element, n_el = lay.n_el;
  const std::size_t stride = lay.stride;

  // 1. Contact points on the face and warm-started projections; the rest is searched at once.
  warm_.assign(points_.size(), 0);
#pragma omp parallel if (parallel)
  {
    std::vector<int> dofs(static_cast<std::size_t>(nen_));
    std::vector<double> rows(static_cast<std::size_t>(per_element) * stride);
    PointGeometry g;
#pragma omp for schedule(static)
    for (int e = 0; e < n_el; ++e) {
      const Element& el = elements_[static_cast<std::size_t>(e)];
      element_dofs(ref_, el.first_u, el.first_v, dofs);
      element_basis(el, rows.data());
      const std::size_t i0 = static_cast<std::size_t>(e) * static_cast<std::size_t>(per_element);
      for (std::size_t i = i0; i < i0 + static_cast<std::size_t>(per_element); ++i) {
        SurfaceContactPoint& cp = points_[i];
        point_geometry(rows.data() + (i - i0) * stride, nen_, dofs.data(), x, c, g);
        cp.x = g.x;
        cp.normal = g.n;
        warm_[i] = warm_project(cp) ? 1 : 0;
      }
    }
  }
  cold_.clear();
  cold_x_.clear();
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (warm_[i] == 0) {
      cold_.push_back(static_cast<int>(i));
      cold_x_.push_back(points_[i].x);
    }
  cold_project();

  // The start state anchors friction (master strategy): before the first commit, a point with
  // a foot has no history yet, and without one it would carry no friction in the first step;
  // the first assembly is at the start state, so its feet are where the points rest.
  if (!anchored_start_ && master)
    for (SurfaceContactPoint& cp : points_)
      if (found(cp.foot.status) && cp.history.patch < 0) {
        cp.history = anchor_at(cp.foot);
        cp.x_committed = cp.x;
      }
  anchored_start_ = true;
}

void SurfaceContact::evaluate(std::span<const Vector3d> x, double c, Eigen::VectorXd& R,
                              std::vector<Eigen::Triplet<double>>* K) {
  const Layout lay = layout();  // plain locals: clang's OpenMP takes no structured bindings
  const bool master = lay.master, parallel = lay.parallel;
  const int per_element = lay.per_element, n_el = lay.n_el;
  const std::size_t stride = lay.stride;

  // 2. Point laws, residual and element tangents.
  LawInputs in;
  in.eps_n = params_.law.eps_n * augmentation_.eps_scale;    // 1 but where updates stalled
  in.eps_t = params_.law.eps_t * augmentation_.eps_t_scale;  // likewise
  in.mu = params_.law.mu;
  in.friction = params_.law.friction();
  in.tangential = augmentation_.tangential;
  const ContactParameters law_params{in.eps_n, in.eps_t, params_.law.mu};
  const std::size_t re_size = 3 * static_cast<std::size_t>(nen_);
  element_R_.assign(static_cast<std::size_t>(n_el) * re_size, 0.0);
  element_active_.assign(static_cast<std::size_t>(n_el), 0);
  // On one thread the triplets go straight into K, after what is there (no second list of the
  // contact's tangent is kept).
  const bool direct = K != nullptr && (!parallel || omp_get_max_threads() == 1);
  thread_K_.resize(direct ? 0 : static_cast<std::size_t>(parallel ? omp_get_max_threads() : 1));
  if (direct) reserve_tangent(*K);
#pragma omp parallel if (parallel && !direct)
  {
    std::vector<Eigen::Triplet<double>>& Kt =
        direct ? *K : thread_K_[static_cast<std::size_t>(omp_get_thread_num())];
    if (!direct) Kt.clear();
    std::vector<int> dofs(static_cast<std::size_t>(nen_));
    // per element: Nall = [.. N_p ..], N_p = (R, R_,1, R_,2); Z: rows nen (3 k + l) + a,
    // [.. N_p M_p^kl ..]; Ke: rows nen (3 k + l) + a, column b: K(3a+k, 3b+l)
    Eigen::MatrixXd Nall(nen_, 3 * per_element), Z(9 * nen_, 3 * per_element), Ke;
    std::vector<double> rows(static_cast<std::size_t>(per_element) * stride);
    PointGeometry g;
#pragma omp for schedule(static)
    for (int e = 0; e < n_el; ++e) {
      const Element& el = elements_[static_cast<std::size_t>(e)];
      element_dofs(ref_, el.first_u, el.first_v, dofs);
      double* Re = element_R_.data() + static_cast<std::size_t>(e) * re_size;
      int n_active = 0;        // points of this element with a tangent contribution
      bool have_rows = false;  // the element's basis is formed at its first point with a foot
      const std::size_t i0 = static_cast<std::size_t>(e) * static_cast<std::size_t>(per_element);
      for (std::size_t i = i0; i < i0 + static_cast<std::size_t>(per_element); ++i) {
        SurfaceContactPoint& cp = points_[i];
        clear_law_state(cp);
        if (!found(cp.foot.status)) continue;
        if (!have_rows) element_basis(el, rows.data());
        have_rows = true;
        const double* B = rows.data() + (i - i0) * stride;
        point_geometry(B, nen_, dofs.data(), x, c, g);
        polish(cp.foot, g.x, g.n);
        const Surface& rigid_patch = rigid_->patch(cp.foot.patch);
        Vector3d f;
        Matrix39 df;
        const bool active = master
                                ? master_law(rigid_patch, g, law_params, in.tangential, cp, f, df)
                                : slave_law(rigid_patch, g, in, cp, f, df);
        if (!active) continue;
        cp.active = true;
        cp.first_contact = !cp.history.active;
        element_active_[static_cast<std::size_t>(e)] = 1;
        add_point_residual(B, nen_, cp.weight, g, f, Re);
        if (!K) continue;
        collect_point_tangent(B, nen_, g, f, df, c, cp.weight, n_active, Nall, Z);
        ++n_active;
      }
      if (K && n_active > 0) add_element_tangent(Z, Nall, n_active, nen_, dofs, turn_, Ke, Kt);
    }
  }
  for (int e = 0; e < n_el; ++e) {
    if (element_active_[static_cast<std::size_t>(e)] == 0) continue;
    element_dofs(ref_, elements_[static_cast<std::size_t>(e)].first_u,
                 elements_[static_cast<std::size_t>(e)].first_v, dofs_);
    const double* Re = element_R_.data() + static_cast<std::size_t>(e) * re_size;
    for (int k = 0; k < nen_; ++k)
      R.segment<3>(3 * dofs_[static_cast<std::size_t>(k)]) +=
          Eigen::Map<const Vector3d>(Re + 3 * k);
  }
  if (K && !direct) join_tangents(*K);
}

void SurfaceContact::reserve_tangent(std::vector<Eigen::Triplet<double>>& K) const {
  // Room for the elements with a foot (a bound of those with an active point).
  const std::size_t n = K.size() + elements_with_foot() * 9 * static_cast<std::size_t>(nen_ * nen_);
  if (n > K.capacity()) K.reserve(n);
}

void SurfaceContact::join_tangents(std::vector<Eigen::Triplet<double>>& K) const {
  std::size_t n = K.size();
  for (const std::vector<Eigen::Triplet<double>>& Kt : thread_K_) n += Kt.size();
  if (n > K.capacity()) K.reserve(n);  // exactly: the tangent's list does not double
  for (const std::vector<Eigen::Triplet<double>>& Kt : thread_K_)
    K.insert(K.end(), Kt.begin(), Kt.end());
}

void SurfaceContact::commit() {
  for (SurfaceContactPoint& cp : points_) {
    ContactHistory h;
    if (found(cp.foot.status)) {
      h.active = cp.active;
      h.patch = cp.foot.patch;
      h.xi = cp.foot.uv;
      h.foot = cp.foot.point;
      h.T = cp.active ? cp.T : Vector2d::Zero();
      // master: the committed tangential force as a 3-D vector (contact_law.hpp)
      h.T_vector = cp.active ? cp.T_vector : Vector3d::Zero();
    }
    cp.history = h;
    cp.x_committed = cp.x;
  }
  augmentation_.commit(points_);
}

AugmentResult SurfaceContact::passed_through() const {
  return iga::passed_through(points_, *rigid_,
                             [](const SurfaceContactPoint& cp) { return cp.active; });
}

AugmentResult SurfaceContact::augment() {
  const bool master = params_.strategy == SurfaceContactStrategy::kRigidMaster;
  return augmentation_.update(
      points_, enforcement_, passed_through(),
      [](const SurfaceContactPoint& cp) { return cp.active; },
      [](const SurfaceContactPoint& cp) { return cp.gap; },
      [](const SurfaceContactPoint& cp) { return cp.N; },
      [this](const SurfaceContactPoint& cp) { return sticks(cp); },
      [](const SurfaceContactPoint& cp) { return cp.slip_distance; },
      [master](const SurfaceContactPoint& cp) -> Vector3d {
        return master ? cp.T_vector : Vector3d(cp.T[0], cp.T[1], 0.0);
      });
}

void SurfaceContact::predict(double t) {
  augmentation_.predict(points_, enforcement_, t);
}

void SurfaceContact::restore() {
  augmentation_.restore(points_);
}

void SurfaceContact::archive(StateArchive& a) {
  iga::archive(a, augmentation_);
  a.io(anchored_start_);
  a.items(
      points_,
      [&](SurfaceContactPoint& p) {
        archive_common(a, p);
        a.io(p.normal);
        a.io(p.gap);
        a.io(p.N);
        a.io(p.T);
        a.io(p.T_vector);
        a.io(p.phi);
        a.io(p.active);
        a.io(p.slip);
        a.io(p.first_contact);
        a.io(p.slip_distance);
      },
      "contact points", /*resize=*/false);
}

bool SurfaceContact::sticks(const SurfaceContactPoint& cp) const {
  return cp.active && !cp.slip && !cp.first_contact && params_.law.friction();
}

double SurfaceContact::roundoff() const {
  const double eps =
      params_.law.eps_n * augmentation_.eps_scale + params_.law.eps_t * augmentation_.eps_t_scale;
  double sum = 0.0;
  for (const SurfaceContactPoint& cp : points_)
    if (cp.active) sum += cp.weight * eps * cp.x.norm();
  // 8 ulps a point: the surface point, its normal and the projection carry a few each.
  return 8.0 * std::numeric_limits<double>::epsilon() * sum;
}

SurfaceContactCounts SurfaceContact::counts() const {
  SurfaceContactCounts c;
  for (const SurfaceContactPoint& cp : points_) {
    if (!found(cp.foot.status)) ++c.failed;
    if (!cp.active) continue;
    ++c.active;
    (sticks(cp) ? c.stick : c.slip)++;
  }
  return c;
}

}  // namespace iga
