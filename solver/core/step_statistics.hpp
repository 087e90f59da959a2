#pragma once
// Counters and timings of one time step: the single statistics record of the solver.
// The mechanics (open-close and contact iterations) and the fluid coupling fill their
// parts during a step; a step cut into sub-steps, and a whole run, accumulate them
// with accumulate(). history.csv, summary.json and the in-memory run record are all
// made from this one struct.

#include <algorithm>

namespace hfdda {

struct StepStatistics {
  // --- mechanics (seed 2.2-2.3) --------------------------------------------------
  int open_close_iterations = 0;
  int alm_iterations = 0;           ///< linear solves of the contact iterations
  int alm_stalls = 0;               ///< ALM solves ended by the stall test (inconsistent contact loops)
  double max_alm_stall_mismatch = 0.0;  ///< largest gap / contact length accepted at a stall
  /// Contact solves in which the friction of sliding penalty contacts still followed its
  /// normal force after kMaxFrictionIterations iterates and was frozen at the last one.
  int friction_iterations_frozen = 0;
  /// Largest ||D(m+1) - D(m)|| / ||D(m+1)|| over the last ALM iteration of each solve
  /// (reported; the stop test is on the contact forces, see docs/seed_errata.md, erratum 2).
  double max_alm_displacement_change = 0.0;
  int factorizations = 0;
  /// Assemblies of K applied to the step's factorisation as a low-rank correction
  /// instead (numerics.low_rank_updates), the springs they changed, and corrections
  /// dropped by their check solve.
  int low_rank_updates = 0, low_rank_terms = 0, low_rank_rejections = 0;
  int bonds_broken = 0;
  int state_changes = 0;            ///< contact state changes applied
  /// Changes refused to contacts caught in an open-close cycle (over max_state_flips in a
  /// step), each resolved by the most open state it had in the step (seed 5.1).
  int cycle_holds = 0;
  int steps_with_cycles = 0;        ///< (sub-)steps that ended with a contact held on a cycle
  /// Largest number of blocks that one assembly of K held as a mechanism (groups the
  /// contact state leaves a rigid motion; dda/mechanism_holds.cpp).
  int max_mechanism_blocks = 0;
  int coupled_state_changes = 0;    ///< fractures newly wetted by the fluid (outer iterations)
  int vertex_vertex_activations = 0;
  int active_vertex_vertex = 0;     ///< active at the end of the (last) step
  int max_active_vertex_vertex = 0; ///< largest active count at the end of a step
  double max_penetration_m = 0.0;
  double max_block_strain = 0.0;    ///< largest principal strain increment of a block, accepted steps
  /// Largest tension on a closed joint contact whose bond is broken, accepted steps [Pa]
  /// (dda::BlockSystem::largest_unbonded_tension_Pa).
  double max_unbonded_tension_Pa = 0.0;

  // --- fluid coupling (seed 2.1, 2.4) ---------------------------------------------
  int step_cuts = 0;                ///< halvings of the step after a failed attempt
  int fractures_wetted = 0;
  int flow_solves = 0;              ///< one per contact iteration of a coupled step
  int flow_newton_iterations = 0;
  int flow_newton_restarts = 0;     ///< flow solves that needed a fallback start
  long flow_krylov_iterations = 0;  ///< GMRES iterations of the flow Newton (flow_jacobian: krylov)
  long flow_inexact_linear_solves = 0;  ///< GMRES solves stopped at their limit (inexact Newton steps)
  int max_flow_nodes = 0;
  double max_flow_residual = 0.0;   ///< largest relative mass residual of a flow solve
  int sensitivity_builds = 0;       ///< S = J K^-1 B built by its solves
  int sensitivity_corrections = 0;  ///< S corrected for low-rank changes of K instead

  // --- wall-clock time [s] ----------------------------------------------------------
  double seconds_assembly = 0.0, seconds_factorization = 0.0, seconds_solve = 0.0;
  double seconds_low_rank = 0.0;     ///< low-rank corrections of K's factorisation and their checks
  double seconds_sensitivity = 0.0;  ///< building S = J K^-1 B
  double seconds_flow = 0.0;         ///< flow solves and the blocks' response to the pressures
  double seconds_total = 0.0;

  /// Adds a later part of the same span (a sub-step of a cut step, or a step of a run):
  /// counts and times add up, maxima take the larger value, and the active
  /// vertex-vertex count is the later one's.
  void accumulate(const StepStatistics& later) {
    open_close_iterations += later.open_close_iterations;
    alm_iterations += later.alm_iterations;
    alm_stalls += later.alm_stalls;
    friction_iterations_frozen += later.friction_iterations_frozen;
    max_alm_stall_mismatch = std::max(max_alm_stall_mismatch, later.max_alm_stall_mismatch);
    max_alm_displacement_change = std::max(max_alm_displacement_change, later.max_alm_displacement_change);
    factorizations += later.factorizations;
    low_rank_updates += later.low_rank_updates;
    low_rank_terms += later.low_rank_terms;
    low_rank_rejections += later.low_rank_rejections;
    bonds_broken += later.bonds_broken;
    state_changes += later.state_changes;
    cycle_holds += later.cycle_holds;
    steps_with_cycles += later.steps_with_cycles;
    max_mechanism_blocks = std::max(max_mechanism_blocks, later.max_mechanism_blocks);
    coupled_state_changes += later.coupled_state_changes;
    vertex_vertex_activations += later.vertex_vertex_activations;
    active_vertex_vertex = later.active_vertex_vertex;
    max_active_vertex_vertex = std::max(max_active_vertex_vertex, later.max_active_vertex_vertex);
    max_penetration_m = std::max(max_penetration_m, later.max_penetration_m);
    max_block_strain = std::max(max_block_strain, later.max_block_strain);
    max_unbonded_tension_Pa = std::max(max_unbonded_tension_Pa, later.max_unbonded_tension_Pa);
    step_cuts += later.step_cuts;
    fractures_wetted += later.fractures_wetted;
    flow_solves += later.flow_solves;
    flow_newton_iterations += later.flow_newton_iterations;
    flow_newton_restarts += later.flow_newton_restarts;
    flow_krylov_iterations += later.flow_krylov_iterations;
    flow_inexact_linear_solves += later.flow_inexact_linear_solves;
    max_flow_nodes = std::max(max_flow_nodes, later.max_flow_nodes);
    max_flow_residual = std::max(max_flow_residual, later.max_flow_residual);
    sensitivity_builds += later.sensitivity_builds;
    sensitivity_corrections += later.sensitivity_corrections;
    seconds_assembly += later.seconds_assembly;
    seconds_factorization += later.seconds_factorization;
    seconds_low_rank += later.seconds_low_rank;
    seconds_solve += later.seconds_solve;
    seconds_sensitivity += later.seconds_sensitivity;
    seconds_flow += later.seconds_flow;
    seconds_total += later.seconds_total;
  }
};

}  // namespace hfdda
