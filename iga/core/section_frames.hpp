// The sections of a rod that turn about its centre line (a rod with torsion): what a contact
// integral needs to roll the rod's surface on a tool ([KS15] (52): the contact point sits on the
// surface, at -R n from the centre line). The body implements it and hands it to its contact
// pairs with its state at every assembly (BodyState, contact_pair.hpp), so that a pair keeps
// no pointer to its body.
//
// Notation (symbol -> code):
//   xi                  curve parameter                                           xi
//   x_i, s_k            the body's control points and scalar unknowns (twists)   x, s
//   (t, d1)             the section's frame at xi: unit tangent and first director  t, d1
//   (t_c, d1_c)         a frame at an earlier state (the last commit)             t_c, d1_c
//   dphi                the section's rotation about t since it had (t_c, d1_c)    value
//   q                   the DOFs that dphi depends on (a few, of one element)      dofs
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "geometry/derivatives.hpp"

namespace iga {

/// The spin dphi of a section since an earlier frame, with its derivatives.
struct SectionSpin {
  double value = 0.0;        ///< dphi, in (-pi, pi]
  std::vector<int> dofs;     ///< Cartesian DOF of each local entry (3 i + c, 3 n + k)
  int positions = 0;         ///< the first `positions` entries are points' (triples)
  Eigen::VectorXd gradient;  ///< d dphi / dq
  Eigen::MatrixXd hessian;   ///< d2 dphi / dq2
  Vector3d t = Vector3d::Zero(), d1 = Vector3d::Zero();  ///< the frame now
};

class SectionFrames {
 public:
  virtual ~SectionFrames() = default;
  /// The section's frame (t, d1) at xi in the state (x, s).
  virtual void frame(double xi, std::span<const Vector3d> x, std::span<const double> s, Vector3d& t,
                     Vector3d& d1) const = 0;
  /// The rotation of the section at xi about its tangent since it had the frame (t_c, d1_c):
  /// the angle from the smallest rotation of d1_c onto the current tangent to d1, with its
  /// derivatives in the DOFs it depends on (without `derivatives`: the value, the frame and the
  /// DOFs only; gradient and hessian empty).
  virtual SectionSpin spin_since(double xi, const Vector3d& t_c, const Vector3d& d1_c,
                                 std::span<const Vector3d> x, std::span<const double> s,
                                 bool derivatives) const = 0;

 protected:
  SectionFrames() = default;
  SectionFrames(const SectionFrames&) = default;
  SectionFrames& operator=(const SectionFrames&) = default;
  SectionFrames(SectionFrames&&) = default;
  SectionFrames& operator=(SectionFrames&&) = default;
};

}  // namespace iga
