#pragma once
// The time loop of a case and its run directory (contract in io/output.hpp).

#include <functional>
#include <string>

#include "core/step_statistics.hpp"
#include "simulation/model.hpp"
#include "simulation/run_record.hpp"

namespace hfdda::simulation {

struct RunOptions {
  std::string output_dir;   ///< run directory; created if missing
  bool quiet = false;       ///< no progress display
  bool write_vtu = true;    ///< overrides nothing when the case disables VTU
  /// A checkpoint (simulation/checkpoint.hpp) every this many steps; 0: none, except
  /// when a stop is requested (the CLI's default is 10).
  int checkpoint_every = 0;
  /// Continue from the checkpoint in output_dir (the model must be freshly built).
  bool restart = false;
  /// Asked after every step; true: write a checkpoint and stop (RunResult::interrupted).
  std::function<bool()> stop_requested{};
  /// Asked within a step of a time-stepped run (not a load ramp), before each of its
  /// open-close and contact iterations; true abandons the step (its attempt rolled back, unless a sub-step of a cut step was
  /// already committed: the step is then finished), writes a checkpoint of the step
  /// before and stops (RunResult::interrupted). A step can take minutes.
  std::function<bool()> abandon_step_requested{};
  /// false: nothing is written (no directory, history, joints, VTU, summary or
  /// checkpoint); the rows stay in RunResult::record. An ensemble realisation runs so.
  bool write_files = true;
  /// Also write DIR/iterations.csv, a row per open-close iteration and per attempt
  /// (simulation/iteration_trace.hpp); needs write_files.
  bool trace_iterations = false;
  /// Called after every completed step with the model at its end, the step and the time.
  std::function<void(const Model&, int step, double time_s)> after_step{};
};

struct RunResult {
  bool completed = false;   ///< false: a step did not converge, or the run was interrupted
  bool interrupted = false; ///< stopped on request after or within a step, with a checkpoint
  std::string message;      ///< why it stopped, if it did not complete
  /// Completed runs: "end_time" or "load_ramp" at their end, or the time.stop_when
  /// condition that ended them early ("fluid_at_edge").
  std::string stop_reason;
  int steps = 0;            ///< steps completed
  double time_s = 0.0;      ///< simulated time reached
  double wall_seconds = 0.0;
  StepStatistics totals;    ///< accumulated over the completed steps
  RunRecord record;         ///< history.csv in memory: one row per completed step
};

/// Runs the case to its end time, writing history.csv every step (and keeping the same
/// rows in RunResult::record; columns in simulation/run_record.hpp), joint CSV and VTU
/// at output steps and at the end, and summary.json. A step that fails to converge
/// ends the run with completed = false; everything up to the last committed step is
/// written, including joints_final.csv. With options.restart, the model, the run's
/// totals, history rows and .pvd lists come from the checkpoint and the loop goes on
/// from the step after it; history.csv is rewritten with the checkpoint's rows first.
/// Throws std::runtime_error if the checkpoint cannot be used.
RunResult run(Model& model, const RunOptions& options);

}  // namespace hfdda::simulation
