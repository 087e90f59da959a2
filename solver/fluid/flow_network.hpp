#pragma once
// Compressible Poiseuille flow in the network of fluid-filled joints (seed 2.1).
//
// Nodes are the mesh's geometric points, fractures are its joints. A fracture joins
// the network ("wetted") once the mechanics opens it next to a pressurised node, and
// stays in it for the rest of the run. Per node i, over a step t -> t + dt, fully
// implicit (eq. 2.5-2.7):
//
//   M_i(t+dt) - M_i(t) = I_i - rho_i Vleak_i - dt sum_j eta_ij (p_i - p_j)
//
//   M_i   = rho(p_i) V_i, stored mass; V_i = sum_j L_ij/2 w_ij(end at i)       [kg]
//   rho   = rho0 (1 + (p - p0) / Kf)                                         (eq. 2.6)
//   eta   = rho_ij w_ij^3 / (12 mu L_ij), rho_ij and w_ij means of the two ends (eq. 2.2)
//   I_i   = injected mass over the step                                       [kg]
//   Vleak = Carter leak-off: both walls of each fracture leak C_L / sqrt(t - t0),
//           half of the fracture charged to each end node, integrated exactly over
//           the step: C_L L 2 (sqrt(t+dt - t0) - sqrt(t - t0))
//           (erratum 4 in docs/seed_errata.md); at a zero-pressure node only the
//           wetted walls leak: rho_i Vleak_i times the fill fraction, so a node never
//           loses more than it receives and its stored mass never goes negative
//
// A node whose pressure would be negative becomes a zero-pressure node: p = 0 and its
// stored mass is solved for instead (seed 2.1, Figure 2.2). Both kinds share one
// unknown per node, the fill state y: y >= 0 is the pressure of a full node, y < 0 a
// node at zero pressure filled to the fraction 1 + y / P; the pressure acting on flow
// and rock is max(y, 0). No switching between node kinds is needed.
//
// Apertures come from the mechanics as an affine model of the nodal pressures,
// w_e(p) = base_e + S_e . p (exact for the linear block system once its contacts are
// fixed), plus the fracture's hydraulic width w0 when it has one, bounded below by w0, by the minimum widths (0.5 um inside the network, 0.1 um at
// tips) and by the closing limit (at most 5 % a step). Newton's method on the nodal
// unknowns then solves the coupled problem without stabilisation constants. Where it
// stalls (a closed new tip whose own pressure opens the fracture behind it makes the
// mass balance non-monotone; a network whose apertures all sit on their floors, where
// only the fluid's compressibility answers a pressure change), the solve falls back,
// in order, on full Newton steps without line search, pseudo-transient continuation,
// restarts with the dry nodes at their neighbours' pressure, continuation in the
// step's inflows, and last holding the closing joints open for the step;
// FlowSolveStatistics::restarts counts them (why and with what evidence:
// docs/design_notes.md sections 3 and 23).
//
// Units SI, per metre of out-of-plane thickness (h = 1 m in eq. 2.2-2.3).

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "fluid/aperture_model.hpp"

namespace hfdda {
class BinaryWriter;
class BinaryReader;
}  // namespace hfdda

namespace hfdda::fluid {

struct FluidProperties {
  double density_kg_m3 = 1000.0;
  double bulk_modulus_Pa = 2.2e9;
  double viscosity_Pa_s = 1.0e-3;
  double reference_pressure_Pa = 0.0;
  double leak_off_coefficient_m_sqrt_s = 0.0;  ///< Carter C_L of one wall

  double density(double pressure_Pa) const {
    return density_kg_m3 * (1.0 + (pressure_Pa - reference_pressure_Pa) / bulk_modulus_Pa);
  }
  double density_derivative() const { return density_kg_m3 / bulk_modulus_Pa; }
};

struct FlowSettings {
  double min_width_main_m = 0.5e-6;
  double min_width_tip_m = 0.1e-6;
  double max_closing_fraction = 0.05;
  double tolerance = 1.0e-9;        ///< Newton: relative pressure change and mass residual
  int max_newton_iterations = 60;
};

struct Fracture {
  int point_p = -1, point_q = -1;
  double length_m = 0.0;
  /// w0: the width through which fluid flows while the fracture is mechanically closed
  /// (a natural fracture, seed 5.2 and Table 5.1). Its hydraulic width, which stores
  /// the fluid and conducts it, is the mechanical opening plus w0, and never less than
  /// w0; such a fracture takes in fluid as soon as one of its ends is pressurised,
  /// open or not [m].
  double hydraulic_width_m = 0.0;
};

struct Injection {
  int point = -1;
  double mass_rate_kg_s = 0.0;
  double start_time_s = 0.0;
  /// Injection stops once this mass has gone in (seed 5.5: 60 kg per metre).
  double mass_limit_kg = std::numeric_limits<double>::infinity();

