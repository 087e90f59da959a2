#pragma once
// From a validated case file to a ready-to-run model: mesh, materials per block,
// joint properties along the case's fractures, loads and constraints. Checks that
// need the mesh (empty material region, fracture off the mesh edges, degenerate or
// inverted blocks) are made here and reported as InputError naming the case file,
// line and key, before anything is written.

#include <memory>
#include <vector>

#include "coupling/coupled_step.hpp"
#include "coupling/hydro_mechanical_coupling.hpp"
#include "coupling/prescribed_pressure.hpp"
#include "dda/block_system.hpp"
#include "fracture/fracture_criteria.hpp"
#include "fluid/flow_network.hpp"
#include "io/case_config.hpp"
#include "mesh/mesh.hpp"
#include "simulation/load_ramp.hpp"

namespace hfdda::simulation {

struct Model {
  io::CaseConfig config;
  std::unique_ptr<dda::BlockSystem> system;
  std::vector<int> fracture_of_joint;  ///< index into config.fractures, -1 if none
  int mesh_seconds_ms = 0;
  // Flow network, when the case has a `fluid` section (fractures = mesh joints).
  std::unique_ptr<fluid::FlowNetwork> flow;
  std::unique_ptr<coupling::HydroMechanicalCoupling> coupling;
  /// Pressures prescribed on fractures (`pressure:`), when some joint has one.
  std::unique_ptr<coupling::PrescribedPressure> prescribed;
  std::vector<int> injection_points;  ///< mesh point of each config.injections item
  std::vector<int> probe_points;      ///< mesh point of each config.probes item
  /// The time step of the case (blocks, fluid models, bond failures) with cut-back.
  std::unique_ptr<coupling::CoupledStep> step;
  /// The load levels of a case with a `load_ramp` (null otherwise: time stepping to end_time).
  std::unique_ptr<LoadRamp> ramp;
};

/// Builds the mesh and the block system of a case. Throws InputError.
Model build_model(const io::CaseConfig& config);

/// The mesh of a case alone (used by build_model, tests and benchmarks).
mesh::Mesh build_case_mesh(const io::CaseConfig& config);

/// Mechanics settings of a case: spring constants are factors times the largest
/// Young's modulus of its materials (seed Table 3.1: k = 100 E).
dda::MechanicsSettings mechanics_settings(const io::CaseConfig& config);

/// The failure rules of seed 2.3 a case sets (numerics section). Rule (i), failure only
/// at an open joint next to fluid, is off in a load ramp: it has no fluid (seed 4.2-4.4).
fracture::FractureRules fracture_rules(const io::CaseConfig& config);

}  // namespace hfdda::simulation
