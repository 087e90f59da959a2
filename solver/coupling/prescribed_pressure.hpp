#pragma once
// Fluid at a prescribed pressure (fracture `pressure:` in a case; the Griffith crack of
// seed 3.1): fixed pressures at the mesh points, acting on both faces of the joints
// that hold fluid as trapezoidal block loads of every step.

#include <vector>

#include "coupling/fluid_load_model.hpp"

namespace hfdda::coupling {

class PrescribedPressure final : public FluidLoadModel {
 public:
  /// Pressure at every mesh point and which joints hold fluid (sizes of the mesh).
  PrescribedPressure(const mesh::Mesh& mesh, std::vector<double> point_pressure_Pa, std::vector<char> joint_wetted);
  /// The pressures prescribed on the joints' properties (prescribed_pressure_Pa >= 0);
  /// a point takes the largest pressure of its wetted joints.
  static PrescribedPressure from_joint_properties(const mesh::Mesh& mesh);
  /// Some joint holds fluid.
  bool any_wetted() const;

  void begin_step(dda::BlockSystem& mechanics, double dt_s) override;
  void prepare(const dda::BlockSystem&, bool) override {}
  void respond(const dda::BlockSystem&, Eigen::VectorXd&) override {}
  int update_states(const dda::BlockSystem&) override { return 0; }
  const std::vector<char>& pressurised_points() const override { return pressurised_; }
  bool wetted(int joint) const override { return joint_wetted_[joint] != 0; }
  void commit(const dda::BlockSystem&) override {}
  void roll_back() override {}

 private:
  const mesh::Mesh& mesh_;
  std::vector<double> point_pressure_;
  std::vector<char> joint_wetted_, pressurised_;
};

}  // namespace hfdda::coupling
