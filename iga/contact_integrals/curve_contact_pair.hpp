// A rod against a rigid surface: the CTRS contact integral of [KS15] Sects. 4-5
// (iga/contact_integrals/curve_contact.hpp) as a ContactPair of the rod (RodProblem::attach).
//
// Notation: N, T, B the contact point's normal force, pulling and dragging tractions (68)-(70)
// -> CurveContactPoint::N, T, B; eta the point's parameter on the rope.
#pragma once

#include <memory>

#include "iga/contact_integrals/curve_contact.hpp"
#include "iga/contact_integrals/rigid_contact_pair.hpp"

namespace iga {

class CurveContactPair final : public RigidContactPair<CurveContact> {
 public:
  /// The pair of the curve `reference` (the rod's centre line) with `rigid` (not null:
  /// std::invalid_argument); the parameters as CurveContact takes them.
  CurveContactPair(const NurbsCurve& reference, const std::shared_ptr<const RigidSurface>& rigid,
                   const CurveContactParameters& params);

  std::unique_ptr<ContactPair> clone() const override;
  /// Friction (mu > 0 and eps_T > 0) makes the tangent non-symmetric ((38)-(39)).
  bool symmetric() const override;
  /// "CTRS contact with a rigid surface of 1 piece(s), 80 contact points".
  std::string describe() const override;
  /// Per rod element, at the samples in it: contact_pressure -N (force per reference length),
  /// contact_traction_T, contact_traction_B (69), (70), each the mean of the element's contact
  /// points weighted as in the contact integral (what the penalty resolves: point by point the
  /// values oscillate about it within an element), and contact_state 0 apart, 1 stick, 2 slip
  /// (2 if any point of the element slides, 1 if one sticks).
  void add_tool_fields(SampledMesh& body) const override;
  /// Active points with N, T, B, slip (0/1) and the surface normal.
  SampledMesh tool_points() const override;
  std::vector<ContactFoot> tool_feet() const override;

 protected:
  ContactCounts local_counts() const override;
  /// The rope's rule (steady_sliding): every active point slips, all pulling one way, and the
  /// friction lies along the rope.
  bool local_sliding_steadily() const override;

 private:
  std::vector<Interval> elements_;  ///< the rod's element ranges
};

}  // namespace iga
