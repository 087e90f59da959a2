#include "fluid/flow_network.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace hfdda::fluid {

namespace {
/// Width of the rounded corner of max(w, floor), relative to the floor.
constexpr double kFloorRounding = 0.01;
/// Half-width of the rounded corner of the pressure max(y, 0) [Pa].
constexpr double kPressureRounding = 1.0e3;
/// Bounds of the fill scale P of a partly filled node [Pa]; the upper one is K_f.
constexpr double kMinFillScale = 10.0 * kPressureRounding;
/// Largest change of an unknown in one full Newton step, unless the unknowns are larger [Pa].
constexpr double kFullStepCap = 1.0e6;
}  // namespace

struct FlowNetwork::Evaluation {
  Eigen::VectorXd pressure, pressure_slope, density, aperture, volume, storage, residual, eta;
  /// Per node (with the Jacobian only): rho' V + dt sum eta, the slope of a full node's
  /// mass balance in its own pressure from storage and flow to its neighbours.
  Eigen::VectorXd conductance;
  Eigen::VectorXd slope;  // per end: d aperture / d mechanical aperture (0 on the floor, 1 above it)
  /// The Jacobian in the unknowns is local + coupling S diag(pressure_slope)
  /// (fluid/aperture_model.hpp): local (n x n) holds every term at fixed apertures,
  /// coupling (n x 2 nf) how each end's aperture enters the nodes' mass balances.
  Eigen::SparseMatrix<double> local, coupling;
};

FlowNetwork::FlowNetwork(int n_points, std::vector<Fracture> fractures, FluidProperties fluid, FlowSettings settings)
    : fractures_(std::move(fractures)), fluid_(fluid), settings_(settings) {
  for (const auto& f : fractures_)
    if (f.point_p < 0 || f.point_q < 0 || f.point_p >= n_points || f.point_q >= n_points || !(f.length_m > 0.0))
      throw std::invalid_argument("FlowNetwork: fracture with invalid points or length");
  const std::size_t nf = fractures_.size();
  wetted_.assign(nf, 0);
  arrival_time_.assign(nf, 0.0);
  aperture_.assign(2 * nf, 0.0);
  point_pressure_.assign(n_points, 0.0);
  point_mass_.assign(n_points, 0.0);
  node_of_point_.assign(n_points, -1);
  guess_state_.assign(n_points, 0.0);
  point_state_.assign(n_points, 0.0);
  reached_.assign(n_points, 0);
  trial_wetted_ = wetted_;
}

void FlowNetwork::add_injection(const Injection& injection) {
  if (injection.point < 0 || injection.point >= n_points())
    throw std::invalid_argument("FlowNetwork: injection at an invalid point");
  injections_.push_back(injection);
}

void FlowNetwork::fill_initially(int f, double width_m, double pressure_Pa) {
  if (!(pressure_Pa >= 0.0)) throw std::invalid_argument("FlowNetwork::fill_initially: negative pressure");
  const double w = std::max(width_m, settings_.min_width_main_m);
  wetted_[f] = 1;
  arrival_time_[f] = time_s_;
  aperture_[2 * f] = aperture_[2 * f + 1] = w;
  const double mass_per_end = fluid_.density(pressure_Pa) * 0.5 * fractures_[f].length_m * w;
  point_mass_[fractures_[f].point_p] += mass_per_end;
  point_mass_[fractures_[f].point_q] += mass_per_end;
  for (int point : {fractures_[f].point_p, fractures_[f].point_q}) {
    reached_[point] = 1;
    point_state_[point] = pressure_Pa;  // full at that pressure
    point_pressure_[point] = pressure_Pa;
  }
  initial_mass_ += 2.0 * mass_per_end;
  trial_wetted_ = wetted_;
}

// ----------------------------------------------------------------------------------
// Trial network of a step

void FlowNetwork::begin_step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("FlowNetwork::begin_step: dt must be positive");
  dt_s_ = dt_s;
  trial_wetted_ = wetted_;
  guess_state_ = point_state_;
  rebuild_trial_topology();
}

