#pragma once
// Conditions that end a time-stepping run before its end time (time.stop_when).

#include <vector>

#include "fluid/flow_network.hpp"
#include "mesh/mesh.hpp"
#include "io/case_config.hpp"

namespace hfdda::simulation {

/// Per mesh point: it lies on the boundary of domain.inner, the edge of the block being
/// fractured (within 1e-9 of the domain size). Empty without domain.inner.
std::vector<char> inner_boundary_points(const mesh::Mesh& mesh, const io::CaseConfig& config);

/// time.stop_when: fluid_at_edge. A joint holding fluid touches a point of `edge_points`:
/// in a laboratory block the fluid would now escape (seed 5.2). (Not a joint that merely
/// broke: a critically stressed natural fracture may slip to the edge without fluid.)
bool fluid_at_edge(const fluid::FlowNetwork& flow, const mesh::Mesh& mesh, const std::vector<char>& edge_points);

}  // namespace hfdda::simulation
