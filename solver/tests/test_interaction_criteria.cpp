// Analytical interaction criteria (solver/analytical/interaction_criteria.hpp,
// docs/interaction_criteria.md), checked against values worked by hand.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analytical/interaction_criteria.hpp"

namespace hfdda::analytical {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const double kMu = std::tan(35.0 * kDeg);  // Blanton's natural fractures (seed Table 5.1)

TEST(InteractionCriteria, StressOnTheNaturalFracture) {
  // 45 degrees, 14 / 5 MPa: sigma_n = (14 + 5) / 2, tau = (14 - 5) / 2.
  const PlaneStress on = stress_on_natural_fracture(45 * kDeg, 14e6, 5e6);
  EXPECT_NEAR(on.normal_Pa, 9.5e6, 1e-6);
  EXPECT_NEAR(on.shear_Pa, 4.5e6, 1e-6);
  // Orthogonal: sigma_H acts across the natural fracture, no shear.
  const PlaneStress ortho = stress_on_natural_fracture(90 * kDeg, 14e6, 5e6);
  EXPECT_NEAR(ortho.normal_Pa, 14e6, 1e-6);
  EXPECT_NEAR(ortho.shear_Pa, 0.0, 1e-6);
}

TEST(InteractionCriteria, RenshawPollardByHand) {
  // mu = tan 35 deg = 0.7002: (0.35 + 0.35 / 0.7002) / 1.06 = 0.8017; T0 = 6, sigma_h = 5 MPa:
  // crossing above sigma_H = 0.8017 x 11 = 8.82 MPa, Delta sigma = 3.82 MPa.
  EXPECT_NEAR(renshaw_pollard_ratio(kMu), 0.80176, 1e-4);
  EXPECT_NEAR(renshaw_pollard_critical_differential_stress(5e6, 6e6, kMu), 3.819e6, 2e3);
  EXPECT_TRUE(renshaw_pollard_crosses(14e6, 5e6, 6e6, kMu));   // Blanton CT20: crossing
  EXPECT_FALSE(renshaw_pollard_crosses(7e6, 5e6, 6e6, kMu));
  // Less friction: slip is easier, crossing needs more clamping.
  EXPECT_GT(renshaw_pollard_critical_differential_stress(5e6, 6e6, 0.3),
            renshaw_pollard_critical_differential_stress(5e6, 6e6, kMu));
}

TEST(InteractionCriteria, WarpinskiTeufelOpeningAndSlip) {
  // Opening below net / sin^2 theta: 2 MPa net at 45 degrees opens up to 4 MPa.
  EXPECT_NEAR(warpinski_teufel_opening_differential_stress(45 * kDeg, 2e6), 4e6, 1e-3);
  EXPECT_NEAR(warpinski_teufel_opening_differential_stress(90 * kDeg, 2e6), 2e6, 1e-3);
  // Slip at 45 degrees, 9 MPa, 1.5 MPa net: tau 4.5 against 0.7002 (9.5 - 6.5) = 2.1 MPa.
  EXPECT_TRUE(warpinski_teufel_slips(45 * kDeg, 9e6, 5e6, 1.5e6, kMu, 0.0));
  // Orthogonal: no shear, no slip whatever the stresses.
  EXPECT_FALSE(warpinski_teufel_slips(90 * kDeg, 9e6, 5e6, 1.5e6, kMu, 0.0));
  // 60 degrees, 20 / 5 MPa, 1.5 MPa net: tau 6.50 against 0.7002 (16.25 - 6.5) = 6.83: holds.
  EXPECT_FALSE(warpinski_teufel_slips(60 * kDeg, 15e6, 5e6, 1.5e6, kMu, 0.0));
  EXPECT_TRUE(warpinski_teufel_slips(60 * kDeg, 9e6, 5e6, 1.5e6, kMu, 0.0));
  // Fluid above the normal stress opens it: no slip of an open fracture.
  EXPECT_FALSE(warpinski_teufel_slips(45 * kDeg, 2e6, 5e6, 1.5e6, kMu, 0.0));
}

TEST(InteractionCriteria, GuWengConstructionReducesToRenshawPollardAtRightAngles) {
  // At 90 degrees both rays are at +-90 degrees: s cos45 (1 + sin45 sin135) = 1.0607 s
  // reaches T0 + sigma_h, and the interface holds if 0.3536 s < mu (sigma_H - 0.3536 s):
  // sigma_H / (T0 + sigma_h) > (1 + 1 / mu) / 3, Renshaw-Pollard with unrounded coefficients.
  const double exact = (1.0 + 1.0 / kMu) / 3.0 * (6e6 + 5e6) - 5e6;  // 3.903 MPa
  const auto at_90 = gu_weng_critical_differential_stress(90 * kDeg, 5e6, 6e6, kMu, 40e6);
  ASSERT_TRUE(at_90.has_value());
  EXPECT_NEAR(*at_90, exact, 2e3);
  EXPECT_NEAR(*at_90, renshaw_pollard_critical_differential_stress(5e6, 6e6, kMu), 0.025 * exact);  // rounding of 0.35, 1.06
  EXPECT_TRUE(gu_weng_crosses(90 * kDeg, 14e6, 5e6, 6e6, kMu));
  EXPECT_FALSE(gu_weng_crosses(90 * kDeg, 8e6, 5e6, 6e6, kMu));
}

TEST(InteractionCriteria, GuWengConstructionNeedsMoreClampingAtSmallerAngles) {
  // Shear on an inclined interface makes it slip sooner: the crossing stress grows as the
  // approach angle falls, and below some angle no differential stress up to 40 MPa crosses.
  double previous = 0.0;
  for (int theta = 90; theta >= 65; theta -= 5) {
    const auto c = gu_weng_critical_differential_stress(theta * kDeg, 5e6, 6e6, kMu, 40e6);
    ASSERT_TRUE(c.has_value()) << theta;
    EXPECT_GT(*c, previous) << theta;
    previous = *c;
  }
  EXPECT_GT(previous, 15e6);  // 65 degrees: 17.3 MPa
  EXPECT_FALSE(gu_weng_critical_differential_stress(45 * kDeg, 5e6, 6e6, kMu, 40e6).has_value());
  // Cohesion on the interface helps it hold: crossing at 75 degrees with 1 MPa cohesion
  // where the cohesionless interface slips.
  EXPECT_FALSE(gu_weng_crosses(75 * kDeg, 5e6 + 6e6, 5e6, 6e6, kMu, 0.0));
  EXPECT_TRUE(gu_weng_crosses(75 * kDeg, 5e6 + 6e6, 5e6, 6e6, kMu, 3e6));
}

}  // namespace
}  // namespace hfdda::analytical