bool FlowNetwork::wet(int f) {
  if (trial_wetted_[f]) return false;
  trial_wetted_[f] = 1;
  rebuild_trial_topology();
  return true;
}

bool FlowNetwork::trial_pressurised(int point) const {
  const int i = node_of_point_[point];
  return i >= 0 && i < unknowns_.size() && unknowns_[i] > 0.0;
}

void FlowNetwork::rebuild_trial_topology() {
  // Warm start: keep the trial pressures of the current nodes.
  for (std::size_t i = 0; i < trial_nodes_.size() && static_cast<Eigen::Index>(i) < unknowns_.size(); ++i)
    guess_state_[trial_nodes_[i]] = state_of_unknown(static_cast<int>(i));
  for (int point : trial_nodes_) node_of_point_[point] = -1;
  trial_fractures_.clear();
  trial_nodes_.clear();
  for (int f = 0; f < n_fractures(); ++f)
    if (trial_wetted_[f]) trial_fractures_.push_back(f);
  const int nf = static_cast<int>(trial_fractures_.size());
  fracture_node_a_.resize(nf);
  fracture_node_b_.resize(nf);
  auto node = [&](int point) {
    if (node_of_point_[point] < 0) {
      node_of_point_[point] = static_cast<int>(trial_nodes_.size());
      trial_nodes_.push_back(point);
    }
    return node_of_point_[point];
  };
  for (int k = 0; k < nf; ++k) {
    fracture_node_a_[k] = node(fractures_[trial_fractures_[k]].point_p);
    fracture_node_b_[k] = node(fractures_[trial_fractures_[k]].point_q);
  }
  const int n = static_cast<int>(trial_nodes_.size());
  const double t0 = time_s_, t1 = time_s_ + dt_s_;

  old_mass_.setZero(n);
  injected_.setZero(n);
  leak_volume_.setZero(n);
  std::vector<int> degree(n, 0);
  for (int i = 0; i < n; ++i) old_mass_[i] = point_mass_[trial_nodes_[i]];
  for (const auto& inj : injections_) {
    const int i = node_of_point_[inj.point];
    const double mass = inj.mass_injected_by(t1) - inj.mass_injected_by(t0);
    if (mass <= 0.0) continue;
    if (i < 0) {
      std::ostringstream msg;
      msg << "injection at mesh point " << inj.point << " is not on a fluid-filled fracture at t = " << t0
          << " s: the injected fluid has nowhere to go";
      throw ModelError(msg.str());
    }
    injected_[i] += mass;
  }
  const double cl = fluid_.leak_off_coefficient_m_sqrt_s;
  for (int k = 0; k < nf; ++k) {
    const int f = trial_fractures_[k];
    ++degree[fracture_node_a_[k]];
    ++degree[fracture_node_b_[k]];
    if (cl <= 0.0) continue;
    // Fluid arrives in a newly wetted fracture at the start of the step.
    const double arrival = wetted_[f] ? arrival_time_[f] : t0;
    const double per_node =
        cl * fractures_[f].length_m * 2.0 * (std::sqrt(t1 - arrival) - std::sqrt(std::max(0.0, t0 - arrival)));
    leak_volume_[fracture_node_a_[k]] += per_node;
    leak_volume_[fracture_node_b_[k]] += per_node;
  }
  floor_.setZero(2 * nf);
  hydraulic_width_.setZero(2 * nf);
  for (int k = 0; k < nf; ++k) {
    const int f = trial_fractures_[k];
    hydraulic_width_.segment<2>(2 * k).setConstant(fractures_[f].hydraulic_width_m);
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? fracture_node_a_[k] : fracture_node_b_[k];
      const double minimum = degree[i] >= 2 ? settings_.min_width_main_m : settings_.min_width_tip_m;
      const double closing = wetted_[f] ? (1.0 - settings_.max_closing_fraction) * aperture_[2 * f + end] : 0.0;
      floor_[2 * k + end] = std::max({minimum, closing, fractures_[f].hydraulic_width_m});
    }
  }
  // Warm start from the last state of each node; a node the fluid reaches for the
  // first time starts empty (fill fraction 0).
  unknowns_.setZero(n);
  fill_scale_.setConstant(n, fluid_.bulk_modulus_Pa);
  for (int i = 0; i < n; ++i) {
    const int point = trial_nodes_[i];
    const double state = reached_[point] ? guess_state_[point] : -1.0;
    unknowns_[i] = state >= 0.0 ? state : state * fill_scale_[i];
  }
  pressure_ = unknowns_.cwiseMax(0.0);
  aperture_trial_.setZero(2 * nf);
  mass_new_.setZero(n);
  leak_mass_.setZero(n);
}

