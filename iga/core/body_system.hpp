// The model's bodies as one NonlinearProblem for the solver: the unknowns are the bodies'
// blocks one after the other, u = [u_1; u_2; ...]; the residual is stacked, the tangent block
// diagonal (bodies couple only through what a later pair between bodies adds); history,
// multipliers, symmetry and status are the bodies'.
//
// Notation: n_b the unknowns of body b, o_b = n_1 + ... + n_{b-1} its offset; u_b = u(o_b :
// o_b + n_b) its block.
#pragma once

#include <string>
#include <vector>

#include "iga/core/body.hpp"
#include "iga/core/sparse_assembly.hpp"

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

  int num_dofs() const override { return offsets_.back(); }
  void assemble(const VectorXd& u, double t, VectorXd& R, SparseMatrix* K) override;
  bool symmetric() const override;
  void commit(const VectorXd& u, double t) override;
  /// The worst of the bodies' (failed > updated > satisfied), messages joined.
  AugmentResult augment(const VectorXd& u, double t) override;
  void restore() override;
  /// Each body's state in its section ("body b", with its number of unknowns checked).
  void archive(StateArchive& a) override;
  double residual_roundoff() const override;
  /// The bodies' status lines, joined by "; " (empty ones left out).
  std::string status() const override;

 private:
  std::vector<Body*> bodies_;
  std::vector<int> offsets_{0};  ///< o_b, and the total at the end
  // Work storage of assemble() for several bodies.
  VectorXd Rb_;
  SparseMatrix Kb_;
  std::vector<Triplet> triplets_;
  PatternAssembler assembler_;
};

}  // namespace iga
