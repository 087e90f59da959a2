#include "coupling/initial_opening.hpp"

#include <algorithm>

#include "coupling/coupled_step.hpp"
#include "coupling/prescribed_pressure.hpp"

namespace hfdda::coupling {

InitialOpening open_by_initial_pressure(dda::BlockSystem& system, const std::vector<PressurisedJoint>& joints,
                                        double dt_s, int max_step_cuts, const fracture::FractureRules& rules) {
  const mesh::Mesh& m = system.mesh();
  std::vector<double> point_pressure(m.points.size(), 0.0);
  std::vector<char> wetted(m.joints.size(), 0);
  for (const PressurisedJoint& j : joints) {
    wetted[j.joint] = 1;
    for (int point : {m.joints[j.joint].point_p, m.joints[j.joint].point_q})
      point_pressure[point] = std::max(point_pressure[point], j.pressure_Pa);
  }
  PrescribedPressure pressure(m, std::move(point_pressure), std::move(wetted));
  CoupledStep step(system, {&pressure}, rules);
  InitialOpening result;
  result.step = step.advance(dt_s, max_step_cuts);
  result.apertures_m.reserve(joints.size());
  for (const PressurisedJoint& j : joints)
    result.apertures_m.push_back({system.joint_gap(j.joint, 0), system.joint_gap(j.joint, 1)});
  return result;
}

}  // namespace hfdda::coupling
