#pragma once
// Checks made after every time step that the computed fields are finite numbers: block
// corners (displacements) and stresses, joint apertures and fluid pressures. A NaN or
// infinity would otherwise be written to every later output without complaint.

#include <string>

namespace hfdda::dda {
class BlockSystem;
}
namespace hfdda::fluid {
class FlowNetwork;
}

namespace hfdda::simulation {

/// Throws ConvergenceError naming the first non-finite quantity found, where it is (block,
/// joint or fluid node with its coordinates) and `step`; the caller keeps the outputs
/// written so far. `flow` may be null (no flow network).
void check_fields_finite(const dda::BlockSystem& system, const fluid::FlowNetwork* flow, int step);

}  // namespace hfdda::simulation
