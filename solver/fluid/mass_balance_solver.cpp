#include "fluid/mass_balance_solver.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace hfdda::fluid {

namespace {
constexpr double kPressureRounding = MassBalance::kPressureRounding;
/// Bounds of the fill scale P of a partly filled node [Pa]; the upper one is K_f.
constexpr double kMinFillScale = 10.0 * kPressureRounding;
/// Largest change of an unknown in one full Newton step, unless the unknowns are larger [Pa].
constexpr double kFullStepCap = 1.0e6;
/// Forcing terms of the linear solves (relative residual; models that solve exactly
/// ignore them, docs/design_notes.md section 43). Exact: well below what the Newton test
/// of 1e-9 on pressure changes needs, so that Newton converges as with exact solves.
/// Inexact: while Newton converges well (inexact Newton, Dembo, Eisenstat and Steihaug,
/// SIAM J. Numer. Anal. 19, 1982), where a tighter solve would not change its course.
constexpr double kExactForcing = 1e-10;
constexpr double kInexactForcing = 1e-4;
/// A step converges well when it was taken whole and the mass residual it left is at
/// most this fraction of the one before.
constexpr double kWellConvergingRatio = 0.5;
}  // namespace

void MassBalanceSolver::rescale_partly_filled_nodes(Evaluation& ev) {
  // Newton crosses the corner of max(y, 0) well only if the mass balance has about the
  // same slope on both sides of it: the excess mass a full step predicts for a node
  // that fills up then turns into a pressure through the node's conductance, not
  // through the fluid's bulk modulus (the stagnation seen at growing tips). So P is
  // set to rho(0) V / g with g = dt sum eta + rho' V, the slope a full node would have.
  // The fill fraction 1 + y / P is kept: the residual does not change, only the
  // storage term on the diagonal of the Jacobian of a node at zero pressure.
  const int n = network_.n_nodes();
  Eigen::VectorXd& fill_scale = network_.fill_scale_Pa;
  const Eigen::VectorXd& conductance = ev.conductance;
  const double rho0 = fluid_.density(0.0);
  // A vent node past full (y > 0) is rescaled the same way: its vented mass
  // rho(0) V y / P then turns into y through the same conductance.
  for (int i = 0; i < n; ++i) {
    double& y = unknowns_[i];
    const bool venting = balance_.is_vent(i) && y > 0.0;
    if ((y > -kPressureRounding && !venting) || !(ev.volume[i] > 0.0) || !(conductance[i] > 0.0)) continue;
    const double deficit = -y / fill_scale[i];  // 1 - fill fraction: > 0, < 0 for a venting node
    // Keep y below the rounded corner, so that the pressure stays exactly zero.
    const double lowest = venting ? kMinFillScale : std::max(kMinFillScale, kPressureRounding / deficit);
    const double scale = std::clamp(rho0 * ev.volume[i] / conductance[i], lowest, fluid_.bulk_modulus_Pa);
    if (scale == fill_scale[i]) continue;
    // Storage and leak-off through the wetted walls both scale with the fill fraction
    // (all walls are wetted at a venting node).
    const double filled_slope =
        rho0 * ev.volume[i] + (venting ? 0.0 : network_.homotopy * ev.density[i] * network_.leak_volume_m3[i]);
    ev.local.coeffRef(i, i) += filled_slope * (1.0 / scale - 1.0 / fill_scale[i]);
    fill_scale[i] = scale;
    y = -deficit * scale;
  }
}

Eigen::VectorXd MassBalanceSolver::self_capacity(const Eigen::VectorXd& x, const ApertureModel& s,
                                                 const Evaluation& ev) const {
  // The slope of each node's mass balance in its own unknown, from the terms that are
  // positive whatever the state: compressibility, conductance to the neighbours, the
  // walls' own compliance, and the fill of a partly filled node.
  Eigen::VectorXd capacity = ev.conductance;
  for (int k = 0; k < network_.n_fractures(); ++k) {
    const int a = network_.node_a[k], b = network_.node_b[k];
    const double half = 0.5 * network_.length_m[k];
    capacity[a] += std::max(0.0, balance_.fill_density(x[a], a) * half * ev.slope[2 * k] * s.self_entry(2 * k, a));
    capacity[b] +=
        std::max(0.0, balance_.fill_density(x[b], b) * half * ev.slope[2 * k + 1] * s.self_entry(2 * k + 1, b));
  }
  const Eigen::VectorXd& leak_volume = network_.leak_volume_m3;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (x[i] < 0.0)
      capacity[i] += (fluid_.density(0.0) * ev.volume[i] + network_.homotopy * ev.density[i] * leak_volume[i]) /
                     network_.fill_scale_Pa[i];
  return capacity;
}

