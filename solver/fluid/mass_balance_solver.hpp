#pragma once
// Solves one step's mass balance (fluid/mass_balance.hpp) for the nodal fill states:
// Newton's method with backtracking from the warm start. Where it stalls (a closed new
// tip whose own pressure opens the fracture behind it makes the mass balance
// non-monotone; a network whose apertures all sit on their floors, where only the
// fluid's compressibility answers a pressure change), the solve falls back, in order,
// on full Newton steps without line search, pseudo-transient continuation, restarts
// with the dry nodes at their neighbours' pressure, continuation in the step's
// inflows, and last holding the closing joints open for the step;
// FlowSolveStatistics::restarts counts them (why and with what evidence:
// docs/design_notes.md sections 2, 3 and 23). Newton and its step modes are in
// mass_balance_solver.cpp, the sequence of fallbacks in mass_balance_fallbacks.cpp.

#include <functional>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "fluid/aperture_model.hpp"
#include "fluid/mass_balance.hpp"

namespace hfdda::fluid {

struct FlowSettings {
  double min_width_main_m = 0.5e-6;
  double min_width_tip_m = 0.1e-6;
  double max_closing_fraction = 0.05;
  double tolerance = 1.0e-9;        ///< Newton: relative pressure change and mass residual
  int max_newton_iterations = 60;
  /// Linear solves that may stop early (iterative aperture models only): at a relative
  /// residual of 1e-4 while Newton converges well, 1e-10 otherwise; false, always 1e-10.
  bool inexact_linear_solves = true;
};

struct FlowSolveStatistics {
  int newton_iterations = 0;
  int restarts = 0;                    ///< fallbacks used after Newton stalled (see the header)
  int zero_pressure_nodes = 0;
  double max_relative_residual = 0.0;  ///< max |mass residual| / mass scale at convergence
};

/// One solve of a trial network's mass balance for the aperture model w = base + S p.
class MassBalanceSolver {
 public:
  /// `unknowns` (one fill state per node) are the warm start and receive the solution.
  /// The solve may change the network's fill scales, and its floors (the last resort,
  /// kept for the rest of the step once it has converged).
  /// `interrupt` (optional, may be empty) is asked before every Newton iteration: true
  /// throws StepInterrupted (a stop requested while the solve runs).
  MassBalanceSolver(TrialNetwork& network, const FluidProperties& fluid, const FlowSettings& settings,
                    Eigen::VectorXd& unknowns, const std::function<bool()>* interrupt = nullptr)
      : network_(network), fluid_(fluid), settings_(settings), unknowns_(unknowns), balance_(fluid, network),
        interrupt_(interrupt) {}

  /// Newton, then the fallbacks if needed; throws ConvergenceError.
  void solve(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats);

 private:
  using Evaluation = MassBalance::Evaluation;
  struct NewtonProgress {
    double residual = 0.0, change = 0.0, max_pressure = 0.0;  // of the last iteration
  };
  /// How a Newton iteration moves from one iterate to the next.
  enum class NewtonStep {
    line_search,       ///< backtracking until the mass residual falls
    full,              ///< the whole step, capped in size, fill fractions kept >= 0
    pseudo_transient,  ///< a diagonal shift that pseudo-time relaxes (a trust region)
  };
  /// Newton from the current unknowns; false if it did not converge.
  bool newton(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats, NewtonProgress& progress,
              NewtonStep mode);
  /// Per node: the positive part of the slope of its mass balance in its own unknown
  /// (the pseudo-transient shift's scale).
  Eigen::VectorXd self_capacity(const Eigen::VectorXd& x, const ApertureModel& s, const Evaluation& ev) const;
  /// Sets each partly filled node's fill scale P from its conductance (keeping its fill
  /// fraction) and corrects the Jacobian's diagonal to it.
  void rescale_partly_filled_nodes(Evaluation& ev);
  /// Newton along lambda = 0 -> 1 (TrialNetwork::homotopy); false if a stage could not be solved.
  bool continuation(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats,
                    NewtonProgress& progress);

  TrialNetwork& network_;
  const FluidProperties& fluid_;
  const FlowSettings& settings_;
  Eigen::VectorXd& unknowns_;
  MassBalance balance_;
  const std::function<bool()>* interrupt_;
};

}  // namespace hfdda::fluid