  /// Mass per metre injected from time 0 to t: the rate from start_time on, up to the limit.
  double mass_injected_by(double t_s) const {
    const double seconds = std::max(0.0, t_s - start_time_s);
    return std::min(mass_rate_kg_s * seconds, mass_limit_kg);
  }
};

struct FlowSolveStatistics {
  int newton_iterations = 0;
  int restarts = 0;                    ///< fallbacks used after Newton stalled (see the header)
  int zero_pressure_nodes = 0;
  double max_relative_residual = 0.0;  ///< max |mass residual| / mass scale at convergence
};

class FlowNetwork {
 public:
  FlowNetwork(int n_points, std::vector<Fracture> fractures, FluidProperties fluid, FlowSettings settings);

  void add_injection(const Injection& injection);
  /// Before the first step: the fracture starts wetted, open by `width_m` (at least
  /// the minimum width) and full of fluid at `pressure_Pa` (>= 0; mass rho(p) L w).
  /// A point shared by fractures filled at different pressures takes the last one.
  void fill_initially(int fracture, double width_m, double pressure_Pa = 0.0);

  // --- one step: begin, then any number of (wet, solve), then commit ----------------
  void begin_step(double dt_s);
  /// Adds a fracture to the trial network; false if it already was in it.
  bool wet(int fracture);
  bool wetted_in_trial(int fracture) const { return trial_wetted_[fracture] != 0; }
  /// Trial network: wetted fractures (ends 2k, 2k+1 of the aperture model are the
  /// ends at point_p and point_q of trial_fractures()[k]) and its nodes.
  const std::vector<int>& trial_fractures() const { return trial_fractures_; }
  const std::vector<int>& trial_nodes() const { return trial_nodes_; }
  int node_index(int point) const { return node_of_point_[point]; }
  /// Solves the step's mass balance for the aperture model w = base + S p (S has one
  /// column per trial node). Throws ConvergenceError.
  FlowSolveStatistics solve(const Eigen::VectorXd& base_aperture_m, const Eigen::MatrixXd& sensitivity_m_Pa);
  /// The same with S given as a model (dense or an operator; fluid/aperture_model.hpp).
  FlowSolveStatistics solve(const Eigen::VectorXd& base_aperture_m, ApertureModel& sensitivity);
  /// Trial pressures per trial node [Pa] (0 at zero-pressure nodes).
  const Eigen::VectorXd& trial_pressure() const { return pressure_; }
  /// Pressurised in the trial: in the network, above zero pressure.
  bool trial_pressurised(int point) const;
  void commit();

  // --- committed state ------------------------------------------------------------
  int n_points() const { return static_cast<int>(node_of_point_.size()); }
  int n_fractures() const { return static_cast<int>(fractures_.size()); }
  const Fracture& fracture(int f) const { return fractures_[f]; }
  bool wetted(int fracture) const { return wetted_[fracture] != 0; }
  double pressure(int point) const { return point_pressure_[point]; }
  bool zero_pressure(int point) const { return reached_[point] && point_state_[point] < 0.0; }
  /// Aperture of a wetted fracture at its end 0 (point_p) or 1 (point_q) [m].
  double aperture(int fracture, int end) const { return aperture_[2 * fracture + end]; }
  /// Mean aperture of the wetted fractures at a point (0 if none) [m].
  double aperture_at_point(int point) const;
  double time() const { return time_s_; }
  double injected_mass() const { return injected_kg_; }
  double initial_mass() const { return initial_mass_; }
  double leaked_mass() const { return leaked_kg_; }
  /// Stored mass of the ledger: each node's mass is updated by what flowed in and out
  /// (old + injected - leaked - outflow), so this closes with injected - leaked by
  /// construction, whether or not the flow solve converged.
  double stored_mass() const;
  /// |initial + injected - stored - leaked| / (initial + injected) with the ledger's
  /// stored mass; 0 without any fluid. A check of the bookkeeping only.
  double mass_balance_error() const;
  /// Fluid mass held by the committed state, computed without the ledger: per node the
  /// fill density of its committed state (rho(p) if full, rho(0) times the fill fraction
  /// if partly filled) times its volume sum L/2 w from the committed apertures [kg].
  double volume_stored_mass() const;
  /// |initial + injected - leaked - volume_stored_mass| / (initial + injected); 0 without
  /// any fluid. Differs from mass_balance_error by the sum of the last solve's mass
  /// residuals, so it exposes an unconverged flow solve or apertures that do not match
  /// the fluid's (docs/design_notes.md, "Mass ledger and volume check").
  double volume_balance_error() const;
  /// Nodes of the committed network (points the fluid has reached).
  int n_nodes() const;
  const FluidProperties& fluid() const { return fluid_; }
  const FlowSettings& settings() const { return settings_; }

  /// Everything a later step depends on (committed state, the warm start of the last
  /// trial, the mass ledger), for a checkpoint; restore_state() into a network built
  /// the same way continues bit for bit (flow_network_state.cpp). Throws
  /// std::runtime_error on a mismatch.
  void save_state(BinaryWriter& out) const;
  void restore_state(BinaryReader& in);

