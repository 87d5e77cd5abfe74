// Constraint bookkeeping of rotation-free models: local bases, fixed / prescribed / tied
// components, reduction to the free unknowns. See dof_map.hpp.
#include "iga/core/dof_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace iga {

DofMap::DofMap(int num_points, std::string owner, FailFn fail, int num_scalars)
    : owner_(std::move(owner)), fail_(fail) {
  points_.resize(static_cast<std::size_t>(std::max(0, num_points)));
  scalars_.resize(static_cast<std::size_t>(std::max(0, num_scalars)));
  renumber();
}

void DofMap::check_point(int point, const char* what) const {
  if (point < 0 || point >= num_points()) {
    const std::string msg = owner_ + "::" + what + ": control point " + std::to_string(point) +
                            " out of range [0, " + std::to_string(num_points() - 1) + "]";
    fail_(msg);
    throw std::invalid_argument(msg);  // fail_ is expected to throw
  }
}

void DofMap::check_scalar(int k, const char* what) const {
  if (k < 0 || k >= num_scalars()) {
    const std::string msg = owner_ + "::" + what + ": scalar unknown " + std::to_string(k) +
                            " out of range [0, " + std::to_string(num_scalars() - 1) + "]";
    fail_(msg);
    throw std::invalid_argument(msg);
  }
}

void DofMap::check_component(int component) const {
  if (component < 0 || component > 2) {
    const std::string msg =
        owner_ + ": component must be 0, 1 or 2, got " + std::to_string(component);
    fail_(msg);
    throw std::invalid_argument(msg);
  }
}

void DofMap::renumber() const {
  stale_ = false;
  num_free_ = 0;
  for (const PointDofs& P : points_)
    for (const Component& c : P.c) {
      c.free = -1;
      c.resolved = c.prescribed;
      c.sign = 1.0;
      if (c.prescribed < 0 && c.tie_point < 0) c.free = num_free_++;
    }
  for (const Component& c : scalars_) {  // after the points
    c.resolved = c.prescribed;
    c.sign = 1.0;
    c.free = c.prescribed < 0 ? num_free_++ : -1;
  }
  // Ties: follow the chain to a component with its own constraint or its own unknown (tie()
  // rejects cycles, so the chain ends).
  for (const PointDofs& P : points_)
    for (const Component& c : P.c) {
      if (c.prescribed >= 0 || c.tie_point < 0) continue;
      double s = c.tie_sign;
      const Component* m = &points_[static_cast<std::size_t>(c.tie_point)]
                                .c[static_cast<std::size_t>(c.tie_component)];
      while (m->prescribed < 0 && m->tie_point >= 0) {
        s *= m->tie_sign;
        m = &points_[static_cast<std::size_t>(m->tie_point)]
                 .c[static_cast<std::size_t>(m->tie_component)];
      }
      c.sign = s;
      c.free = m->free;
      c.resolved = m->prescribed;
    }
  plain_free_.resize(3 * points_.size());
  plain_sign_.resize(3 * points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i)
    for (std::size_t a = 0; a < 3; ++a) {
      const Component& c = points_[i].c[a];
      plain_free_[3 * i + a] = points_[i].rotated ? -2 : c.free;
      plain_sign_[3 * i + a] = c.sign;
    }
}

std::vector<Vector3d> DofMap::constraint_forces(const std::vector<Vector3d>& g) const {
  const std::size_t n = points_.size();
  if (g.size() != n)
    throw std::invalid_argument(owner_ + "::constraint_forces: " + std::to_string(g.size()) +
                                " forces for " + std::to_string(n) + " points");
  // Generalized force of each component, moved along the tie chains to their ends.
  std::vector<std::array<double, 3>> F(n, {0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < n; ++i) {
    const PointDofs& P = points_[i];
    for (int c = 0; c < 3; ++c) {
      double f = 0.0;
      for (int a = 0; a < 3; ++a) f += g[i][a] * axis(P, a, c);
      std::size_t m = i;
      int mc = c;
      double sign = 1.0;
      const Component* k = &P.c[static_cast<std::size_t>(c)];
      while (k->prescribed < 0 && k->tie_point >= 0) {  // a tied component: to its master
        sign *= k->tie_sign;
        m = static_cast<std::size_t>(k->tie_point);
        mc = k->tie_component;
        k = &points_[m].c[static_cast<std::size_t>(mc)];
      }
      F[m][static_cast<std::size_t>(mc)] += sign * f;
    }
  }
  std::vector<Vector3d> r(n, Vector3d::Zero());
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a)
        r[i][a] += F[i][static_cast<std::size_t>(c)] * axis(points_[i], a, c);
  return r;
}

