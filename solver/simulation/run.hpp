#pragma once
// The time loop of a case and its run directory (contract in io/output.hpp).

#include <functional>
#include <string>

#include "simulation/model.hpp"

namespace hfdda::simulation {

struct RunOptions {
  std::string output_dir;   ///< run directory; created if missing
  bool quiet = false;       ///< no progress display
  bool write_vtu = true;    ///< overrides nothing when the case disables VTU
};

/// Totals over the run (also written to summary.json).
struct RunTotals {
  int steps = 0;
  int open_close_iterations = 0, alm_iterations = 0, alm_stalls = 0, factorizations = 0;
  double max_alm_stall_mismatch = 0.0;  ///< largest gap / contact length accepted at an ALM stall
  int bonds_broken = 0, vertex_vertex_activations = 0, max_active_vertex_vertex = 0;
  double seconds_assembly = 0.0, seconds_factorization = 0.0, seconds_solve = 0.0;
};

struct RunResult {
  bool completed = false;   ///< false: a step did not converge (outputs so far are kept)
  std::string message;      ///< why it stopped, if it did not complete
  double time_s = 0.0;      ///< simulated time reached
  double wall_seconds = 0.0;
  RunTotals totals;
};

/// Per-step counters of the fluid coupling, summed over the sub-steps of a cut step.
struct FlowStepCounters {
  int fractures_wetted = 0, newton_iterations = 0, newton_restarts = 0, step_cuts = 0;
  double max_relative_residual = 0.0;
  double seconds_sensitivity = 0.0;  ///< building S = J K^-1 B
  double seconds_flow = 0.0;         ///< flow solves and the blocks' pressure response
};

/// One (coupled) step of length dt; a step that does not converge is cut in two
/// halves, up to `cuts_left` times deep. Statistics are added to `stats` and
/// `counters`. Rethrows the last ConvergenceError if even the smallest step fails.
void advance(Model& model, double dt_s, int cuts_left, dda::StepStatistics& stats, FlowStepCounters& counters);

/// Runs the case to its end time, writing history.csv every step, joint CSV and VTU
/// at output steps and at the end, and summary.json. A step that fails to converge
/// ends the run with completed = false; everything up to the last committed step is
/// written, including joints_final.csv.
RunResult run(Model& model, const RunOptions& options);

}  // namespace hfdda::simulation
