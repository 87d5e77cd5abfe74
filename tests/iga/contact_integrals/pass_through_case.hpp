// What the tests of passed_through (iga/contact_integrals/pass_through.hpp) share for both
// integrals: a slab 0.5 thick (top z = 0, bottom z = -0.5: two bounded 4 x 4 squares with
// outward normals), and a probe that assembles the contact with the body's reference control
// points shifted by dz (after the caller committed the reference state) and returns the check.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "contact/rigid_surface.hpp"
#include "geometry/constructions.hpp"
#include "iga/core/nonlinear_problem.hpp"

namespace iga::test {

inline RigidSurface slab() {
  RigidSurface s;
  s.add(make_plane_patch(Vector3d(-2, -2, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)));
  s.add(make_plane_patch(Vector3d(-2, -2, -0.5), Vector3d(0, 4, 0), Vector3d(4, 0, 0)));
  return s;
}

/// contact: CurveContact or SurfaceContact; ref: its reference curve or surface.
template <class Contact, class Reference>
AugmentResult moved_by(Contact& contact, const Reference& ref, double dz) {
  std::vector<Vector3d> x = ref.control_points();
  for (Vector3d& q : x) q.z() += dz;
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(x.size()));
  contact.assemble(x, R, nullptr);
  return contact.passed_through();
}

}  // namespace iga::test
