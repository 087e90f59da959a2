#include "coupling/initial_opening.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/binary_io.hpp"
#include "coupling/coupled_step.hpp"
#include "coupling/prescribed_pressure.hpp"

namespace hfdda::coupling {

namespace {

std::vector<std::array<double, 2>> joint_apertures(const dda::BlockSystem& system,
                                                   const std::vector<PressurisedJoint>& joints) {
  std::vector<std::array<double, 2>> apertures_m;
  apertures_m.reserve(joints.size());
  for (const PressurisedJoint& j : joints) apertures_m.push_back({system.joint_gap(j.joint, 0), system.joint_gap(j.joint, 1)});
  return apertures_m;
}

/// Largest change of a joint end between two sets of apertures: in metres, and relative
/// to the end's aperture (or to width_floor_m, if larger).
struct ApertureChange {
  double largest_m = 0.0;
  double largest_relative = 0.0;
};

ApertureChange largest_change(const std::vector<std::array<double, 2>>& before,
                              const std::vector<std::array<double, 2>>& after, double width_floor_m) {
  ApertureChange change;
  for (std::size_t i = 0; i < before.size(); ++i)
    for (int end = 0; end < 2; ++end) {
      const double moved_m = std::abs(after[i][end] - before[i][end]);
      change.largest_m = std::max(change.largest_m, moved_m);
      change.largest_relative = std::max(
          change.largest_relative, moved_m / std::max({std::abs(before[i][end]), std::abs(after[i][end]), width_floor_m}));
    }
  return change;
}

}  // namespace

InitialOpening open_by_initial_pressure(dda::BlockSystem& system, const std::vector<PressurisedJoint>& joints,
                                        double dt_s, int max_step_cuts, const fracture::FractureRules& rules,
                                        double width_floor_m) {
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
  result.steps = 1;
  result.last_relative_change = std::numeric_limits<double>::quiet_NaN();
  result.apertures_m = joint_apertures(system, joints);
  double last_change_m = std::numeric_limits<double>::infinity();
  while (result.steps < kMaxSettlingSteps) {
    BinaryWriter before;
    system.save_state(before);
    const StepStatistics stats = step.advance(dt_s, max_step_cuts);
    std::vector<std::array<double, 2>> apertures_m = joint_apertures(system, joints);
    const ApertureChange change = largest_change(result.apertures_m, apertures_m, width_floor_m);
    if (change.largest_m > last_change_m) {
      // Growing changes (in metres: the relative measure saturates at thin ends): a
      // contact state that the repeated load drives further each step (measured: sliding
      // contacts whose friction winds up the normal forces of their neighbours). Back to
      // the state before this step.
      BinaryReader in(before.bytes());
      system.restore_state(in);
      result.growing = true;
      break;
    }
    result.step.accumulate(stats);
    result.apertures_m = std::move(apertures_m);
    result.last_relative_change = change.largest_relative;
    last_change_m = change.largest_m;
    ++result.steps;
    if (change.largest_relative <= kSettledChange) break;
  }
  result.settled = result.last_relative_change <= kSettledChange;
  return result;
}

}  // namespace hfdda::coupling
