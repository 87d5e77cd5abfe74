// A shell against a rigid surface: the STAS contact integral of [KS15] Sects. 2-3
// (iga/contact_integrals/surface_contact.hpp) as a ContactPair of the shell (ShellProblem::attach).
//
// Notation: N the normal force per reference area (34), T_vector the tangential force on the
// shell, gap the signed distance xi3 of a contact point; (u, v) the shell's parameters.
#pragma once

#include <memory>

#include "geometry/nurbs_surface.hpp"
#include "iga/contact_integrals/rigid_contact_pair.hpp"
#include "iga/contact_integrals/surface_contact.hpp"

namespace iga {

class SurfaceContactPair final : public RigidContactPair<SurfaceContact> {
 public:
  /// The pair of the surface `reference` (the shell's mid-surface; params.thickness must be the
  /// shell's) with `rigid` (not null: std::invalid_argument), its contact points in the
  /// elements of `block` (SurfaceContact).
  SurfaceContactPair(const NurbsSurface& reference,
                     const std::shared_ptr<const RigidSurface>& rigid,
                     const SurfaceContactParameters& params, const ElementBlock& block = {});

  std::unique_ptr<ContactPair> clone() const override;
  /// Friction (mu > 0 and eps_T > 0) makes the tangent non-symmetric ((38)-(39)); so does the
  /// rigid-slave strategy (the ray direction depends on the shell's control points, (5)).
  bool symmetric() const override;
  /// "STAS contact (rigid master, mu = 0.2) with a rigid surface of 1 piece(s), 256 contact
  /// points" (those of the whole patch; "..., 256 contact points (128 here)" for a process's
  /// part of a cut shell).
  std::string describe() const override;
  /// contact_pressure, contact_gap, contact_state, contact_undefined (1 where the gap is unknown,
  /// no point near has a foot, or a value is not finite; such values are written as 0) and
  /// contact_traction at the samples' parameters: the element's contact points interpolated
  /// (surface_contact_pair.cpp, ShellContactField).
  void add_tool_fields(SampledMesh& body) const override;
  /// Active points with N, gap, slip (0/1), the shell normal and the tangential force.
  SampledMesh tool_points() const override;
  std::vector<ContactFoot> tool_feet() const override;

 protected:
  ContactCounts local_counts() const override;

 private:
  std::vector<double> breaks_u_, breaks_v_;  ///< the shell's element borders
};

}  // namespace iga
