#pragma once
// Checkpoints of a run (DIR/checkpoint.bin): everything the next step depends on, so
// that a run continued from one produces the same numbers, bit for bit, as a run that
// was never stopped. Layout (native byte order, doubles as their bytes):
//   "HFDDA-CK" | format version | fingerprint of the case | step, time, wall time |
//   run totals | history columns and rows | .pvd datasets | block system state |
//   flow network state (if any) | load ramp state (if any) | "HFDDA-END"
// The file is written to a temporary name and renamed, so it is always whole.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/step_statistics.hpp"
#include "simulation/model.hpp"
#include "simulation/run_record.hpp"

namespace hfdda::simulation {

// 2: load ramp keeps the contact states of its last level; 3: and its crack tips; 4: vented fluid mass
constexpr std::uint32_t kCheckpointVersion = 4;

/// Where the run stands after a committed step, besides the model's state.
struct RunProgress {
  int step = 0;              ///< steps completed
  double time_s = 0.0;       ///< simulated time reached
  double wall_s = 0.0;       ///< wall time spent so far (over every part of a restarted run)
  StepStatistics totals;     ///< accumulated over the completed steps
  RunRecord record;          ///< history rows so far
  std::vector<std::pair<double, std::string>> blocks_pvd, joints_pvd;  ///< VTU datasets so far
};

/// The checkpoint file of a run directory.
std::string checkpoint_path(const std::string& run_dir);

/// 64-bit FNV-1a over the text of the case file and of every file it extends (followed
/// through its `extends:` lines), and the mesh (sizes and initial corners): a restart
/// with a different case is refused.
std::uint64_t case_fingerprint(const Model& model);

/// Writes the model's state and the progress atomically. Throws std::runtime_error.
void write_checkpoint(const std::string& path, const Model& model, const RunProgress& progress);

/// Restores the model (freshly built from the same case) from a checkpoint and returns
/// the progress. Throws std::runtime_error for a missing, truncated or foreign file, a
/// different format version or a different case.
RunProgress read_checkpoint(const std::string& path, Model& model);

}  // namespace hfdda::simulation
