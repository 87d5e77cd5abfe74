// CTRS contact integral ([KS15] Sects. 4-5, eqs. (52), (66)-(70), (77)-(78)).
#include "iga/contact_integrals/curve_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include "geometry/differential_geometry.hpp"
#include "iga/contact_integrals/contact_state.hpp"
#include "iga/contact_integrals/pass_through.hpp"
#include "iga/core/quadrature.hpp"

namespace iga {

namespace {
void check_parameters(const CurveContactParameters& p) {
  p.law.check("CurveContactParameters");
  if (!(p.radius >= 0.0) || !std::isfinite(p.radius))
    throw std::invalid_argument("CurveContactParameters: radius must be >= 0 and finite, got " +
                                std::to_string(p.radius));
  if (p.points_per_element < 1 || p.points_per_element > 16)
    throw std::invalid_argument("contact points per element must be in 1..16, got " +
                                std::to_string(p.points_per_element));
}
}  // namespace

CurveContact::CurveContact(const NurbsCurve& reference, const RigidSurface& rigid,
                           const CurveContactParameters& params)
    : ref_(reference), rigid_(&rigid), params_(params) {
  check_parameters(params);
  const int points_per_element = params.points_per_element;
  std::array<double, kMaxGaussPoints> gx{}, gw{};
  gauss_legendre(points_per_element, gx, gw);
  const std::vector<double> br = ref_.knots().breaks();
  for (std::size_t e = 0; e + 1 < br.size(); ++e)
    for (int k = 0; k < points_per_element; ++k) {
      CurveContactPoint cp;
      const double half = 0.5 * (br[e + 1] - br[e]);
      cp.eta = br[e] + half * (1.0 + gx[static_cast<std::size_t>(k)]);
      cp.weight = gw[static_cast<std::size_t>(k)] * half * ref_.derivs(cp.eta, 1).d[1].norm();
      cp.foot.patch = -1;
      points_.push_back(cp);
      basis_.push_back(rational_basis(ref_, cp.eta));  // fixed eta: once, used every assembly
    }
  double chord = 0.0;
  for (std::size_t e = 0; e + 1 < br.size(); ++e)
    chord = std::max(chord, (ref_.point(br[e + 1]) - ref_.point(br[e])).norm());
  search_distance_ = params_.radius + chord;
}

void CurveContact::set_parameters(const CurveContactParameters& p) {
  check_parameters(p);
  if (p.points_per_element != params_.points_per_element)
    throw std::invalid_argument("CurveContact::set_parameters: points_per_element cannot change (" +
                                std::to_string(params_.points_per_element) + " -> " +
                                std::to_string(p.points_per_element) + ")");
  params_ = p;
}

void CurveContact::set_enforcement(const ContactEnforcement& e) {
  e.check("CurveContact");
  enforcement_ = e;
}

namespace {

// Current position r_s = sum_j R_j x_j (77) of a contact point.
void set_position(const RationalBasis& basis, int p, std::span<const Vector3d> x,
                  CurveContactPoint& cp) {
  const BasisValues& Rb = basis.N;
  const int first = basis.first;
  cp.x.setZero();
  for (int j = 0; j <= p; ++j) cp.x += Rb[j] * x[static_cast<std::size_t>(first + j)];
}

// The points without a warm start (cold, at positions cold_x) get their feet from the broad
// phase; a point without one stays cold.
void project_cold(const RigidSurface& rigid, const std::vector<int>& cold,
                  const std::vector<Vector3d>& cold_x, double search_distance,
                  std::vector<CurveContactPoint>& points) {
  const std::vector<ProjectionResult> feet = rigid.closest_points(cold_x, search_distance);
  for (std::size_t k = 0; k < cold.size(); ++k) {
    CurveContactPoint& cp = points[static_cast<std::size_t>(cold[k])];
    cp.foot = feet[k];
    if (!found(cp.foot.status)) cp.foot.patch = -1;  // stays cold
  }
}

// The point law at a point with its foot found: false (law cleared) without a foot or beyond
// an open edge, where there is no contact; `anchor_start`: the first assembly (see assemble);
// `roll`: the rolling displacement of a rod with torsion (null: none).
bool evaluate_point(const RigidSurface& rigid, const ContactParameters& law_params, double radius,
                    bool tangential, bool anchor_start, const Vector3d* roll,
                    CurveContactPoint& cp) {
  cp.law = ContactPoint();
  cp.N = cp.T = cp.B = 0.0;
  if (!found(cp.foot.status)) return false;
  if (anchor_start && cp.history.patch < 0) {
    cp.history = anchor_at(cp.foot);
    cp.x_committed = cp.x;
  }
  if (beyond_open_edge(cp.foot, cp.x)) return false;  // not in contact
  cp.law = evaluate_contact(rigid.patch(cp.foot.patch), cp.foot, cp.x, law_params, cp.history,
                            cp.lambda_n, tangential ? &cp.lambda_t : nullptr, roll, radius);
  return true;
}

// The rolling displacement of a rope that rolls at a point (CurveContact::set_rolling):
// s(dphi) = -R dphi b_c, b_c = t_c x n_c, and its first two derivatives in dphi.
struct Roll {
  Vector3d s, s1, s2;
};
Roll roll_of(const CurveContactPoint& cp, double R) {
  const Vector3d b = cp.tangent_c.cross(cp.normal_c);  // in the tool's frame
  return {-R * cp.spin * b, -R * b, Vector3d::Zero()};
}

// A rod with torsion: the section's spin at the point since the commit (sp; the first
// assembly takes the frame at rest as the committed one) and the rolling displacement. x: the
// rod's points in world orientation; Q: the tool's turn.
Roll spin_and_roll(const SectionFrames& rod, std::span<const Vector3d> x,
                   std::span<const double> alpha, double radius, const Matrix3d& Q,
                   CurveContactPoint& cp, SectionSpin& sp) {
  if (cp.frame_t_c.isZero()) {
    rod.frame(cp.eta, x, alpha, cp.frame_t_c, cp.frame_d1_c);
    cp.tangent_c = Q.transpose() * cp.frame_t_c;
    if (found(cp.foot.status)) cp.normal_c = cp.foot.normal;
  }
  sp = rod.spin_since(cp.eta, cp.frame_t_c, cp.frame_d1_c, x, alpha, /*derivatives=*/false);
  cp.frame_t = sp.t;
  cp.frame_d1 = sp.d1;
  cp.spin = sp.value;
  return roll_of(cp, radius);
}

// The twist part of an active point: the friction's work T.s_phi d(dphi) on the DOFs of the rod
// element holding it (sp: the spin and its derivatives there), and the coupling blocks of the
// tangent (see CurveContact::set_rolling): with f = w T.s_phi,
//   R_j -= f g_j (g = d dphi / dq),
//   K_(a r) k -= w R_a (dT/ds s_phi)_r g_k,   K_j (b c) -= w g_j (s_phi^T dT/dr)_c R_b,
//   K_jk -= w [(s_phi^T dT/ds s_phi + T.s_phi2) g_j g_k + T.s_phi H_jk].
void add_twist_terms(const CurveContactPoint& cp, const RationalBasis& basis, int p,
                     const SectionSpin& sp, const Roll& roll, const Matrix3d& Q, Eigen::VectorXd& R,
                     std::vector<Eigen::Triplet<double>>* K) {
  // With a moving tool (Q its turn) the law's vectors are in the tool's frame and the spin's
  // derivatives are with respect to world positions: the residual's position entries are
  // turned back (the pair turns them forward), the coupling blocks turned to the world.
  const Vector3d& T = cp.law.T_vector;
  const double w = cp.weight, f = T.dot(roll.s1);
  const auto ne = static_cast<int>(sp.gradient.size());
  const auto dof = [&](int j) { return sp.dofs[static_cast<std::size_t>(j)]; };
  for (int j = 0; j < sp.positions; j += 3) {
    const Vector3d gt = Q.transpose() * Vector3d(sp.gradient.segment<3>(j));
    for (int c = 0; c < 3; ++c) R[dof(j + c)] -= w * f * gt[c];
  }
  for (int j = sp.positions; j < ne; ++j) R[dof(j)] -= w * f * sp.gradient[j];
  if (!K) return;
  const Vector3d ks_tool = cp.law.stiffness_roll * roll.s1;  // dT/ds s_phi
  const Vector3d ks = Q * ks_tool;                           // in the world
  const Eigen::RowVector3d sk =
      roll.s1.transpose() * cp.law.stiffness_tangential * Q.transpose();  // s^T dT/dr, world
  const double kss = roll.s1.dot(ks_tool) + T.dot(roll.s2);
  for (int a = 0; a <= p; ++a) {
    const double Ra = basis.N[a];
    const int A = basis.first + a;
    for (int k = 0; k < ne; ++k) {
      const int gk = dof(k);
      for (int r = 0; r < 3; ++r) {
        K->emplace_back(3 * A + r, gk, -w * Ra * ks[r] * sp.gradient[k]);
        K->emplace_back(gk, 3 * A + r, -w * sp.gradient[k] * sk[r] * Ra);
      }
    }
  }
  for (int j = 0; j < ne; ++j)
    for (int k = 0; k < ne; ++k) {
      const double v = kss * sp.gradient[j] * sp.gradient[k] + f * sp.hessian(j, k);
      if (v != 0.0) K->emplace_back(dof(j), dof(k), -w * v);
    }
}

// R_a -= int R_a f ds at an active point.
void add_point_residual(const CurveContactPoint& cp, const RationalBasis& basis, int p,
                        Eigen::VectorXd& R) {
  const BasisValues& Rb = basis.N;
  for (int a = 0; a <= p; ++a) {
    const int A = basis.first + a;
    R.segment<3>(3 * A) -= cp.weight * Rb[a] * cp.law.force;
  }
}

// K_ab -= int R_a R_b df/dr ds at an active point.
void add_point_tangent(const CurveContactPoint& cp, const RationalBasis& basis, int p,
                       const Matrix3d& turn, std::vector<Eigen::Triplet<double>>& K) {
  const BasisValues& Rb = basis.N;
  const int first = basis.first;
  const Matrix3d kt = turn * cp.law.stiffness * turn.transpose();
  for (int a = 0; a <= p; ++a) {
    const int A = first + a;
    for (int b = 0; b <= p; ++b) {
      const int B = first + b;
      const Matrix3d k = -cp.weight * Rb[a] * Rb[b] * kt;
      for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 3; ++j) K.emplace_back(3 * A + r, 3 * B + j, k(r, j));
    }
  }
}

// Output: the curve's frame tau (tangent), e = -n, g = tau x e (41)-(42); (68)-(70).
void set_frame_forces(const RationalBasis& basis, int p, std::span<const Vector3d> x,
                      CurveContactPoint& cp) {
  Vector3d tangent = Vector3d::Zero();  // r' = sum R_j' x_j, normalized
  for (int j = 0; j <= p; ++j)
    tangent += basis.dN[j] * x[static_cast<std::size_t>(basis.first + j)];
  tangent.normalize();
  const Vector3d e = -cp.law.normal;
  const Vector3d g = tangent.cross(e);
  // [KS15]'s T^i rho_i acts on the surface, -f_T: T = -T^i (rho_i.tau) = f_T.tau.
  cp.N = cp.law.N;                      // (68)
  cp.T = cp.law.T_vector.dot(tangent);  // (69)
  cp.B = cp.law.T_vector.dot(g);        // (70)
}

// The normal penalty stiffness eps_N n n^T of a point near contact, in the tangent only (see
// assemble).
void add_near_stiffness(const CurveContactPoint& cp, const RationalBasis& basis, int p,
                        double eps_n, const Matrix3d& turn,
                        std::vector<Eigen::Triplet<double>>& K) {
  const BasisValues& Rb = basis.N;
  const int first = basis.first;
  const Vector3d n = turn * cp.law.normal;
  const Matrix3d kn = eps_n * n * n.transpose();
  for (int a = 0; a <= p; ++a)
    for (int b = 0; b <= p; ++b) {
      const Matrix3d k = cp.weight * Rb[a] * Rb[b] * kn;
      for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 3; ++j)
          K.emplace_back(3 * (first + a) + r, 3 * (first + b) + j, k(r, j));
    }
}

}  // namespace

