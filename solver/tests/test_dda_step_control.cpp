// Unit tests of what controls a DDA step's contact states: cycle detection (seed 5.1),
// the re-lock rule after a bond fails, the guards that refuse a converged state (faces
// through each other, crushed blocks; docs/design_notes.md sections 24 and 30) and the
// mechanism hold (section 25).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "coupling/coupled_step.hpp"
#include "dda/block_system.hpp"
#include "dda_test_support.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {
namespace {

using test_support::alm_settings;
using test_support::small_mesh;
using test_support::step;

/// Two unit squares side by side, the left one fixed at two corners, the joint between
/// them open and never changing state (a cycle held at once): the right block is held
/// by nothing but its inertia, 2 M / tau^2 of the mechanism hold (tau = 1e6 s: the
/// step's own 2 M / dt^2). A point load `fx_N` along x acts at its centre.
std::unique_ptr<BlockSystem> free_block_beside_fixed(double fx_N, double mechanism_inertia_time_s = 1e6,
                                                     bool close_penetrating_cycles = false) {
  mesh::Mesh m = small_mesh(2, 1, 1.0, mesh::CellSplit::none);
  for (auto& j : m.joints) j.properties.initially_open = true;
  MechanicsSettings settings = alm_settings(25e9);
  settings.max_state_flips = 0;
  settings.mechanism_inertia_time_s = mechanism_inertia_time_s;
  settings.close_penetrating_cycles = close_penetrating_cycles;
  auto system = std::make_unique<BlockSystem>(m, std::vector<Material>{Material{}}, settings);
  system->add_fixed_point({0.0, 0.0});
  system->add_fixed_point({0.0, 1.0});
  system->add_point_load({1.5, 0.5}, {fx_N, 0.0});
  return system;
}

/// Mean x of a block's corners [m].
double mean_x(const BlockSystem& system, int b) {
  double x = 0.0;
  for (int k = 0; k < system.n_corners(b); ++k) x += system.corner(b, k).x() / system.n_corners(b);
  return x;
}

/// The push that drives the free block 1.2 m in a static step of 1 s (inertia 2 rho A / dt^2) [N].
const double kPushOf1_2m = 1.2 * 2.0 * Material{}.density_kg_m3;

TEST(DdaCycles, ContactFlippingTooOftenIsHeldInItsMostOpenState) {
  // A joint contact driven open, closed, open... within one step: after max_state_flips
  // changes it is set to the most open state it had (open) and held there (seed 5.1),
  // and every refused change is counted.
  const mesh::Mesh m = small_mesh(2, 1, 1.0, mesh::CellSplit::none);
  for (int max_flips : {2, 4}) {
    MechanicsSettings settings = alm_settings(25e9);
    settings.max_state_flips = max_flips;
    BlockSystem system(m, {Material{}}, settings);
    system.add_fixed_point({0.0, 0.0});
    system.begin_step(1.0);
    StepStatistics stats;
    system.assemble_and_factorise(stats);
    const Eigen::VectorXd d = Eigen::VectorXd::Zero(6 * system.n_blocks());
    const int ci = system.joint_contacts(0)[0];
    const ContactState cycle[] = {ContactState::open, ContactState::locked, ContactState::open,
                                  ContactState::locked, ContactState::open, ContactState::locked};
    int applied = 0;
    for (ContactState to : cycle) applied += system.apply_state_changes(d, {ContactChange{ci, to}}, stats);
    // The change over the limit resolves the contact to "open" (applied), the later ones are refused.
    EXPECT_EQ(system.contacts()[ci].state, ContactState::open);
    EXPECT_EQ(stats.cycle_holds, 6 - max_flips);
    EXPECT_EQ(applied, max_flips + 1);
  }
}

TEST(DdaCycles, BondBrokenInTheStepIsReLockedBySlipReversalOnlyWhenAsked) {
  // A bond breaks in shear (locked -> sliding, friction in +t); the right block then moves
  // back along the joint, reversing the slip since the failure. DDA's rule re-locks a
  // sliding contact whose slip reverses; with relock_in_failure_step = false a contact
  // whose bond broke in this step stays sliding, and from the next step on the same
  // reversal re-locks it again.
  const mesh::Mesh m = small_mesh(2, 1, 1.0, mesh::CellSplit::none);
  for (const bool relock : {true, false}) {
    MechanicsSettings settings = alm_settings(25e9);
    settings.relock_in_failure_step = relock;
    BlockSystem system(m, {Material{}}, settings);
    system.add_fixed_point({0.0, 0.0});
    system.add_fixed_point({0.0, 1.0});
    system.begin_step(1.0);
    StepStatistics stats;
    system.assemble_and_factorise(stats);
    const int ci = system.joint_contacts(0)[0];
    ASSERT_TRUE(system.contacts()[ci].bonded);
    const int right = system.contacts()[ci].block_a == 0 ? 1 : 0;  // either block will do: it moves alone
    Eigen::VectorXd d = Eigen::VectorXd::Zero(6 * system.n_blocks());
    system.apply_state_changes(d, {ContactChange{ci, ContactState::sliding, true, 1.0}}, stats);
    ASSERT_FALSE(system.contacts()[ci].bonded);
    // Of the two senses of motion along the joint (y), one reverses the slip.
    auto relocked_after = [&](double dy) {
      d.setZero();
      d[6 * right + 1] = dy;
      for (const ContactChange& ch : system.trial_contacts(d, stats).changes)
        if (ch.contact == ci && ch.to == ContactState::locked) return true;
      return false;
    };
    const bool up = relocked_after(1e-6), down = relocked_after(-1e-6);
    if (relock) {
      EXPECT_NE(up, down) << "exactly one sense reverses the slip";
    } else {
      EXPECT_FALSE(up || down) << "re-locked in the step its bond broke";
      // The next step: the contact (still sliding, its slip measured from the start of
      // the step) re-locks on a reversal as any sliding contact does.
      d.setZero();
      system.commit(d, 1.0, stats);
      system.begin_step(1.0);
      system.assemble_and_factorise(stats);
      EXPECT_NE(relocked_after(1e-6), relocked_after(-1e-6));
    }
  }
}

TEST(DdaOverlap, FacesPushedIntoEachOtherAreMeasuredAlongTheJoint) {
  // Two unit squares sharing the joint x = 1: moving the right block 0.3 m into the left
  // one overlaps both ends of the joint by 0.3 m, 0.3 of its length; moving it away
  // overlaps nothing.
  const mesh::Mesh m = small_mesh(2, 1, 1.0, mesh::CellSplit::none);
  BlockSystem system(m, {Material{}}, alm_settings(25e9));
  system.begin_step(1.0);
  const mesh::Joint& joint = m.joints[0];
  auto mean_x = [&](int b) {
    double x = 0.0;
    for (int k = 0; k < system.n_corners(b); ++k) x += system.corner(b, k).x() / system.n_corners(b);
    return x;
  };
  const int right = mean_x(joint.block_a) > mean_x(joint.block_b) ? joint.block_a : joint.block_b;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(6 * system.n_blocks());
  d[6 * right] = -0.3;
  const BlockSystem::FaceOverlap into = system.largest_face_overlap(d);
  EXPECT_EQ(into.joint, 0);
  EXPECT_NEAR(into.overlap_m, 0.3, 1e-12);
  EXPECT_NEAR(into.fraction_of_length, 0.3, 1e-12);
  d[6 * right] = 0.3;
  EXPECT_EQ(system.largest_face_overlap(d).joint, -1);
}

TEST(DdaOverlap, StepEndingWithFacesPassedThroughEachOtherIsRejected) {
  // The joint starts open and its contact may not change state (a cycle held at once),
  // so a load pushing the free block into the fixed one meets nothing but the block's
  // inertia: the step would end with the faces 1.2 m through each other. It is refused
  // (ConvergenceError, which cuts a step) naming the joint; a twentieth of the load ends
  // 0.06 of the joint's length into it, which passes.
  for (const double load_fraction : {1.0, 0.05}) {
    const auto system = free_block_beside_fixed(-load_fraction * kPushOf1_2m);
    if (load_fraction == 1.0) {
      try {
        step(*system, 1.0);
        ADD_FAILURE() << "a step with faces 1.2 m through each other was accepted";
      } catch (const ConvergenceError& e) {
        EXPECT_NE(std::string(e.what()).find("faces of joint"), std::string::npos) << e.what();
      }
    } else {
      EXPECT_NO_THROW(step(*system, 1.0));
    }
  }
}

TEST(DdaOverlap, FailedStepReportsTheTimeItsConvergedHalvesCommitted) {
  // The free block of the test above, pushed into the fixed one: 1.2 m of overlap in a
  // step of 1 s, 0.3 m in 0.5 s (both refused), 0.075 m in 0.25 s (accepted); the next
  // quarter would reach 0.15 m, refused with no cuts left. The quarter that converged
  // stays committed, and the step says so: 0.25 s of it.
  const auto system = free_block_beside_fixed(-kPushOf1_2m);
  coupling::CoupledStep stepper(*system, {});
  EXPECT_THROW(stepper.advance(1.0, 2), ConvergenceError);
  EXPECT_DOUBLE_EQ(stepper.committed_time_s(), 0.25);
  EXPECT_NO_THROW(stepper.advance(0.25 * 0.5, 0));  // a step that converges commits all of it
  EXPECT_DOUBLE_EQ(stepper.committed_time_s(), 0.125);
}

TEST(DdaOverlap, LargestStepStrainIsThePrincipalStrainOfTheWorstBlock) {
  // exx = 0.05, eyy = -0.2 on block 1: principal strains 0.05 and -0.2; the shear of
  // block 0 (gxy = 0.1, principal +-0.05) is smaller.
  const mesh::Mesh m = small_mesh(2, 1, 1.0, mesh::CellSplit::none);
  BlockSystem system(m, {Material{}}, alm_settings(25e9));
  Eigen::VectorXd d = Eigen::VectorXd::Zero(6 * system.n_blocks());
  d[6 * 0 + 5] = 0.1;
  d[6 * 1 + 3] = 0.05, d[6 * 1 + 4] = -0.2;
  const BlockSystem::BlockStrain worst = system.largest_step_strain(d);
  EXPECT_EQ(worst.block, 1);
  EXPECT_NEAR(worst.strain, 0.2, 1e-15);
}

TEST(DdaOverlap, StepThatCrushesABlockIsRejected) {
  // One unit square held at two corners and pulled at the third: a load of E / 4 (in N
  // per metre of thickness) strains it by about 0.25, beyond the 0.1 a step may; the
  // step is refused naming the block. A hundredth of the load passes.
  for (const double load : {0.25 * 25e9, 0.0025 * 25e9}) {
    const auto pulled = test_support::pulled_unit_block(load);
    BlockSystem& system = *pulled;
    if (load > 0.01 * 25e9) {
      try {
        step(system, 1.0);
        ADD_FAILURE() << "a step straining a block by about 0.25 was accepted";
      } catch (const ConvergenceError& e) {
        EXPECT_NE(std::string(e.what()).find("would be strained"), std::string::npos) << e.what();
      }
    } else {
      EXPECT_NO_THROW(step(system, 1.0));
    }
  }
}

TEST(DdaCycles, CycleHeldOpenThroughClosedFacesClosesWhenAskedTo) {
  // The set-up above at the full load: held open by the cycle rule, the faces would pass
  // 1.2 m through each other. With close_penetrating_cycles the contact is closed and held
  // sliding instead; the step completes with the free block pressed against the fixed one.
  const auto system = free_block_beside_fixed(-kPushOf1_2m, 1e6, true);
  const int right = mean_x(*system, 0) > mean_x(*system, 1) ? 0 : 1;
  const double right_x0 = mean_x(*system, right);
  StepStatistics stats;
  ASSERT_NO_THROW(stats = step(*system, 1.0));
  EXPECT_GT(stats.cycle_holds, 0);
  const ContactState state = system->contacts()[system->joint_contacts(0)[0]].state;
  EXPECT_EQ(state, ContactState::sliding);
  EXPECT_LT(std::abs(mean_x(*system, right) - right_x0), 1e-3);
}

TEST(DdaCycles, HeldOpenContactClosesAboveTheElasticPenetrationOfAClosedOne) {
  // The bound is 1e-5 of the joint's length (design notes section 39): a cycle-held
  // contact whose faces would pass 1e-4 of its 1 m joint through each other is closed,
  // one at 1e-6 is left open as the seed's rule holds it.
  for (const double penetration_m : {1e-4, 1e-6}) {
    const auto system = free_block_beside_fixed(-kPushOf1_2m * penetration_m / 1.2, 1e6, true);
    ASSERT_NO_THROW(step(*system, 1.0));
    const ContactState state = system->contacts()[system->joint_contacts(0)[0]].state;
    EXPECT_EQ(state, penetration_m > 1e-5 ? ContactState::sliding : ContactState::open) << penetration_m << " m";
  }
}

/// The free block pulled away (+x) by 1 kN for one static step of 1 s; how far it
/// moved [m].
double free_block_pull(double mechanism_inertia_time_s, std::vector<int>* mechanism = nullptr) {
  const auto system = free_block_beside_fixed(1000.0, mechanism_inertia_time_s);
  const int right = mean_x(*system, 0) > mean_x(*system, 1) ? 0 : 1;
  const double x0 = system->corner(right, 0).x();
  step(*system, 1.0);
  if (mechanism) *mechanism = system->mechanism_blocks();
  return system->corner(right, 0).x() - x0;
}

TEST(DdaMechanism, BlockThatNoContactHoldsTakesTheMechanismInertia) {
  // 2 M / tau^2 with tau = 0.1 s: 1 kN moves the 1 m^2 block F tau^2 / (2 rho A); with tau
  // no shorter than the step, the step's own 2 M / dt^2 (dt = 1 s).
  const double rho = Material{}.density_kg_m3;
  std::vector<int> mechanism;
  EXPECT_NEAR(free_block_pull(0.1, &mechanism), 1000.0 * 0.01 / (2.0 * rho), 1e-12);
  EXPECT_EQ(mechanism.size(), 1u);
  EXPECT_NEAR(free_block_pull(1e6), 1000.0 / (2.0 * rho), 1e-10);
}

TEST(DdaMechanism, GroupPinnedAtOnePointIsAMechanism) {
  // The right square, cut off by the open joint, fixed at one corner may turn about it;
  // fixed at two corners it may not. The left square is fixed at two corners throughout.
  mesh::Mesh m = small_mesh(2, 1, 1.0, mesh::CellSplit::none);
  for (auto& j : m.joints) j.properties.initially_open = true;
  for (const bool second_pin : {false, true}) {
    BlockSystem system(m, {Material{}}, alm_settings(25e9));
    system.add_fixed_point({0.0, 0.0});
    system.add_fixed_point({0.0, 1.0});
    system.add_fixed_point({2.0, 0.0});
    if (second_pin) system.add_fixed_point({2.0, 1.0});
    system.begin_step(60.0);
    EXPECT_EQ(system.mechanism_blocks().size(), second_pin ? 0u : 1u) << "second pin " << second_pin;
  }
}

TEST(DdaMechanism, BondedRockMassIsNoMechanism) {
  // Every joint locked: with fixed points the one group holds them; without, the group is
  // the rock mass held by its far-field loads. Neither is a mechanism.
  const mesh::Mesh m = small_mesh(4, 3, 1.0, mesh::CellSplit::two);
  for (const bool fixed : {true, false}) {
    BlockSystem system(m, {Material{}}, alm_settings(25e9));
    if (fixed) system.add_fixed_point({0.0, 0.0});
    system.begin_step(60.0);
    EXPECT_TRUE(system.mechanism_blocks().empty());
  }
}

}  // namespace
}  // namespace hfdda::dda
