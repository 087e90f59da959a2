#pragma once
// Set-ups shared by the DDA unit tests (test_dda.cpp, test_dda_step_control.cpp).

#include <memory>
#include <vector>

#include "coupling/coupled_step.hpp"
#include "dda/block_system.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda::test_support {

inline mesh::Mesh small_mesh(int nx, int ny, double h, mesh::CellSplit split) {
  mesh::StructuredMeshSpec spec;
  spec.outer = Rect{0.0, nx * h, 0.0, ny * h};
  spec.cell_size_m = h;
  spec.split = split;
  mesh::Mesh m = mesh::build_structured_mesh(spec);
  mesh::build_topology(m, mesh::JointProperties{});
  return m;
}

inline MechanicsSettings alm_settings(double youngs_modulus) {
  MechanicsSettings s;
  s.normal_stiffness_N_m = s.shear_stiffness_N_m = s.fixed_point_stiffness_N_m = 100.0 * youngs_modulus;
  s.alm_force_tolerance = 1e-10;
  s.max_alm_iterations = 500;
  return s;
}

/// One unit square of E = 25 GPa held at two corners, (0, 0) and (0, 1), and pulled along x
/// at (1, 0.5) by `load_N` [N per metre]: E / 4 strains it by about 0.25 in a step.
inline std::unique_ptr<BlockSystem> pulled_unit_block(double load_N) {
  const mesh::Mesh m = small_mesh(1, 1, 1.0, mesh::CellSplit::none);
  auto system = std::make_unique<BlockSystem>(m, std::vector<Material>{Material{25e9, 0.25, 2650.0}}, alm_settings(25e9));
  system->add_fixed_point({0.0, 0.0});
  system->add_fixed_point({0.0, 1.0});
  system->add_point_load({1.0, 0.5}, {load_N, 0.0});
  return system;
}

/// One step of the blocks alone, without cut-back.
inline StepStatistics step(BlockSystem& system, double dt_s, fracture::FractureRules rules = {}) {
  return coupling::CoupledStep(system, {}, rules).advance(dt_s, 0);
}

}  // namespace hfdda::dda::test_support
