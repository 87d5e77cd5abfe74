// Common NonlinearProblem part of rotation-free models; see control_point_problem.hpp.
#include "iga/core/control_point_problem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "iga/core/state_archive.hpp"

namespace iga {

ControlPointProblem::ControlPointProblem(std::vector<Vector3d> X, std::string owner,
                                         DofMap::FailFn fail, int num_scalars)
    : dofs_(static_cast<int>(X.size()), std::move(owner), fail, num_scalars), X_(std::move(X)) {}

ControlPointProblem::ControlPointProblem(const ControlPointProblem& o)
    : Body(o), dofs_(o.dofs_), X_(o.X_), dead_loads_(o.dead_loads_), point_terms_(o.point_terms_) {
  for (const auto& p : o.pairs_) pairs_.push_back(p->clone());
}

ControlPointProblem& ControlPointProblem::operator=(const ControlPointProblem& o) {
  if (this == &o) return *this;
  Body::operator=(o);
  dofs_ = o.dofs_;
  X_ = o.X_;
  dead_loads_ = o.dead_loads_;
  point_terms_ = o.point_terms_;
  pairs_.clear();
  for (const auto& p : o.pairs_) pairs_.push_back(p->clone());
  return *this;
}

int ControlPointProblem::attach(std::unique_ptr<ContactPair> pair) {
  pairs_.push_back(std::move(pair));
  return static_cast<int>(pairs_.size()) - 1;
}

bool ControlPointProblem::symmetric() const {
  if (!model_symmetric()) return false;
  for (const auto& p : pairs_)
    if (!p->symmetric()) return false;
  return true;
}

void ControlPointProblem::commit(const VectorXd& u, double t) {
  (void)u, (void)t;
  for (const auto& p : pairs_) p->commit();
}

AugmentResult ControlPointProblem::augment(const VectorXd& u, double t) {
  (void)u, (void)t;
  AugmentResult r;
  for (const auto& p : pairs_) merge_augment(r, p->augment());
  return r;
}

void ControlPointProblem::restore() {
  for (const auto& p : pairs_) p->restore();
}

void ControlPointProblem::archive(StateArchive& a) {
  int n = num_pairs();
  a.io(n);
  if (a.loading() && n != num_pairs())
    a.fail("the file has " + std::to_string(n) + " contact pairs, the body " +
           std::to_string(num_pairs()));
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    a.section("pair " + std::to_string(k));
    pairs_[k]->archive(a);
  }
}

double ControlPointProblem::residual_roundoff() const {
  double r = 0.0;
  for (const auto& p : pairs_) r = std::max(r, p->roundoff());
  return r;
}

std::string ControlPointProblem::status() const {
  std::string s;
  for (const auto& p : pairs_) s += (s.empty() ? "" : "; ") + p->status();
  return s;
}

SampledMesh ControlPointProblem::sample(const VectorXd& u, double t, int samples) const {
  if (!share().assembles) return {};  // another process samples the body
  SampledMesh m = sample_model(u, t, samples);
  if (pairs_.size() == 1) pairs_.front()->add_fields(m);
  if (pairs_.size() <= 1) return m;
  // Several pairs: each one's fields under its own names, <field>_<k> for pair k.
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    SampledMesh own;
    own.params = m.params;
    own.elements = m.elements;
    own.points = m.points;
    pairs_[k]->add_fields(own);
    char suffix[24];  // (not "_" + std::to_string(k): a false -Wrestrict of GCC 12)
    std::snprintf(suffix, sizeof suffix, "_%zu", k);
    for (auto& f : own.fields.scalars) f.first += suffix;
    for (auto& f : own.fields.vectors) f.first += suffix;
    m.fields.add(std::move(own.fields));
  }
  return m;
}

VectorXd ControlPointProblem::residual_keeping_pairs(const VectorXd& u, double t) {
  // The residual is evaluated with copies of the pairs; the pairs themselves stay untouched.
  std::vector<std::unique_ptr<ContactPair>> copies;
  for (const auto& p : pairs_) copies.push_back(p->clone());
  std::swap(pairs_, copies);
  try {
    assemble_cartesian(u, t, false);
  } catch (...) {
    std::swap(pairs_, copies);
    throw;
  }
  std::swap(pairs_, copies);
  return g_;
}

std::vector<Vector3d> ControlPointProblem::reactions(const VectorXd& u, double t) {
  const VectorXd g = residual_keeping_pairs(u, t);
  std::vector<Vector3d> r(X_.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = g.segment<3>(3 * static_cast<Eigen::Index>(i));
  return dofs_.constraint_forces(r);
}

std::vector<double> ControlPointProblem::scalar_reactions(const VectorXd& u, double t) {
  const VectorXd g = residual_keeping_pairs(u, t);
  const auto n3 = 3 * static_cast<Eigen::Index>(X_.size());
  return {g.data() + n3, g.data() + g.size()};
}

void ControlPointProblem::add_nodal_load(std::vector<std::pair<int, Vector3d>> forces,
                                         LoadCurve curve, bool split) {
  dead_loads_.push_back(NodalLoad{std::move(forces), std::move(curve), split});
}

void ControlPointProblem::add_nodal_load(const std::vector<Vector3d>& f, LoadCurve curve,
                                         bool split) {
  std::vector<std::pair<int, Vector3d>> forces;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f[i].squaredNorm() > 0.0) forces.emplace_back(static_cast<int>(i), f[i]);
  add_nodal_load(std::move(forces), std::move(curve), split);
}

