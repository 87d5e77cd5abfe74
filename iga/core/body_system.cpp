// Several bodies as one problem; see body_system.hpp.
#include "iga/core/body_system.hpp"

#include <algorithm>
#include <string>

#include "iga/core/state_archive.hpp"

namespace iga {

void BodySystem::add(Body& body) {
  bodies_.push_back(&body);
  offsets_.push_back(offsets_.back() + body.num_dofs());
}

VectorXd BodySystem::block(const VectorXd& u, int b) const {
  return u.segment(offset(b), offset(b + 1) - offset(b));
}

void BodySystem::assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) {
  if (bodies_.size() == 1) {  // the block is the whole: no copies
    bodies_[0]->assemble(u, t, R, K);
    return;
  }
  const int n = num_dofs();
  R.resize(n);
  if (K) triplets_.clear();
  for (int b = 0; b < num_bodies(); ++b) {
    const int o = offset(b), nb = offset(b + 1) - o;
    bodies_[static_cast<std::size_t>(b)]->assemble(u.segment(o, nb), t, Rb_, K ? &Kb_ : nullptr);
    R.segment(o, nb) = Rb_;
    if (!K) continue;
    for (int j = 0; j < Kb_.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Kb_, j); it; ++it)
        triplets_.emplace_back(o + static_cast<int>(it.row()), o + static_cast<int>(it.col()),
                               it.value());
  }
  if (!K) return;
  assembler_.assemble(triplets_, n, n, *K);  // the pattern kept while the bodies' are
}

bool BodySystem::symmetric() const {
  return std::all_of(bodies_.begin(), bodies_.end(), [](const Body* b) { return b->symmetric(); });
}

void BodySystem::commit(const VectorXd& u, double t) {
  for (int b = 0; b < num_bodies(); ++b)
    bodies_[static_cast<std::size_t>(b)]->commit(block(u, b), t);
}

AugmentResult BodySystem::augment(const VectorXd& u, double t) {
  AugmentResult r;
  for (int b = 0; b < num_bodies(); ++b)
    merge_augment(r, bodies_[static_cast<std::size_t>(b)]->augment(block(u, b), t));
  return r;
}

void BodySystem::restore() {
  for (Body* b : bodies_) b->restore();
}

void BodySystem::archive(StateArchive& a) {
  int n = num_bodies();
  a.section("bodies");
  a.io(n);
  if (a.loading() && n != num_bodies())
    a.fail("the file has " + std::to_string(n) + " bodies, the model " +
           std::to_string(num_bodies()));
  for (int b = 0; b < num_bodies(); ++b) {
    a.section("body " + std::to_string(b));
    int dofs = body(b).num_dofs();
    a.io(dofs);
    if (a.loading() && dofs != body(b).num_dofs())
      a.fail("the file's body has " + std::to_string(dofs) + " unknowns, the model's " +
             std::to_string(body(b).num_dofs()));
    body(b).archive(a);
  }
}

double BodySystem::residual_roundoff() const {
  double r = 0.0;
  for (const Body* b : bodies_) r = std::max(r, b->residual_roundoff());
  return r;
}

std::string BodySystem::status() const {
  std::string s;
  for (const Body* b : bodies_) {
    const std::string sb = b->status();
    if (!sb.empty()) s += (s.empty() ? "" : "; ") + sb;
  }
  return s;
}

}  // namespace iga
