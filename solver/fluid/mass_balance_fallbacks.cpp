#include <algorithm>
#include <sstream>
#include <utility>

#include "core/errors.hpp"
#include "fluid/mass_balance_solver.hpp"

// The solve's sequence: Newton from the warm start, then the fallbacks, tried in order
// when it stalls (why and with what evidence: docs/design_notes.md sections 3 and 23).

namespace hfdda::fluid {

bool MassBalanceSolver::continuation(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats,
                                     NewtonProgress& progress) {
  struct Restore {
    double& value;
    ~Restore() { value = 1.0; }
  } restore{network_.homotopy};
  double lambda = 0.0, step = 0.125;
  int failures = 0;
  while (lambda < 1.0) {
    const double next = std::min(1.0, lambda + step);
    const Eigen::VectorXd x0 = unknowns_, scale0 = network_.fill_scale_Pa;
    network_.homotopy = next;
    if (newton(base, s, stats, progress, NewtonStep::line_search)) {
      lambda = next;
      step *= 2.0;
      continue;
    }
    unknowns_ = x0;
    network_.fill_scale_Pa = scale0;
    step *= 0.25;
    if (++failures > 12 || step < 1e-6) return false;
  }
  return true;
}

void MassBalanceSolver::solve(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats) {
  Eigen::VectorXd& fill_scale = network_.fill_scale_Pa;
  const Eigen::VectorXd start = unknowns_, start_scale = fill_scale;
  NewtonProgress progress;
  if (newton(base, s, stats, progress, NewtonStep::line_search)) return;
  const Eigen::VectorXd stalled = unknowns_, stalled_scale = fill_scale;
  // Full steps from the warm start: where the network sits on the floors of its
  // apertures, the line search stalls against their corners (design notes section 23).
  for (const NewtonStep mode : {NewtonStep::full, NewtonStep::pseudo_transient}) {
    ++stats.restarts;
    unknowns_ = start;
    fill_scale = start_scale;
    if (newton(base, s, stats, progress, mode)) return;
  }
  // Further starts. A node that is not yet pressurised but takes in more fluid than it
  // can hold must end up near the pressure of the node feeding it. On the way there its
  // mass balance is not monotone: its own pressure opens the fracture behind it and
  // draws more fluid in, so Newton from the empty side can stall at a local minimum of
  // the residual (seen at new tips of inclined fractures). Such nodes start at the
  // largest pressure of their neighbours instead: first those of the warm start, then
  // those Newton had reached when it stalled (the warm start may not be pressurised
  // yet, e.g. at the first step).
  auto flooded = [&](const Eigen::VectorXd& from) {
    Eigen::VectorXd x = from;
    for (int k = 0; k < network_.n_fractures(); ++k) {
      const int a = network_.node_a[k], b = network_.node_b[k];
      if (from[a] <= 0.0) x[a] = std::max(x[a], from[b]);
      if (from[b] <= 0.0) x[b] = std::max(x[b], from[a]);
    }
    return x;
  };
  for (const auto& [from, scale] : {std::pair{start, start_scale}, std::pair{stalled, stalled_scale}}) {
    const Eigen::VectorXd guess = flooded(from);
    if (guess == from) continue;
    for (const NewtonStep mode : {NewtonStep::line_search, NewtonStep::pseudo_transient}) {
      ++stats.restarts;
      unknowns_ = guess;
      fill_scale = scale;
      if (newton(base, s, stats, progress, mode)) return;
    }
  }
  // Last resort, continuation: the step's inflows, leak-off and flow scaled by lambda
  // from 0 (the nodes keep their masses: solved by the warm start's fill states) to 1,
  // each stage solved by Newton from the last. The path follows the physical filling
  // of the network instead of jumping to it.
  ++stats.restarts;
  unknowns_ = start;
  fill_scale = start_scale;
  if (continuation(base, s, stats, progress)) return;
  // Last resort: the closing limit waits for the fluid. The limit (at most 5 % a step,
  // seed 2.1) is there "to facilitate convergence"; where no solve meets it, a node
  // cannot pass on the fluid its closing joints squeeze out. That happens at a tip of a
  // fluid-filled fracture with nothing injected (shut-in, or before an injection
  // starts): the mechanics pins the tip end shut, so its fluid must leave through the
  // thin joint behind it, whose conductance only a large pressure opens. The joints
  // then do not close in this step (floor = the committed aperture); the raised floors
  // hold for the rest of the step.
  ++stats.restarts;
  const Eigen::VectorXd floor = network_.floor_m;
  network_.floor_m = network_.held_open_floor_m;
  for (const NewtonStep mode : {NewtonStep::line_search, NewtonStep::full, NewtonStep::pseudo_transient}) {
    unknowns_ = start;
    fill_scale = start_scale;
    if (newton(base, s, stats, progress, mode)) return;
  }
  network_.floor_m = floor;
  std::ostringstream msg;
  // The unknowns are pressures at full nodes and scaled fill deficits (y < 0) at partly
  // filled ones, so the largest |y| is not a pressure: both are given.
  const double largest_pressure = unknowns_.size() > 0 ? std::max(0.0, unknowns_.maxCoeff()) : 0.0;
  msg << "fluid flow: Newton iterations did not converge in " << settings_.max_newton_iterations
      << " iterations (mass residual " << progress.residual << " of the stored mass, last change of the unknowns "
      << progress.change << " Pa against unknowns up to " << progress.max_pressure << " Pa in magnitude; largest pressure "
      << largest_pressure << " Pa; " << network_.n_nodes() << " nodes)";
  throw ConvergenceError(msg.str());
}

}  // namespace hfdda::fluid
