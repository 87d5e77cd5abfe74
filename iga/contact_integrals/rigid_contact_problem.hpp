// A body with one contact pair attached, as one object (RodContactProblem: CTRS,
// ShellContactProblem: STAS; [KS15]): what tests, benchmarks and the example programs use when
// they build a rod or shell in contact by hand. The pair does the work (rigid_contact_pair.hpp):
// the body's residual, tangent, history, status, symmetry and reactions include it through
// Body::attach.
#pragma once

#include <memory>
#include <utility>

#include "iga/contact_integrals/rigid_contact_pair.hpp"

namespace iga {

/// Base: a ControlPointProblem (RodProblem, ShellProblem) constructible from its body model.
/// Pair: its ContactPair (CurveContactPair, SurfaceContactPair).
template <class Base, class Pair>
class RigidContactProblem : public Base {
 public:
  const Pair& contact_pair() const { return static_cast<const Pair&>(this->pair(index_)); }
  Pair& contact_pair() { return static_cast<Pair&>(this->pair(index_)); }
  /// The contact integral (CurveContact, SurfaceContact).
  const auto& contact() const { return contact_pair().contact(); }
  auto& contact() { return contact_pair().contact(); }
  const RigidSurface& rigid() const { return contact_pair().rigid(); }
  /// Wall time spent in the contact integral (projections, point law, its assembly) since
  /// construction, seconds; part of the solver's assembly time.
  double contact_time() const { return contact_pair().time(); }

 protected:
  /// make(base) builds the pair once the base problem exists.
  template <class Model, class Make>
  RigidContactProblem(Model model, Make make) : Base(std::move(model)) {
    index_ = this->attach(make(static_cast<const Base&>(*this)));
  }

 private:
  int index_ = 0;
};

}  // namespace iga
