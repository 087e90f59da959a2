#pragma once
// The quasi-static load ramp of a case (io::LoadRampConfig; seed 4.2-4.4): which load
// level each step applies, the skip to just below the first failure, the stop
// condition, and what the run records about them.
//
// Between two bond failures a static DDA system is linear in its loads (intact joints
// stay bonded, open crack faces stay open): the margin of every intact bond to its limit
// (fracture::failure_margin_N) is then linear in the level, so two levels without a
// failure predict the next one. The ramp goes on from 2 increments (or 1 %, the larger)
// below the prediction; every level from there on is solved, so each failure level has
// the resolution of one increment, as in the seed's ramps. If a bond fails at a level
// reached by a jump itself, the prediction was not safe there and the outcome says so.
// With the energy criterion a tip's energy release rate is quadratic in the level
// (forces and openings each linear), so its level comes from the root of a quadratic
// (fracture::level_at_critical_ratio): sqrt(G_c / G) times the level under a load
// proportional to it.

#include <limits>
#include <string>
#include <cstdint>
#include <vector>

#include "coupling/bond_list.hpp"
#include "dda/block_system.hpp"
#include "fracture/fracture_criteria.hpp"
#include "io/case_config.hpp"

namespace hfdda {
class BinaryWriter;
class BinaryReader;
}  // namespace hfdda

namespace hfdda::simulation {

struct LoadRampOutcome {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  int levels_solved = 0;
  double last_level_Pa = kNone;
  double predicted_first_failure_Pa = kNone;  ///< linear prediction of the first failure (NaN: none made)
  double jumped_to_Pa = kNone;                ///< level of the first jump (NaN: no jump)
  double first_failure_Pa = kNone;            ///< level of the first bond failure (NaN: none)
  int first_failure_step = 0;
  /// Level at which a whole joint (both ends) not initially open first failed (NaN: none);
  /// the seed's "initiation" of a crack whose tip half-joint may have failed earlier.
  double first_joint_failure_Pa = kNone;
  bool first_failure_at_jump = false;  ///< it failed at the jumped-to level: resolution not guaranteed
  int jumps = 0;                       ///< jumps made over linear stretches
  int failures_at_jump = 0;            ///< levels reached by a jump at which bonds failed (should be 0)
  bool stop_reached = false;
  double stop_Pa = kNone;              ///< level at which the stop condition was met
  int stop_step = 0;
  double broken_fraction = 0.0;        ///< broken_fraction stop: its value after the last step
};

class LoadRamp {
 public:
  /// `fracture_of_joint`: per joint, index into `fracture_names` (-1: none), the model's
  /// fractures (written, then generated).
  /// `bonds`: the bond list of the model's coupled step (must outlive the ramp);
  /// `rules`: the failure rules of that step (the criterion, shear failure of intact joints).
  LoadRamp(const io::CaseConfig& config, const dda::BlockSystem& system, const std::vector<int>& fracture_of_joint,
           const std::vector<std::string>& fracture_names, const coupling::BondList& bonds,
           const fracture::FractureRules& rules);

  /// True while there is a level to solve and the stop condition is not met.
  bool has_next() const;
  /// The level of the next step [Pa] (advances the ramp).
  double next_level();
  /// After the step at the level last returned: first failure, stop condition, jump.
  void after_step(const dda::BlockSystem& system, int step, int bonds_broken_in_step);

  const LoadRampOutcome& outcome() const { return outcome_; }
  /// Broken fraction of the stop joints now (0 without a broken_fraction stop).
  double broken_fraction() const { return outcome_.broken_fraction; }

  /// The ramp's progress (next level, margins of the last level, outcome so far) for a
  /// checkpoint; restore into a ramp built from the same case and mesh.
  void save_state(BinaryWriter& out) const;
  void restore_state(BinaryReader& in);

 private:
  /// The margin of every bond of bond_contacts_ (+infinity once broken, or while a
  /// crack tip governs it) and, with the energy criterion, the crack tips.
  std::vector<double> margins(const dda::BlockSystem& system, std::vector<fracture::CrackTip>& tips) const;
  /// The lowest level at which a tip's mixed-mode ratio reaches 1, from the tips at the
  /// last level and now (+infinity: none, or the tips are not the same joints).
  double tips_critical_level(const std::vector<fracture::CrackTip>& now) const;
  /// State of every contact (open, locked, sliding; bonded; vertex-vertex active).
  static std::vector<std::uint8_t> contact_states(const dda::BlockSystem& system);
  /// A closed, unbonded contact whose normal and shear forces are both at most this
  /// fraction of the largest contact force counts as open in contact_states().
  static constexpr double kInertContactForce = 1.0e-6;
  void try_jump(const dda::BlockSystem& system);
  bool stop_condition_met(const dda::BlockSystem& system);

  io::LoadRampConfig config_;
  const coupling::BondList& bonds_;
  double dt_s_;
  bool shear_failure_;
  fracture::FailureCriterion criterion_;
  fracture::Toughness toughness_;
  bool uniform_;
  long long n_levels_ = 0;   // uniform: levels start + k increment, k < n_levels_; history: steps
  long long next_index_ = 0;
  double current_level_ = 0.0;
  bool jumped_this_step_ = false;
  std::vector<int> bond_contacts_;       // intact breakable bonds at the start
  std::vector<double> bond_margins_;     // their margins at the last level (no failure yet)
  std::vector<fracture::CrackTip> tips_;  // energy criterion: the crack tips at that level
  double margins_level_ = 0.0;
  bool have_margins_ = false;
  // The contact states at that level: a prediction needs the same states at both levels
  // (the response is linear only while no contact opens, closes or starts to slide).
  std::vector<std::uint8_t> states_at_margins_;
  std::vector<int> stop_contacts_;       // contacts of the stop joints
  double stop_length_m_ = 0.0;
  std::vector<int> intact_joints_;       // breakable joints not initially open
  LoadRampOutcome outcome_;
};

}  // namespace hfdda::simulation