// ----------------------------------------------------------------------------------
// Mass balance and its Jacobian

void FlowNetwork::evaluate(const Eigen::VectorXd& x, const Eigen::VectorXd& base, const ApertureModel& s,
                           Evaluation& out, bool with_jacobian) const {
  evaluate_pressure(x, out);
  evaluate_aperture(base, s, out);
  evaluate_storage(x, out);
  evaluate_flow(out);
  if (!with_jacobian) return;
  evaluate_jacobian(x, out);
}

void FlowNetwork::evaluate_pressure(const Eigen::VectorXd& x, Evaluation& out) const {
  const int n = static_cast<int>(trial_nodes_.size());
  // The unknown y of a node is its fill state: for y >= 0 the node is full at pressure
  // y and stores rho(y) V (eq. 2.6); for y < 0 it is a zero-pressure node (seed 2.1,
  // Figure 2.2) filled to the fraction 1 + y / P, storing rho(0) V (1 + y / P). The
  // pressure that drives the flow and loads the rock is max(y, 0), its corner rounded
  // within kPressureRounding. P (fill_scale_) only shapes the path Newton takes.
  out.pressure.resize(n);
  out.pressure_slope.resize(n);
  for (int i = 0; i < n; ++i) {
    const double y = x[i];
    if (y >= kPressureRounding) {
      out.pressure[i] = y, out.pressure_slope[i] = 1.0;
    } else if (y <= -kPressureRounding) {
      out.pressure[i] = 0.0, out.pressure_slope[i] = 0.0;
    } else {
      out.pressure[i] = (y + kPressureRounding) * (y + kPressureRounding) / (4.0 * kPressureRounding);
      out.pressure_slope[i] = (y + kPressureRounding) / (2.0 * kPressureRounding);
    }
  }
}

void FlowNetwork::evaluate_aperture(const Eigen::VectorXd& base, const ApertureModel& s, Evaluation& out) const {
  const int nf = static_cast<int>(trial_fractures_.size());
  // w = max(w_mechanics, floor), its corner rounded by a parabola within 1 % of the
  // floor (C1, exact outside that band) so that Newton sees a smooth mass balance.
  s.apply(out.pressure, out.aperture);
  out.aperture += base + hydraulic_width_;
  out.slope.resize(2 * nf);
  for (int e = 0; e < 2 * nf; ++e) {
    const double band = kFloorRounding * floor_[e];
    const double z = out.aperture[e] - floor_[e];
    if (z >= band) {
      out.slope[e] = 1.0;
    } else if (z <= -band) {
      out.aperture[e] = floor_[e];
      out.slope[e] = 0.0;
    } else {
      out.aperture[e] = floor_[e] + (z + band) * (z + band) / (4.0 * band);
      out.slope[e] = (z + band) / (2.0 * band);
    }
  }
}

void FlowNetwork::evaluate_storage(const Eigen::VectorXd& x, Evaluation& out) const {
  const int n = static_cast<int>(trial_nodes_.size());
  const int nf = static_cast<int>(trial_fractures_.size());
  out.density.resize(n);
  for (int i = 0; i < n; ++i) out.density[i] = fluid_.density(out.pressure[i]);
  out.volume.setZero(n);
  for (int k = 0; k < nf; ++k) {
    const double half = 0.5 * fractures_[trial_fractures_[k]].length_m;
    out.volume[fracture_node_a_[k]] += half * out.aperture[2 * k];
    out.volume[fracture_node_b_[k]] += half * out.aperture[2 * k + 1];
  }
  out.storage.resize(n);
  out.residual.resize(n);
  for (int i = 0; i < n; ++i) {
    out.storage[i] = fill_density(x[i], i) * out.volume[i];
    out.residual[i] = out.storage[i] - old_mass_[i] +
                      homotopy_ * (wetted_fraction(x[i], i) * out.density[i] * leak_volume_[i] - injected_[i]);
  }
}

