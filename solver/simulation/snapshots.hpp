#pragma once
// Views of the committed block-system state in the output contract's shapes.

#include <vector>

#include "dda/block_system.hpp"
#include "fluid/flow_network.hpp"
#include "io/output.hpp"

namespace hfdda::simulation {

/// The blocks' corners, displacements, stresses and materials; with `zone_of_material`
/// (Model::zone_of_material), the material written is the zone of the case.
io::BlockFrame block_frame(const dda::BlockSystem& system, const std::vector<int>& zone_of_material = {});
/// One row per joint; with a flow network, "fluid" marks the joints it has wetted,
/// without one the joints with a prescribed pressure.
std::vector<io::JointRow> joint_rows(const dda::BlockSystem& system, const fluid::FlowNetwork* flow = nullptr);

/// Aperture at each geometric point along a set of joints: mean of the face
/// separations the joints report at that point (>= 0). Returns (point, aperture) pairs.
std::vector<std::pair<int, double>> apertures_at_points(const dda::BlockSystem& system, const std::vector<int>& joints);

}  // namespace hfdda::simulation
