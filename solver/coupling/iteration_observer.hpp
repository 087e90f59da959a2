#pragma once
// What a coupled step's open-close iterations did, one record per iteration, for a user
// who needs to see where a run's contact iterations go astray (`hfdda run
// --trace-iterations`, DIR/iterations.csv; docs/design_notes.md section 39).

#include <string>

namespace hfdda::coupling {

/// One open-close iteration (seed 2.4, Figure 2.8) of one attempt at a step. Counts are
/// those of the attempt so far, except the changes, which are this iteration's.
struct IterationRecord {
  double attempt_dt_s = 0.0;   ///< the attempt's time step (a cut step's half, quarter, ...)
  int iteration = 0;           ///< 1, 2, ... within the attempt
  int contact_changes = 0;     ///< contact state changes and bond failures applied now
  int coupled_changes = 0;     ///< changes the fluid models made (joints wetted, ...)
  int bonds_broken = 0;        ///< bonds broken since the attempt began
  int cycle_holds = 0;         ///< changes refused by the cycle rule since the attempt began
  int mechanism_blocks = 0;    ///< largest group held as a mechanism in the attempt
  /// The trial displacement's worst joint overlap, as a fraction of the joint's length,
  /// and its joint (-1: none); the guard of design notes section 24 judges this at the end.
  double overlap_fraction = 0.0;
  int overlap_joint = -1;
  /// The trial displacement's largest principal strain of a block, and the block (-1:
  /// none); the guard of design notes section 30 judges this at the end.
  double block_strain = 0.0;
  int strain_block = -1;
  std::string first_change;    ///< the first change applied now ("" if none)
};

/// Told about each iteration and the end of each attempt of CoupledStep::advance.
class IterationObserver {
 public:
  virtual ~IterationObserver() = default;
  virtual void iteration(const IterationRecord& record) = 0;
  /// The attempt of `dt_s` ended after `iterations` open-close iterations; `refusal` is
  /// empty if it converged and was committed, else why it was refused (it is then cut).
  virtual void attempt_ended(double dt_s, int iterations, const std::string& refusal) = 0;
};

}  // namespace hfdda::coupling