void FlowNetwork::evaluate_flow(Evaluation& out) const {
  const int nf = static_cast<int>(trial_fractures_.size());
  out.eta.resize(nf);
  const double mu12 = 12.0 * fluid_.viscosity_Pa_s;
  for (int k = 0; k < nf; ++k) {
    const int a = fracture_node_a_[k], b = fracture_node_b_[k];
    const double length = fractures_[trial_fractures_[k]].length_m;
    const double rho = 0.5 * (out.density[a] + out.density[b]);
    const double w = 0.5 * (out.aperture[2 * k] + out.aperture[2 * k + 1]);
    out.eta[k] = rho * w * w * w / (mu12 * length);  // eq. 2.2
    const double outflow = flow_dt() * out.eta[k] * (out.pressure[a] - out.pressure[b]);
    out.residual[a] += outflow;
    out.residual[b] -= outflow;
  }
}

void FlowNetwork::evaluate_jacobian(const Eigen::VectorXd& x, Evaluation& out) const {
  const int n = static_cast<int>(trial_nodes_.size());
  const int nf = static_cast<int>(trial_fractures_.size());
  out.conductance = fluid_.density_derivative() * out.volume;
  for (int k = 0; k < nf; ++k) {
    out.conductance[fracture_node_a_[k]] += flow_dt() * out.eta[k];
    out.conductance[fracture_node_b_[k]] += flow_dt() * out.eta[k];
  }

  // Derivatives with respect to the pressures p first (local and coupling), then by
  // the chain rule to the unknowns y: the columns of both scale by dp/dy, which for
  // the coupling part is the d of J = A + E S diag(d).
  const double drho = fluid_.density_derivative();
  std::vector<Eigen::Triplet<double>> local, coupling;
  local.reserve(n + 4 * nf);
  coupling.reserve(6 * nf);
  for (int i = 0; i < n; ++i) local.emplace_back(i, i, homotopy_ * drho * wetted_fraction(x[i], i) * leak_volume_[i]);
  for (int k = 0; k < nf; ++k) {
    const double half = 0.5 * fractures_[trial_fractures_[k]].length_m;
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? fracture_node_a_[k] : fracture_node_b_[k];
      if (out.slope[2 * k + end] > 0.0)
        coupling.emplace_back(i, 2 * k + end, fill_density(x[i], i) * half * out.slope[2 * k + end]);
    }
  }
  add_flow_jacobian(out, local, coupling);
  out.local.resize(n, n);
  out.local.setFromTriplets(local.begin(), local.end());
  out.coupling.resize(n, 2 * nf);
  out.coupling.setFromTriplets(coupling.begin(), coupling.end());
  out.local = out.local * out.pressure_slope.asDiagonal();
  for (int i = 0; i < n; ++i) {
    double diagonal = fill_density_slope(x[i], i) * out.volume[i];  // storage
    if (x[i] < 0.0) diagonal += homotopy_ * out.density[i] * leak_volume_[i] / fill_scale_[i];  // wetted part
    out.local.coeffRef(i, i) += diagonal;
  }
}

