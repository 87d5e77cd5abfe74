// Several bodies as one problem; see body_system.hpp.
#include "iga/core/body_system.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>
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

void BodySystem::distribute(const Communicator& comm, std::vector<int> owner) {
  if (owner.size() != bodies_.size())
    throw std::invalid_argument("BodySystem::distribute: " + std::to_string(owner.size()) +
                                " owners for " + std::to_string(bodies_.size()) + " bodies");
  for (std::size_t b = 0; b < owner.size(); ++b)
    if (owner[b] < -1 || owner[b] >= comm.size())
      throw std::invalid_argument("BodySystem::distribute: body " + std::to_string(b) +
                                  " owned by process " + std::to_string(owner[b]) + " of " +
                                  std::to_string(comm.size()));
  std::vector<int> dof_owner(static_cast<std::size_t>(num_dofs()), 0), reads;
  partition(comm, owner, dof_owner, reads);
  comm_ = &comm;
  owner_ = std::move(owner);
  layout_ = DofLayout(comm, std::move(dof_owner), reads);
}

void BodySystem::partition(const Communicator& comm, const std::vector<int>& owner,
                           std::vector<int>& dof_owner, std::vector<int>& reads) {
  const int r = comm.rank();
  for (std::size_t b = 0; b < owner.size(); ++b) {
    const bool cut = owner[b] < 0;
    bodies_[b]->set_share({cut || owner[b] == r, cut ? r == 0 : owner[b] == r});
    const int o = offsets_[b], nb = offsets_[b + 1] - o;
    if (!cut) {  // its unknowns the process's
      std::fill(dof_owner.begin() + o, dof_owner.begin() + o + nb, owner[b]);
      if (owner[b] == r)
        for (int k = 0; k < nb; ++k) reads.push_back(o + k);
      continue;
    }
    for (int k = 0; k < bodies_[b]->num_pairs(); ++k)  // a part of each pair on every process
      bodies_[b]->pair(k).spread(comm);
    std::vector<int> ob, rb;
    bodies_[b]->partition(r, comm.size(), ob, rb);
    if (ob.size() != static_cast<std::size_t>(nb))
      throw std::logic_error("BodySystem::distribute: body " + std::to_string(b) + " gave " +
                             std::to_string(ob.size()) + " owners for " + std::to_string(nb) +
                             " unknowns");
    std::copy(ob.begin(), ob.end(), dof_owner.begin() + o);
    for (const int k : rb) reads.push_back(o + k);
  }
}

void BodySystem::assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) {
  // One body: its residual and tangent (on several processes, its share) are the system's,
  // without copies (the tangent's copies were most of a process's memory at its peak).
  const bool whole = bodies_.size() == 1;
  const int n = num_dofs();
  // Over several processes a failure of one process's share is every process's: each takes
  // part in the reductions whatever happened, then all throw the first process's error (a
  // process that left alone would leave the others waiting).
  std::string error;
  try {
    if (whole) {
      bodies_[0]->assemble(u, t, R, K);
    } else {
      R.setZero(n);
      if (K) triplets_.clear();
      for (int b = 0; b < num_bodies(); ++b) {
        const int o = offset(b), nb = offset(b + 1) - o;
        bodies_[static_cast<std::size_t>(b)]->assemble(u.segment(o, nb), t, Rb_,
                                                       K ? &Kb_ : nullptr);
        R.segment(o, nb) = Rb_;
        if (!K) continue;
        for (int j = 0; j < Kb_.outerSize(); ++j)
          for (SparseMatrix::InnerIterator it(Kb_, j); it; ++it)
            triplets_.emplace_back(o + static_cast<int>(it.row()), o + static_cast<int>(it.col()),
                                   it.value());
      }
    }
  } catch (const std::exception& e) {
    if (!distributed()) throw;
    error = e.what();
    if (R.size() != n) R.setZero(n);  // the reductions below need every process's n entries
  }
  if (distributed()) {
    layout_.add_to_owners(R);
    if (combine_tallies(!error.empty())) throw std::runtime_error(comm_->first_message(error));
  }
  if (!K || whole) return;
  assembler_.assemble(triplets_, n, n, *K);  // the pattern kept while the bodies' are
}

