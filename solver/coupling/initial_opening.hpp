#pragma once
// Fractures that start full of fluid, in equilibrium with it (fractures[].initial_opening:
// elastic).
//
// A fluid-filled fracture given only an initial width holds fluid that the rock does not
// hold open: at t = 0 the blocks have not moved, the faces touch, and in the first steps
// the fluid is squeezed out while the closing limit (seed 2.1: at most 5 % of an aperture
// a step) keeps the joints on their floors, where only the fluid's compressibility
// answers a change of pressure (docs/design_notes.md sections 23 and 31). Instead, the
// rock is first brought to equilibrium with the initial pressure: one mechanics step
// before t = 0 with that pressure prescribed on the faces of the fluid-filled joints
// (trapezoidal face loads, seed 2.4) and the open-close iterations of any step, so that
// faces the pressure of a neighbour presses together close; the fractures then hold the
// volume this step opens, at the initial pressure.

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

/// What the step before t = 0 did.
struct InitialOpening {
  /// Aperture [m] of both ends (point p, point q) of each joint, in the order given: the
  /// normal separation of its faces after the step (may be <= 0 where faces closed).
  std::vector<std::array<double, 2>> apertures_m;
  StepStatistics step;
};

/// Commits one step of dt_s of the block system with the pressures on the faces of these
/// joints (a point shared by joints at different pressures takes the largest) and the
/// case's other loads, cut back up to max_step_cuts times like any step. Throws
/// ConvergenceError if it does not converge (the system then holds the sub-steps that did).
InitialOpening open_by_initial_pressure(dda::BlockSystem& system, const std::vector<PressurisedJoint>& joints,
                                        double dt_s, int max_step_cuts, const fracture::FractureRules& rules);

}  // namespace hfdda::coupling
