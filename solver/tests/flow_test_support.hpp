#pragma once
// Shared by the flow-network tests: water at 20 C and a solve with rigid walls.

#include <Eigen/Dense>

#include "fluid/flow_network.hpp"

namespace hfdda::fluid::testing {

inline FluidProperties water() {
  FluidProperties f;
  f.density_kg_m3 = 1000.0;
  f.bulk_modulus_Pa = 2.2e9;
  f.viscosity_Pa_s = 1.0e-3;
  return f;
}

/// Rigid walls: every wetted end keeps aperture `w` whatever the pressure.
inline void solve_rigid(FlowNetwork& net, double w) {
  const int ends = 2 * static_cast<int>(net.trial_fractures().size());
  const int nodes = static_cast<int>(net.trial_nodes().size());
  net.solve(Eigen::VectorXd::Constant(ends, w), Eigen::MatrixXd::Zero(ends, nodes));
}

}  // namespace hfdda::fluid::testing