void FlowNetwork::add_flow_jacobian(const Evaluation& out, std::vector<Eigen::Triplet<double>>& local,
                                    std::vector<Eigen::Triplet<double>>& coupling) const {
  const int nf = static_cast<int>(trial_fractures_.size());
  const double drho = fluid_.density_derivative();
  for (int k = 0; k < nf; ++k) {
    const int a = fracture_node_a_[k], b = fracture_node_b_[k];
    const double rho = 0.5 * (out.density[a] + out.density[b]);
    const double w = 0.5 * (out.aperture[2 * k] + out.aperture[2 * k + 1]);
    const double dp = out.pressure[a] - out.pressure[b];
    const double g = flow_dt() * out.eta[k];
    // Outflow dt eta (p_a - p_b) from a to b: eta ~ rho w^3 (eq. 2.2).
    for (int end = 0; end < 2; ++end)
      if (out.slope[2 * k + end] > 0.0) {
        const double d_outflow = flow_dt() * dp * 1.5 * out.eta[k] / w * out.slope[2 * k + end];
        coupling.emplace_back(a, 2 * k + end, d_outflow);
        coupling.emplace_back(b, 2 * k + end, -d_outflow);
      }
    const double d_density = flow_dt() * dp * 0.5 * drho * out.eta[k] / rho;
    local.emplace_back(a, a, g + d_density);
    local.emplace_back(a, b, -g + d_density);
    local.emplace_back(b, b, g - d_density);
    local.emplace_back(b, a, -g - d_density);
  }
}

double FlowNetwork::fill_density(double y, int i) const {
  return y >= 0.0 ? fluid_.density(y) : fluid_.density(0.0) * (1.0 + y / fill_scale_[i]);
}

double FlowNetwork::residual_round_off() const {
  const double gross = old_mass_.sum() + injected_.sum() + fluid_.density(0.0) * leak_volume_.sum();
  return 64.0 * std::numeric_limits<double>::epsilon() * gross;
}

double FlowNetwork::wetted_fraction(double y, int i) const {
  // Leak-off leaves through the wetted walls: all of them at a full node, the filled
  // fraction of them at a partly filled one. So a node cannot lose more fluid than it
  // receives: as it empties, its leak-off vanishes with its content.
  return y >= 0.0 ? 1.0 : 1.0 + y / fill_scale_[i];
}

double FlowNetwork::fill_density_slope(double y, int i) const {
  return y >= 0.0 ? fluid_.density_derivative() : fluid_.density(0.0) / fill_scale_[i];
}

double FlowNetwork::state_of_unknown(int i) const {
  const double y = unknowns_[i];
  return y >= 0.0 ? y : y / fill_scale_[i];
}

void FlowNetwork::rescale_partly_filled_nodes(Evaluation& ev) {
  // Newton crosses the corner of max(y, 0) well only if the mass balance has about the
  // same slope on both sides of it: the excess mass a full step predicts for a node
  // that fills up then turns into a pressure through the node's conductance, not
  // through the fluid's bulk modulus (the stagnation seen at growing tips). So P is
  // set to rho(0) V / g with g = dt sum eta + rho' V, the slope a full node would have.
  // The fill fraction 1 + y / P is kept: the residual does not change, only the
  // storage term on the diagonal of the Jacobian of a node at zero pressure.
  const int n = static_cast<int>(trial_nodes_.size());
  const Eigen::VectorXd& conductance = ev.conductance;
  const double rho0 = fluid_.density(0.0);
  for (int i = 0; i < n; ++i) {
    double& y = unknowns_[i];
    if (y > -kPressureRounding || !(ev.volume[i] > 0.0) || !(conductance[i] > 0.0)) continue;
    const double deficit = -y / fill_scale_[i];  // 1 - fill fraction, > 0
    // Keep y below the rounded corner, so that the pressure stays exactly zero.
    const double scale = std::clamp(rho0 * ev.volume[i] / conductance[i],
                                    std::max(kMinFillScale, kPressureRounding / deficit), fluid_.bulk_modulus_Pa);
    if (scale == fill_scale_[i]) continue;
    // Storage and leak-off through the wetted walls both scale with the fill fraction.
    const double filled_slope = rho0 * ev.volume[i] + homotopy_ * ev.density[i] * leak_volume_[i];
    ev.local.coeffRef(i, i) += filled_slope * (1.0 / scale - 1.0 / fill_scale_[i]);
    fill_scale_[i] = scale;
    y = -deficit * scale;
  }
}

