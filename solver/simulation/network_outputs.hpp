#pragma once
// The files `hfdda network` writes for the fracture network of a case (seed 5.3):
//   network.csv            one row per joint of a generated fracture, along each fracture:
//                          fracture,set,joint,x1,y1,x2,y2
//   network_fractures.csv  one row per generated fracture:
//                          name,set,joints,length_m,target_length_m,reached_target,seed_joint
//   network_sets.csv       one row per set: name,azimuth_deg,candidates,seeds,absorbed_seeds,
//                          fractures,reaching_target,joints,total_length_m
//   network.vtu            every joint of the mesh as a line, with cell data `set` (index of
//                          the generated fracture's set, -1: none), `fracture` (index of the
//                          generated fracture, -1: none), `natural` and `joint_id`
// Each file is written to a temporary name and renamed (io::write_file_atomically).

#include <string>

#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace hfdda::simulation {

/// Writes the four files above into `dir` (which must exist).
void write_network_outputs(const std::string& dir, const io::CaseConfig& config, const FracturedMesh& fractured);

}  // namespace hfdda::simulation
