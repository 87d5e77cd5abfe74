// A contact pair on a moving tool, as the tests of the contact integrals take it: the skew rigid
// motion G they use (a turn by 0.9 about the axis (1, 2, 2) through (1, -1, 2), then a shift by
// (0.3, 2, -1), held from t = 0) and a pair evaluated at t = 1 as test::tangent_error's Contact.
#pragma once

#include <memory>
#include <vector>

#include "contact/rigid_motion.hpp"
#include "iga/core/contact_pair.hpp"

namespace iga::test {

inline std::shared_ptr<RigidMotion> skew_motion() {
  auto motion = std::make_shared<RigidMotion>();
  motion->set_rotation(Vector3d(1, -1, 2), Vector3d(1, 2, 2), 0.9, [](double) { return 1.0; });
  motion->set_translation(Vector3d(0.3, 2.0, -1.0), [](double) { return 1.0; });
  return motion;
}

/// The pair's add() at t = 1 as assemble(x, R, K).
struct PairAtTime {
  ContactPair& pair;
  void assemble(const std::vector<Vector3d>& x, Eigen::VectorXd& R,
                std::vector<Eigen::Triplet<double>>* K) {
    pair.add(BodyState{x, {}, nullptr}, 1.0, R, K);
  }
};

}  // namespace iga::test
