#include "dda/block_state.hpp"

#include <string>

#include "core/errors.hpp"

namespace hfdda::dda {

BlockState::BlockState(const mesh::Mesh& mesh, int n_materials) {
  const int nb = static_cast<int>(mesh.blocks.size());
  corner_offset.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) corner_offset[b + 1] = corner_offset[b] + static_cast<int>(mesh.blocks[b].points.size());
  corners.resize(corner_offset[nb]);
  material.resize(nb);
  for (int b = 0; b < nb; ++b) {
    const auto& block = mesh.blocks[b];
    for (std::size_t k = 0; k < block.points.size(); ++k) corners[corner_offset[b] + k] = mesh.points[block.points[k]];
    if (block.material < 0 || block.material >= n_materials)
      throw ModelError("block " + std::to_string(b) + " refers to material " + std::to_string(block.material) +
                       " but only " + std::to_string(n_materials) + " are defined");
    material[b] = block.material;
  }
  initial_corners = corners;
  stress.assign(nb, Eigen::Vector3d::Zero());
  velocity.assign(nb, Vec6::Zero());
  last_d.assign(nb, Vec6::Zero());
}

}  // namespace hfdda::dda
