#pragma once
// DIR/iterations.csv of `hfdda run --trace-iterations`: one row per open-close iteration
// of every attempt at every step, and one row per attempt's end (committed, or refused
// and cut, with the reason), so that a run whose contact iterations go astray shows
// where, when and how (docs/design_notes.md section 39).
//
// Columns: step, step_start_s, attempt_dt_s, row ("iteration" or "attempt"), iteration
// (the attempt's iterations on its "attempt" row), contact_changes, coupled_changes,
// bonds_broken, cycle_holds, mechanism_blocks, overlap_fraction, overlap_joint,
// block_strain, strain_block, text (the iteration's first change, or "committed", or
// why the attempt was refused). Text is quoted as CSV; numbers are empty on attempt rows.

#include <fstream>
#include <string>

#include "coupling/iteration_observer.hpp"

namespace hfdda::simulation {

class IterationTrace final : public coupling::IterationObserver {
 public:
  /// Creates `path` with its header; for a run restarted after step `restarted_after`
  /// (>= 0) keeps the rows of the steps up to it that `path` holds and drops the later
  /// ones, which the stopped run wrote after its checkpoint and the restart does again.
  IterationTrace(const std::string& path, int restarted_after = -1);
  /// The step that the next iterations belong to and the time it starts at [s].
  void begin_step(int step, double start_s) {
    step_ = step;
    start_s_ = start_s;
  }
  void iteration(const coupling::IterationRecord& record) override;
  void attempt_ended(double dt_s, int iterations, const std::string& refusal) override;

 private:
  void write(const std::string& line);
  std::ofstream out_;
  std::string path_;
  int step_ = 0;
  double start_s_ = 0.0;
};

}  // namespace hfdda::simulation
