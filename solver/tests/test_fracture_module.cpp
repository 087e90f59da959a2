// The fracture criteria of seed 2.3 as pure functions (fracture/fracture_criteria):
// the tensile and Mohr-Coulomb limits just below and above, eligibility rule (i) and
// the selection of the most stressed bond, rule (iii).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fracture/fracture_criteria.hpp"

namespace hfdda::fracture {
namespace {

constexpr double kLength = 0.5;  // contact length Lc [m]

Bond bond(double normal_N, double shear_N, BondStrength strength = {1.0e6, 2.0e6, 0.0}) {
  Bond b;
  b.contact = 0;
  b.point = 0;
  b.other_point = 1;
  b.length_m = kLength;
  b.normal_N = normal_N;
  b.shear_N = shear_N;
  b.strength = strength;
  b.open_neighbour = true;
  return b;
}

TEST(FractureCriteria, BondStrengthFromJointProperties) {
  mesh::JointProperties p;
  p.tensile_strength_Pa = 3e6;
  p.cohesion_Pa = 5e6;
  p.friction_angle_rad = std::numbers::pi / 6.0;
  const BondStrength s = bond_strength(p, 0.5);
  EXPECT_EQ(s.tensile_strength_Pa, 3e6);
  EXPECT_EQ(s.cohesion_Pa, 5e6);
  EXPECT_EQ(s.tan_friction, std::tan(std::numbers::pi / 6.0));
  EXPECT_EQ(bond_strength(p, 7.0).tensile_strength_Pa, 3e6);  // without a toughness the length is not used
}

TEST(FractureCriteria, BondStrengthFromFractureToughnessAndJointLength) {
  // Seed eq. 4.13: K_IC = T0 sqrt(pi L / 2). K_IC = 0.886 MPa m^0.5 (seed 4.5) gives
  // T0 = 1 MPa on a joint of 0.5 m and 0.707 MPa on one of 1 m; the toughness replaces
  // the tensile strength, cohesion and friction are kept.
  mesh::JointProperties p;
  p.tensile_strength_Pa = 9e6;
  p.cohesion_Pa = 5e6;
  p.friction_angle_rad = std::numbers::pi / 6.0;
  p.fracture_toughness_Pa_sqrt_m = 0.886e6;
  EXPECT_NEAR(bond_strength(p, 0.5).tensile_strength_Pa, 1.0e6, 0.001e6);
  EXPECT_NEAR(bond_strength(p, 1.0).tensile_strength_Pa, 0.707e6, 0.001e6);
  EXPECT_EQ(bond_strength(p, 1.0).cohesion_Pa, 5e6);
  EXPECT_EQ(bond_strength(p, 1.0).tan_friction, std::tan(std::numbers::pi / 6.0));
  // The matched pair of erratum 7 (docs/seed_errata.md): 4.43 MPa m^0.5 is T0 = 5 MPa at
  // L = 0.5 m and 3.536 MPa at L = 1 m; and the inverse relation holds exactly.
  EXPECT_NEAR(tensile_strength_from_toughness(4.43e6, 0.5), 5.0e6, 0.002e6);
  EXPECT_NEAR(tensile_strength_from_toughness(4.43e6, 1.0), 3.536e6, 0.002e6);
  const double t0 = tensile_strength_from_toughness(2.0e6, 0.8);
  EXPECT_NEAR(t0 * std::sqrt(std::numbers::pi * 0.8 / 2.0), 2.0e6, 1e-9 * 2.0e6);
}

TEST(FractureCriteria, TensionJustBelowAndAboveTheTensileLimit) {
  const double limit = 1.0e6 * kLength;  // T0 Lc
  EXPECT_EQ(failure_mode(bond(limit * (1 - 1e-12), 0.0), true), FailureMode::none);
  EXPECT_EQ(failure_mode(bond(limit, 0.0), true), FailureMode::none);  // strictly over the limit
  EXPECT_EQ(failure_mode(bond(limit * (1 + 1e-12), 0.0), true), FailureMode::tension);
  // Tension wins over shear when both limits are exceeded.
  EXPECT_EQ(failure_mode(bond(2 * limit, 1e9), true), FailureMode::tension);
}

TEST(FractureCriteria, ShearJustBelowAndAboveTheCohesionOnlyWhenEnabled) {
  const double limit = 2.0e6 * kLength;  // C0 Lc, no normal force
  EXPECT_EQ(failure_mode(bond(0.0, limit * (1 - 1e-12)), true), FailureMode::none);
  EXPECT_EQ(failure_mode(bond(0.0, -limit * (1 + 1e-12)), true), FailureMode::shear);
  EXPECT_EQ(failure_mode(bond(0.0, limit * (1 + 1e-12)), false), FailureMode::none);
}

TEST(FractureCriteria, CompressionRaisesTheShearLimitByFriction) {
  const BondStrength s{1.0e6, 2.0e6, 0.5};
  const double normal = -4.0e6;                         // compression [N]
  const double limit = 2.0e6 * kLength + 0.5 * 4.0e6;   // C0 Lc + |N| tan phi
  EXPECT_EQ(failure_mode(bond(normal, limit * (1 - 1e-12), s), true), FailureMode::none);
  EXPECT_EQ(failure_mode(bond(normal, limit * (1 + 1e-12), s), true), FailureMode::shear);
  // Tension below T0 Lc adds no friction: the limit is the cohesion alone.
  EXPECT_EQ(failure_mode(bond(0.4e6, 2.0e6 * kLength * (1 + 1e-12), s), true), FailureMode::shear);
}

TEST(FractureCriteria, EligibilityNeedsBreakableOpenNeighbourAndPressure) {
  const FractureRules rules;  // rule (i) on
  const std::vector<char> dry{0, 0}, wet_here{1, 0}, wet_there{0, 1};
  Bond b = bond(1e9, 0.0);
  EXPECT_FALSE(may_fail(b, dry, rules));
  EXPECT_TRUE(may_fail(b, wet_here, rules));
  EXPECT_TRUE(may_fail(b, wet_there, rules));  // the joint's other end counts
  b.open_neighbour = false;
  EXPECT_FALSE(may_fail(b, wet_here, rules));
  FractureRules free = rules;
  free.failure_needs_open_neighbour_and_fluid = false;
  EXPECT_TRUE(may_fail(b, dry, free));
  b.breakable = false;
  EXPECT_FALSE(may_fail(b, wet_here, free));
}

TEST(FractureCriteria, NaturalFractureFailsInShearOnlyAtItsTip) {
  // Seed 5.1: a natural-fracture bond fails in shear even with shear failure of intact
  // (rock) joints off, and only at a pressurised point or next to a failed contact.
  const FractureRules rules;  // shear_failure_of_intact_joints off, localisation on
  const std::vector<char> dry{0, 0}, wet_here{1, 0}, wet_there{0, 1};
  Bond b = bond(-1.0e6, 1.0e6, {0.0, 0.0, std::tan(35.0 * std::numbers::pi / 180.0)});
  b.open_neighbour = false;
  EXPECT_EQ(failure_mode(b, false), FailureMode::none);  // rock: no shear failure
  b.natural = true;
  EXPECT_EQ(failure_mode(b, false), FailureMode::shear);  // |S| > N tan 35 deg
  EXPECT_FALSE(may_fail(b, dry, rules));        // neither pressurised nor next to a failure
  EXPECT_FALSE(may_fail(b, wet_there, rules));  // only its own point's fluid counts
  EXPECT_TRUE(may_fail(b, wet_here, rules));
  b.failed_neighbour = true;
  EXPECT_TRUE(may_fail(b, dry, rules));
  const auto failures = failing_bonds({b}, dry, rules);
  ASSERT_EQ(failures.size(), 1u);
  EXPECT_EQ(failures[0].mode, FailureMode::shear);
  // Below the friction limit nothing fails, wherever it is.
  b.shear_N = 0.5e6;
  EXPECT_EQ(failure_mode(b, false), FailureMode::none);
}

TEST(FractureCriteria, OnlyTheMostStressedFailsWithItsTies) {
  EXPECT_TRUE(most_stressed({}, 1e-3).empty());
  EXPECT_EQ(most_stressed({1.0, 3.0, 2.0}, 1e-3), std::vector<int>({1}));
  // Within the relative tie tolerance of the largest: both fail.
  EXPECT_EQ(most_stressed({3.0 * (1 - 0.9e-3), 1.0, 3.0}, 1e-3), std::vector<int>({0, 2}));
  EXPECT_EQ(most_stressed({3.0 * (1 - 1.1e-3), 1.0, 3.0}, 1e-3), std::vector<int>({2}));
}

TEST(FractureCriteria, FailingBondsListsShearFirstThenSelectedTension) {
  FractureRules rules;
  rules.shear_failure_of_intact_joints = true;
  const std::vector<char> wet{1, 1};
  std::vector<Bond> bonds;
  auto add = [&](int contact, double normal, double shear) {
    Bond b = bond(normal, shear);
    b.contact = contact;
    bonds.push_back(b);
  };
  add(4, 2.0e6, 0.0);   // tension, 4 MPa
  add(7, 0.0, -2.0e6);  // shear, negative sense
  add(9, 3.0e6, 0.0);   // tension, 6 MPa: the most stressed
  add(11, 0.1e6, 0.0);  // holds
  const auto failures = failing_bonds(bonds, wet, rules);
  ASSERT_EQ(failures.size(), 2u);
  EXPECT_EQ(failures[0].contact, 7);
  EXPECT_EQ(failures[0].mode, FailureMode::shear);
  EXPECT_EQ(failures[0].friction_sign, -1.0);
  EXPECT_EQ(failures[1].contact, 9);
  EXPECT_EQ(failures[1].mode, FailureMode::tension);
  // Without fluid at its points, nothing is eligible under rule (i).
  EXPECT_TRUE(failing_bonds(bonds, std::vector<char>{0, 0}, rules).empty());
}

}  // namespace
}  // namespace hfdda::fracture
