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
// fixed), plus the fracture's hydraulic width w0 when it has one, bounded below by w0,
// by the minimum widths (0.5 um inside the network, 0.1 um at tips) and by the closing
// limit (at most 5 % a step). Newton's method on the nodal unknowns then solves the
// coupled problem without stabilisation constants, with fallbacks where it stalls.
//
// Three parts:
// - FlowNetwork (this file, flow_network.cpp, flow_network_state.cpp): the network
//   (fractures, injections, the wetted set and the trial topology of a step), the
//   committed state, the mass ledger, the step API (begin_step, wet, solve, commit) and
//   checkpoints. It builds each step's TrialNetwork: end nodes, old masses, inflows,
//   leak-off volumes, floors and fill scales.
// - MassBalance (fluid/mass_balance.hpp): the step's mass balance as an operator,
//   residual and Jacobian at given unknowns.
// - MassBalanceSolver (fluid/mass_balance_solver.hpp): Newton, its step modes and the
//   fallback sequence; FlowSolveStatistics::restarts counts the fallbacks (why and with
//   what evidence: docs/design_notes.md sections 3 and 23).
//
// Units SI, per metre of out-of-plane thickness (h = 1 m in eq. 2.2-2.3).

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <functional>
#include <vector>

#include "fluid/aperture_model.hpp"
#include "fluid/mass_balance.hpp"
#include "fluid/mass_balance_solver.hpp"

namespace hfdda {
class BinaryWriter;
class BinaryReader;
}  // namespace hfdda

namespace hfdda::fluid {

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
  /// Compliance of the injection system (pump, lines and borehole) upstream of the
  /// fracture: at injection pressure p it holds rho(0) C p more fluid than at zero
  /// pressure, taken from the pump's flow while the pressure rises and given back as it
  /// falls. 0: a stiff system, all of the pump's flow enters the fracture [m^2/Pa, per
  /// metre of out-of-plane thickness].
  double system_compliance_m2_Pa = 0.0;

  /// Mass per metre injected from time 0 to t: the rate from start_time on, up to the limit.
  double mass_injected_by(double t_s) const {
    const double seconds = std::max(0.0, t_s - start_time_s);
    return std::min(mass_rate_kg_s * seconds, mass_limit_kg);
  }
};

class FlowNetwork {
 public:
  FlowNetwork(int n_points, std::vector<Fracture> fractures, FluidProperties fluid, FlowSettings settings);

  void add_injection(const Injection& injection);
  /// Before the first step: the fracture starts wetted, open by `width_m` and full of
  /// fluid at `pressure_Pa` (>= 0; mass rho(p) L w), its hydraulic width w0 (Fracture)
  /// full as well: w = width + w0, at least the minimum width.
  /// A point shared by fractures filled at different pressures takes the last one.
  void fill_initially(int fracture, double width_m, double pressure_Pa = 0.0);
  /// The same with an opening per end (point p, point q), each at least the minimum
  /// width of a tip (the caller gives a node that joins two fractures at least the
  /// larger minimum, as the floors of the trial network do): the rock's opening under
  /// the initial pressure (coupling/initial_opening.hpp).
  void fill_initially(int fracture, const std::array<double, 2>& end_width_m, double pressure_Pa);
  /// Points where the network meets a free edge of the rock, open to a reservoir at
  /// zero pressure (one flag per point): a node there stays at zero pressure, fills,
  /// and passes on what it cannot hold (vented_mass). Before the first step.
  void set_vents(std::vector<char> vent_points);

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
  /// Fluid mass that has left through the vents since t = 0 [kg].
  double vented_mass() const { return vented_kg_; }
  bool vent(int point) const { return !vent_point_.empty() && vent_point_[point] != 0; }
  /// Stored mass of the ledger: each node's mass is updated by what flowed in and out
  /// (old + injected - leaked - outflow), so this closes with injected - leaked by
  /// construction, whether or not the flow solve converged (and vented, with vents).
  double stored_mass() const;
  /// |initial + injected - stored - leaked - vented| / (initial + injected) with the ledger's
  /// stored mass; 0 without any fluid. A check of the bookkeeping only.
  double mass_balance_error() const;
  /// Fluid mass held by the committed state, computed without the ledger: per node the
  /// fill density of its committed state (rho(p) if full, rho(0) times the fill fraction
  /// if partly filled) times its volume sum L/2 w from the committed apertures [kg].
  double volume_stored_mass() const;
  /// |initial + injected - leaked - vented - volume_stored_mass| / (initial + injected); 0 without
  /// any fluid. Differs from mass_balance_error by the sum of the last solve's mass
  /// residuals, so it exposes an unconverged flow solve or apertures that do not match
  /// the fluid's (docs/design_notes.md, "Mass ledger and volume check").
  double volume_balance_error() const;
  /// Nodes of the committed network (points the fluid has reached).
  int n_nodes() const;
  const FluidProperties& fluid() const { return fluid_; }
  const FlowSettings& settings() const { return settings_; }
  /// Asked before every Newton iteration of the flow solve; true throws StepInterrupted.
  void interrupt_when(std::function<bool()> requested) { interrupt_ = std::move(requested); }

  /// Everything a later step depends on (committed state, the warm start of the last
  /// trial, the mass ledger), for a checkpoint; restore_state() into a network built
  /// the same way continues bit for bit (flow_network_state.cpp). Throws
  /// std::runtime_error on a mismatch.
  void save_state(BinaryWriter& out) const;
  void restore_state(BinaryReader& in);

 private:
  void rebuild_trial_topology();
  /// Per trial fracture: its length and hydraulic width, and the held-open floors of
  /// its ends from its floors (see TrialNetwork).
  void set_trial_fracture_data();
  /// Committed form of a trial node's fill state (MassBalance::state_of_unknown).
  double state_of_unknown(int node) const;

  std::vector<Fracture> fractures_;
  FluidProperties fluid_;
  FlowSettings settings_;
  std::function<bool()> interrupt_;
  std::vector<Injection> injections_;
  std::vector<char> vent_point_;  ///< per point, or empty: no vents

  // Committed state.
  double time_s_ = 0.0;
  std::vector<char> wetted_;
  std::vector<double> arrival_time_;     ///< per fracture: time it was wetted [s]
  std::vector<double> aperture_;         ///< per fracture end [m]
  std::vector<double> point_pressure_, point_mass_;
  double injected_kg_ = 0.0, leaked_kg_ = 0.0, vented_kg_ = 0.0;
  double initial_mass_ = 0.0;            ///< fluid present at t = 0 [kg]

  // Trial of the current step.
  std::vector<char> trial_wetted_;
  std::vector<int> trial_fractures_, trial_nodes_, node_of_point_;
  TrialNetwork trial_;  // what its mass balance needs: end nodes, masses, inflows, floors, dt
  Eigen::VectorXd unknowns_, pressure_, aperture_trial_, mass_new_, leak_mass_, vent_mass_;  // per trial node or end
  std::vector<double> point_state_;                      // per point: pressure [Pa] if full, else fill fraction - 1
  std::vector<char> reached_;                            // the fluid has been at the point
  std::vector<double> guess_state_;                      // per point, warm start across topology changes
};

}  // namespace hfdda::fluid