void DofMap::constrain(int point, int component, Prescribed p) {
  check_point(point, "constrain");
  check_component(component);
  set_prescribed(
      points_[static_cast<std::size_t>(point)].c[static_cast<std::size_t>(component)].prescribed,
      std::move(p));
}

void DofMap::set_prescribed(int& index, Prescribed p) {
  if (index >= 0) {
    prescribed_[static_cast<std::size_t>(index)] = std::move(p);
  } else {
    index = static_cast<int>(prescribed_.size());
    prescribed_.push_back(std::move(p));
  }
  stale_ = true;
}

void DofMap::set_local_basis(int point, const Matrix3d& Q) {
  check_point(point, "set_local_basis");
  PointDofs& P = points_[static_cast<std::size_t>(point)];
  for (const Component& c : P.c)
    if (c.prescribed >= 0 || c.tie_point >= 0 || c.master)
      fail_(owner_ + "::set_local_basis: control point " + std::to_string(point) +
            " already has constrained or tied components; set the basis first");
  if (!((Q.transpose() * Q - Matrix3d::Identity()).norm() <= 1e-10))
    fail_(owner_ + "::set_local_basis: the basis of control point " + std::to_string(point) +
          " is not orthonormal");
  P.Q = Q;
  P.rotated = !Q.isIdentity(0.0);
  stale_ = true;  // reduce_in_place's lookup changes
}

const Matrix3d& DofMap::local_basis(int point) const {
  check_point(point, "local_basis");
  return points_[static_cast<std::size_t>(point)].Q;
}

void DofMap::fix(int point) {
  for (int c = 0; c < 3; ++c) fix(point, c);
}
void DofMap::fix(int point, int component) {
  constrain(point, component, Prescribed{});
}
void DofMap::prescribe(int point, int component, double value, LoadCurve curve) {
  constrain(point, component, Prescribed{value, std::move(curve)});
}

int DofMap::axis_along(int point, const Vector3d& d, double* sign) const {
  check_point(point, "axis_along");
  const PointDofs& P = points_[static_cast<std::size_t>(point)];
  const Vector3d e = d.normalized();
  for (int c = 0; c < 3; ++c) {
    const double cs = P.rotated ? P.Q.col(c).dot(e) : e[c];
    if (std::abs(cs) > 1.0 - 1e-10) {
      if (sign) *sign = cs > 0.0 ? 1.0 : -1.0;
      return c;
    }
  }
  return -1;
}

void DofMap::fix_along(int point, const Vector3d& d) {
  if (!(d.norm() > 0.0)) fail_(owner_ + "::fix_along: the direction must be non-zero");
  const int c = axis_along(point, d);
  if (c >= 0) {
    fix(point, c);
    return;
  }
  const Vector3d e = d.normalized();
  Matrix3d Q;
  Q.col(2) = e;
  Q.col(0) = e.unitOrthogonal();
  Q.col(1) = e.cross(Q.col(0));
  set_local_basis(point, Q);  // fails if the point has constraints in another basis
  fix(point, 2);
}

void DofMap::tie(int slave, int component, int master, int master_component) {
  check_point(slave, "tie");
  check_point(master, "tie");
  check_component(component);
  check_component(master_component);
  const PointDofs& S = points_[static_cast<std::size_t>(slave)];
  const PointDofs& M = points_[static_cast<std::size_t>(master)];
  const Vector3d es = S.rotated ? Vector3d(S.Q.col(component)) : Vector3d::Unit(component);
  const Vector3d em =
      M.rotated ? Vector3d(M.Q.col(master_component)) : Vector3d::Unit(master_component);
  const double cs = es.dot(em);
  if (!(std::abs(cs) > 1.0 - 1e-10))
    fail_(owner_ + "::tie: component " + std::to_string(component) + " of control point " +
          std::to_string(slave) + " is not parallel to component " +
          std::to_string(master_component) + " of control point " + std::to_string(master));
  // Reject cycles: the master's chain must not reach the slave.
  int p = master, c = master_component;
  for (std::size_t steps = 0; p >= 0; ++steps) {
    if ((p == slave && c == component) || steps > 3 * points_.size())
      fail_(owner_ + "::tie: tying control point " + std::to_string(slave) + " to " +
            std::to_string(master) + " would close a cycle of ties");
    const Component& m = points_[static_cast<std::size_t>(p)].c[static_cast<std::size_t>(c)];
    p = m.tie_point;
    c = m.tie_component;
  }
  Component& s = points_[static_cast<std::size_t>(slave)].c[static_cast<std::size_t>(component)];
  s.tie_point = master;
  s.tie_component = master_component;
  s.tie_sign = cs > 0.0 ? 1.0 : -1.0;
  points_[static_cast<std::size_t>(master)].c[static_cast<std::size_t>(master_component)].master =
      true;
  stale_ = true;
}

