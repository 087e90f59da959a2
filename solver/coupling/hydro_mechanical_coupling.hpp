#pragma once
// The fully implicit hydro-mechanical step (seed 2.4, Figures 2.7-2.8), without the
// seed's stabilisation constants (docs/formulation.md section 4.6).
//
// Within one open-close iteration the contact springs are fixed, so the blocks are
// linear: D = K^-1 (F_mech + B p), with B the trapezoidal pressure loads of the
// wetted joints per unit nodal pressure. The apertures of the wetted joint ends are
// then affine in the nodal pressures,
//     w(p) = g0 + J K^-1 F_mech + (J K^-1 B) p,
// where J holds the linearised gaps. The coupling keeps X = K^-1 B (multi-right-hand-
// side solves), forms S = J X and hands w(p) to the flow network, whose Newton
// iteration solves the coupled mass balance exactly; the block displacement follows as
// X p. Within a step X follows K's changes (Woodbury identity on the springs that
// changed) and the network's growth (solves for new columns only), instead of being
// solved anew at every open-close iteration (docs/design_notes.md section 37).
// Outer iterations (the coupled step's
// open-close loop) add the joints the fluid reaches: a joint joins the network once
// one of its end contacts is open at a pressurised node (Figure 2.8).

#include <array>
#include <memory>
#include <vector>

#include "coupling/aperture_operator.hpp"
#include "coupling/fluid_load_model.hpp"
#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"

namespace hfdda::coupling {

/// How the flow Newton's linear systems are solved (docs/design_notes.md, "Flow Jacobian"):
/// dense: S formed (one solve per node, 64 at a time) and J factorised by dense LU;
/// krylov: S as an operator, GMRES with the two-level preconditioner (aperture_operator.hpp).
/// augmented: S as an operator, each Newton step one sparse LU of the augmented system
/// [K -B D; E G A] (augmented_flow_system.hpp; docs/design_notes.md section 46).
/// automatic: dense below kOperatorFromNodes wetted nodes, augmented from there. Where the
/// flow Newton needs hundreds of iterations a step (junctions, fluid-filled starts) the
/// operator paths lose to the dense LU; the n solves that form S and its n^2 memory lose
/// to them on large networks (docs/design_notes.md section 43). The augmented LU was
/// measured 7 % faster than GMRES at 2,905 nodes, 16 % at 4,705, 29 % at 6,937 and 5.2
/// times at 10,585, where the two-level preconditioner needed about 200 iterations
/// (section 46).
enum class FlowJacobian { dense, krylov, augmented, automatic };

struct CouplingStatistics {
  int flow_solves = 0;            ///< one per ALM iteration
  int newton_iterations = 0;
  int newton_restarts = 0;        ///< flow solves that needed the flooded second start
  int fractures_wetted = 0;
  int max_nodes = 0;
  double max_relative_residual = 0.0;
  double seconds_sensitivity = 0.0;  ///< building S = J K^-1 B
  int sensitivity_builds = 0;        ///< X = K^-1 B solved for all its columns
  int sensitivity_corrections = 0;   ///< X updated for springs changed in K and new columns instead
  int response_columns_solved = 0;   ///< columns of X solved (builds and new columns)
  int response_products = 0;         ///< block displacements taken as X p instead of a solve
  double seconds_flow = 0.0;
  long sensitivity_products = 0;  ///< products with the operator S (krylov)
  long krylov_iterations = 0;
  long inexact_linear_solves = 0;   ///< Krylov solves stopped at their limit (inexact Newton steps)
};

/// Couples a FlowNetwork whose fractures are the mesh joints (same indices) with the
/// block system it is passed to.
class HydroMechanicalCoupling final : public FluidLoadModel {
 public:
  explicit HydroMechanicalCoupling(fluid::FlowNetwork& network, FlowJacobian jacobian = FlowJacobian::dense);

  void begin_step(dda::BlockSystem& system, double dt_s) override;
  void prepare(const dda::BlockSystem& system, bool stiffness_changed) override;
  /// d += K^-1 B p for the pressures the flow solve finds with the apertures of d.
  void respond(const dda::BlockSystem& system, Eigen::VectorXd& d) override;
  int update_states(const dda::BlockSystem& system) override;
  const std::vector<char>& pressurised_points() const override { return pressurised_; }
  bool wetted(int joint) const override { return network_.wetted(joint); }
  void commit(const dda::BlockSystem& system) override;
  void roll_back() override;
  void add_statistics(StepStatistics& step) const override;
  void interrupt_when(std::function<bool()> requested) override { network_.interrupt_when(std::move(requested)); }

  /// Statistics of the last step attempt (committed or not).
  const CouplingStatistics& statistics() const { return stats_; }
  /// Krylov path: hops of the preconditioner's near field (ApertureOperator::kNearHops;
  /// 0 leaves it out, for comparisons). Takes effect at the next operator built.
  void set_near_field_hops(int hops) { near_field_hops_ = hops; }
  const fluid::FlowNetwork& network() const { return network_; }
  /// S as handed to the flow solve by the last prepare() (dense path; empty on the krylov
  /// path): tests compare an updated S with one rebuilt from a new factorisation
  /// (docs/design_notes.md section 37).
  const Eigen::MatrixXd& sensitivity() const { return sensitivity_; }
  /// Largest entry of J (X_updated - X_before) of the last update of X for springs
  /// changed in K, relative to the largest of S (0 when the last prepare made none).
  double last_update_size() const { return last_update_size_; }

