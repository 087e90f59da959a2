#include "coupling/prescribed_pressure.hpp"

#include <algorithm>
#include <stdexcept>

namespace hfdda::coupling {

PrescribedPressure::PrescribedPressure(const mesh::Mesh& mesh, std::vector<double> point_pressure_Pa,
                                       std::vector<char> joint_wetted)
    : mesh_(mesh), point_pressure_(std::move(point_pressure_Pa)), joint_wetted_(std::move(joint_wetted)) {
  if (point_pressure_.size() != mesh_.points.size() || joint_wetted_.size() != mesh_.joints.size())
    throw std::invalid_argument("PrescribedPressure: sizes do not match the mesh");
  pressurised_.assign(mesh_.points.size(), 0);
  for (std::size_t j = 0; j < mesh_.joints.size(); ++j) {
    if (!joint_wetted_[j]) continue;
    const auto& joint = mesh_.joints[j];
    if (point_pressure_[joint.point_p] > 0.0) pressurised_[joint.point_p] = 1;
    if (point_pressure_[joint.point_q] > 0.0) pressurised_[joint.point_q] = 1;
  }
}

PrescribedPressure PrescribedPressure::from_joint_properties(const mesh::Mesh& m) {
  std::vector<double> point_pressure(m.points.size(), 0.0);
  std::vector<char> wetted(m.joints.size(), 0);
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const double p = m.joints[j].properties.prescribed_pressure_Pa;
    if (p < 0.0) continue;
    wetted[j] = 1;
    point_pressure[m.joints[j].point_p] = std::max(point_pressure[m.joints[j].point_p], p);
    point_pressure[m.joints[j].point_q] = std::max(point_pressure[m.joints[j].point_q], p);
  }
  return PrescribedPressure(m, std::move(point_pressure), std::move(wetted));
}

bool PrescribedPressure::any_wetted() const {
  return std::any_of(joint_wetted_.begin(), joint_wetted_.end(), [](char w) { return w != 0; });
}

void PrescribedPressure::begin_step(dda::BlockSystem& mechanics, double) {
  // Both faces of each wetted joint, trapezoidal along each face (seed 2.4): part of
  // the step's block loads, as any other external load.
  for (std::size_t j = 0; j < mesh_.joints.size(); ++j) {
    if (!joint_wetted_[j]) continue;
    const auto& joint = mesh_.joints[j];
    mechanics.add_joint_pressure_load(static_cast<int>(j), point_pressure_[joint.point_p],
                                      point_pressure_[joint.point_q], mechanics.step_loads());
  }
}

}  // namespace hfdda::coupling