bool DofMap::constrained(int point, int component) const {
  check_point(point, "constrained");
  check_component(component);
  // Without renumbering (a loop of constrained / fix calls stays O(n)): follow the ties to
  // the component that decides, as renumber() does; constrained iff it has a constraint.
  const Component* m =
      &points_[static_cast<std::size_t>(point)].c[static_cast<std::size_t>(component)];
  while (m->prescribed < 0 && m->tie_point >= 0)
    m = &points_[static_cast<std::size_t>(m->tie_point)]
             .c[static_cast<std::size_t>(m->tie_component)];
  return m->prescribed >= 0;
}

int DofMap::dof(int point, int component) const {
  refresh();
  check_point(point, "dof");
  check_component(component);
  return points_[static_cast<std::size_t>(point)].c[static_cast<std::size_t>(component)].free;
}

void DofMap::fix_scalar(int k) {
  check_scalar(k, "fix_scalar");
  prescribe_scalar(k, 0.0, LoadCurve{});
}

void DofMap::prescribe_scalar(int k, double value, LoadCurve curve) {
  check_scalar(k, "prescribe_scalar");
  set_prescribed(scalars_[static_cast<std::size_t>(k)].prescribed,
                 Prescribed{curve ? value : 0.0, std::move(curve)});
}

bool DofMap::scalar_constrained(int k) const {
  check_scalar(k, "scalar_constrained");
  return scalars_[static_cast<std::size_t>(k)].prescribed >= 0;
}

int DofMap::scalar_dof(int k) const {
  refresh();
  check_scalar(k, "scalar_dof");
  return scalars_[static_cast<std::size_t>(k)].free;
}

void DofMap::current_scalars(const VectorXd& u, double t, std::vector<double>& s) const {
  refresh();
  if (u.size() != num_free_)
    throw std::invalid_argument(owner_ + ": state has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(num_free_));
  s.resize(scalars_.size());
  for (std::size_t k = 0; k < scalars_.size(); ++k) {
    const Component& c = scalars_[k];
    if (c.free >= 0) {
      s[k] = u[c.free];
    } else {
      const Prescribed& pr = prescribed_[static_cast<std::size_t>(c.resolved)];
      s[k] = pr.curve ? pr.value * pr.curve(t) : 0.0;
    }
  }
}

bool DofMap::prescribed_moves(double t0, double t1) const {
  return std::any_of(prescribed_.begin(), prescribed_.end(), [&](const Prescribed& p) {
    return p.curve && p.value * p.curve(t0) != p.value * p.curve(t1);
  });
}

void DofMap::current_points(std::span<const Vector3d> X, const VectorXd& u, double t,
                            std::vector<Vector3d>& x) const {
  refresh();
  if (u.size() != num_free_)
    throw std::invalid_argument(owner_ + ": state has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(num_free_));
  const std::size_t n = points_.size();
  x.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PointDofs& P = points_[i];
    Vector3d d;
    for (int k = 0; k < 3; ++k) {
      const Component& c = P.c[static_cast<std::size_t>(k)];
      if (c.free >= 0) {
        d[k] = c.sign * u[c.free];
      } else {
        const Prescribed& pr = prescribed_[static_cast<std::size_t>(c.resolved)];
        d[k] = pr.curve ? c.sign * pr.value * pr.curve(t) : 0.0;
      }
    }
    x[i] = X[i] + (P.rotated ? Vector3d(P.Q * d) : d);
  }
}

void DofMap::reduce(const VectorXd& g, VectorXd& R) const {
  refresh();
  if (g.size() != num_cartesian())
    throw std::invalid_argument(owner_ + ": residual has " + std::to_string(g.size()) +
                                " entries, expected " + std::to_string(num_cartesian()));
  R.setZero(num_free_);
  const auto n3 = 3 * static_cast<Eigen::Index>(points_.size());
  for (std::size_t k = 0; k < scalars_.size(); ++k)
    if (scalars_[k].free >= 0) R[scalars_[k].free] += g[n3 + static_cast<Eigen::Index>(k)];
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const PointDofs& P = points_[i];
    const Vector3d gi = g.segment<3>(3 * static_cast<Eigen::Index>(i));
    for (int k = 0; k < 3; ++k) {
      const Component& c = P.c[static_cast<std::size_t>(k)];
      if (c.free >= 0) R[c.free] += c.sign * (P.rotated ? P.Q.col(k).dot(gi) : gi[k]);
    }
  }
}

void DofMap::reduce(const std::vector<Triplet>& cart, std::vector<Triplet>& free) const {
  refresh();
  free.reserve(free.size() + cart.size());
  for (const Triplet& tr : cart) reduce_triplet(tr, free);
}