  /// X = K^-1 B is kept while it takes at most this many bytes (600 nodes on 7,700
  /// blocks: 0.22 GB); a prepare that changes its columns holds the old and the new X
  /// for a moment, twice this. Larger networks have S formed column block by column
  /// block and the displacements solved, as before X was kept; within a step S then
  /// follows the springs changed in K by itself (update_sensitivity) while the trial
  /// network stays the same.
  static constexpr double kMaxResponseBytes = 256.0 * 1024 * 1024;
  /// Replaces kMaxResponseBytes (tests set 0 to take the path of large networks).
  void set_max_response_bytes(double bytes) { max_response_bytes_ = bytes; }
  /// |K X v - B v| / |B v| (v all ones) above which an updated X is dropped and solved
  /// anew: the bound of a corrected factorisation (dda::BlockSystem::kLowRankResidual).
  static constexpr double kResponseResidual = 1e-7;
  /// FlowJacobian::automatic takes the augmented path from this many wetted nodes of the
  /// trial network: between the sizes where the scaling benchmark measured the dense path
  /// faster (1,945 nodes: 24 s a step against 30 s with GMRES and 37 s augmented) and
  /// slower (2,905 nodes: 45 s against 32 and 30 s).
  static constexpr int kOperatorFromNodes = 2500;
  /// Replaces kOperatorFromNodes (tests).
  void set_operator_from_nodes(int nodes) { operator_from_nodes_ = nodes; }

 private:
  void refresh_pressurised();
  /// S as an operator (GMRES or the augmented LU) rather than formed densely.
  bool use_operator(int n_nodes) const {
    return jacobian_ == FlowJacobian::krylov || jacobian_ == FlowJacobian::augmented ||
           (jacobian_ == FlowJacobian::automatic && n_nodes >= operator_from_nodes_);
  }
  /// S = J K^-1 B for the current K and network: from the kept X where it can follow
  /// (update_responses, new columns solved), from solves of every column otherwise.
  void form_sensitivity(const dda::BlockSystem& system, const dda::SpdSolver& solver, bool keep);
  /// X for the springs changed in K since X's version: X -= Y N^-1 (Y^T B), Y = K^-1 C,
  /// N = D - C^T Y (Woodbury identity with the new factor); false when X cannot follow
  /// (K changed otherwise, too many springs, the check solve fails).
  bool update_responses(const dda::BlockSystem& system);
  /// Y = K^-1 C (the new factor) and N^-1 (Y^T B) for the nodal `loads`, of the springs
  /// changed in K since `version`; false when K changed otherwise (no spring log), the
  /// springs are `max_springs` or more, or N is singular where they act. No spring
  /// changed: y and coefficients empty, true.
  bool stiffness_change(const dda::BlockSystem& system, int version, const std::vector<std::vector<NodeLoad>>& loads,
                        int max_springs, Eigen::MatrixXd& y, Eigen::MatrixXd& coefficients) const;
  /// Where X is not kept (too large): S for the springs changed in K since S was formed,
  /// S -= (J Y) N^-1 (Y^T B), r solves instead of n; false when S cannot follow (the
  /// trial network changed, K changed otherwise, too many springs, the check fails).
  bool update_sensitivity(const dda::BlockSystem& system);
  /// X p replaces a solve where X is of the current K and reads no more memory than
  /// the solve's two passes through the factor.
  bool responses_apply(const dda::BlockSystem& system) const;
  /// B p: the block forces of nodal pressures p (in work_).
  const Eigen::VectorXd& pressure_load(const dda::BlockSystem& system, const Eigen::VectorXd& p);
  /// J u: the normal gaps of the fracture ends for block displacements u.
  Eigen::VectorXd end_gaps(const Eigen::VectorXd& u) const;
  /// J U, column by column.
  Eigen::MatrixXd end_gaps_of(const Eigen::MatrixXd& u) const;

  fluid::FlowNetwork& network_;
  FlowJacobian jacobian_;
  int near_field_hops_ = ApertureOperator::kNearHops;
  int operator_from_nodes_ = kOperatorFromNodes;
  bool topology_changed_ = true;
  std::vector<dda::JointEndGap> gaps_;           // per trial fracture end
  std::vector<std::vector<NodeLoad>> loads_;     // per trial node
  Eigen::MatrixXd sensitivity_;                  // S = J K^-1 B [m/Pa] (dense path)
  // X = K^-1 B [m/Pa, rad/Pa] for the K numbered response_version_ (-1: none kept), one
  // column per node: the node's mesh point and the loads B's column had when solved.
  Eigen::MatrixXd responses_;
  int response_version_ = -1;
  std::vector<int> response_points_;
  std::vector<std::vector<NodeLoad>> response_loads_;
  double last_update_size_ = 0.0;
  // Without X: the K version S was formed or updated for (-1: none to update), and the
  // trial fractures and nodes it was formed for.
  int sensitivity_version_ = -1;
  double max_response_bytes_ = kMaxResponseBytes;
  std::vector<int> sensitivity_fractures_, sensitivity_points_;
  std::vector<std::array<int, 2>> nodes_of_fracture_;  // per trial fracture
  std::unique_ptr<ApertureOperator> operator_;   // S as an operator (krylov path)
  Eigen::VectorXd work_;
  std::vector<char> pressurised_;
  CouplingStatistics stats_;
  // J K^-1 B p of the last respond() (converged response): valid until K or the network changes.
  Eigen::VectorXd pressure_response_;
  bool pressure_response_valid_ = false;
};

}  // namespace hfdda::coupling