bool MassBalanceSolver::newton(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats,
                               NewtonProgress& progress, NewtonStep mode) {
  const bool pseudo_transient = mode == NewtonStep::pseudo_transient;
  const int n = network_.n_nodes();
  const double mass_scale = balance_.mass_scale();
  const double tol = settings_.tolerance;
  // Below this a residual is round-off of its largest terms: with a strong leak-off,
  // rho Vleak can exceed the fluid present by orders of magnitude.
  const double round_off = balance_.residual_round_off();
  Evaluation ev, trial;
  Eigen::VectorXd& x = unknowns_;
  double forcing = kExactForcing;
  auto solve_linear = [&](const Eigen::SparseMatrix<double>& local) {
    s.factorize(local, ev.coupling, ev.pressure_slope);
    Eigen::VectorXd dx = s.solve(-ev.residual, forcing);
    ++stats.newton_iterations;
    return dx;
  };
  // Pseudo-transient continuation: (J + shift D) dx = -R with D = self_capacity, the
  // shift relaxed as the residual falls (switched evolution relaxation) and raised when
  // a step would more than double the residual. A large shift moves each node towards
  // its own balance (a node short of fluid fills up, even where the full Jacobian
  // points the other way); a vanishing shift is Newton.
  double shift = 1.0;
  Eigen::SparseMatrix<double> shifted;
  const int max_iterations = pseudo_transient ? 4 * settings_.max_newton_iterations : settings_.max_newton_iterations;
  double previous_merit = 0.0, previous_alpha = 0.0;
  for (int it = 0; it < max_iterations; ++it) try {
    if (interrupt_ && *interrupt_ && (*interrupt_)())
      throw StepInterrupted("the step was abandoned on request (in the flow solve); the state is that of its start");
    balance_.evaluate(x, base, s, ev, true);
    rescale_partly_filled_nodes(ev);
    progress.residual = std::max(0.0, ev.residual.cwiseAbs().maxCoeff() - round_off) / mass_scale;
    const double merit = ev.residual.norm();
    const bool converged_residual = merit <= tol * mass_scale + round_off;
    // Inexact linear solves only in line-search mode (the first attempt and the restarts
    // that reuse it) and only while it converges well: near a fold of the mass balance
    // (section 19) Newton needs its directions almost exactly; the full-step and
    // pseudo-transient fallbacks keep them exact.
    const bool converging_well =
        it == 0 || (previous_alpha == 1.0 && merit <= kWellConvergingRatio * previous_merit);
    forcing = settings_.inexact_linear_solves && mode == NewtonStep::line_search && converging_well ? kInexactForcing
                                                                                                   : kExactForcing;
    previous_merit = merit;
    Eigen::VectorXd dx;
    double alpha = 1.0;
    if (pseudo_transient) {
      const Eigen::VectorXd capacity = self_capacity(x, s, ev);
      for (int attempt = 0; attempt < 30; ++attempt) {
        shifted = ev.local;
        for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += shift * capacity[i];
        dx = solve_linear(shifted);
        if (converged_residual) break;
        balance_.evaluate(x + dx, base, s, trial, false);
        const double ratio = trial.residual.norm() / merit;
        if (ratio <= 2.0) {
          shift *= std::max(ratio, 1e-3);
          break;
        }
        shift = std::max(10.0 * shift, 1.0);  // too long a pseudo-time step: shorten it
      }
    } else {
      dx = solve_linear(ev.local);
      if (mode == NewtonStep::full) {
        // Where every end near the solution sits on its floor the Jacobian sees only the
        // fluid's compressibility, and its step runs far past the floors' corners; the
        // next Jacobian, on the other side, steps back (an active-set iteration in effect).
        // A residual that must fall at every step would cut such steps to nothing
        // (docs/design_notes.md section 23). The cap only keeps iterates finite.
        const double cap = std::max(kFullStepCap, x.cwiseAbs().maxCoeff());
        const double largest = dx.cwiseAbs().maxCoeff();
        if (largest > cap) alpha = cap / largest;
      } else {
        // Backtracking on the mass residual: apertures and transmissivities have kinks at
        // the minimum widths, where full Newton steps may overshoot.
        for (int cut = 0; cut < 30 && !converged_residual; ++cut, alpha *= 0.5) {
          balance_.evaluate(x + alpha * dx, base, s, trial, false);
          if (trial.residual.norm() <= (1.0 - 1e-4 * alpha) * merit) break;
        }
      }
    }
    x += alpha * dx;
    previous_alpha = alpha;
    if (mode == NewtonStep::full) x = x.cwiseMax(-network_.fill_scale_Pa);  // a fill fraction is never negative
    progress.max_pressure = 0.0, progress.change = 0.0;
    for (int i = 0; i < n; ++i) {
      progress.max_pressure = std::max(progress.max_pressure, std::abs(x[i]));
      progress.change = std::max(progress.change, std::abs(alpha * dx[i]));
    }
    // Relative pressure change and mass residual (erratum 2 in docs/seed_errata.md); 1 mPa absolute floor.
    if (progress.residual <= tol && progress.change <= tol * progress.max_pressure + 1e-3) {
      stats.max_relative_residual = std::max(stats.max_relative_residual, progress.residual);
      return true;
    }
  } catch (const ConvergenceError&) {
    // A singular Jacobian (e.g. an iterate that has swung a barely held block far open):
    // this Newton run has failed; the caller's fallbacks start again from their own guess.
    return false;
  }
  return false;
}

}  // namespace hfdda::fluid
