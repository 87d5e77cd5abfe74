// The CTRS pair of a rod with a rigid surface; see curve_contact_pair.hpp.
#include "iga/contact_integrals/curve_contact_pair.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace iga {

namespace {

CurveContact make_contact(const NurbsCurve& reference, const RigidSurface* rigid,
                          const CurveContactParameters& params) {
  if (rigid == nullptr) throw std::invalid_argument("CurveContactPair: the rigid surface is null");
  return CurveContact(reference, *rigid, params);
}

}  // namespace

CurveContactPair::CurveContactPair(const NurbsCurve& reference,
                                   const std::shared_ptr<const RigidSurface>& rigid,
                                   const CurveContactParameters& params)
    : RigidContactPair(rigid, make_contact(reference, rigid.get(), params)) {
  const std::vector<double> br = reference.knots().breaks();
  for (std::size_t k = 0; k + 1 < br.size(); ++k) elements_.push_back({br[k], br[k + 1]});
}

std::unique_ptr<ContactPair> CurveContactPair::clone() const {
  return std::make_unique<CurveContactPair>(*this);
}

bool CurveContactPair::symmetric() const {
  return !contact().parameters().law.friction();
}

ContactCounts CurveContactPair::local_counts() const {
  const CurveContactCounts c = contact().counts();
  return {c.active, c.stick, c.slip};
}

bool CurveContactPair::local_sliding_steadily() const {
  const CurveContactCounts c = contact().counts();
  return steady_sliding(c.active, c.slip, std::min(c.slip_positive, c.slip_negative),
                        c.drag_ratio(), mu());
}

std::string CurveContactPair::describe() const {
  return "CTRS contact with a rigid surface of " + std::to_string(rigid().num_patches()) +
         " piece(s), " + std::to_string(contact().points().size()) + " contact points";
}

void CurveContactPair::add_tool_fields(SampledMesh& body) const {
  struct Fields {
    double pressure = 0.0, T = 0.0, B = 0.0, state = 0.0, torque = 0.0;
  };
  // The weighted means per element.
  std::vector<Fields> per(elements_.size());
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Interval& I = elements_[e];
    Fields& f = per[e];
    double w = 0.0;
    for (const CurveContactPoint& cp : contact().points()) {
      if (cp.eta < I.lo || cp.eta > I.hi) continue;
      w += cp.weight;
      if (!cp.law.active) continue;
      f.pressure += cp.weight * -cp.N;
      f.T += cp.weight * cp.T;
      f.B += cp.weight * cp.B;
      f.torque += cp.weight * cp.torque;
      f.state = std::max(f.state, cp.law.slip ? 2.0 : 1.0);
    }
    if (w > 0.0) {
      f.pressure /= w;
      f.T /= w;
      f.B /= w;
      f.torque /= w;
    }
  }
  // A rod with torsion: also the friction torque about the centre line per length.
  const bool twist = contact().rolling();
  PointFields c;
  if (twist)
    c.name({"contact_pressure", "contact_traction_T", "contact_traction_B", "contact_state",
            "contact_torque"},
           {});
  else
    c.name({"contact_pressure", "contact_traction_T", "contact_traction_B", "contact_state"}, {});
  for (int e : body.elements) {
    const Fields f = e >= 0 && static_cast<std::size_t>(e) < per.size()
                         ? per[static_cast<std::size_t>(e)]
                         : Fields{};
    if (twist)
      c.append({f.pressure, f.T, f.B, f.state, f.torque}, {});
    else
      c.append({f.pressure, f.T, f.B, f.state}, {});
  }
  body.fields.add(std::move(c));
}

SampledMesh CurveContactPair::tool_points() const {
  SampledMesh m;
  const bool twist = contact().rolling();  // then also the friction torque
  if (twist)
    m.fields.name({"N", "T", "B", "slip", "torque"}, {"normal"});
  else
    m.fields.name({"N", "T", "B", "slip"}, {"normal"});
  for (const CurveContactPoint& cp : contact().points()) {
    if (!cp.law.active) continue;
    m.points.push_back(cp.x);
    if (twist)
      m.fields.append({cp.N, cp.T, cp.B, cp.law.slip ? 1.0 : 0.0, cp.torque}, {cp.law.normal});
    else
      m.fields.append({cp.N, cp.T, cp.B, cp.law.slip ? 1.0 : 0.0}, {cp.law.normal});
  }
  return m;
}

std::vector<ContactFoot> CurveContactPair::tool_feet() const {
  std::vector<ContactFoot> f;
  for (const CurveContactPoint& cp : contact().points()) {
    if (!cp.law.active) continue;
    // On the tool the traction is opposite to the rope's; the footprint is 1.5 times the
    // point's length share of the rope.
    f.push_back({cp.law.foot, -cp.N, cp.law.slip ? 2.0 : 1.0, 1.5 * cp.weight, -cp.law.T_vector});
  }
  return f;
}

}  // namespace iga