Eigen::VectorXd FlowNetwork::self_capacity(const Eigen::VectorXd& x, const ApertureModel& s,
                                           const Evaluation& ev) const {
  // The slope of each node's mass balance in its own unknown, from the terms that are
  // positive whatever the state: compressibility, conductance to the neighbours, the
  // walls' own compliance, and the fill of a partly filled node.
  Eigen::VectorXd capacity = ev.conductance;
  for (std::size_t k = 0; k < trial_fractures_.size(); ++k) {
    const int a = fracture_node_a_[k], b = fracture_node_b_[k];
    const double half = 0.5 * fractures_[trial_fractures_[k]].length_m;
    capacity[a] += std::max(0.0, fill_density(x[a], a) * half * ev.slope[2 * k] * s.self_entry(2 * k, a));
    capacity[b] += std::max(0.0, fill_density(x[b], b) * half * ev.slope[2 * k + 1] * s.self_entry(2 * k + 1, b));
  }
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (x[i] < 0.0)
      capacity[i] += (fluid_.density(0.0) * ev.volume[i] + homotopy_ * ev.density[i] * leak_volume_[i]) / fill_scale_[i];
  return capacity;
}

bool FlowNetwork::newton(const Eigen::VectorXd& base, ApertureModel& s, FlowSolveStatistics& stats,
                         NewtonProgress& progress, NewtonStep mode) {
  const bool pseudo_transient = mode == NewtonStep::pseudo_transient;
  const int n = static_cast<int>(trial_nodes_.size());
  const double mass_scale = std::max(old_mass_.sum() + injected_.sum(), 1e-300);
  const double tol = settings_.tolerance;
  // Below this a residual is round-off of its largest terms: with a strong leak-off,
  // rho Vleak can exceed the fluid present by orders of magnitude.
  const double round_off = residual_round_off();
  Evaluation ev, trial;
  Eigen::VectorXd& x = unknowns_;
  auto solve_linear = [&](const Eigen::SparseMatrix<double>& local) {
    s.factorize(local, ev.coupling, ev.pressure_slope);
    Eigen::VectorXd dx = s.solve(-ev.residual);
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
  for (int it = 0; it < max_iterations; ++it) try {
    evaluate(x, base, s, ev, true);
    rescale_partly_filled_nodes(ev);
    progress.residual = std::max(0.0, ev.residual.cwiseAbs().maxCoeff() - round_off) / mass_scale;
    const double merit = ev.residual.norm();
    const bool converged_residual = merit <= tol * mass_scale + round_off;
    Eigen::VectorXd dx;
    double alpha = 1.0;
    if (pseudo_transient) {
      const Eigen::VectorXd capacity = self_capacity(x, s, ev);
      for (int attempt = 0; attempt < 30; ++attempt) {
        shifted = ev.local;
        for (int i = 0; i < n; ++i) shifted.coeffRef(i, i) += shift * capacity[i];
        dx = solve_linear(shifted);
        if (converged_residual) break;
        evaluate(x + dx, base, s, trial, false);
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
          evaluate(x + alpha * dx, base, s, trial, false);
          if (trial.residual.norm() <= (1.0 - 1e-4 * alpha) * merit) break;
        }
      }
    }
    x += alpha * dx;
    if (mode == NewtonStep::full) x = x.cwiseMax(-fill_scale_);  // a fill fraction is never negative
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

FlowSolveStatistics FlowNetwork::solve(const Eigen::VectorXd& base, const Eigen::MatrixXd& s) {
  DenseApertureModel model(s);
  return solve(base, model);
}

FlowSolveStatistics FlowNetwork::solve(const Eigen::VectorXd& base, ApertureModel& s) {
  const int n = static_cast<int>(trial_nodes_.size());
  const int nf = static_cast<int>(trial_fractures_.size());
  if (base.size() != 2 * nf || s.n_ends() != 2 * nf || s.n_nodes() != n)
    throw std::invalid_argument("FlowNetwork::solve: aperture model does not match the trial network");
  FlowSolveStatistics stats;
  if (n == 0) return stats;
  Evaluation ev;
  solve_mass_balance(base, s, stats);
  evaluate(unknowns_, base, s, ev, false);
  // Mass-conservative update: the stored mass is what flowed in, to round-off.
  pressure_ = ev.pressure;
  aperture_trial_ = ev.aperture;
  const double round_off = settings_.tolerance * std::max(old_mass_.sum() + injected_.sum(), 1e-300) +
                           residual_round_off();
  for (int i = 0; i < n; ++i) {
    mass_new_[i] = ev.storage[i] - ev.residual[i];
    // Stored mass is never negative: a node emptied to within the solve's tolerance
    // holds none (the ledger then closes to that tolerance); beyond it, the step fails.
    if (mass_new_[i] < 0.0) {
      if (mass_new_[i] < -round_off)
        throw ConvergenceError("fluid flow: a node would store negative mass (" + std::to_string(mass_new_[i]) +
                               " kg): more fluid leaves it than it holds");
      mass_new_[i] = 0.0;
    }
    leak_mass_[i] = wetted_fraction(unknowns_[i], i) * ev.density[i] * leak_volume_[i];
    stats.zero_pressure_nodes += unknowns_[i] < 0.0;
  }
  return stats;
}

void FlowNetwork::commit() {
  const int n = static_cast<int>(trial_nodes_.size());
  const double t0 = time_s_;
  for (std::size_t k = 0; k < trial_fractures_.size(); ++k) {
    const int f = trial_fractures_[k];
    if (!wetted_[f]) arrival_time_[f] = t0;
    wetted_[f] = 1;
    aperture_[2 * f] = aperture_trial_[2 * k];
    aperture_[2 * f + 1] = aperture_trial_[2 * k + 1];
  }
  for (int i = 0; i < n; ++i) {
    const int point = trial_nodes_[i];
    point_pressure_[point] = pressure_[i];
    point_mass_[point] = mass_new_[i];
    point_state_[point] = state_of_unknown(i);
    reached_[point] = 1;
  }
  injected_kg_ += injected_.sum();
  leaked_kg_ += leak_mass_.sum();
  time_s_ += dt_s_;
  trial_wetted_ = wetted_;
}

double FlowNetwork::stored_mass() const {
  double m = 0.0;
  for (double v : point_mass_) m += v;
  return m;
}

double FlowNetwork::mass_balance_error() const {
  // The fluid present at t = 0 counts as injected before the first step.
  const double supplied = injected_kg_ + initial_mass_;
  if (supplied <= 0.0) return 0.0;
  return std::abs(supplied - stored_mass() - leaked_kg_) / supplied;
}

double FlowNetwork::volume_stored_mass() const {
  // Volume per point from the committed apertures of the wetted fractures.
  std::vector<double> volume(point_state_.size(), 0.0);
  for (int f = 0; f < n_fractures(); ++f) {
    if (!wetted_[f]) continue;
    const double half = 0.5 * fractures_[f].length_m;
    volume[fractures_[f].point_p] += half * aperture_[2 * f];
    volume[fractures_[f].point_q] += half * aperture_[2 * f + 1];
  }
  double m = 0.0;
  for (std::size_t point = 0; point < volume.size(); ++point) {
    if (!reached_[point] || volume[point] == 0.0) continue;
    const double state = point_state_[point];  // pressure if full, fill fraction - 1 if not
    const double density = state >= 0.0 ? fluid_.density(state) : fluid_.density(0.0) * (1.0 + state);
    m += density * volume[point];
  }
  return m;
}

double FlowNetwork::volume_balance_error() const {
  const double supplied = injected_kg_ + initial_mass_;
  if (supplied <= 0.0) return 0.0;
  return std::abs(supplied - volume_stored_mass() - leaked_kg_) / supplied;
}

int FlowNetwork::n_nodes() const {
  int n = 0;
  for (char r : reached_) n += r != 0;
  return n;
}

double FlowNetwork::aperture_at_point(int point) const {
  double sum = 0.0;
  int count = 0;
  for (int f = 0; f < n_fractures(); ++f) {
    if (!wetted_[f]) continue;
    if (fractures_[f].point_p == point) sum += aperture_[2 * f], ++count;
    if (fractures_[f].point_q == point) sum += aperture_[2 * f + 1], ++count;
  }
  return count ? sum / count : 0.0;
}

}  // namespace hfdda::fluid
