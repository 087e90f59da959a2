#pragma once
// Conditions that end a time-stepping run before its end time (time.stop_when).

#include <vector>

#include "dda/block_system.hpp"
#include "io/case_config.hpp"

namespace hfdda::simulation {

/// Per mesh point: it lies on the boundary of domain.inner, the edge of the block being
/// fractured (within 1e-9 of the domain size). Empty without domain.inner.
std::vector<char> inner_boundary_points(const mesh::Mesh& mesh, const io::CaseConfig& config);

/// time.stop_when: fracture_at_edge. A joint whose bond has broken at either end touches
/// a point of `edge_points`: in a laboratory block the fluid would now escape (seed 5.2).
bool fracture_at_edge(const dda::BlockSystem& system, const std::vector<char>& edge_points);

}  // namespace hfdda::simulation
