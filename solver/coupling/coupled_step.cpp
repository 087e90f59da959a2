#include "coupling/coupled_step.hpp"

#include <cstdio>

#include "core/errors.hpp"

namespace hfdda::coupling {

CoupledStep::CoupledStep(dda::BlockSystem& mechanics, HydroMechanicalCoupling* flow, bool trace_cuts)
    : mechanics_(mechanics), flow_(flow), trace_cuts_(trace_cuts) {}

StepStatistics CoupledStep::advance(double dt_s, int max_step_cuts) {
  StepStatistics stats;
  advance_into(dt_s, max_step_cuts, stats);
  return stats;
}

void CoupledStep::advance_into(double dt_s, int cuts_left, StepStatistics& stats) {
  try {
    StepStatistics step = mechanics_.step(dt_s, flow_);
    if (flow_) {
      const CouplingStatistics& cs = flow_->statistics();
      step.fractures_wetted += cs.fractures_wetted;
      step.flow_solves += cs.flow_solves;
      step.flow_newton_iterations += cs.newton_iterations;
      step.flow_newton_restarts += cs.newton_restarts;
      step.max_flow_nodes = std::max(step.max_flow_nodes, cs.max_nodes);
      step.max_flow_residual = std::max(step.max_flow_residual, cs.max_relative_residual);
      step.seconds_sensitivity += cs.seconds_sensitivity;
      step.seconds_flow += cs.seconds_flow;
    }
    stats.accumulate(step);
  } catch (const ConvergenceError& e) {
    if (cuts_left <= 0) throw;
    ++stats.step_cuts;
    if (trace_cuts_) std::fprintf(stderr, "step of %g s cut: %s\n", dt_s, e.what());
    advance_into(0.5 * dt_s, cuts_left - 1, stats);
    advance_into(0.5 * dt_s, cuts_left - 1, stats);
  }
}

}  // namespace hfdda::coupling
