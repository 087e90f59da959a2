#include "simulation/load_ramp.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "core/binary_io.hpp"
#include "fracture/fracture_criteria.hpp"

namespace hfdda::simulation {

namespace {

/// s(t) of a piecewise-linear history, constant beyond its ends.
double history_level(const std::vector<Vec2>& history, double t) {
  if (t <= history.front().x()) return history.front().y();
  for (std::size_t i = 1; i < history.size(); ++i)
    if (t <= history[i].x()) {
      const double w = (t - history[i - 1].x()) / (history[i].x() - history[i - 1].x());
      return (1.0 - w) * history[i - 1].y() + w * history[i].y();
    }
  return history.back().y();
}

/// A fracture belongs to a stop name if it is named so, or is a line of the breakable
/// pattern or a fracture of the set of that name (`<name>.<family>`, `<name>.<k>`).
bool belongs_to(const std::string& fracture_name, const std::vector<std::string>& names) {
  for (const std::string& n : names)
    if (fracture_name == n || fracture_name.starts_with(n + ".")) return true;
  return false;
}

}  // namespace

LoadRamp::LoadRamp(const io::CaseConfig& config, const dda::BlockSystem& system,
                   const std::vector<int>& fracture_of_joint, const std::vector<std::string>& fracture_names,
                   const coupling::BondList& bonds, const fracture::FractureRules& rules)
    : config_(*config.load_ramp),
      bonds_(bonds),
      dt_s_(config.time.dt_s),
      shear_failure_(rules.shear_failure_of_intact_joints),
      criterion_(rules.criterion),
      toughness_(rules.toughness),
      uniform_(config.load_ramp->history.empty()) {
  if (uniform_) {
    const double start = config_.start_Pa.value_or(0.0);
    // The tolerance keeps a maximum that is a whole number of increments from start.
    n_levels_ = static_cast<long long>(std::floor((*config_.maximum_Pa - start) / *config_.increment_Pa + 1e-9)) + 1;
  } else {
    n_levels_ = static_cast<long long>(std::floor(config_.history.back().x() / dt_s_ + 1e-9));
  }
  const auto& joints = system.mesh().joints;
  const auto& contacts = system.contacts();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const auto ends = system.joint_contacts(static_cast<int>(j));
    if (joints[j].properties.breakable)
      for (int ci : ends)
        if (contacts[ci].bonded) bond_contacts_.push_back(ci);
    const int f = fracture_of_joint[j];
    if (config_.stop_when == "broken_fraction" && f >= 0 && belongs_to(fracture_names[f], config_.stop_joints))
      for (int ci : ends) {
        stop_contacts_.push_back(ci);
        stop_length_m_ += contacts[ci].length_m;
      }
    if (joints[j].properties.breakable && !joints[j].properties.initially_open)
      intact_joints_.push_back(static_cast<int>(j));
  }
}

bool LoadRamp::has_next() const { return !outcome_.stop_reached && next_index_ < n_levels_; }

double LoadRamp::next_level() {
  const long long k = next_index_++;
  current_level_ = uniform_ ? config_.start_Pa.value_or(0.0) + static_cast<double>(k) * *config_.increment_Pa
                            : history_level(config_.history, static_cast<double>(k + 1) * dt_s_);
  return current_level_;
}

