#pragma once
// One time step of a case: the blocks, with the fluid network when the case has one,
// and the step cut-back that retries a step that did not converge (seed 2.4).

#include <string>

#include "core/step_statistics.hpp"
#include "coupling/hydro_mechanical_coupling.hpp"
#include "dda/block_system.hpp"

namespace hfdda::coupling {

class CoupledStep {
 public:
  /// `flow` may be null (mechanics alone). Both must outlive the step object.
  CoupledStep(dda::BlockSystem& mechanics, HydroMechanicalCoupling* flow, bool trace_cuts = false);

  /// Advances by dt. A step that does not converge is cut in two halves, recursively
  /// up to `max_step_cuts` levels deep; the statistics of every sub-step are summed.
  /// Throws the last ConvergenceError if even the smallest sub-step fails (the
  /// committed state is then the last converged sub-step).
  StepStatistics advance(double dt_s, int max_step_cuts);

 private:
  void advance_into(double dt_s, int cuts_left, StepStatistics& stats);

  dda::BlockSystem& mechanics_;
  HydroMechanicalCoupling* flow_;
  bool trace_cuts_;
};

}  // namespace hfdda::coupling
