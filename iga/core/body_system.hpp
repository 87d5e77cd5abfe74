// The model's bodies as one NonlinearProblem for the solver: the unknowns are the bodies'
// blocks one after the other, u = [u_1; u_2; ...]; the residual is stacked, the tangent block
// diagonal (bodies couple only through what a later pair between bodies adds); history,
// multipliers, symmetry and status are the bodies'.
//
// Spread over the processes of a run (distribute): every process holds every body and a copy of
// u; each assembles its share of the bodies (Body::share). Each unknown has an owner (layout():
// a whole body's are its process's, a cut body's those of its points' owners, Body::partition);
// the residuals' parts are added into the owners (every process has R complete at its own
// unknowns), u is kept current at a process's own unknowns and its ghosts, and the tangent
// stays in parts (distributed());
// the pairs' figures of each assembly (counts, tool forces, round-off) are combined into every
// process's pairs (ContactPair::set_total), the bodies' augmentation results into one.
//
// Notation: n_b the unknowns of body b, o_b = n_1 + ... + n_{b-1} its offset; u_b = u(o_b :
// o_b + n_b) its block; P the processes, owner(b) the process that assembles body b whole, or
// -1 for a body cut into parts, one on every process.
#pragma once

#include <string>
#include <vector>

#include "iga/core/body.hpp"
#include "iga/core/sparse_assembly.hpp"
#include "iga/parallel/communicator.hpp"

namespace iga {

class BodySystem : public NonlinearProblem {
 public:
  BodySystem() = default;
  /// Adds a body (not owned; it must outlive the system and keep its number of unknowns).
  void add(Body& body);
  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  Body& body(int b) const { return *bodies_.at(static_cast<std::size_t>(b)); }
  int offset(int b) const { return offsets_.at(static_cast<std::size_t>(b)); }
  /// u_b, the block of body b in u.
  VectorXd block(const VectorXd& u, int b) const;

  /// Spreads the system over the processes of `comm` (it must outlive the system): owner[b]
  /// the process that assembles body b whole, or -1 for a body that built its own part on
  /// every process (then process 0 adds its point terms). Sets the bodies' shares.
  void distribute(const Communicator& comm, std::vector<int> owner);
  const Communicator& communicator() const { return *comm_; }
  /// owner(b) of distribute (0 on one process).
  int owner(int b) const { return owner_.empty() ? 0 : owner_.at(static_cast<std::size_t>(b)); }
  bool distributed() const override { return comm_->size() > 1; }
  /// The owners and ghosts of the unknowns (distribute), null on one process.
  const DofLayout* layout() const override { return distributed() ? &layout_ : nullptr; }

  int num_dofs() const override { return offsets_.back(); }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override;
  bool symmetric() const override;
  /// The bodies' load_rate stacked; false where one body's is (on any process: then on all).
  bool load_rate(const VectorXd& u, double t, double h, VectorXd& R_t) override;
  void commit(const VectorXd& u, double t) override;
  /// The worst of the bodies' (failed > updated > satisfied), messages joined.
  AugmentResult augment(const VectorXd& u, double t) override;
  void restore() override;
  /// Each body's state in its section ("body b", with its number of unknowns checked).
  void archive(StateArchive& a) override;
  double residual_roundoff() const override;
  /// Each body's near null space in its block of rows (its columns beside the others').
  Eigen::MatrixXd near_null_space(const VectorXd& u, double t) const override;
  /// The bodies' status lines, joined by "; " (empty ones left out).
  std::string status() const override;

 private:
  /// After an assembly over several processes: every pair's figures combined (set_total),
  /// unless some process `failed`. Returns whether one did.
  bool combine_tallies(bool failed);
  /// distribute's shares, the bodies' owners of their unknowns (dof_owner, the system's) and
  /// the unknowns this process reads.
  void partition(const Communicator& comm, const std::vector<int>& owner,
                 std::vector<int>& dof_owner, std::vector<int>& reads);
  /// The pairs of all bodies, in the bodies' order.
  std::vector<ContactPair*> all_pairs() const;

  std::vector<Body*> bodies_;
  const Communicator* comm_ = &serial_communicator();
  std::vector<int> owner_;       ///< empty: one process
  std::vector<int> offsets_{0};  ///< o_b, and the total at the end
  DofLayout layout_;             ///< set by distribute
  // Work storage of assemble() for several bodies.
  VectorXd Rb_;
  SparseMatrix Kb_;
  std::vector<Triplet> triplets_;
  PatternAssembler assembler_;
};

}  // namespace iga
