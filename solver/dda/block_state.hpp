#pragma once
// Committed state of the blocks (seed 2.2): their own copies of the corners (blocks
// separate while the mesh topology stays fixed), accumulated stresses, velocities and
// the displacement of the last step.

#include <span>
#include <vector>

#include "dda/block_kinematics.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {

struct BlockState {
  /// Corners from the mesh points; throws ModelError for a block with an unknown material.
  BlockState(const mesh::Mesh& mesh, int n_materials);

  int n_blocks() const { return static_cast<int>(material.size()); }
  int n_corners(int block) const { return corner_offset[block + 1] - corner_offset[block]; }
  Vec2& corner(int block, int local) { return corners[corner_offset[block] + local]; }
  const Vec2& corner(int block, int local) const { return corners[corner_offset[block] + local]; }
  /// Corner after `local`, counter-clockwise (the end of the edge starting at `local`).
  const Vec2& next_corner(int block, int local) const { return corner(block, (local + 1) % n_corners(block)); }
  std::span<const Vec2> corners_of(int block) const {
    return std::span<const Vec2>(corners.data() + corner_offset[block], n_corners(block));
  }

  std::vector<int> corner_offset;
  std::vector<Vec2> corners, initial_corners;
  std::vector<int> material;
  std::vector<Eigen::Vector3d> stress;
  std::vector<Vec6> velocity;
  std::vector<Vec6> last_d;
};

}  // namespace hfdda::dda
