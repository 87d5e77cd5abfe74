// The unknowns of a problem spread over the processes of a run, each owned by one process, with
// ghosts: a process keeps current the unknowns it owns and those its share of the model reads
// but others own (its ghosts); the rest of its copy of a vector is not kept current during a
// step. The residual's parts are added into the owners, the owners' values are sent to the
// ghosts, dot products are sums over the owners, and one gather per converged step makes every
// entry current again (for what reads any point: monitors, reactions, output, restart).
// The linear solver's rows of a process are its own unknowns: the unknowns are numbered by
// owner (row), each process's in their serial order.
//
// Notation: n the unknowns (serial numbering i), P the processes, owner(i) in [0, P); O_r the
// unknowns process r owns (ascending), G_r its ghosts (read by r, owned by others); row(i) =
// sum_{q < owner(i)} |O_q| + the position of i in O_owner(i), the linear solver's numbering.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "iga/parallel/communicator.hpp"

namespace iga {

class DofLayout {
 public:
  /// Every unknown on this one process (no communication).
  DofLayout() = default;
  /// `owner`: owner(i) for every unknown, the same on every process; `reads`: the unknowns this
  /// process's share reads or adds to (any order, repeats allowed; its own are added anyway).
  /// Not collective (a model's build may fail on one process alone): the owners learn who
  /// ghosts their unknowns at the first add_to_owners or update_ghosts, which every process
  /// calls. Throws std::invalid_argument for an owner outside [0, P). `comm` must outlive the
  /// layout.
  DofLayout(const Communicator& comm, std::vector<int> owner, std::span<const int> reads);

  int size() const { return static_cast<int>(owner_.size()); }
  /// Whether the unknowns are spread (a layout over more than one process).
  bool spread() const { return comm_ != nullptr && comm_->size() > 1; }
  int owner(int i) const { return owner_[static_cast<std::size_t>(i)]; }
  /// O_r, ascending.
  const std::vector<int>& owned() const { return owned_; }
  /// G_r, ascending.
  const std::vector<int>& ghosts() const { return ghosts_; }
  /// row(i) for every unknown.
  const std::vector<int>& rows() const { return rows_; }
  /// row of this process's first unknown (its rows are [first_row, first_row + |O_r|)).
  int first_row() const { return first_row_; }

  /// Collective: each owned entry of R becomes its sum over the processes (this process's value
  /// plus the ghosts' values the others send); ghost entries keep this process's own part.
  void add_to_owners(Eigen::VectorXd& R) const;
  /// Collective: each ghost entry of x gets its owner's value.
  void update_ghosts(Eigen::VectorXd& x) const;
  /// Collective: every entry of x gets its owner's value (one sum of n entries).
  void gather(Eigen::VectorXd& x) const;
  /// Collective: a . b summed over the owners (the same on every process).
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  /// The unknowns of any process that some other process reads: the values one add_to_owners
  /// sends from here.
  long long sent_per_exchange() const;

 private:
  /// Collective, once: owned_by_me_for_ from the other processes' ghosts.
  void connect() const;
  /// Collective: x at from_places[q] sent to process q, which sets (or adds) them at its
  /// to_places[this process].
  void send(const std::vector<std::vector<int>>& from_places,
            const std::vector<std::vector<int>>& to_places, Eigen::VectorXd& x, bool add) const;

  const Communicator* comm_ = nullptr;
  std::vector<int> owner_, owned_, ghosts_, rows_;
  int first_row_ = 0;
  /// Per process q: the ghosts of this process that q owns (ascending); the unknowns of this
  /// process that q ghosts (ascending, as q listed them).
  std::vector<std::vector<int>> ghosts_of_;
  mutable std::vector<std::vector<int>> owned_by_me_for_;
  mutable bool connected_ = false;
};

}  // namespace iga
