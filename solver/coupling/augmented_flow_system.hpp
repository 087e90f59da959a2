#pragma once
// The flow Newton's linear system solved together with the block displacements that the
// pressure change moves, as one sparse system, instead of through the aperture
// sensitivity S = G K^-1 B (fluid/aperture_model.hpp):
//
//     [ K      -B D ] [u]   [0]
//     [ E G     A   ] [x] = [r]
//
// K the block stiffness (fixed while the system is used), B the blocks' forces per unit
// nodal pressure, D = diag(d) the slope of each node's pressure in its unknown, G the
// gaps of the fracture ends in the block unknowns (dda::JointEndGap), E and A as in
// J = A + E S D. Eliminating u = K^-1 B D x gives J x = r exactly, so a Newton step costs
// one sparse LU of this matrix (UMFPACK, SuiteSparse) and no Krylov iteration: the
// coupling of every fracture end with every node, which S holds densely and which a
// preconditioner of J must approximate, stays in K's sparsity. On the scaling benchmark's
// largest network GMRES needed about 200 products with S per Newton iteration there
// (docs/design_notes.md sections 45-46).
//
// The pressure unknowns are scaled so that their columns are of the size of K's
// (UMFPACK scales the rows); the symbolic analysis (METIS ordering) is kept while the
// pattern is unchanged, so a Newton iteration pays for the numeric factorisation only.

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "dda/block_system.hpp"

namespace hfdda::coupling {

struct NodeLoad {  // block forces of a unit pressure at one node
  int block;
  dda::Vec6 force;
};

class AugmentedFlowSystem {
 public:
  /// `gaps`: per fracture end; `loads`: per node. K is the system's assembled stiffness
  /// now; it must not change while this object is used.
  AugmentedFlowSystem(const dda::BlockSystem& system, const std::vector<dda::JointEndGap>& gaps,
                      const std::vector<std::vector<NodeLoad>>& loads);
  ~AugmentedFlowSystem();
  AugmentedFlowSystem(const AugmentedFlowSystem&) = delete;
  AugmentedFlowSystem& operator=(const AugmentedFlowSystem&) = delete;

  /// Assembles the augmented matrix for J = A + E S diag(d) and factorises it. Throws
  /// ConvergenceError if UMFPACK finds it singular or fails.
  void factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                 const Eigen::VectorXd& d);
  /// x with J x = r, for the last factorize.
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const;

  int factorizations() const { return factorizations_; }
  int symbolic_analyses() const { return analyses_; }
  /// Entries of the last LU's factors (L and U with their diagonals).
  double factor_entries() const { return factor_entries_; }

 private:
  struct Umfpack;  // UMFPACK's symbolic and numeric objects and its control settings

  int n_unknowns_ = 0;                 // 6 x blocks
  int n_nodes_ = 0;
  double pressure_scale_ = 1.0;        // x = pressure_scale_ x~ [Pa per unit of x~]
  Eigen::SparseMatrix<double> k_full_;  // K with both triangles
  Eigen::SparseMatrix<double> gap_rows_;   // G: fracture ends x block unknowns
  Eigen::SparseMatrix<double> node_loads_; // B: block unknowns x nodes
  // The augmented matrix in compressed columns (UMFPACK's int indices).
  std::vector<int> column_start_, row_index_;
  std::vector<double> value_;
  std::vector<int> analysed_start_, analysed_rows_;  // the pattern of the symbolic analysis
  std::unique_ptr<Umfpack> umfpack_;
  int factorizations_ = 0;
  int analyses_ = 0;
  double factor_entries_ = 0.0;
};

}  // namespace hfdda::coupling
