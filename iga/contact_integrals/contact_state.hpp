// The state of contact points for a restart (iga/core/state_archive.hpp): every field of the
// points' history, multipliers, last foot (the warm start of the next search) and law state, so
// that a restarted run repeats the uninterrupted one.
#pragma once

#include "contact/contact_law.hpp"
#include "contact/projection.hpp"
#include "iga/contact_integrals/contact_augmentation.hpp"
#include "iga/core/state_archive.hpp"

namespace iga {

inline void archive(StateArchive& a, ProjectionResult& r) {
  a.io(r.uv);
  a.io(r.point);
  a.io(r.normal);
  a.io(r.distance);
  int status = static_cast<int>(r.status);
  a.io(status);
  if (a.loading() && (status < 0 || status > static_cast<int>(ProjectionStatus::far)))
    a.fail("a projection status out of range: " + std::to_string(status));
  r.status = static_cast<ProjectionStatus>(status);
  a.io(r.iterations);
  a.io(r.patch);
  a.io(r.residual);
  a.io(r.certified);
}

inline void archive(StateArchive& a, ContactHistory& h) {
  a.io(h.active);
  a.io(h.patch);
  a.io(h.xi);
  a.io(h.foot);
  a.io(h.T);
  a.io(h.T_vector);
}

inline void archive(StateArchive& a, ContactPoint& p) {
  a.io(p.active);
  a.io(p.slip);
  a.io(p.gap);
  a.io(p.N);
  a.io(p.phi);
  a.io(p.slip_distance);
  a.io(p.T);
  a.io(p.T_vector);
  a.io(p.xi);
  a.io(p.foot);
  a.io(p.normal);
  a.io(p.force);
  a.io(p.stiffness);
  a.io(p.stiffness_roll);
  a.io(p.stiffness_tangential);
}

inline void archive(StateArchive& a, ContactMultipliers& m) {
  a.io(m.lambda_n);
  a.io(m.lambda_n_committed);
  a.io(m.lambda_n_before);
  a.io(m.lambda_t);
}

inline void archive(StateArchive& a, NormalAugmentation& n) {
  a.io(n.step_updates);
  a.io(n.total_updates);
  a.io(n.max_gap);
  a.io(n.t_last);
  a.io(n.t_committed);
  a.io(n.t_before);
  a.io(n.commits);
  a.io(n.eps_scale);
  a.io(n.previous_gap);
  a.io(n.max_slip);
  a.io(n.previous_slip);
  a.io(n.eps_t_scale);
  a.io(n.tangential);
}

/// The fields both integrals' points have (CurveContactPoint, SurfaceContactPoint): the
/// multipliers, the current position and foot, the history and the position at the commit.
template <class Point>
void archive_common(StateArchive& a, Point& p) {
  archive(a, static_cast<ContactMultipliers&>(p));
  a.io(p.x);
  archive(a, p.foot);
  archive(a, p.history);
  a.io(p.x_committed);
}

}  // namespace iga