void CurveContact::locate(std::span<const Vector3d> x, bool parallel, std::vector<char>& warm) {
  const int p = ref_.degree();
  const auto n_points = static_cast<std::ptrdiff_t>(points_.size());
  // Current positions (77); the points without a warm start go through the broad phase.
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t i = 0; i < n_points; ++i)
    set_position(basis_[static_cast<std::size_t>(i)], p, x, points_[static_cast<std::size_t>(i)]);
  cold_.clear();
  cold_x_.clear();
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const CurveContactPoint& cp = points_[i];
    if (cp.foot.patch < 0 || !found(cp.foot.status)) {
      cold_.push_back(static_cast<int>(i));
      cold_x_.push_back(cp.x);
      warm[i] = 0;
    }
  }
  broad_phase_points_ = static_cast<int>(cold_.size());
  if (!cold_.empty()) project_cold(*rigid_, cold_, cold_x_, search_distance_, points_);
}

void CurveContact::assemble(const BodyState& state, Eigen::VectorXd& R,
                            std::vector<Eigen::Triplet<double>>* K) {
  const int p = ref_.degree();
  const std::span<const Vector3d> x = state.x;
  const std::size_t n = static_cast<std::size_t>(ref_.num_control_points());
  if (x.size() != n)
    throw std::invalid_argument("CurveContact: " + std::to_string(x.size()) +
                                " control points for a curve of " + std::to_string(n));
  if (rolling_ && !state.frames)
    throw std::invalid_argument("CurveContact: a rope that rolls needs its body's section frames");
  const SectionFrames* frames = rolling_ ? state.frames : nullptr;
  // A rope that rolls: its frames are world frames, from the points turned back to the world's
  // orientation (xw); its scalars (twists) are not turned.
  thread_local std::vector<Vector3d> xw;
  if (frames) {
    xw.resize(n);
    for (std::size_t i = 0; i < n; ++i) xw[i] = turn_ * x[i];
  }
  // The points in parallel (OpenMP) where they are many: their positions, projections and
  // laws touch only the point itself; the residual and tangent are then summed over the points
  // in order by one thread, so R and K do not depend on the number of threads, bit for bit.
  const auto n_points = static_cast<std::ptrdiff_t>(points_.size());
  const bool parallel = n_points >= kParallelCurvePoints;
  std::vector<char> warm(points_.size(), 1);
  locate(x, parallel, warm);
  // The start state anchors friction: before the first commit, a point with a foot has no
  // history yet, and without one it would carry no friction in the first step (a rope laid on
  // an inclined surface would have nothing to hold it). The first assembly is at the start
  // state, so its feet are where the points rest.
  const bool anchor_start = !anchored_start_;
  anchored_start_ = true;
  ContactParameters law_params = params_.law;
  law_params.eps_n *= augmentation_.eps_scale;  // 1 but where augmentations stalled
  law_params.eps_t *= augmentation_.eps_t_scale;
  // Each point's law: the closest point warm-started from its last foot (cold ones: done
  // above), the section's spin and roll of a rod with torsion, the law, the frame forces.
  // (xw is this thread's: passed by reference into the parallel loop.)
  const std::vector<Vector3d>& x_world = xw;
  const std::span<const double> twists = state.s;
  std::vector<SectionSpin> spins(frames ? points_.size() : 0);
  std::vector<Roll> rolls(points_.size(),
                          Roll{Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()});
  std::vector<char> evaluated(points_.size(), 0);
#pragma omp parallel for schedule(dynamic, 16) if (parallel)
  for (std::ptrdiff_t ii = 0; ii < n_points; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    CurveContactPoint& cp = points_[i];
    if (warm[i] != 0) cp.foot = rigid_->closest_point(cp.x, cp.foot);
    if (frames)
      rolls[i] = spin_and_roll(*frames, x_world, twists, params_.radius, turn_, cp, spins[i]);
    cp.torque = 0.0;
    evaluated[i] = evaluate_point(*rigid_, law_params, params_.radius, augmentation_.tangential,
                                  anchor_start, frames ? &rolls[i].s : nullptr, cp)
                       ? 1
                       : 0;
    if (evaluated[i] == 0 || !cp.law.active) continue;
    if (frames) {  // the spin's derivatives only where the point is active
      cp.torque = cp.law.T_vector.dot(rolls[i].s1);
      spins[i] = frames->spin_since(cp.eta, cp.frame_t_c, cp.frame_d1_c, x_world, twists,
                                    /*derivatives=*/true);
    }
    set_frame_forces(basis_[i], p, x, cp);
  }
  near_.clear();
  bool any_active = false;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const CurveContactPoint& cp = points_[i];
    if (evaluated[i] == 0) continue;
    if (!cp.law.active) {
      if (cp.law.gap >= 0.0 && cp.law.gap <= near_distance()) near_.push_back(static_cast<int>(i));
      continue;
    }
    any_active = true;
    // R_a -= int R_a f ds; K_ab -= int R_a R_b df/dr ds
    add_point_residual(cp, basis_[i], p, R);
    if (K) add_point_tangent(cp, basis_[i], p, turn_, *K);
    if (frames) add_twist_terms(cp, basis_[i], p, spins[i], rolls[i], turn_, R, K);
  }
  // No point in contact, some a hair above the surface: the tangent gets their normal penalty
  // stiffness eps_N n n^T (no force, so the residual and the converged state are unchanged).
  // Without it a body held only by the contact (a rope pinned at one end, its Gauss points a
  // round-off above the cylinder it is fitted to) has a rigid mode at the start, and the first
  // Newton correction is huge (|R| ~ 1e21 with 2 points per element on data/capstan.json).
  if (K && !any_active)
    for (int i : near_)
      add_near_stiffness(points_[static_cast<std::size_t>(i)], basis_[static_cast<std::size_t>(i)],
                         p, params_.law.eps_n, turn_, *K);
}

