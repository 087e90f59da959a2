// The mixed-mode crack relations of analytical/lefm_mixed.hpp (seed 4.4, erratum 5): the
// G-criterion failure stress, the seed's eq. 4.30, the maximum hoop stress kink angle,
// and the exact crack field (far field, free faces, near-tip limit) with the normal force
// it puts on a joint leaving the tip.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analytical/lefm_mixed.hpp"

namespace hfdda {
namespace {

using namespace analytical;
constexpr double kPi = std::numbers::pi;
const double kBeta = kPi / 6.0;  // 30 degrees

TEST(LefmMixed, GCriterionRelationSolvesKi2PlusKii2EqualsKic2) {
  const double t0 = 1.0e6, l = 1.0, a = 3.0;
  const double s = mixed_mode_failure_stress_g(t0, l, a, kBeta);
  const StressPattern p = inclined_tension(kBeta);
  const double k_i = s * p.syy * std::sqrt(kPi * a), k_ii = s * p.sxy * std::sqrt(kPi * a);  // eq. 4.27
  const double k_ic = t0 * std::sqrt(kPi * l / 2.0);                                      // eq. 4.13
  EXPECT_NEAR(k_i * k_i + k_ii * k_ii, k_ic * k_ic, 1e-9 * k_ic * k_ic);
  EXPECT_NEAR(s, t0 * std::sqrt(1.0 / (6.0 * 0.75)), 1e-6);
  // Eq. 4.30 as printed: lower by sqrt(1 + 2 sin cos) = sqrt(1 + sqrt(3) / 2).
  EXPECT_NEAR(s / mixed_mode_failure_stress_eq430(t0, l, a, kBeta), std::sqrt(1.0 + std::sqrt(3.0) / 2.0), 1e-12);
  EXPECT_NEAR(p.sxx, 0.25, 1e-15);
  EXPECT_NEAR(p.syy, 0.75, 1e-15);
}

TEST(LefmMixed, HoopStressKinkIsMinus43DegreesForBeta30) {
  const double theta = max_hoop_stress_kink_angle(0.75, 0.75 * std::tan(kBeta));
  EXPECT_NEAR(theta * 180.0 / kPi, -43.2, 0.05);
  // The hoop stress is largest there.
  const double h = 1e-4;
  const double k_ii = 0.75 * std::tan(kBeta);
  EXPECT_GT(hoop_stress_factor(0.75, k_ii, theta), hoop_stress_factor(0.75, k_ii, theta + h));
  EXPECT_GT(hoop_stress_factor(0.75, k_ii, theta), hoop_stress_factor(0.75, k_ii, theta - h));
  EXPECT_EQ(max_hoop_stress_kink_angle(1.0, 0.0), 0.0);
  EXPECT_GT(max_hoop_stress_kink_angle(1.0, -0.5), 0.0);  // the other sense of shear kinks upwards
}

TEST(LefmMixed, CrackFieldHasTheFarFieldFreeFacesAndTheNearTipLimit) {
  const StressPattern p = inclined_tension(kBeta);
  const double a = 2.0;
  const Stress far = crack_stress(3.0e4, -2.0e4, a, p);
  EXPECT_NEAR(far.sxx, p.sxx, 1e-7);
  EXPECT_NEAR(far.syy, p.syy, 1e-7);
  EXPECT_NEAR(far.sxy, p.sxy, 1e-7);
  for (double y : {1e-10, -1e-10}) {  // both faces of the crack are free of traction
    const Stress face = crack_stress(0.7, y, a, p);
    EXPECT_NEAR(face.syy, 0.0, 1e-8);
    EXPECT_NEAR(face.sxy, 0.0, 1e-8);
  }
  // Ahead of the tip, syy and sxy tend to K_I / sqrt(2 pi r) and K_II / sqrt(2 pi r).
  const double r = 1e-7;
  const Stress tip = crack_stress(a + r, 0.0, a, p);
  EXPECT_NEAR(tip.syy * std::sqrt(2.0 * kPi * r) / (p.syy * std::sqrt(kPi * a)), 1.0, 1e-6);
  EXPECT_NEAR(tip.sxy * std::sqrt(2.0 * kPi * r) / (p.sxy * std::sqrt(kPi * a)), 1.0, 1e-6);
  // No crack: the uniform field.
  const Stress none = crack_stress(0.3, 0.0, 0.0, p);
  EXPECT_EQ(none.sxy, p.sxy);
}

TEST(LefmMixed, JointForceIsTheUniformStressWithoutCrackAndTheHoopStressNearTheTip) {
  const StressPattern p = inclined_tension(kBeta);
  // a = 0: L times the normal stress; on a -45 degree joint it is cos^2(15 deg).
  const double l = std::sqrt(0.5);
  EXPECT_NEAR(joint_normal_force(0.0, p, -kPi / 4.0, l), l * std::pow(std::cos(kPi / 12.0), 2), 1e-12);
  EXPECT_NEAR(joint_failure_stress(1.0e6, 0.0, p, 0.0, 1.0), 1.0e6 / 0.75, 1e-3);
  // A joint much shorter than the crack sees the singular field only:
  // F = sqrt(2 L / pi) (hoop factor), the force of seed eq. 4.9 at angle theta.
  const double a = 1.0e4, short_joint = 1.0e-3;
  for (double theta : {0.0, -kPi / 4.0, -kPi / 2.0}) {
    const double k_i = p.syy * std::sqrt(kPi * a), k_ii = p.sxy * std::sqrt(kPi * a);
    const double singular = std::sqrt(2.0 * short_joint / kPi) * hoop_stress_factor(k_i, k_ii, theta);
    // The rest (T-stress, higher terms) is of order sqrt(L / a) = 3e-4 of it.
    EXPECT_NEAR(joint_normal_force(a, p, theta, short_joint) / singular, 1.0, 1e-3) << theta;
  }
}

}  // namespace
}  // namespace hfdda
