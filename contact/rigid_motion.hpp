// Prescribed rigid-body motion of a rigid tool (issue 14, item 3): the tool's points X (its
// geometry as given in the model, the tool's own frame) are at
//   x(t) = c(t) + Q(t) (X - c0)
// at pseudo-time t: first a rotation about the axis through the point c0 by the angle
// theta(t) = angle * f_rot(t) (right-handed about `axis`), then a translation by
// d(t) = vector * f_trans(t), so c(t) = c0 + d(t). Contact with a moving tool is computed in
// the tool's own frame: the body's points are mapped back by the inverse motion
// X = c0 + Q^T (x - c), every projection, closed form and search structure of the tool works
// unchanged there, and forces, tangents and output are turned forward by Q.
//
// Notation: Q the rotation (Rodrigues), c0 the rotation's point, c the point's current position.
#pragma once

#include <functional>

#include <Eigen/Core>

namespace iga {

/// The tool's placement at one time: x = c + Q (X - c0).
struct RigidPose {
  Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), c0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d to_world(const Eigen::Vector3d& X) const { return c + Q * (X - c0); }
  Eigen::Vector3d to_tool(const Eigen::Vector3d& x) const { return c0 + Q.transpose() * (x - c); }
  /// Q is the identity (a translation or no motion): vectors need no turning.
  bool turns() const { return !Q.isIdentity(0.0); }
};

class RigidMotion {
 public:
  using Curve = std::function<double(double)>;
  /// No motion.
  RigidMotion() = default;
  /// Rotation by angle * curve(t) (radians) about `axis` (non-zero) through `point`.
  void set_rotation(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double angle,
                    Curve curve);
  /// Translation by vector * curve(t) (after the rotation).
  void set_translation(const Eigen::Vector3d& vector, Curve curve);
  /// The pose at t.
  RigidPose pose(double t) const;
  bool rotates() const { return static_cast<bool>(rot_curve_); }
  const Eigen::Vector3d& point() const { return point_; }
  const Eigen::Vector3d& axis() const { return axis_; }
  /// The rotation angle at t (0 without rotation).
  double angle(double t) const { return rot_curve_ ? angle_ * rot_curve_(t) : 0.0; }

 private:
  Eigen::Vector3d point_ = Eigen::Vector3d::Zero(), axis_ = Eigen::Vector3d::UnitZ();
  double angle_ = 0.0;
  Curve rot_curve_;
  Eigen::Vector3d vector_ = Eigen::Vector3d::Zero();
  Curve trans_curve_;
};

}  // namespace iga
