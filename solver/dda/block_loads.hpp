#pragma once
// External loads and constraints of the blocks (SI, per metre of out-of-plane
// thickness): fixed points (stiff springs to an anchor), point loads, far-field
// tractions on boundary edges and a body force.

#include <vector>

#include "dda/block_kinematics.hpp"

namespace hfdda::dda {

struct ExternalLoads {
  struct PointAttachment {   // a fixed point or point load attached to a block
    int block;
    Vec2 position;           // current position [m]
    Vec2 anchor;             // fixed points: where the point must stay [m]
    Vec2 force_N;
  };
  struct BoundaryStress {
    int boundary_edge;
    Eigen::Matrix2d stress_Pa;
  };

  std::vector<PointAttachment> fixed_points, point_loads;
  std::vector<BoundaryStress> boundary_stresses;
  /// Ramped far-field tractions: stress per unit of the load level (dimensionless), scaled
  /// by `ramp_level_Pa` (seed 4.2-4.4: stresses incremented until failure).
  std::vector<BoundaryStress> ramped_boundary_stresses;
  double ramp_level_Pa = 0.0;
  Vec2 body_force{0, 0};
};

}  // namespace hfdda::dda
