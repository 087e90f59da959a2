#pragma once
// A fluid acting on the blocks within their time step (seed 2.4). The coupled step
// calls it at fixed points of the step:
//   begin_step -> { [K factorised] prepare -> respond (per contact iteration)
//   -> update_states } -> commit, or roll_back if the step fails.
// A model loads the blocks either through the step's block loads (begin_step) or by
// correcting the mechanical displacement through the factorised K (respond).

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/step_statistics.hpp"
#include "dda/block_system.hpp"

namespace hfdda::coupling {

class FluidLoadModel {
 public:
  virtual ~FluidLoadModel() = default;
  /// After the mechanics' begin_step: may add loads to mechanics.step_loads().
  virtual void begin_step(dda::BlockSystem& mechanics, double dt_s) = 0;
  /// K (factorised in mechanics.solver()) or the model's own set changed since the last call.
  virtual void prepare(const dda::BlockSystem& mechanics, bool stiffness_changed) = 0;
  /// Turns the displacement for the mechanical loads into the coupled one, in place.
  virtual void respond(const dda::BlockSystem& mechanics, Eigen::VectorXd& d) = 0;
  /// After the contact-state update: changes of the model's own states (outer iterations).
  virtual int update_states(const dda::BlockSystem& mechanics) = 0;
  /// Points where the fluid is pressurised now (propagation rule, seed 2.3 i).
  virtual const std::vector<char>& pressurised_points() const = 0;
  /// Whether the fluid fills a joint now.
  virtual bool wetted(int joint) const = 0;
  virtual void commit(const dda::BlockSystem& mechanics) = 0;
  virtual void roll_back() = 0;
  /// Adds the model's counters of the step just committed.
  virtual void add_statistics(StepStatistics&) const {}
  /// Asked by long inner iterations (the flow solve's Newton iterations); true makes them
  /// throw StepInterrupted (CoupledStep::interrupt_when). Empty: never.
  virtual void interrupt_when(std::function<bool()> /*requested*/) {}
};

}  // namespace hfdda::coupling