std::vector<double> LoadRamp::margins(const dda::BlockSystem& system, std::vector<fracture::CrackTip>& tips) const {
  const auto& contacts = system.contacts();
  std::vector<char> at_tip;
  tips.clear();
  if (criterion_ == fracture::FailureCriterion::energy_release_rate) {
    std::vector<coupling::CrackTipState> states;
    bonds_.crack_tips().find(system, coupling::CrackTips::committed_tractions(system), Eigen::VectorXd(), states,
                             at_tip);
    for (const auto& t : states)
      if (t.failing_joint >= 0) tips.push_back(t.tip);
  }
  std::vector<double> m;
  m.reserve(bond_contacts_.size());
  for (int ci : bond_contacts_) {
    // Broken since, or left to a crack tip's criterion: no strength limit to reach.
    if (!contacts[ci].bonded || (!at_tip.empty() && at_tip[ci])) {
      m.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    const auto [normal_N, shear_N] = system.contact_forces(ci);
    m.push_back(fracture::failure_margin_N(bonds_.bond(system, ci, normal_N, shear_N), shear_failure_));
  }
  return m;
}

std::vector<std::uint8_t> LoadRamp::contact_states(const dda::BlockSystem& system) {
  const auto& contacts = system.contacts();
  std::vector<std::pair<double, double>> forces(contacts.size());
  double largest_N = 0.0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    forces[i] = system.contact_forces(static_cast<int>(i));
    largest_N = std::max({largest_N, std::abs(forces[i].first), std::abs(forces[i].second)});
  }
  std::vector<std::uint8_t> states(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const auto& c = contacts[i];
    // An unbonded contact closed without force is the open one's solution: its faces meet
    // with no gap, slip or load, as at the corner of a crack's tip, where the two faces
    // share the tip's point and round-off decides each level whether the contact counts
    // as touching. Such a flip changes nothing the next levels depend on, so it is not a
    // change of state here (docs/design_notes.md section 13).
    const bool inert = !c.bonded && c.state != dda::ContactState::open &&
                       std::max(std::abs(forces[i].first), std::abs(forces[i].second)) <= kInertContactForce * largest_N;
    const int state = inert ? static_cast<int>(dda::ContactState::open) : static_cast<int>(c.state);
    states[i] = static_cast<std::uint8_t>(state | (c.bonded ? 8 : 0) | (c.vertex_vertex_active ? 16 : 0));
  }
  return states;
}

double LoadRamp::tips_critical_level(const std::vector<fracture::CrackTip>& now) const {
  double level = std::numeric_limits<double>::infinity();
  if (now.size() != tips_.size()) return level;
  for (std::size_t i = 0; i < now.size(); ++i) {
    if (now[i].joint != tips_[i].joint || now[i].behind_joint != tips_[i].behind_joint) return level;
    level = std::min(level, fracture::level_at_critical_ratio(margins_level_, tips_[i], current_level_, now[i], toughness_));
  }
  return level;
}

void LoadRamp::try_jump(const dda::BlockSystem& system) {
  std::vector<fracture::CrackTip> tips;
  std::vector<double> now = margins(system, tips);
  std::vector<std::uint8_t> states = contact_states(system);
  // Two levels predict the next failure only if no contact changed state between them:
  // a contact that opened or started to slide (crack faces in shear) makes the response
  // non-linear and path-dependent, and a jump over it can land past the failure.
  if (!have_margins_ || current_level_ == margins_level_ || states != states_at_margins_) {
    bond_margins_ = std::move(now);
    tips_ = std::move(tips);
    states_at_margins_ = std::move(states);
    margins_level_ = current_level_;
    have_margins_ = true;
    return;
  }
  double predicted = tips_critical_level(tips);
  for (std::size_t i = 0; i < now.size(); ++i)
    predicted = std::min(predicted, fracture::level_at_zero_margin(margins_level_, bond_margins_[i], current_level_, now[i]));
  bond_margins_ = std::move(now);  // the next prediction may start from this level
  tips_ = std::move(tips);
  states_at_margins_ = std::move(states);
  margins_level_ = current_level_;
  if (!std::isfinite(predicted)) return;
  if (std::isnan(outcome_.first_failure_Pa) && std::isnan(outcome_.predicted_first_failure_Pa))
    outcome_.predicted_first_failure_Pa = predicted;
  const double increment = *config_.increment_Pa;
  const double target = predicted - std::max(2.0 * increment, 0.01 * std::abs(predicted));
  const double k = std::floor((target - config_.start_Pa.value_or(0.0)) / increment);
  if (k > static_cast<double>(next_index_) && k < static_cast<double>(n_levels_)) {
    next_index_ = static_cast<long long>(k);
    jumped_this_step_ = true;  // the next step is the jump
    ++outcome_.jumps;
  }
}

