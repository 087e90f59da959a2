#pragma once
// Set-ups shared by the DDA unit tests (test_dda.cpp, test_dda_step_control.cpp).

#include <memory>

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

/// One step of the blocks alone, without cut-back.
inline StepStatistics step(BlockSystem& system, double dt_s, fracture::FractureRules rules = {}) {
  return coupling::CoupledStep(system, {}, rules).advance(dt_s, 0);
}

}  // namespace hfdda::dda::test_support