void ControlPointProblem::current_points(const VectorXd& u, double t,
                                         std::vector<Vector3d>& x) const {
  dofs_.current_points(X_, u, t, x);
}

Eigen::MatrixXd ControlPointProblem::near_null_space(const VectorXd& u, double t) const {
  const std::vector<Vector3d> x = current_points(u, t);
  Vector3d c = Vector3d::Zero();
  for (const Vector3d& p : x) c += p;
  if (!x.empty()) c /= static_cast<double>(x.size());
  Eigen::MatrixXd Z(dofs_.num_free(), 6);
  VectorXd g = VectorXd::Zero(dofs_.num_cartesian()), z;
  for (int m = 0; m < 6; ++m) {
    const Vector3d e = Vector3d::Unit(m % 3);
    for (std::size_t i = 0; i < x.size(); ++i)
      g.segment<3>(3 * static_cast<Eigen::Index>(i)) = m < 3 ? e : Vector3d(e.cross(x[i] - c));
    dofs_.reduce(g, z);
    Z.col(m) = z;
  }
  return Z;
}

std::vector<Vector3d> ControlPointProblem::current_points(const VectorXd& u, double t) const {
  std::vector<Vector3d> x;
  current_points(u, t, x);
  return x;
}

std::vector<double> ControlPointProblem::current_scalars(const VectorXd& u, double t) const {
  std::vector<double> s;
  dofs_.current_scalars(u, t, s);
  return s;
}

std::vector<Vector3d> ControlPointProblem::control_point_displacements(const VectorXd& u,
                                                                       double t) const {
  std::vector<Vector3d> x = current_points(u, t);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] -= X_[i];
  return x;
}

VectorXd ControlPointProblem::dead_load(double t) const {
  VectorXd f = VectorXd::Zero(dofs_.num_cartesian());
  for (const NodalLoad& L : dead_loads_) {
    const double lam = L.curve(t);
    for (const auto& [i, F] : L.forces) f.segment<3>(3 * i) += lam * F;
  }
  return f;
}

void ControlPointProblem::assemble_cartesian(const VectorXd& u, double t, bool tangent) {
  cart_triplets_.clear();
  // The tangent's list is most of an assembly's memory: it is kept at the last assembly's size
  // and an eighth more (a list that doubled as it grew, or one too small, is replaced: it is
  // empty here, nothing is copied), so that it does not double while it is filled.
  const std::size_t want = cart_size_ + cart_size_ / 8;
  if (tangent && (cart_triplets_.capacity() < cart_size_ ||
                  cart_triplets_.capacity() > cart_size_ + cart_size_ / 4)) {
    std::vector<Triplet>().swap(cart_triplets_);  // the old one freed first
    cart_triplets_.reserve(want);
  }
  if (!share().assembles) {  // another process assembles the body
    g_.setZero(dofs_.num_cartesian());
    return;
  }
  current_points(u, t, x_);
  dofs_.current_scalars(u, t, s_);
  std::vector<Triplet>* K = tangent ? &cart_triplets_ : nullptr;
  assemble_model(x_, s_, t, g_, K);  // g = f_int (- configuration-dependent loads)
  if (g_.size() != dofs_.num_cartesian())
    throw std::logic_error(describe() + ": the model's residual has " + std::to_string(g_.size()) +
                           " entries, expected " + std::to_string(dofs_.num_cartesian()));
  subtract_dead_loads(t, g_);
  const BodyState state{x_, s_, section_frames()};
  for (const auto& p : pairs_) p->add(state, t, g_, K);
  if (K) cart_size_ = K->size();
}

void ControlPointProblem::assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) {
  assemble_cartesian(u, t, K != nullptr);
  dofs_.reduce(g_, R);  // R = P^T g
  if (!K) return;
  dofs_.reduce_in_place(cart_triplets_);  // K_free = P^T K_cart P
  // the pattern is built again only when the triplets' sequence changed (the active set)
  assembler_.assemble(cart_triplets_, dofs_.num_free(), dofs_.num_free(), *K);
}

void ControlPointProblem::subtract_dead_loads(double t, VectorXd& g) const {
  for (const NodalLoad& L : dead_loads_) {
    const double lam = L.curve(t);
    for (const auto& [i, F] : L.forces)
      if (L.split || adds_point_terms(i)) g.segment<3>(3 * i) -= lam * F;  // g -= f_ext
  }
}