bool LoadRamp::stop_condition_met(const dda::BlockSystem& system) {
  const auto& contacts = system.contacts();
  if (config_.stop_when == "broken_fraction") {
    double broken = 0.0;
    for (int ci : stop_contacts_)
      if (!contacts[ci].bonded) broken += contacts[ci].length_m;
    outcome_.broken_fraction = stop_length_m_ > 0.0 ? broken / stop_length_m_ : 0.0;
    return outcome_.broken_fraction > config_.stop_fraction;
  }
  if (config_.stop_when == "failed_both_sides") {
    const Vec2 direction = config_.crack_direction.normalized();
    const auto& mesh = system.mesh();
    bool before = false, after = false;
    for (int j : intact_joints_) {
      const auto ends = system.joint_contacts(j);
      if (contacts[ends[0]].bonded || contacts[ends[1]].bonded) continue;
      const Vec2 mid = 0.5 * (mesh.points[mesh.joints[j].point_p] + mesh.points[mesh.joints[j].point_q]);
      const double s = (mid - config_.crack_centre).dot(direction);
      before = before || s < 0.0;
      after = after || s > 0.0;
    }
    return before && after;
  }
  return false;
}

void LoadRamp::after_step(const dda::BlockSystem& system, int step, int bonds_broken_in_step) {
  const bool was_jump = jumped_this_step_;
  jumped_this_step_ = false;
  ++outcome_.levels_solved;
  outcome_.last_level_Pa = current_level_;
  if (was_jump && std::isnan(outcome_.jumped_to_Pa)) outcome_.jumped_to_Pa = current_level_;
  if (bonds_broken_in_step > 0) {
    have_margins_ = false;  // the response changed: two new levels before the next prediction
    if (was_jump) ++outcome_.failures_at_jump;
  }
  if (bonds_broken_in_step > 0 && std::isnan(outcome_.first_failure_Pa)) {
    outcome_.first_failure_Pa = current_level_;
    outcome_.first_failure_step = step;
    outcome_.first_failure_at_jump = was_jump;
  }
  if (std::isnan(outcome_.first_joint_failure_Pa) && bonds_broken_in_step > 0) {
    const auto& contacts = system.contacts();
    for (int j : intact_joints_) {
      const auto ends = system.joint_contacts(j);
      if (!contacts[ends[0]].bonded && !contacts[ends[1]].bonded) {
        outcome_.first_joint_failure_Pa = current_level_;
        break;
      }
    }
  }
  if (stop_condition_met(system)) {
    outcome_.stop_reached = true;
    outcome_.stop_Pa = current_level_;
    outcome_.stop_step = step;
    return;
  }
  if (uniform_ && config_.predict_failures && bonds_broken_in_step == 0) try_jump(system);
}

void LoadRamp::save_state(BinaryWriter& out) const {
  static_assert(std::is_trivially_copyable_v<LoadRampOutcome>);
  out.put_vector(bond_contacts_);
  out.put_vector(stop_contacts_);
  out.put(n_levels_);
  out.put(next_index_);
  out.put(current_level_);
  out.put(jumped_this_step_);
  out.put_vector(bond_margins_);
  out.put_vector(tips_);
  out.put(margins_level_);
  out.put(have_margins_);
  out.put_vector(states_at_margins_);
  out.put(outcome_);
}

void LoadRamp::restore_state(BinaryReader& in) {
  std::vector<int> bonds, stops;
  in.get_vector(bonds);
  in.get_vector(stops);
  if (bonds != bond_contacts_ || stops != stop_contacts_)
    throw std::runtime_error("checkpoint does not match the model: load ramp joints");
  in.get(n_levels_);
  in.get(next_index_);
  in.get(current_level_);
  in.get(jumped_this_step_);
  in.get_vector(bond_margins_);
  in.get_vector(tips_);
  in.get(margins_level_);
  in.get(have_margins_);
  in.get_vector(states_at_margins_);
  in.get(outcome_);
}

}  // namespace hfdda::simulation
