#pragma once
// The aperture sensitivity S = J_gap K^-1 B as an operator (fluid/aperture_model.hpp):
// a product S p is one solve with the factorised block stiffness K, and S is never
// formed, so memory and cost grow with the network instead of with its square (the
// dense S has 2 nf x n entries and its Jacobian an n^3 factorisation).
//
// The flow Newton's linear systems J x = r, J = A + E S diag(d), are solved either
// - by one sparse LU of the augmented system [K -B D; E G A] (FlowLinearSolve::augmented,
//   coupling/augmented_flow_system.hpp): exact, no Krylov iteration; or
// - by GMRES (Eigen's, left-preconditioned; FlowLinearSolve::gmres) with a two-level
//   preconditioner:
//   coarse: the nodes grouped into about 2 sqrt(n) connected aggregates (breadth-first
//           along the network); S P (P: aggregate indicator columns) is computed once
//           per factorisation of K (one multi-right-hand-side solve), and
//           J_c = P^T A P + P^T E (S P) diag(d_c), d_c the mean of d per aggregate,
//           is factorised densely (it is small);
//   local:  the sparse part A (storage, leak-off and flow between nodes) plus the near
//           field of the elastic coupling, E S_near diag(d), factorised by sparse LU;
//           S_near holds S(end, node) for the nodes within kNearHops of the end's node
//           along the network, probed with one right-hand side per colour of a
//           colouring that puts nodes of a colour more than 2 kNearHops apart (so each
//           end sees one near node per colour); it resolves what varies from node to
//           node, the coarse part the smooth far-field coupling.
//   Applied multiplicatively: y = P J_c^-1 P^T v, then y + L^-1 (v - J_c-model of y), L
//   the local part.
//   On a model crack (docs/design_notes.md, "Flow Jacobian") GMRES then needs 10-25
//   iterations from 400 to 3,200 nodes where A alone needs 30-70. On the scaling
//   benchmark's 217-node fishbone the near field takes GMRES from 61 to 23 iterations
//   per Newton iteration (section 40); on its 10,585-node network about 200 (section 45),
//   where the augmented LU is faster (section 46).

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <array>
#include <memory>
#include <vector>

#include "coupling/augmented_flow_system.hpp"
#include "dda/block_system.hpp"
#include "fluid/aperture_model.hpp"

namespace hfdda::coupling {

/// How ApertureOperator solves J x = r (see the file comment).
enum class FlowLinearSolve { gmres, augmented };

class ApertureOperator final : public fluid::ApertureModel {
 public:
  /// `gaps`: per trial fracture end; `loads`: per trial node; `nodes_of_fracture`: the
  /// two nodes of each trial fracture (ends 2k, 2k+1). All must outlive the operator;
  /// the system's factorisation must not change while it is used.
  /// Hops along the network within which the local part holds S exactly (probed).
  static constexpr int kNearHops = 4;

  /// `near_hops` 0: the local part is A alone (for comparisons; GMRES only).
  ApertureOperator(const dda::BlockSystem& system, const std::vector<dda::JointEndGap>& gaps,
                   const std::vector<std::vector<NodeLoad>>& loads,
                   const std::vector<std::array<int, 2>>& nodes_of_fracture, int near_hops = kNearHops,
                   FlowLinearSolve linear_solve = FlowLinearSolve::gmres);
  ~ApertureOperator() override;

  int n_ends() const override { return static_cast<int>(gaps_.size()); }
  int n_nodes() const override { return static_cast<int>(loads_.size()); }
  void apply(const Eigen::VectorXd& p, Eigen::VectorXd& out) const override;
  /// An estimate: the end's response to its aggregate's pressure over the aggregate's
  /// size (used only to scale the pseudo-transient shift; with the augmented solve, S P
  /// is formed on the first call).
  double self_entry(int end, int node) const override;
  void factorize(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& e,
                 const Eigen::VectorXd& d) override;
  /// GMRES to the relative preconditioned residual `forcing`, at most kMaxLinearIterations;
  /// or the augmented LU's solve (exact; `forcing` unused).
  Eigen::VectorXd solve(const Eigen::VectorXd& r, double forcing) override;
  long products() const override { return products_; }
  long linear_iterations() const override { return iterations_; }
  long inexact_solves() const override { return inexact_solves_; }
  int n_aggregates() const { return static_cast<int>(aggregate_size_.size()); }
  /// The augmented system's LU factorisations so far (0 on the GMRES path).
  int augmented_factorizations() const { return augmented_ ? augmented_->factorizations() : 0; }

  /// J v for the last factorize (one product with S; GMRES path only).
  Eigen::VectorXd jacobian_times(const Eigen::VectorXd& v) const;
  /// The two-level preconditioner applied to v.
  Eigen::VectorXd precondition(const Eigen::VectorXd& v) const;

 private:
  void build_aggregates(const std::vector<std::array<int, 2>>& nodes_of_fracture);
  /// S P and the near field's probes: solves with one right-hand side per aggregate and
  /// per colour.
  void form_probes() const;
  /// Colours the nodes so that two of a colour are more than 2 near_hops apart along the
  /// network, and lists each end's near nodes (within near_hops of the end's node).
  void build_near_field(const std::vector<std::array<int, 2>>& nodes_of_fracture, int near_hops);

  const dda::BlockSystem& system_;
  const std::vector<dda::JointEndGap>& gaps_;
  const std::vector<std::vector<NodeLoad>>& loads_;
  std::vector<int> aggregate_;          // per node
  std::vector<int> aggregate_size_;     // per aggregate
  mutable Eigen::MatrixXd s_times_p_;   // S P, 2 nf x m [m/Pa]
  mutable bool probes_formed_ = false;
  std::vector<int> colour_;             // per node, for probing the near field of S
  int n_colours_ = 0;
  /// Per end: its near nodes and the probed entries S(end, node) [m/Pa].
  mutable std::vector<std::vector<std::pair<int, double>>> near_;
  mutable Eigen::VectorXd rhs_;         // 6 nb work vector
  mutable long products_ = 0;
  long iterations_ = 0;
  long inexact_solves_ = 0;

  Eigen::SparseMatrix<double> a_, e_;
  Eigen::VectorXd d_, d_coarse_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> local_lu_;
  Eigen::PartialPivLU<Eigen::MatrixXd> coarse_lu_;
  std::unique_ptr<AugmentedFlowSystem> augmented_;  // set: the augmented LU solves J x = r
};

}  // namespace hfdda::coupling