void CurveContact::commit() {
  for (CurveContactPoint& cp : points_) {
    cp.history = found(cp.foot.status) ? commit_contact(cp.law, cp.foot.patch) : ContactHistory{};
    cp.x_committed = cp.x;
    if (rolling_) {  // the rolling displacement starts again from here
      cp.frame_t_c = cp.frame_t;
      cp.frame_d1_c = cp.frame_d1;
      cp.tangent_c = turn_.transpose() * cp.frame_t;  // the turn of the last assembly
      cp.normal_c = cp.law.active           ? cp.law.normal
                    : found(cp.foot.status) ? cp.foot.normal
                                            : Vector3d::Zero();
      cp.spin = 0.0;
    }
  }
  augmentation_.commit(points_);
}

AugmentResult CurveContact::passed_through() const {
  return iga::passed_through(points_, *rigid_,
                             [](const CurveContactPoint& cp) { return cp.law.active; });
}

AugmentResult CurveContact::augment() {
  const bool friction = params_.law.friction();
  return augmentation_.update(
      points_, enforcement_, passed_through(),
      [](const CurveContactPoint& cp) { return cp.law.active; },
      [](const CurveContactPoint& cp) { return cp.law.gap; },
      [](const CurveContactPoint& cp) { return cp.law.N; },
      [friction](const CurveContactPoint& cp) {
        return friction && cp.law.active && !cp.law.slip && cp.history.patch >= 0;
      },
      [](const CurveContactPoint& cp) { return cp.law.slip_distance; },
      [](const CurveContactPoint& cp) -> Vector3d { return cp.law.T_vector; });
}

