#include "coupling/coupled_step.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/errors.hpp"

namespace hfdda::coupling {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The round's changes in the order the open-close check makes them: open-close
/// changes and shear failures by contact, then the tension failures (seed 2.3 iii).
std::vector<dda::ContactChange> merge_failures(const std::vector<dda::ContactChange>& open_close,
                                               const std::vector<fracture::BondFailure>& failures) {
  std::vector<dda::ContactChange> changes;
  changes.reserve(open_close.size() + failures.size());
  auto next = open_close.begin();
  for (const auto& f : failures) {
    if (f.mode != fracture::FailureMode::shear) continue;
    for (; next != open_close.end() && next->contact < f.contact; ++next) changes.push_back(*next);
    changes.push_back({f.contact, dda::ContactState::sliding, true, f.friction_sign});
  }
  changes.insert(changes.end(), next, open_close.end());
  for (const auto& f : failures)
    if (f.mode == fracture::FailureMode::tension) changes.push_back({f.contact, dda::ContactState::open, true});
  return changes;
}

}  // namespace

CoupledStep::CoupledStep(dda::BlockSystem& mechanics, std::vector<FluidLoadModel*> fluids,
                         fracture::FractureRules rules)
    : mechanics_(mechanics), fluids_(std::move(fluids)), rules_(rules), bonds_(mechanics) {
  pressurised_.assign(mechanics_.mesh().points.size(), 0);
}

StepStatistics CoupledStep::advance(double dt_s, int max_step_cuts) {
  StepStatistics stats;
  committed_s_ = 0.0;
  advance_into(dt_s, max_step_cuts, stats);
  return stats;
}

void CoupledStep::advance_into(double dt_s, int cuts_left, StepStatistics& stats) {
  try {
    stats.accumulate(attempt(dt_s));
    if (observer_) observer_->attempt_ended(dt_s, attempt_iterations_, {});
    committed_s_ += dt_s;
  } catch (const StepInterrupted& e) {
    if (observer_) observer_->attempt_ended(dt_s, attempt_iterations_, e.what());
    throw;
  } catch (const ConvergenceError& e) {
    if (observer_) observer_->attempt_ended(dt_s, attempt_iterations_, e.what());
    if (cuts_left <= 0) throw;
    ++stats.step_cuts;
    advance_into(0.5 * dt_s, cuts_left - 1, stats);
    advance_into(0.5 * dt_s, cuts_left - 1, stats);
  }
}

void CoupledStep::interrupt_when(std::function<bool()> requested) {
  interrupt_requested_ = std::move(requested);
  // The fluids' inner iterations ask the same question, under the same condition.
  for (FluidLoadModel* f : fluids_)
    f->interrupt_when(interrupt_requested_ ? std::function<bool()>([this] { return may_abandon(); })
                                           : std::function<bool()>{});
}

bool CoupledStep::may_abandon() const {
  return committed_s_ == 0.0 && interrupt_requested_ && interrupt_requested_();
}

void CoupledStep::stop_if_interrupted() const {
  // A cut step whose first sub-steps are committed is finished instead: its state is no
  // longer the step's start, which is what a checkpoint (and a restart) must hold.
  if (may_abandon())
    throw StepInterrupted("the step was abandoned on request; the state is that of its start");
}

StepStatistics CoupledStep::attempt(double dt_s) {
  const auto step_start = Clock::now();
  StepStatistics stats;
  attempt_dt_s_ = dt_s;
  attempt_iterations_ = 0;
  try {
    const auto start = Clock::now();
    mechanics_.begin_step(dt_s);
    for (FluidLoadModel* f : fluids_) f->begin_step(mechanics_, dt_s);
    stats.seconds_assembly += seconds_since(start);
    const Eigen::VectorXd d = open_close_iterations(stats);
    reject_overlapping_faces(d);
    reject_crushed_blocks(d, stats);
    stats.max_unbonded_tension_Pa = mechanics_.largest_unbonded_tension_Pa(d);  // reported, not a guard
    mechanics_.commit(d, dt_s, stats);
    for (FluidLoadModel* f : fluids_) f->commit(mechanics_);
  } catch (...) {
    mechanics_.roll_back();
    for (FluidLoadModel* f : fluids_) f->roll_back();
    throw;
  }
  stats.seconds_total = seconds_since(step_start);
  for (FluidLoadModel* f : fluids_) f->add_statistics(stats);
  return stats;
}

void CoupledStep::reject_overlapping_faces(const Eigen::VectorXd& d) const {
  const double limit = mechanics_.settings().max_overlap_fraction;
  const dda::BlockSystem::FaceOverlap worst = mechanics_.largest_face_overlap(d);
  if (worst.joint < 0 || worst.fraction_of_length <= limit) return;
  const mesh::Joint& joint = mechanics_.mesh().joints[worst.joint];
  const int point = worst.end == 0 ? joint.point_p : joint.point_q;
  const Vec2& at = mechanics_.mesh().points[point];
  std::ostringstream msg;
  msg << "the faces of joint " << worst.joint << " overlap by " << worst.overlap_m << " m at point " << point
      << " (" << at.x() << ", " << at.y() << ") m, " << worst.fraction_of_length
      << " of the joint's length (limit " << limit
      << "): the contact state the iterations ended on is not a solution";
  throw ConvergenceError(msg.str());
}

