// Prescribed rigid-body motion of a rigid tool; see rigid_motion.hpp.
#include "contact/rigid_motion.hpp"

#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>

namespace iga {

void RigidMotion::set_rotation(const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                               double angle, Curve curve) {
  if (!(axis.norm() > 0.0) || !axis.allFinite())
    throw std::invalid_argument("RigidMotion: the rotation axis must be a non-zero vector");
  point_ = point;
  axis_ = axis.normalized();
  angle_ = angle;
  rot_curve_ = std::move(curve);
}

void RigidMotion::set_translation(const Eigen::Vector3d& vector, Curve curve) {
  vector_ = vector;
  trans_curve_ = std::move(curve);
}

RigidPose RigidMotion::pose(double t) const {
  RigidPose p;
  p.c0 = point_;
  p.c = point_;
  if (rot_curve_) p.Q = Eigen::AngleAxisd(angle(t), axis_).toRotationMatrix();  // Rodrigues
  if (trans_curve_) p.c += vector_ * trans_curve_(t);
  return p;
}

}  // namespace iga