 private:
  struct Evaluation;
  void rebuild_trial_topology();
  void evaluate(const Eigen::VectorXd& unknowns, const Eigen::VectorXd& base, const ApertureModel& s,
                Evaluation& out, bool with_jacobian) const;
  /// Pieces of evaluate, in its order: pressure of the fill state, floored apertures,
  /// storage and the node terms of the residual, flow between nodes, Jacobian.
  void evaluate_pressure(const Eigen::VectorXd& unknowns, Evaluation& out) const;
  void evaluate_aperture(const Eigen::VectorXd& base, const ApertureModel& s, Evaluation& out) const;
  void evaluate_storage(const Eigen::VectorXd& unknowns, Evaluation& out) const;
  void evaluate_flow(Evaluation& out) const;
  void evaluate_jacobian(const Eigen::VectorXd& unknowns, Evaluation& out) const;
  /// Adds the derivatives of the flow between nodes (in the pressures) to the local and
  /// coupling parts of the Jacobian.
  void add_flow_jacobian(const Evaluation& out, std::vector<Eigen::Triplet<double>>& local,
                         std::vector<Eigen::Triplet<double>>& coupling) const;
  struct NewtonProgress {
    double residual = 0.0, change = 0.0, max_pressure = 0.0;  // of the last iteration
  };
  /// How a Newton iteration moves from one iterate to the next.
  enum class NewtonStep {
    line_search,       ///< backtracking until the mass residual falls
    full,              ///< the whole step, capped in size, fill fractions kept >= 0
    pseudo_transient,  ///< a diagonal shift that pseudo-time relaxes (a trust region)
  };
  /// Newton from the current unknowns; false if it did not converge.
  bool newton(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats,
              NewtonProgress& progress, NewtonStep mode);
  /// Per node: the positive part of the slope of its mass balance in its own unknown
  /// (the pseudo-transient shift's scale).
  Eigen::VectorXd self_capacity(const Eigen::VectorXd& x, const ApertureModel& s, const Evaluation& ev) const;
  /// Newton along lambda = 0 -> 1 (homotopy_); false if a stage could not be solved.
  bool continuation(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats,
                    NewtonProgress& progress);
  /// Scale of the step's inflows, leak-off and flow in the mass balance (1 except
  /// during continuation), and the flow's time factor it gives.
  double homotopy_ = 1.0;
  double flow_dt() const { return homotopy_ * dt_s_; }
  /// Newton, then pseudo-transient continuation, flooded starts and continuation in
  /// the step's inflows if needed; throws ConvergenceError.
  void solve_mass_balance(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats);
  /// Stored mass per volume of a node in fill state y, and its derivative in y.
  double fill_density(double y, int node) const;
  double fill_density_slope(double y, int node) const;
  /// Fraction of a node's fracture walls that the fluid wets in fill state y (1 if full).
  double wetted_fraction(double y, int node) const;
  /// Round-off of the step's mass balance [kg]: 64 eps times its largest terms.
  double residual_round_off() const;
  /// Committed form of a trial node's fill state: the pressure [Pa] if full, else the
  /// fill fraction minus one, in [-1, 0) (independent of the fill scale).
  double state_of_unknown(int node) const;
  void rescale_partly_filled_nodes(Evaluation& ev);

  std::vector<Fracture> fractures_;
  FluidProperties fluid_;
  FlowSettings settings_;
  std::vector<Injection> injections_;

  // Committed state.
  double time_s_ = 0.0;
  std::vector<char> wetted_;
  std::vector<double> arrival_time_;     ///< per fracture: time it was wetted [s]
  std::vector<double> aperture_;         ///< per fracture end [m]
  std::vector<double> point_pressure_, point_mass_;
  double injected_kg_ = 0.0, leaked_kg_ = 0.0;
  double initial_mass_ = 0.0;            ///< fluid present at t = 0 [kg]

  // Trial of the current step.
  double dt_s_ = 0.0;
  std::vector<char> trial_wetted_;
  std::vector<int> trial_fractures_, trial_nodes_, node_of_point_;
  std::vector<int> fracture_node_a_, fracture_node_b_;   // per trial fracture: node indices
  Eigen::VectorXd old_mass_, injected_, leak_volume_;    // per trial node
  Eigen::VectorXd floor_;                                // per trial end: lower bound of the aperture
  Eigen::VectorXd hydraulic_width_;                      // per trial end: w0 of its fracture
  Eigen::VectorXd unknowns_, pressure_, aperture_trial_, mass_new_, leak_mass_;
  Eigen::VectorXd fill_scale_;                           // per trial node: P of the fill state [Pa]
  std::vector<double> point_state_;                      // per point: pressure [Pa] if full, else fill fraction - 1
  std::vector<char> reached_;                            // the fluid has been at the point
  std::vector<double> guess_state_;                      // per point, warm start across topology changes
};

}  // namespace hfdda::fluid