void CoupledStep::reject_crushed_blocks(const Eigen::VectorXd& d, StepStatistics& stats) const {
  const double limit = mechanics_.settings().max_step_strain;
  const dda::BlockSystem::BlockStrain worst = mechanics_.largest_step_strain(d);
  // Non-finite strains are left to the run's check of non-finite fields, which says so.
  if (worst.block < 0 || !(worst.strain > limit) || !std::isfinite(worst.strain)) {
    if (std::isfinite(worst.strain)) stats.max_block_strain = std::max(stats.max_block_strain, worst.strain);
    return;
  }
  const Vec2 at = mechanics_.centroid(worst.block);
  std::ostringstream msg;
  msg << "block " << worst.block << " at (" << at.x() << ", " << at.y() << ") m would be strained by "
      << worst.strain << " in this step (limit " << limit
      << "): the contact state the iterations ended on is not a solution";
  throw ConvergenceError(msg.str());
}

void CoupledStep::report_iteration(int iteration, int contact_changes, int coupled_changes, const StepStatistics& stats,
                                   const Eigen::VectorXd& d) const {
  IterationRecord r;
  r.attempt_dt_s = attempt_dt_s_;
  r.iteration = iteration;
  r.contact_changes = contact_changes;
  r.coupled_changes = coupled_changes;
  r.bonds_broken = stats.bonds_broken;
  r.cycle_holds = stats.cycle_holds;
  r.mechanism_blocks = stats.max_mechanism_blocks;
  const dda::BlockSystem::FaceOverlap overlap = mechanics_.largest_face_overlap(d);
  r.overlap_fraction = overlap.joint >= 0 ? overlap.fraction_of_length : 0.0;
  r.overlap_joint = overlap.joint;
  const dda::BlockSystem::BlockStrain strain = mechanics_.largest_step_strain(d);
  r.block_strain = strain.block >= 0 ? strain.strain : 0.0;
  r.strain_block = strain.block;
  if (contact_changes > 0) r.first_change = mechanics_.first_change();
  observer_->iteration(r);
}

Eigen::VectorXd CoupledStep::open_close_iterations(StepStatistics& stats) {
  const int max_iterations = mechanics_.settings().max_open_close_iterations;
  bool stiffness_changed = true;
  for (int oc = 1; oc <= max_iterations; ++oc) {
    stop_if_interrupted();
    stats.open_close_iterations = oc;
    if (stiffness_changed) {
      mechanics_.assemble_and_factorise(stats);
      if (mechanics_.settings().converged_response() && !fluids_.empty()) mechanics_.factorise_converged_response(stats);
    }
    const auto start = Clock::now();
    for (FluidLoadModel* f : fluids_) f->prepare(mechanics_, stiffness_changed);
    stats.seconds_solve += seconds_since(start);
    Eigen::VectorXd d = solve_contacts(stats);
    const int contact_changes = update_contact_states(d, stats);
    int coupled_changes = 0;
    for (FluidLoadModel* f : fluids_) coupled_changes += f->update_states(mechanics_);
    stats.coupled_state_changes += coupled_changes;
    attempt_iterations_ = oc;
    if (observer_) report_iteration(oc, contact_changes, coupled_changes, stats, d);
    if (contact_changes + coupled_changes == 0) {
      if (stats.cycle_holds > 0) stats.steps_with_cycles = 1;
      return d;
    }
    stiffness_changed = contact_changes > 0;
  }
  std::ostringstream msg;
  msg << "open-close iterations did not converge in " << max_iterations
      << " iterations: contacts still changing state, e.g. " << mechanics_.first_change();
  throw ConvergenceError(msg.str());
}

Eigen::VectorXd CoupledStep::solve_contacts(StepStatistics& stats) {
  Eigen::VectorXd d, d_previous;
  double displacement_change = 0.0;
  mechanics_.begin_contact_iterations();
  for (int it = 0;; ++it) {
    if (it > 0) stop_if_interrupted();
    const Eigen::VectorXd rhs = mechanics_.contact_rhs();
    const auto start = Clock::now();
    d_previous.swap(d);
    d = mechanics_.solver().solve(rhs);
    for (FluidLoadModel* f : fluids_) f->respond(mechanics_, d);
    stats.seconds_solve += seconds_since(start);
    ++stats.alm_iterations;
    // ||D(m+1) - D(m)|| / ||D(m+1)|| of the inner iterations (erratum 2 in docs/seed_errata.md), reported.
    const double d_norm = d.norm();
    displacement_change = it == 0 || d_norm == 0.0 ? 0.0 : (d - d_previous).norm() / d_norm;
    if (mechanics_.update_multipliers(d, it, stats) != dda::ContactIteration::again) break;
  }
  stats.max_alm_displacement_change = std::max(stats.max_alm_displacement_change, displacement_change);
  return d;
}

