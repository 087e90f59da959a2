#pragma once
// The aperture sensitivity S = J_gap K^-1 B as an operator (fluid/aperture_model.hpp):
// a product S p is one solve with the factorised block stiffness K, and S is never
// formed, so memory and cost grow with the network instead of with its square (the
// dense S has 2 nf x n entries and its Jacobian an n^3 factorisation).
//
// The flow Newton's linear systems J x = r, J = A + E S diag(d), are solved by GMRES
// (Eigen's, left-preconditioned) with a two-level preconditioner:
//   coarse: the nodes grouped into about 2 sqrt(n) connected aggregates (breadth-first
//           along the network); S P (P: aggregate indicator columns) is computed once
//           per factorisation of K (one multi-right-hand-side solve), and
//           J_c = P^T A P + P^T E (S P) diag(d_c), d_c the mean of d per aggregate,
//           is factorised densely (it is small);
//   local:  the sparse part A alone (storage, leak-off and flow between nodes),
//           factorised by sparse LU; it resolves what varies from node to node, the
//           coarse part the smooth far-field coupling that elasticity adds.
// Applied multiplicatively: y = P J_c^-1 P^T v, then y + A^-1 (v - J_c-model of y).
// On a model crack (docs/design_notes.md, "Flow Jacobian") GMRES then needs 10-25
// iterations from 400 to 3,200 nodes where A alone needs 30-70.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <array>
#include <vector>

#include "dda/block_system.hpp"
#include "fluid/aperture_model.hpp"

namespace hfdda::coupling {

struct NodeLoad {  // block forces of a unit pressure at one node
  int block;
  dda::Vec6 force;
};

class ApertureOperator final : public fluid::ApertureModel {
 public:
  /// `gaps`: per trial fracture end; `loads`: per trial node; `nodes_of_fracture`: the
  /// two nodes of each trial fracture (ends 2k, 2k+1). All must outlive the operator;
  /// the system's factorisation must not change while it is used.
  ApertureOperator(const dda::BlockSystem& system, const std::vector<dda::JointEndGap>& gaps,
                   const std::vector<std::vector<NodeLoad>>& loads,
                   const std::vector<std::array<int, 2>>& nodes_of_fracture);

  int n_ends() const override { return static_cast<int>(gaps_.size()); }
  int n_nodes() const override { return static_cast<int>(loads_.size()); }
  void apply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const override;
  /// An estimate: the end's response to its aggregate's pressure over the aggregate's
  /// size (used only to scale the pseudo-transient shift).
  double self_entry(int end, int node) const override;
  void factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                 const Eigen::VectorXd& d) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& r) override;
  long products() const override { return products_; }
  long linear_iterations() const override { return iterations_; }
  long inexact_solves() const override { return inexact_solves_; }
  int n_aggregates() const { return static_cast<int>(aggregate_size_.size()); }

  /// J v for the last factorize (one product with S).
  Eigen::VectorXd jacobian_times(const Eigen::VectorXd& v) const;
  /// The two-level preconditioner applied to v.
  Eigen::VectorXd precondition(const Eigen::VectorXd& v) const;

 private:
  void build_aggregates(const std::vector<std::array<int, 2>>& nodes_of_fracture);

  const dda::BlockSystem& system_;
  const std::vector<dda::JointEndGap>& gaps_;
  const std::vector<std::vector<NodeLoad>>& loads_;
  std::vector<int> aggregate_;          // per node
  std::vector<int> aggregate_size_;     // per aggregate
  Eigen::MatrixXd s_times_p_;           // S P, 2 nf x m [m/Pa]
  mutable Eigen::VectorXd rhs_;         // 6 nb work vector
  mutable long products_ = 0;
  long iterations_ = 0;
  long inexact_solves_ = 0;

  Eigen::SparseMatrix<double> a_, e_;
  Eigen::VectorXd d_, d_coarse_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> local_lu_;
  Eigen::PartialPivLU<Eigen::MatrixXd> coarse_lu_;
};

}  // namespace hfdda::coupling
