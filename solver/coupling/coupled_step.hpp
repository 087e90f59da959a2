#pragma once
// One time step of a case (seed 2.4, Figures 2.7-2.8): the composition of the blocks
// (dda::BlockSystem), the fluid models acting on them (flow network, prescribed
// pressure) and the bond failures (fracture/), with the step cut-back that retries a
// step that did not converge.
//
// A step: mechanics.begin_step, fluids' begin_step; then open-close iterations, each
//   [assemble and factorise K if the contact states changed] -> fluids' prepare ->
//   contact iterations (rhs -> K^-1 -> fluids' respond -> multiplier update) ->
//   trial tractions -> bond failures -> contact state changes -> fluids' state changes
// until nothing changes; then commit everything, or roll everything back.

#include <functional>
#include <vector>

#include "core/step_statistics.hpp"
#include "coupling/bond_list.hpp"
#include "coupling/fluid_load_model.hpp"
#include "coupling/iteration_observer.hpp"
#include "dda/block_system.hpp"
#include "fracture/fracture_criteria.hpp"

namespace hfdda::coupling {

class CoupledStep {
 public:
  /// `fluids` may be empty (mechanics alone); their loads add up and a point is
  /// pressurised if any of them pressurises it. All must outlive the step object.
  CoupledStep(dda::BlockSystem& mechanics, std::vector<FluidLoadModel*> fluids, fracture::FractureRules rules = {});

  /// Advances by dt. A step that does not converge is cut in two halves, recursively
  /// up to `max_step_cuts` levels deep; the statistics of every sub-step are summed.
  /// Throws the last ConvergenceError if even the smallest sub-step fails (the
  /// committed state is then the last converged sub-step).
  StepStatistics advance(double dt_s, int max_step_cuts);
  /// The time the last advance() committed [s]: its dt when it returned; when it threw,
  /// the sum of the sub-steps that converged before the one that failed (0 if none did),
  /// so that a run stopped there can say which time its state is at.
  double committed_time_s() const { return committed_s_; }
  /// Reports every open-close iteration and every attempt's end to `observer` (nullptr:
  /// nobody; the default). The observer must outlive its use; observing costs one pass
  /// over the joints and blocks per iteration.
  void observe_iterations(IterationObserver* observer) { observer_ = observer; }
  /// Asked before every open-close and contact iteration; true abandons the step with
  /// StepInterrupted, the attempt rolled back, so long as no sub-step of a cut step has
  /// been committed yet (the state is then the step's start; otherwise the step goes on
  /// to its end). Empty (the default): never.
  void interrupt_when(std::function<bool()> requested);
  /// The intact bonds of the mechanics (also read by the load ramp).
  const BondList& bonds() const { return bonds_; }

 private:
  void advance_into(double dt_s, int cuts_left, StepStatistics& stats);
  /// Tells the observer about open-close iteration `iteration` of the current attempt.
  void report_iteration(int iteration, int contact_changes, int coupled_changes, const StepStatistics& stats,
                        const Eigen::VectorXd& d) const;
  /// One step without cut-back; throws ConvergenceError after rolling everything back.
  StepStatistics attempt(double dt_s);
  /// Throws ConvergenceError (the step is cut) where the iterations ended with two
  /// faces of a joint overlapping by more than max_overlap_fraction of its length.
  void reject_overlapping_faces(const Eigen::VectorXd& d) const;
  /// Throws ConvergenceError if d strains a block beyond MechanicsSettings::max_step_strain.
  /// Records the largest strain in stats.max_block_strain.
  void reject_crushed_blocks(const Eigen::VectorXd& d, StepStatistics& stats) const;
  /// Open-close iterations until no state changes; the converged displacement.
  Eigen::VectorXd open_close_iterations(StepStatistics& stats);
  /// The contact iterations (ALM or penalty) of one open-close iteration.
  Eigen::VectorXd solve_contacts(StepStatistics& stats);
  /// Trial tractions, bond failures and contact state changes; returns the count applied.
  int update_contact_states(const Eigen::VectorXd& d, StepStatistics& stats);
  /// Intact breakable bonds over their tensile or shear limit at the trial state, but
  /// those marked in `skip` (per joint contact; empty: none).
  std::vector<fracture::Bond> overloaded_bonds(const dda::OpenCloseTrial& trial,
                                               const std::vector<char>& skip = {}) const;
  /// The failures of the energy_release_rate criterion: at every crack tip whose
  /// mixed-mode ratio reaches 1 its failing joint (both bonded contacts open), and the
  /// strength rules for the bonds away from tips; tip failures go first, so the strength
  /// tension failures wait for a round without one (seed 2.3 iii: one change at a time).
  std::vector<fracture::BondFailure> toughness_failures(const dda::OpenCloseTrial& trial, const Eigen::VectorXd& d);
  const std::vector<char>& pressurised_points();
  /// Throws StepInterrupted if a stop was requested and the step may still be abandoned.
  void stop_if_interrupted() const;
  /// A stop was requested and the step may still be abandoned (nothing of it committed).
  bool may_abandon() const;

  dda::BlockSystem& mechanics_;
  std::vector<FluidLoadModel*> fluids_;
  fracture::FractureRules rules_;
  IterationObserver* observer_ = nullptr;
  std::function<bool()> interrupt_requested_;
  double attempt_dt_s_ = 0.0;   // time step of the current attempt [s]
  int attempt_iterations_ = 0;  // open-close iterations of the current attempt so far
  double committed_s_ = 0.0;  // time committed by the current or last advance() [s]
  BondList bonds_;
  std::vector<char> pressurised_;                      // union of the fluids' masks
  std::vector<CrackTipState> tips_;                    // energy criterion: this round's tips
  std::vector<char> at_tip_;                           // per joint contact: governed by a tip
};

}  // namespace hfdda::coupling