void ControlPointProblem::point_partition(int /*rank*/, int /*processes*/,
                                          std::vector<int>& /*owner*/,
                                          std::vector<char>& /*reads*/) const {
  throw std::logic_error(describe() + " cannot be cut over several processes");
}

void ControlPointProblem::partition(int rank, int processes, std::vector<int>& owner,
                                    std::vector<int>& reads) {
  std::vector<int> point_owner;
  std::vector<char> point_read;
  point_partition(rank, processes, point_owner, point_read);
  const int n = num_control_points();
  if (point_owner.size() != static_cast<std::size_t>(n) || point_read.size() != point_owner.size())
    throw std::logic_error(describe() + ": a partition of " + std::to_string(point_owner.size()) +
                           " points for " + std::to_string(n));
  point_terms_.assign(point_owner.size(), 0);
  owner.assign(static_cast<std::size_t>(num_dofs()), -1);
  for (int i = 0; i < n; ++i) {
    const auto pi = static_cast<std::size_t>(i);
    point_terms_[pi] = point_owner[pi] == rank ? 1 : 0;
    for (int c = 0; c < 3; ++c) {
      const int f = dofs_.dof(i, c);
      if (f < 0) continue;
      int& o = owner[static_cast<std::size_t>(f)];
      if (o < 0) o = point_owner[pi];
      if (point_read[pi] != 0 || point_owner[pi] == rank) reads.push_back(f);
    }
  }
  for (int k = 0; k < num_scalars(); ++k) {  // (no body with scalars is cut: process 0's)
    const int f = dofs_.scalar_dof(k);
    if (f < 0) continue;
    owner[static_cast<std::size_t>(f)] = 0;
    reads.push_back(f);
  }
}

bool ControlPointProblem::load_rate(const VectorXd& u, double t, double h, VectorXd& R_t) {
  const double t1 = t + h;
  if (dofs_.prescribed_moves(t, t1)) return false;
  if (std::any_of(pairs_.begin(), pairs_.end(),
                  [&](const auto& p) { return p->depends_on_time(t, t1); }))
    return false;
  // g(t1) - g(t0) at the same x, s: the internal forces and the pairs' part cancel.
  VectorXd g0 = VectorXd::Zero(dofs_.num_cartesian()), g1 = g0;
  if (share().assembles) {
    std::vector<Vector3d> x;
    std::vector<double> s;
    current_points(u, t, x);
    dofs_.current_scalars(u, t, s);
    if (!add_load_terms(x, s, t1, g1) || !add_load_terms(x, s, t, g0)) return false;
    subtract_dead_loads(t, g0);
    subtract_dead_loads(t1, g1);
  }
  g1 -= g0;
  g1 /= h;
  dofs_.reduce(g1, R_t);
  return true;
}

std::vector<Vector3d> ControlPointProblem::nodal_residual(const VectorXd& u, double t) {
  assemble_cartesian(u, t, false);
  std::vector<Vector3d> r(X_.size());
  for (std::size_t i = 0; i < r.size(); ++i) r[i] = g_.segment<3>(3 * static_cast<Eigen::Index>(i));
  return r;
}

void ControlPointProblem::end_symmetry(int i0, int i1, const Vector3d& normal,
                                       const std::string& who, DofMap::FailFn fail) {
  if (!(normal.norm() > 0.0) || !normal.allFinite())
    fail(who + ": the plane's normal must be a non-zero vector");
  const Vector3d n = normal.normalized();
  const Vector3d T = reference_point(i1) - reference_point(i0);
  if (!(std::abs(T.normalized().dot(n)) > 1.0 - 1e-9))
    fail(who +
         ": the rod's end tangent is not along the plane's normal (the rod must cross the "
         "symmetry plane at right angles)");
  int axis = -1;  // n along a coordinate axis?
  for (int k = 0; k < 3; ++k)
    if (std::abs(n[k]) > 1.0 - 1e-14) axis = k;
  if (axis >= 0) {
    if (!dofs_.rotated(i0) && !dofs_.rotated(i1)) {
      if (!constrained(i0, axis)) fix(i0, axis);
      for (int k = 0; k < 3; ++k)
        if (k != axis) dofs_.tie(i1, k, i0, k);
      return;
    }
  }
  for (int i : {i0, i1})
    for (int k = 0; k < 3; ++k)
      if (dofs_.rotated(i) || constrained(i, k))
        fail(who + ": control point " + std::to_string(i) +
             " already has a local basis or constraints (a plane normal to a coordinate axis "
             "works with them)");
  Matrix3d Q;
  Q.col(2) = n;
  Q.col(0) = n.unitOrthogonal();
  Q.col(1) = n.cross(Q.col(0));
  set_local_basis(i0, Q);
  set_local_basis(i1, Q);
  fix(i0, 2);
  dofs_.tie(i1, 0, i0, 0);
  dofs_.tie(i1, 1, i0, 1);
}

}  // namespace iga
