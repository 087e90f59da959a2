#pragma once
// The fluid part of build_model (simulation/model.cpp): the flow network over the joints,
// its initially filled fractures, injections, vents and probes, and the fractures that
// start in equilibrium with their fluid (initial_opening: elastic). Internal to
// simulation/.

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "coupling/initial_opening.hpp"
#include "simulation/model.hpp"

namespace hfdda::simulation::detail {

/// "(x, y)" for messages about mesh points.
inline std::string format_point(const Vec2& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

/// The larger side of the outer domain [m]: the scale of the mesh-point tolerances.
inline double domain_size(const io::CaseConfig& c) {
  return std::max(c.domain.outer.width(), c.domain.outer.height());
}

/// What build_flow_network leaves for open_by_initial_pressure.
struct InitialFill {
  /// Joints of fractures with initial_opening: elastic, not yet filled.
  std::vector<coupling::PressurisedJoint> opened_by_fluid;
  /// Per mesh point: how many fluid-filled joints end there.
  std::vector<int> filled_joints_at;
};

/// Builds model.flow and model.coupling (seed 2.1, 3.2) and fills the fractures given an
/// initial width; needs model.system, the fractures and the case.
InitialFill build_flow_network(Model& model, const io::CaseConfig& c);

/// initial_opening: elastic (coupling/initial_opening.hpp): the rock brought to
/// equilibrium with the initial pressure of the joints by a step before t = 0, which stays
/// committed (the run starts from the opened rock), and the joints filled with the volume
/// it opened. A pressure that breaks bonds or that the step cannot balance is an error of
/// the case (ModelError), not a start.
void open_by_initial_pressure(Model& model, const InitialFill& fill);

}  // namespace hfdda::simulation::detail
