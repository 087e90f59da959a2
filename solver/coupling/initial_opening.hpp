#pragma once
// Fractures that start full of fluid, in equilibrium with it (fractures[].initial_opening:
// elastic).
//
// A fluid-filled fracture given only an initial width holds fluid that the rock does not
// hold open: at t = 0 the blocks have not moved, the faces touch, and in the first steps
// the fluid is squeezed out while the closing limit (seed 2.1: at most 5 % of an aperture
// a step) keeps the joints on their floors, where only the fluid's compressibility
// answers a change of pressure (docs/design_notes.md sections 23 and 31). Instead, the
// rock is first brought to equilibrium with the initial pressure: mechanics steps before
// t = 0 with that pressure prescribed on the faces of the fluid-filled joints (trapezoidal
// face loads, seed 2.4) and the open-close iterations of any step, so that faces the
// pressure of a neighbour presses together close; the fractures then hold the volume
// these steps open, at the initial pressure.
//
// One such step is not yet a state the next step leaves alone: the faces start it
// touching and unloaded, so a contact that slides in it carries no friction (tan phi
// times the normal force at the step's start, eq. 2.16), and the first step of the run
// then applies friction the start did not have. The steps are repeated until none of
// the pressurised joint ends moves by more than kSettledChange of its aperture (the
// settled state: less than the closing limit's 5 %, so the first step starts off its
// floors), at most kMaxSettlingSteps times; should the changes grow instead of fall,
// the state before the growing step is put back (docs/design_notes.md section 31).

#include <array>
#include <vector>

#include "core/step_statistics.hpp"
#include "dda/block_system.hpp"
#include "fracture/fracture_criteria.hpp"

namespace hfdda::coupling {

/// A joint and the fluid pressure on its faces at t = 0.
struct PressurisedJoint {
  int joint = -1;
  double pressure_Pa = 0.0;
};

/// Largest change of a pressurised joint end between two steps before t = 0, relative to
/// its aperture (or to the width floor, for ends that barely open), at which the start
/// counts as settled.
inline constexpr double kSettledChange = 0.01;
/// Steps before t = 0 at most (the first included).
inline constexpr int kMaxSettlingSteps = 10;

/// What the steps before t = 0 did.
struct InitialOpening {
  /// Aperture [m] of both ends (point p, point q) of each joint, in the order given: the
  /// normal separation of its faces after the steps (may be <= 0 where faces closed).
  std::vector<std::array<double, 2>> apertures_m;
  StepStatistics step;  ///< summed over the steps kept
  int steps = 0;        ///< steps kept (committed and not put back)
  /// Largest change of an end in the last step kept, relative to max(|aperture|, the
  /// width floor); NaN after a single step (nothing to compare it with).
  double last_relative_change = 0.0;
  bool settled = false;  ///< last_relative_change <= kSettledChange
  bool growing = false;  ///< the changes grew and the step that grew them was put back
};

/// Commits steps of dt_s of the block system with the pressures on the faces of these
/// joints (a point shared by joints at different pressures takes the largest) and the
/// case's other loads, each cut back up to max_step_cuts times like any step, until
/// settled (see the file comment). width_floor_m [m] (> 0) is the aperture below which
/// changes are measured against it rather than against the end's own aperture. Throws
/// ConvergenceError if a step does not converge (the system then holds the sub-steps that
/// did).
InitialOpening open_by_initial_pressure(dda::BlockSystem& system, const std::vector<PressurisedJoint>& joints,
                                        double dt_s, int max_step_cuts, const fracture::FractureRules& rules,
                                        double width_floor_m);

}  // namespace hfdda::coupling
