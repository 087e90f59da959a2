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

}  // namespace
}  // namespace hfdda::analytical
