// The network, its trial topology of a step (and the TrialNetwork its mass balance is
// solved on), the commit of a solved step and the mass ledger. The mass balance itself
// is in mass_balance.cpp, its solve in mass_balance_solver.cpp and
// mass_balance_fallbacks.cpp.

#include "fluid/flow_network.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"

namespace hfdda::fluid {

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
  if (vent(injection.point)) throw std::invalid_argument("FlowNetwork: an injection point cannot be a vent");
  if (!(injection.system_compliance_m2_Pa >= 0.0))
    throw std::invalid_argument("FlowNetwork: negative compliance of an injection system");
  // The system starts at zero pressure with its lines full: what it holds is counted
  // from there, so a fluid already under pressure at its point would need a share of
  // its own (not modelled; refused).
  if (injection.system_compliance_m2_Pa > 0.0 && reached_[injection.point] && point_state_[injection.point] > 0.0)
    throw std::invalid_argument("FlowNetwork: an injection system with a compliance must start at zero pressure");
  injections_.push_back(injection);
}

void FlowNetwork::fill_initially(int f, double width_m, double pressure_Pa) {
  // At least the minimum width in all, w0 included (a closed fracture with w0 holds w0).
  const double w0 = fractures_[f].hydraulic_width_m;
  const double w = std::max(width_m + w0, settings_.min_width_main_m) - w0;
  fill_initially(f, {w, w}, pressure_Pa);
}

void FlowNetwork::fill_initially(int f, const std::array<double, 2>& end_width_m, double pressure_Pa) {
  if (!(pressure_Pa >= 0.0)) throw std::invalid_argument("FlowNetwork::fill_initially: negative pressure");
  for (const auto& inj : injections_)
    if (pressure_Pa > 0.0 && inj.system_compliance_m2_Pa > 0.0 &&
        (inj.point == fractures_[f].point_p || inj.point == fractures_[f].point_q))
      throw std::invalid_argument("FlowNetwork: an injection system with a compliance must start at zero pressure");
  wetted_[f] = 1;
  arrival_time_[f] = time_s_;
  const int points[2] = {fractures_[f].point_p, fractures_[f].point_q};
  for (int end = 0; end < 2; ++end) {
    // The fluid fills the hydraulic width, w0 included (the flow's aperture is the
    // opening plus w0), so that a filled fracture with w0 starts full.
    const double w = std::max(end_width_m[end] + fractures_[f].hydraulic_width_m, settings_.min_width_tip_m);
    aperture_[2 * f + end] = w;
    const double mass = fluid_.density(pressure_Pa) * 0.5 * fractures_[f].length_m * w;
    point_mass_[points[end]] += mass;
    initial_mass_ += mass;
    reached_[points[end]] = 1;
    point_state_[points[end]] = pressure_Pa;  // full at that pressure
    point_pressure_[points[end]] = pressure_Pa;
  }
  trial_wetted_ = wetted_;
}

void FlowNetwork::set_vents(std::vector<char> vent_points) {
  if (vent_points.size() != node_of_point_.size())
    throw std::invalid_argument("FlowNetwork::set_vents: one flag per point expected");
  for (const auto& inj : injections_)
    if (vent_points[inj.point])
      throw std::invalid_argument("FlowNetwork::set_vents: an injection point cannot be a vent");
  vent_point_ = std::move(vent_points);
}

// ----------------------------------------------------------------------------------
// Trial network of a step

void FlowNetwork::begin_step(double dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("FlowNetwork::begin_step: dt must be positive");
  trial_.dt_s = dt_s;
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
  return i >= 0 && i < unknowns_.size() && unknowns_[i] > 0.0 && !vent(point);  // a vent stays at zero pressure
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
  std::vector<int>& node_a = trial_.node_a;
  std::vector<int>& node_b = trial_.node_b;
  node_a.resize(nf);
  node_b.resize(nf);
  auto node = [&](int point) {
    if (node_of_point_[point] < 0) {
      node_of_point_[point] = static_cast<int>(trial_nodes_.size());
      trial_nodes_.push_back(point);
    }
    return node_of_point_[point];
  };
  for (int k = 0; k < nf; ++k) {
    node_a[k] = node(fractures_[trial_fractures_[k]].point_p);
    node_b[k] = node(fractures_[trial_fractures_[k]].point_q);
  }
  const int n = static_cast<int>(trial_nodes_.size());
  const double t0 = time_s_, t1 = time_s_ + trial_.dt_s;

  Eigen::VectorXd& leak_volume = trial_.leak_volume_m3;
  trial_.old_mass_kg.setZero(n);
  trial_.injected_kg.setZero(n);
  leak_volume.setZero(n);
  std::vector<int> degree(n, 0);
  for (int i = 0; i < n; ++i) trial_.old_mass_kg[i] = point_mass_[trial_nodes_[i]];
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
    trial_.injected_kg[i] += mass;
  }
  const double cl = fluid_.leak_off_coefficient_m_sqrt_s;
  for (int k = 0; k < nf; ++k) {
    const int f = trial_fractures_[k];
    ++degree[node_a[k]];
    ++degree[node_b[k]];
    if (cl <= 0.0) continue;
    // Fluid arrives in a newly wetted fracture at the start of the step.
    const double arrival = wetted_[f] ? arrival_time_[f] : t0;
    const double per_node =
        cl * fractures_[f].length_m * 2.0 * (std::sqrt(t1 - arrival) - std::sqrt(std::max(0.0, t0 - arrival)));
    leak_volume[node_a[k]] += per_node;
    leak_volume[node_b[k]] += per_node;
  }
  trial_.floor_m.setZero(2 * nf);
  for (int k = 0; k < nf; ++k) {
    const int f = trial_fractures_[k];
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? node_a[k] : node_b[k];
      const double minimum = degree[i] >= 2 ? settings_.min_width_main_m : settings_.min_width_tip_m;
      const double closing = wetted_[f] ? (1.0 - settings_.max_closing_fraction) * aperture_[2 * f + end] : 0.0;
      trial_.floor_m[2 * k + end] = std::max({minimum, closing, fractures_[f].hydraulic_width_m});
    }
  }
  set_trial_fracture_data();
  // Warm start from the last state of each node; a node the fluid reaches for the
  // first time starts empty (fill fraction 0).
  Eigen::VectorXd& fill_scale = trial_.fill_scale_Pa;
  unknowns_.setZero(n);
  fill_scale.setConstant(n, fluid_.bulk_modulus_Pa);
  for (int i = 0; i < n; ++i) {
    const int point = trial_nodes_[i];
    const double state = reached_[point] ? guess_state_[point] : -1.0;
    unknowns_[i] = state >= 0.0 ? state : state * fill_scale[i];
  }
  pressure_ = unknowns_.cwiseMax(0.0);  // a vent's committed state is never above 0
  aperture_trial_.setZero(2 * nf);
  mass_new_.setZero(n);
  leak_mass_.setZero(n);
  vent_mass_.setZero(n);
}

