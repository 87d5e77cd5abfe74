// Unknowns owned by one process, with ghosts; see dof_layout.hpp.
#include "iga/parallel/dof_layout.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace iga {

DofLayout::DofLayout(const Communicator& comm, std::vector<int> owner, std::span<const int> reads)
    : comm_(&comm), owner_(std::move(owner)) {
  const int P = comm.size(), me = comm.rank(), n = size();
  std::vector<int> count(static_cast<std::size_t>(P), 0);
  for (int i = 0; i < n; ++i) {
    const int q = owner_[static_cast<std::size_t>(i)];
    if (q < 0 || q >= P)
      throw std::invalid_argument("DofLayout: unknown " + std::to_string(i) + " owned by process " +
                                  std::to_string(q) + " of " + std::to_string(P));
    ++count[static_cast<std::size_t>(q)];
    if (q == me) owned_.push_back(i);
  }
  // row(i): the owners' blocks one after the other, each in the serial order
  std::vector<int> next(static_cast<std::size_t>(P), 0);
  for (int q = 1; q < P; ++q)
    next[static_cast<std::size_t>(q)] =
        next[static_cast<std::size_t>(q - 1)] + count[static_cast<std::size_t>(q - 1)];
  first_row_ = next[static_cast<std::size_t>(me)];
  rows_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    rows_[static_cast<std::size_t>(i)] = next[static_cast<std::size_t>(owner_[i])]++;
  // ghosts: what this process reads and others own
  for (const int i : reads) {
    if (i < 0 || i >= n)
      throw std::invalid_argument("DofLayout: process " + std::to_string(me) + " reads unknown " +
                                  std::to_string(i) + " of " + std::to_string(n));
    if (owner_[static_cast<std::size_t>(i)] != me) ghosts_.push_back(i);
  }
  std::sort(ghosts_.begin(), ghosts_.end());
  ghosts_.erase(std::unique(ghosts_.begin(), ghosts_.end()), ghosts_.end());
  ghosts_of_.assign(static_cast<std::size_t>(P), {});
  for (const int i : ghosts_) ghosts_of_[static_cast<std::size_t>(owner_[i])].push_back(i);
}

void DofLayout::connect() const {
  if (connected_) return;
  // the owners learn which of their unknowns each process ghosts
  std::vector<std::vector<double>> to(ghosts_of_.size());
  for (std::size_t q = 0; q < to.size(); ++q)
    to[q].assign(ghosts_of_[q].begin(), ghosts_of_[q].end());
  const std::vector<std::vector<double>> from = comm_->exchange(to);
  owned_by_me_for_.assign(ghosts_of_.size(), {});
  for (std::size_t q = 0; q < from.size(); ++q)
    for (const double v : from[q]) owned_by_me_for_[q].push_back(static_cast<int>(v));
  connected_ = true;
}

void DofLayout::send(const std::vector<std::vector<int>>& from_places,
                     const std::vector<std::vector<int>>& to_places, Eigen::VectorXd& x,
                     bool add) const {
  std::vector<std::vector<double>> to(from_places.size());
  for (std::size_t q = 0; q < to.size(); ++q)
    for (const int i : from_places[q]) to[q].push_back(x[i]);
  const std::vector<std::vector<double>> from = comm_->exchange(to);
  for (std::size_t q = 0; q < from.size(); ++q) {
    const std::vector<int>& at = to_places[q];
    if (from[q].size() != at.size())  // the layouts of the processes disagree
      throw std::logic_error("DofLayout: " + std::to_string(from[q].size()) +
                             " values from process " + std::to_string(q) + " for " +
                             std::to_string(at.size()) + " places");
    for (std::size_t k = 0; k < at.size(); ++k) x[at[k]] = add ? x[at[k]] + from[q][k] : from[q][k];
  }
}

void DofLayout::add_to_owners(Eigen::VectorXd& R) const {
  if (!spread()) return;
  connect();
  send(ghosts_of_, owned_by_me_for_, R, /*add=*/true);
}

void DofLayout::update_ghosts(Eigen::VectorXd& x) const {
  if (!spread()) return;
  connect();
  send(owned_by_me_for_, ghosts_of_, x, /*add=*/false);
}

void DofLayout::gather(Eigen::VectorXd& x) const {
  if (!spread()) return;
  Eigen::VectorXd mine = Eigen::VectorXd::Zero(x.size());
  for (const int i : owned_) mine[i] = x[i];
  comm_->sum(std::span<double>(mine.data(), static_cast<std::size_t>(mine.size())));
  x.swap(mine);
}

double DofLayout::dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  if (!spread()) return a.dot(b);
  double s = 0.0;
  for (const int i : owned_) s += a[i] * b[i];
  return comm_->sum(s);
}

long long DofLayout::sent_per_exchange() const {
  long long s = 0;
  for (const auto& g : ghosts_of_) s += static_cast<long long>(g.size());
  return s;
}

}  // namespace iga