void DofMap::reduce_triplet(const Triplet& tr, std::vector<Triplet>& free) const {
  const int n3 = 3 * num_points();
  if (tr.row() >= n3 || tr.col() >= n3) {  // a scalar's row or column
    reduce_scalar_triplet(tr, free);
    return;
  }
  Triplet plain;
  switch (reduce_plain(tr, plain)) {
    case 1:
      free.push_back(plain);
      return;
    case 0:
      return;
    default:
      break;  // a rotated point
  }
  const int i = tr.row() / 3, a = tr.row() % 3, j = tr.col() / 3, b = tr.col() % 3;
  const PointDofs& Pi = points_[static_cast<std::size_t>(i)];
  const PointDofs& Pj = points_[static_cast<std::size_t>(j)];
  for (int ki = 0; ki < 3; ++ki) {
    const Component& ci = Pi.c[static_cast<std::size_t>(ki)];
    if (ci.free < 0) continue;
    const double qi = ci.sign * axis(Pi, a, ki);
    if (qi == 0.0) continue;
    for (int kj = 0; kj < 3; ++kj) {
      const Component& cj = Pj.c[static_cast<std::size_t>(kj)];
      if (cj.free < 0) continue;
      const double qj = cj.sign * axis(Pj, b, kj);
      if (qj != 0.0) free.emplace_back(ci.free, cj.free, qi * tr.value() * qj);
    }
  }
}

int DofMap::reduce_plain(const Triplet& tr, Triplet& out) const {
  const int n3 = 3 * num_points();
  if (tr.row() >= n3 || tr.col() >= n3) return -1;  // a scalar's row or column
  const PointDofs& Pi = points_[static_cast<std::size_t>(tr.row() / 3)];
  const PointDofs& Pj = points_[static_cast<std::size_t>(tr.col() / 3)];
  if (Pi.rotated || Pj.rotated) return -1;
  const Component& ci = Pi.c[static_cast<std::size_t>(tr.row() % 3)];
  const Component& cj = Pj.c[static_cast<std::size_t>(tr.col() % 3)];
  if (ci.free < 0 || cj.free < 0) return 0;
  out = Triplet(ci.free, cj.free, ci.sign * cj.sign * tr.value());
  return 1;
}

void DofMap::reduce_in_place(std::vector<Triplet>& t) const {
  refresh();
  std::vector<Triplet> spread;  // of rotated points and scalars
  std::size_t w = 0;
  const std::size_t n3 = plain_free_.size();
  for (std::size_t r = 0; r < t.size(); ++r) {
    const Triplet tr = t[r];
    // reduce_plain by lookup (a negative index is large as a size_t: not a point's)
    const auto i = static_cast<std::size_t>(tr.row()), j = static_cast<std::size_t>(tr.col());
    if (i < n3 && j < n3) {
      const int fi = plain_free_[i], fj = plain_free_[j];
      if (fi >= 0 && fj >= 0) {  // w <= r: t[r] has been read
        t[w++] = Triplet(fi, fj, plain_sign_[i] * plain_sign_[j] * tr.value());
        continue;
      }
      if (fi != -2 && fj != -2) continue;  // a side constrained, no local axes: no image
    }
    reduce_triplet(tr, spread);
  }
  t.resize(w);
  t.insert(t.end(), spread.begin(), spread.end());
}

void DofMap::reduce_scalar_triplet(const Triplet& tr, std::vector<Triplet>& free) const {
  // One side at least is a scalar (a unit column of P); the other may be a point's component,
  // spread over its local axes as in reduce(). Each side as (free DOF, weight) pairs.
  const int n3 = 3 * num_points();
  std::array<std::pair<int, double>, 3> rows{}, cols{};
  const auto side = [&](int cart_index, std::array<std::pair<int, double>, 3>& out) {
    int count = 0;
    if (cart_index >= n3) {
      const Component& c = scalars_.at(static_cast<std::size_t>(cart_index - n3));
      if (c.free >= 0) out[count++] = {c.free, 1.0};
      return count;
    }
    const PointDofs& P = points_[static_cast<std::size_t>(cart_index / 3)];
    const int a = cart_index % 3;
    for (int k = 0; k < 3; ++k) {
      const Component& c = P.c[static_cast<std::size_t>(k)];
      const double q = c.free >= 0 ? c.sign * axis(P, a, k) : 0.0;
      if (q != 0.0) out[count++] = {c.free, q};
    }
    return count;
  };
  const int nr = side(tr.row(), rows), nc = side(tr.col(), cols);
  for (int r = 0; r < nr; ++r)
    for (int c = 0; c < nc; ++c)
      free.emplace_back(rows[static_cast<std::size_t>(r)].first,
                        cols[static_cast<std::size_t>(c)].first,
                        rows[static_cast<std::size_t>(r)].second * tr.value() *
                            cols[static_cast<std::size_t>(c)].second);
}

}  // namespace iga