void FlowNetwork::set_trial_fracture_data() {
  const int nf = static_cast<int>(trial_fractures_.size());
  trial_.length_m.resize(nf);
  trial_.hydraulic_width_m.setZero(2 * nf);
  trial_.held_open_floor_m = trial_.floor_m;
  trial_.vent.assign(trial_nodes_.size(), 0);
  trial_.system_compliance_m2_Pa.resize(0);
  for (const auto& inj : injections_) {
    const int i = node_of_point_[inj.point];
    if (i < 0 || inj.system_compliance_m2_Pa == 0.0) continue;
    if (trial_.system_compliance_m2_Pa.size() == 0) trial_.system_compliance_m2_Pa.setZero(trial_nodes_.size());
    trial_.system_compliance_m2_Pa[i] += inj.system_compliance_m2_Pa;
  }
  if (!vent_point_.empty())
    for (std::size_t i = 0; i < trial_nodes_.size(); ++i) trial_.vent[i] = vent_point_[trial_nodes_[i]];
  for (int k = 0; k < nf; ++k) {
    const int f = trial_fractures_[k];
    trial_.length_m[k] = fractures_[f].length_m;
    trial_.hydraulic_width_m.segment<2>(2 * k).setConstant(fractures_[f].hydraulic_width_m);
    // A closing joint held open does not close in this step: its floor is its committed aperture.
    if (!wetted_[f]) continue;
    for (int end = 0; end < 2; ++end)
      trial_.held_open_floor_m[2 * k + end] = std::max(trial_.floor_m[2 * k + end], aperture_[2 * f + end]);
  }
}

double FlowNetwork::state_of_unknown(int i) const {
  return MassBalance(fluid_, trial_).state_of_unknown(unknowns_[i], i);
}

// ----------------------------------------------------------------------------------
// Solve and commit

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
  MassBalanceSolver(trial_, fluid_, settings_, unknowns_, &interrupt_).solve(base, s, stats);
  const MassBalance balance(fluid_, trial_);
  MassBalance::Evaluation ev;
  balance.evaluate(unknowns_, base, s, ev, false);
  // Mass-conservative update: the stored mass is what flowed in, to round-off.
  pressure_ = ev.pressure;
  aperture_trial_ = ev.aperture;
  const double round_off = settings_.tolerance * balance.mass_scale() + balance.residual_round_off();
  for (int i = 0; i < n; ++i) {
    mass_new_[i] = ev.storage[i] - ev.vented[i] - ev.residual[i];
    vent_mass_[i] = ev.vented[i];
    // Stored mass is never negative: a node emptied to within the solve's tolerance
    // holds none (the ledger then closes to that tolerance); beyond it, the step fails.
    if (mass_new_[i] < 0.0) {
      if (mass_new_[i] < -round_off)
        throw ConvergenceError("fluid flow: a node would store negative mass (" + std::to_string(mass_new_[i]) +
                               " kg): more fluid leaves it than it holds");
      mass_new_[i] = 0.0;
    }
    leak_mass_[i] = balance.wetted_fraction(unknowns_[i], i) * ev.density[i] * trial_.leak_volume_m3[i];
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
  injected_kg_ += trial_.injected_kg.sum();
  leaked_kg_ += leak_mass_.sum();
  vented_kg_ += vent_mass_.sum();
  time_s_ += trial_.dt_s;
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
  return std::abs(supplied - stored_mass() - leaked_kg_ - vented_kg_) / supplied;
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
  // What the injection systems hold under pressure: at the pressure the solve used
  // (rounded near zero, MassBalance::kPressureRounding), not the fill state.
  for (const auto& inj : injections_)
    if (reached_[inj.point]) m += fluid_.density(0.0) * inj.system_compliance_m2_Pa * point_pressure_[inj.point];
  return m;
}

double FlowNetwork::volume_balance_error() const {
  const double supplied = injected_kg_ + initial_mass_;
  if (supplied <= 0.0) return 0.0;
  return std::abs(supplied - volume_stored_mass() - leaked_kg_ - vented_kg_) / supplied;
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