int CoupledStep::update_contact_states(const Eigen::VectorXd& d, StepStatistics& stats) {
  const dda::OpenCloseTrial trial = mechanics_.trial_contacts(d, stats);
  if (rules_.failures_on_settled_contacts) {
    // Bonds are judged only on a state whose contacts no longer change: a failure decided
    // while another contact is still, say, locked with a shear force beyond friction
    // would be decided on a state that is not a solution (docs/design_notes.md section 34).
    const int applied = mechanics_.apply_state_changes(d, trial.changes, stats);
    if (applied > 0) return applied;
  }
  const auto failures = rules_.criterion == fracture::FailureCriterion::strength
                            ? fracture::failing_bonds(overloaded_bonds(trial), pressurised_points(), rules_)
                            : toughness_failures(trial, d);
  // Settled: this round's contact changes were offered above and none was applied (those
  // left are held by the cycle rule, already counted); only the failures remain.
  const std::vector<dda::ContactChange> none;
  const auto& open_close = rules_.failures_on_settled_contacts ? none : trial.changes;
  return mechanics_.apply_state_changes(d, merge_failures(open_close, failures), stats);
}

std::vector<fracture::BondFailure> CoupledStep::toughness_failures(const dda::OpenCloseTrial& trial,
                                                                   const Eigen::VectorXd& d) {
  bonds_.crack_tips().find(mechanics_, trial.tractions, d, tips_, at_tip_);
  const std::vector<char>& pressurised = pressurised_points();
  std::vector<double> ratios(tips_.size(), 0.0);
  for (std::size_t i = 0; i < tips_.size(); ++i) {
    const CrackTipState& t = tips_[i];
    if (t.failing_joint < 0) continue;
    const int ci = t.failing_contact;
    // Rule (i) of seed 2.3 at the tip: the contact that would open first must be eligible.
    fracture::Bond b = bonds_.bond(mechanics_, ci, trial.tractions[ci].normal_N, trial.tractions[ci].shear_N);
    if (rules_.failure_needs_open_neighbour_and_fluid) BondList::add_neighbours(mechanics_, b);
    if (fracture::may_fail(b, pressurised, rules_)) ratios[i] = fracture::mixed_mode_ratio(t.tip, rules_.toughness);
  }
  std::vector<fracture::BondFailure> failures = fracture::failing_bonds(overloaded_bonds(trial, at_tip_), pressurised, rules_);
  const std::vector<int> critical = fracture::critical_tips(ratios);
  std::vector<int> opening_joints;
  if (critical.empty()) {
    for (const auto& f : failures)
      if (f.mode == fracture::FailureMode::tension) opening_joints.push_back(mechanics_.contacts()[f.contact].joint);
  } else {
    for (int i : critical) opening_joints.push_back(tips_[i].failing_joint);
  }
  // A joint opens whole: a half-open joint would leave its tip inside the joint, where
  // the closure data of whole joints cannot see it.
  std::erase_if(failures, [](const fracture::BondFailure& f) { return f.mode == fracture::FailureMode::tension; });
  const auto& contacts = mechanics_.contacts();
  for (int joint : opening_joints)
    for (int ci : mechanics_.joint_contacts(joint))
      if (contacts[ci].bonded && std::none_of(failures.begin(), failures.end(), [ci](const auto& f) { return f.contact == ci; }))
        failures.push_back({ci, fracture::FailureMode::tension, 0.0});  // two tips may pick one joint
  return failures;
}

std::vector<fracture::Bond> CoupledStep::overloaded_bonds(const dda::OpenCloseTrial& trial,
                                                          const std::vector<char>& skip) const {
  std::vector<fracture::Bond> bonds;
  for (int ci = 0; ci < static_cast<int>(trial.tractions.size()); ++ci) {
    if (!bonds_.is_candidate(mechanics_, ci) || (!skip.empty() && skip[ci])) continue;
    fracture::Bond b = bonds_.bond(mechanics_, ci, trial.tractions[ci].normal_N, trial.tractions[ci].shear_N);
    // Only a bond over a limit is a candidate; the neighbour searches (seed 2.3 i, 5.1)
    // are then made for those few, not for every intact bond of every iteration.
    if (fracture::failure_mode(b, rules_.shear_failure_of_intact_joints) == fracture::FailureMode::none) continue;
    if (rules_.failure_needs_open_neighbour_and_fluid) BondList::add_neighbours(mechanics_, b);
    bonds.push_back(b);
  }
  return bonds;
}

const std::vector<char>& CoupledStep::pressurised_points() {
  if (fluids_.size() == 1) return fluids_.front()->pressurised_points();
  std::fill(pressurised_.begin(), pressurised_.end(), 0);
  for (const FluidLoadModel* f : fluids_) {
    const auto& mask = f->pressurised_points();
    for (std::size_t p = 0; p < pressurised_.size(); ++p) pressurised_[p] |= mask[p];
  }
  return pressurised_;
}

}  // namespace hfdda::coupling