void CurveContact::predict(double t) {
  augmentation_.predict(points_, enforcement_, t);
}

void CurveContact::restore() {
  augmentation_.restore(points_);
}

void CurveContact::archive(StateArchive& a) {
  iga::archive(a, augmentation_);
  a.io(anchored_start_);
  a.items(
      points_,
      [&](CurveContactPoint& p) {
        archive_common(a, p);
        iga::archive(a, p.law);
        a.io(p.N);
        a.io(p.T);
        a.io(p.B);
        a.io(p.frame_t);
        a.io(p.frame_d1);
        a.io(p.frame_t_c);
        a.io(p.frame_d1_c);
        a.io(p.normal_c);
        a.io(p.tangent_c);
        a.io(p.spin);
        a.io(p.torque);
      },
      "contact points", /*resize=*/false);
}

double CurveContact::roundoff() const {
  const double eps =
      params_.law.eps_n * augmentation_.eps_scale + params_.law.eps_t * augmentation_.eps_t_scale;
  double sum = 0.0;
  for (const CurveContactPoint& cp : points_)
    if (cp.law.active) sum += cp.weight * eps * (cp.x.norm() + params_.radius);
  // 8 ulps a point: the surface point, its normal and the projection carry a few each.
  return 8.0 * std::numeric_limits<double>::epsilon() * sum;
}

CurveContactCounts CurveContact::counts() const {
  CurveContactCounts c;
  for (const CurveContactPoint& cp : points_)
    if (cp.law.active) {
      ++c.active;
      (cp.law.slip ? c.slip : c.stick)++;
      c.along += cp.weight * std::abs(cp.T);
      c.across += cp.weight * std::abs(cp.B);
      if (cp.law.slip) (cp.T > 0.0 ? c.slip_positive : c.slip_negative)++;
    }
  return c;
}

}  // namespace iga