bool BodySystem::load_rate(const VectorXd& u, double t, double h, VectorXd& R_t) {
  R_t.setZero(num_dofs());
  bool can = true;
  VectorXd Rb;
  try {
    for (int b = 0; b < num_bodies() && can; ++b) {
      const int o = offset(b), nb = offset(b + 1) - o;
      can = bodies_[static_cast<std::size_t>(b)]->load_rate(u.segment(o, nb), t, h, Rb);
      if (can) R_t.segment(o, nb) = Rb;
    }
  } catch (const std::exception&) {
    if (!distributed()) throw;
    can = false;  // the assembly that follows meets the error on every process alike
  }
  if (!distributed()) return can;
  // Every process takes the same path: the rates' sum, or an assembly everywhere.
  std::array<double, 1> cannot{can ? 0.0 : 1.0};
  comm_->max(cannot);
  if (cannot[0] != 0.0) return false;
  layout_.add_to_owners(R_t);
  return true;
}

std::vector<ContactPair*> BodySystem::all_pairs() const {
  std::vector<ContactPair*> pairs;
  for (Body* b : bodies_)
    for (int k = 0; k < b->num_pairs(); ++k) pairs.push_back(&b->pair(k));
  return pairs;
}

bool BodySystem::combine_tallies(bool failed) {
  // Per pair: the sums (active, stick, slip, force, moment, round-off) and the maxima (|gap|,
  // 1 where a part with contact does not slide steadily), each in one reduction; the last
  // maximum is 1 where a process failed.
  constexpr int kSums = 10, kMaxima = 2;
  const std::vector<ContactPair*> pairs = all_pairs();
  std::vector<double> sums(kSums * pairs.size()), maxima(kMaxima * pairs.size() + 1);
  maxima.back() = failed ? 1.0 : 0.0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const ContactTally c = pairs[k]->local_tally();
    double* s = sums.data() + kSums * k;
    s[0] = c.counts.active;
    s[1] = c.counts.stick;
    s[2] = c.counts.slip;
    for (int i = 0; i < 3; ++i) {
      s[3 + i] = c.force[i];
      s[6 + i] = c.moment[i];
    }
    s[9] = c.roundoff;
    maxima[kMaxima * k] = c.max_gap;
    maxima[kMaxima * k + 1] = c.steady ? 0.0 : 1.0;
  }
  if (!sums.empty()) comm_->sum(sums);
  comm_->max(maxima);
  if (maxima.back() != 0.0) return true;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double* s = sums.data() + kSums * k;
    ContactTally c;
    c.counts = {static_cast<int>(s[0]), static_cast<int>(s[1]), static_cast<int>(s[2])};
    c.force = Vector3d(s[3], s[4], s[5]);
    c.moment = Vector3d(s[6], s[7], s[8]);
    c.roundoff = s[9];
    c.max_gap = maxima[kMaxima * k];
    c.steady = maxima[kMaxima * k + 1] == 0.0;
    pairs[k]->set_total(c);
  }
  return false;
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
  if (!distributed()) return r;
  // The worst status over the processes, with the message of the first process that has it;
  // and each pair's largest gap of this check over its parts (the status line's, which the
  // assembly's tallies had before the check).
  const std::vector<ContactPair*> pairs = all_pairs();
  std::vector<double> maxima{static_cast<double>(augment_severity(r.status))};
  for (const ContactPair* p : pairs) maxima.push_back(p->local_tally().max_gap);
  comm_->max(maxima);
  for (std::size_t k = 0; k < pairs.size(); ++k) pairs[k]->set_total_gap(maxima[k + 1]);
  const double worst = maxima.front();
  const bool mine = static_cast<double>(augment_severity(r.status)) == worst;
  AugmentResult whole;
  for (AugmentStatus s : {AugmentStatus::satisfied, AugmentStatus::updated, AugmentStatus::failed,
                          AugmentStatus::passed_through})
    if (static_cast<double>(augment_severity(s)) == worst) whole.status = s;
  whole.message = comm_->first_message(mine ? r.message : std::string());
  return whole;
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

Eigen::MatrixXd BodySystem::near_null_space(const VectorXd& u, double t) const {
  std::vector<Eigen::MatrixXd> parts;
  Eigen::Index cols = 0;
  for (int b = 0; b < num_bodies(); ++b) {
    parts.push_back(bodies_[static_cast<std::size_t>(b)]->near_null_space(block(u, b), t));
    cols += parts.back().cols();
  }
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(num_dofs(), cols);
  Eigen::Index at = 0;
  for (int b = 0; b < num_bodies(); ++b) {
    const Eigen::MatrixXd& P = parts[static_cast<std::size_t>(b)];
    if (P.cols() == 0) continue;
    Z.block(offset(b), at, P.rows(), P.cols()) = P;
    at += P.cols();
  }
  return Z;
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
