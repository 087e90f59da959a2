#pragma once
// The mass balance of one step's trial network (seed 2.1, eq. 2.5-2.7) as an operator:
// given the network's data (TrialNetwork) and the nodal unknowns, the apertures, the
// stored masses, the residual per node and its Jacobian. No iteration here: Newton and
// its fallbacks are in fluid/mass_balance_solver.hpp, the network and its committed
// state in fluid/flow_network.hpp (whose header states the equations).
//
// Per node i, over a step t -> t + dt:
//
//   R_i = M_i(t+dt) - M_i(t) + lambda (f_i rho_i Vleak_i - I_i) + lambda dt sum_j eta_ij (p_i - p_j)
//
// where M_i = rho V_i, plus rho(0) C_i p_i at a node fed by an injection system of
// compliance C_i (the pump, lines and borehole upstream of the fracture).
//
// with f_i the wetted fraction of the node's walls and lambda the homotopy scale (1 but
// in continuation). The unknown y of a node is its fill state: the pressure max(y, 0)
// of a full node for y >= 0, a zero-pressure node filled to 1 + y / P for y < 0. The
// corners of max(y, 0) and of the aperture floors max(w, floor) are rounded so that
// the residual is C1 (docs/design_notes.md section 2).
//
// A vent node (where the network meets a free edge of the rock, open to a reservoir at
// zero pressure) is at zero pressure whatever its fill: its fill state runs on past
// full (y > 0), and the mass beyond full, rho(0) V y / P, leaves through the vent
// instead of being stored. The node fills at zero pressure first and vents only what
// it cannot hold (never takes fluid in from outside), and its mass balance stays
// smooth across full (docs/design_notes.md section 27).
//
// Units SI, per metre of out-of-plane thickness.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <vector>

#include "fluid/aperture_model.hpp"

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

/// One step's trial network as its mass balance sees it: the nodes each wetted fracture
/// joins, and per node and fracture end what the step brings. FlowNetwork fills it for
/// each trial topology; the solver changes only fill_scale_Pa (the path Newton takes),
/// floor_m (the last resort) and homotopy (continuation).
struct TrialNetwork {
  // Per trial fracture k: its end 2k is at node_a[k], its end 2k + 1 at node_b[k].
  std::vector<int> node_a, node_b;
  std::vector<double> length_m;
  // Per trial node.
  Eigen::VectorXd old_mass_kg;     ///< stored at the start of the step
  Eigen::VectorXd injected_kg;     ///< injected over the step
  Eigen::VectorXd leak_volume_m3;  ///< Carter leak-off of its walls over the step, if all wetted
  Eigen::VectorXd fill_scale_Pa;   ///< P of the fill state (only shapes Newton's path)
  std::vector<char> vent;          ///< vent node: held at zero pressure, its excess leaves
  /// Compliance C of an injection system feeding the node (Injection): it stores
  /// rho(0) C p besides the node's fractures [m^2/Pa]. Empty: none anywhere.
  Eigen::VectorXd system_compliance_m2_Pa;
  // Per trial end.
  Eigen::VectorXd floor_m;            ///< lower bound of the aperture
  Eigen::VectorXd hydraulic_width_m;  ///< w0 of its fracture
  /// The floor with the closing joints held open for the step (the committed aperture
  /// of a wetted end if larger): the solver's last resort.
  Eigen::VectorXd held_open_floor_m;
  double dt_s = 0.0;
  /// Scale of the step's inflows, leak-off and flow in the mass balance (1 except
  /// during continuation), and the flow's time factor it gives.
  double homotopy = 1.0;
  double flow_dt() const { return homotopy * dt_s; }

  int n_nodes() const { return static_cast<int>(old_mass_kg.size()); }
  int n_fractures() const { return static_cast<int>(node_a.size()); }
};

class MassBalance {
 public:
  /// Half-width of the rounded corner of the pressure max(y, 0) [Pa].
  static constexpr double kPressureRounding = 1.0e3;

  struct Evaluation {
    /// storage: the mass a node's fill state accounts for (at a vent node including
    /// what leaves through it); vented: the part of it that leaves through a vent.
    Eigen::VectorXd pressure, pressure_slope, density, aperture, volume, storage, vented, residual, eta;
    /// Per node (with the Jacobian only): rho' V + dt sum eta, the slope of a full node's
    /// mass balance in its own pressure from storage and flow to its neighbours.
    Eigen::VectorXd conductance;
    Eigen::VectorXd slope;  // per end: d aperture / d mechanical aperture (0 on the floor, 1 above it)
    /// The Jacobian in the unknowns is local + coupling S diag(pressure_slope)
    /// (fluid/aperture_model.hpp): local (n x n) holds every term at fixed apertures,
    /// coupling (n x 2 nf) how each end's aperture enters the nodes' mass balances.
    Eigen::SparseMatrix<double> local, coupling;
  };

  /// A view: both are read at each evaluation, so changes to the network show.
  MassBalance(const FluidProperties& fluid, const TrialNetwork& network) : fluid_(fluid), network_(network) {}

  /// Apertures w = base + S p (floored), storage and residual at the unknowns x; the
  /// Jacobian as well if asked for.
  void evaluate(const Eigen::VectorXd& unknowns, const Eigen::VectorXd& base, const ApertureModel& s,
                Evaluation& out, bool with_jacobian) const;
  /// Mass per volume of a node in fill state y (stored, and at a vent node vented as
  /// well), and its derivative in y.
  double fill_density(double y, int node) const;
  double fill_density_slope(double y, int node) const;
  /// Fraction of a node's fracture walls that the fluid wets in fill state y (1 if full).
  double wetted_fraction(double y, int node) const;
  /// Committed form of a node's fill state y: the pressure [Pa] if full (0 at a vent),
  /// else the fill fraction minus one, in [-1, 0) (independent of the fill scale).
  double state_of_unknown(double y, int node) const;
  /// Mass scale of the convergence test: mass present plus mass injected in the step [kg].
  double mass_scale() const;
  /// Round-off of the step's mass balance [kg]: 64 eps times its largest terms.
  double residual_round_off() const;
  bool is_vent(int node) const { return !network_.vent.empty() && network_.vent[node] != 0; }
  /// rho(0) C of the node's injection system [kg/Pa] (0 without one).
  double system_storage_slope(int node) const {
    return network_.system_compliance_m2_Pa.size() == 0 ? 0.0
                                                         : fluid_.density(0.0) * network_.system_compliance_m2_Pa[node];
  }

 private:
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

  const FluidProperties& fluid_;
  const TrialNetwork& network_;
};

}  // namespace hfdda::fluid
