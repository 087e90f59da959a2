// A block on an inclined joint under gravity: the classic DDA validation of the
// friction law (Shi 1988, seed ref. [74]; Doolin and Sitar 2002, seed ref. [81]; this
// family of checks is reviewed by M. M. MacLaughlin and D. M. Doolin, Review of
// validation of the discontinuous deformation analysis (DDA) method, Int. J. Numer.
// Anal. Meth. Geomech. 30 (2006) 271-305).
//
// The law under test is the Mohr-Coulomb limit of a closed contact, S <= Lc C0 + N tan phi
// (W. E. Morgan, PhD dissertation, Georgia Institute of Technology, 2014, section 2.3,
// eq. 2.16), on an unbonded joint (T0 = C0 = 0): a sliding contact carries the friction
// force N tan phi (solver/dda/contact_iterations.cpp), a locked one slides once its
// shear exceeds it (open_close.cpp).
// The block terms, inertia included, are seed 2.2 (eqs. 2.12-2.22).
//
// Analytical solution for a rigid block of mass m released from rest on a plane inclined
// at theta: it slides when tan phi < tan theta, with the constant acceleration
//   a = g (sin theta - cos theta tan phi),   s(t) = a t^2 / 2,
// and does not move when tan phi >= tan theta; the joint carries N = m g cos theta and,
// sliding, S = N tan phi (stuck: S = m g sin theta).
//
// Time integration. A step solves (K + 2M/dt^2) d = F + (2M/dt) v and sets
// v' = 2 d / dt - v (Shi's scheme: block_loads.cpp, block_system.cpp). Under a constant
// net force m a on a translating block d_k = v_k dt + a dt^2 / 2 and v_(k+1) = v_k + a dt,
// so s_n = a (n dt)^2 / 2 exactly: no discretisation error at any dt. The static
// analysis (the default, used by the verification cases) resets v to 0 every step, so
// each step moves the block a dt^2 / 2 from rest: s_n = n a dt^2 / 2.
//
// Tolerances. The blocks are elastic and the rigid-block solution ignores it. The length
// behind every tolerance is the self-weight settling of the base, de = rho g H^2 / E
// (2.6e-7 m; the stuck slider is measured to move 2.3e-7 m):
// - static analysis: the first step includes a settling of at most de; later steps move
//   exactly a dt^2 / 2 (measured: offsets of 4.4e-8 and 1.1e-8 m), so
//   |s_k - s(t_k)| <= 2 de;
// - dynamic analysis: Shi's scheme turns that settling into a velocity of order
//   2 de / dt, which a freely sliding block keeps: |s_k - s(t_k)| <= (2k + 1) de
//   (measured after 20 steps: 5.5e-9 m at phi = 20 deg, 3.6e-6 m at 29.9 deg, against 2.1e-5 m). Normal to the
//   joint the same velocity flips sign every step against the contact (the scheme's
//   amplification tends to -1 for stiff modes), so the normal force, and with it the
//   friction, oscillates by up to 4 m de / dt^2 (2.8 N, 1e-3 of N; measured 2.0 N);
// - the Augmented Lagrangian stops at 1e-10 of the contact forces (static: N measured
//   within 2e-7 of m g cos theta); a stuck slider moves by the settling alone, <= 2 de.
// Each tolerance below is twice its estimate. A relative friction error r changes a by
// r cos theta tan phi / (sin theta - cos theta tan phi): 1.7 r at phi = 20 deg and 250 r
// at phi = theta - 0.1 deg, so the sliding cases catch r of about 4e-4; halving tan phi
// moves s by 85 % at phi = 20 deg and sets the stuck block at 35 deg sliding.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "coupling/coupled_step.hpp"
#include "dda/block_system.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {
namespace {

constexpr double kGravity_m_s2 = 9.81;
constexpr double kDensity_kg_m3 = 2650.0;
constexpr double kYoungsModulus_Pa = 25e9;
constexpr double kSlopeDeg = 30.0;
// Slider L x h on a base L x H, the joint along the slope. A flat slider (h / L = 0.1)
// keeps the friction moment small: both joint ends stay closed.
constexpr double kLength_m = 1.0, kHeight_m = 0.1, kBaseHeight_m = 0.5;
constexpr int kSlider = 1;
constexpr double kDt_s = 0.01;

/// Self-weight settling of the base, the elastic length behind every tolerance.
constexpr double kSettling_m = kDensity_kg_m3 * kGravity_m_s2 * kBaseHeight_m * kBaseHeight_m / kYoungsModulus_Pa;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }
double slider_mass_kg() { return kDensity_kg_m3 * kLength_m * kHeight_m; }

/// Acceleration of a rigid block down a plane at `tilt_deg` to gravity's normal (0 if it holds).
double analytical_acceleration(double tilt_deg, double phi_deg) {
  const double tilt = radians(tilt_deg), phi = radians(phi_deg);
  return std::max(0.0, kGravity_m_s2 * (std::sin(tilt) - std::cos(tilt) * std::tan(phi)));
}

/// `steps` steps with gravity at `tilt_deg` from the joint's normal (the slope angle:
/// vertical gravity; another angle: the same block under a tilted gravity).
struct Phase {
  int steps;
  double tilt_deg;
};

struct SlideRun {
  std::vector<double> slip_m;  ///< centroid displacement of the slider down the slope, per step
  double normal_offset_m = 0.0;           ///< centroid displacement normal to the slope at the end
  double normal_N = 0.0, shear_N = 0.0;   ///< joint forces at the end (both ends, magnitudes)
  int sliding_ends = 0;
  double seconds = 0.0;
};

/// Base block fixed at its two lower corners, slider resting on it along a joint
/// inclined at kSlopeDeg (unbonded: initially open, T0 = C0 = 0, friction angle phi).
SlideRun slide(double phi_deg, bool dynamic, const std::vector<Phase>& phases, bool penalty = false,
               bool friction_at_solution = false) {
  const double theta = radians(kSlopeDeg);
  const Vec2 down(std::cos(theta), -std::sin(theta)), up_normal(std::sin(theta), std::cos(theta));
  auto at = [&](double along, double across) -> Vec2 { return along * down + across * up_normal; };
  mesh::Mesh m;
  m.points = {at(0, -kBaseHeight_m), at(kLength_m, -kBaseHeight_m), at(kLength_m, 0), at(0, 0),
              at(kLength_m, kHeight_m), at(0, kHeight_m)};
  m.blocks = {{{0, 1, 2, 3}, 0}, {{3, 2, 4, 5}, 0}};  // base, slider (counter-clockwise)
  mesh::JointProperties joint;
  joint.friction_angle_rad = radians(phi_deg);
  joint.initially_open = true;  // no bond: the friction law alone holds the slider
  mesh::build_topology(m, joint);
  EXPECT_EQ(m.joints.size(), 1u);

  MechanicsSettings settings;
  settings.normal_stiffness_N_m = settings.shear_stiffness_N_m = settings.fixed_point_stiffness_N_m =
      100.0 * kYoungsModulus_Pa;
  settings.alm_force_tolerance = 1e-10;
  settings.max_alm_iterations = 500;
  settings.dynamic = dynamic;
  settings.augmented_lagrangian = !penalty;
  settings.friction_at_solution = friction_at_solution;
  BlockSystem system(m, {Material{kYoungsModulus_Pa, 0.25, kDensity_kg_m3}}, settings);
  system.add_fixed_point(m.points[0]);
  system.add_fixed_point(m.points[1]);

  SlideRun run;
  Vec2 moved = Vec2::Zero();
  const auto start = std::chrono::steady_clock::now();
  coupling::CoupledStep step(system, {});
  // One step with gravity normal to the joint closes it without tangential motion, so
  // the test starts from a closed, locked, unbonded joint: a contact that closes while
  // the block also moves along it takes its shear reference at the trial, so that
  // motion would cost no friction (docs/design_notes.md section 11).
  system.set_body_force(-kDensity_kg_m3 * kGravity_m_s2 * up_normal);
  step.advance(kDt_s, 0);
  for (const Phase& phase : phases) {
    const double tilt = radians(phase.tilt_deg);
    system.set_body_force(kDensity_kg_m3 * kGravity_m_s2 * (std::sin(tilt) * down - std::cos(tilt) * up_normal));
    for (int k = 0; k < phase.steps; ++k) {
      step.advance(kDt_s, 0);
      moved += system.last_step_displacement()[kSlider].head<2>();  // (u0, v0): the centroid
      run.slip_m.push_back(moved.dot(down));
    }
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.normal_offset_m = moved.dot(up_normal);
  double normal = 0.0, shear = 0.0;
  for (int c : system.joint_contacts(0)) {
    const auto [n, s] = system.contact_forces(c);
    normal += n, shear += s;
    run.sliding_ends += system.contacts()[c].state == ContactState::sliding;
  }
  run.normal_N = std::abs(normal), run.shear_N = std::abs(shear);
  return run;
}

/// Tolerance on the slip after k steps (header: twice the settling estimate).
double slip_tolerance(int k, bool dynamic) { return 2.0 * (dynamic ? 2 * k + 1 : 2) * kSettling_m; }

/// Tolerance on the joint forces (header: twice the estimate of the oscillation).
double force_tolerance(bool dynamic) {
  const double weight = slider_mass_kg() * kGravity_m_s2;
  return dynamic ? 2.0 * 4.0 * slider_mass_kg() * kSettling_m / (kDt_s * kDt_s) : 1e-6 * weight;
}

struct SlideCase {
  double phi_deg;
  bool dynamic;
};

// Names the case in test listings (gtest would otherwise print its bytes, padding included).
void PrintTo(const SlideCase& c, std::ostream* os) {
  *os << "phi " << c.phi_deg << " deg, " << (c.dynamic ? "dynamic" : "static");
}

class SlidingBlock : public ::testing::TestWithParam<SlideCase> {};

TEST_P(SlidingBlock, FollowsTheFrictionLaw) {
  const auto [phi_deg, dynamic] = GetParam();
  constexpr int steps = 20;
  const SlideRun run = slide(phi_deg, dynamic, {{steps, kSlopeDeg}});
  const double a = analytical_acceleration(kSlopeDeg, phi_deg);
  const double theta = radians(kSlopeDeg), tan_phi = std::tan(radians(phi_deg));
  const double m = slider_mass_kg(), w = m * kGravity_m_s2;
  auto analytical = [&](int k) { return dynamic ? 0.5 * a * (k * kDt_s) * (k * kDt_s) : k * 0.5 * a * kDt_s * kDt_s; };
  const double expected = analytical(steps);
  std::printf("SLIDE theta %.1f deg, phi %.1f deg, %s: s = %.6e m, analytical %.6e m, error %.2e m "
              "(relative %.1e, tolerance %.1e m); normal offset %.2e m; N = %.3f N (m g cos theta %.3f), "
              "S = %.3f N (N tan phi %.3f, m g sin theta %.3f); %d sliding ends; %.1f ms\n",
              kSlopeDeg, phi_deg, dynamic ? "dynamic" : "static", run.slip_m.back(), expected,
              run.slip_m.back() - expected, expected > 0 ? (run.slip_m.back() - expected) / expected : 0.0,
              a > 0 ? slip_tolerance(steps, dynamic) : 4.0 * kSettling_m, run.normal_offset_m, run.normal_N,
              w * std::cos(theta), run.shear_N, run.normal_N * tan_phi, w * std::sin(theta), run.sliding_ends,
              1e3 * run.seconds);

  // The joint carries the normal component of the weight in every case.
  EXPECT_NEAR(run.normal_N, w * std::cos(theta), force_tolerance(dynamic));
  EXPECT_LT(std::abs(run.normal_offset_m), 4.0 * kSettling_m);
  if (a > 0.0) {
    // Sliding: s follows the analytical law at every step, and the joint carries N tan phi.
    for (int k = 1; k <= steps; ++k)
      EXPECT_NEAR(run.slip_m[k - 1], analytical(k), slip_tolerance(k, dynamic))
          << "step " << k << ", phi " << phi_deg << " deg";
    EXPECT_EQ(run.sliding_ends, 2);
    EXPECT_NEAR(run.shear_N, run.normal_N * tan_phi, 1e-9 * w);
    // The friction the block felt, from its motion: m (g sin theta - a_measured).
    const double span = dynamic ? steps * steps * kDt_s * kDt_s : steps * kDt_s * kDt_s;  // s = a span / 2
    const double felt = m * (kGravity_m_s2 * std::sin(theta) - 2.0 * run.slip_m.back() / span);
    EXPECT_NEAR(felt, run.shear_N, force_tolerance(dynamic) + 2.0 * m * slip_tolerance(steps, dynamic) / span);
  } else {
    // Stuck: elastic settling only, and the joint holds the whole tangential weight.
    for (int k = 1; k <= steps; ++k)
      EXPECT_LT(std::abs(run.slip_m[k - 1]), 4.0 * kSettling_m) << "step " << k << ", phi " << phi_deg << " deg";
    EXPECT_NEAR(run.shear_N, w * std::sin(theta), force_tolerance(dynamic));
  }
}

// 20 deg slides, 35 deg holds; 29.9 and 30.1 deg bracket the threshold tan phi = tan theta.
INSTANTIATE_TEST_SUITE_P(Slope30Deg, SlidingBlock,
                         ::testing::Values(SlideCase{20.0, true}, SlideCase{35.0, true}, SlideCase{29.9, true},
                                           SlideCase{30.1, true}, SlideCase{20.0, false}, SlideCase{35.0, false},
                                           SlideCase{29.9, false}, SlideCase{30.1, false}),
                         [](const ::testing::TestParamInfo<SlideCase>& info) {
                           const int tenths = static_cast<int>(std::lround(10.0 * info.param.phi_deg));
                           return std::string(info.param.dynamic ? "Dynamic" : "Static") + "Phi" +
                                  std::to_string(tenths / 10) + "_" + std::to_string(tenths % 10) + "Deg";
                         });

// The friction of a sliding contact is N tan(phi) with N its normal force at the end of
// the step (eq. 2.16), not at its start. Static analysis, the block sliding throughout:
// gravity at 30 degrees to the joint's normal for n1 steps, then at 25 degrees (both above
// phi = 20 degrees), so N grows by m g (cos 25 - cos 30) = 10.5 N at the change. Each step
// moves the block a(tilt) dt^2 / 2 from rest. With the friction of the step's start the
// first step at 25 degrees runs with the old N: g tan(phi) (cos 25 - cos 30) = 0.144 m/s^2
// more acceleration, 7.2e-6 m more slip, against a tolerance of 1.0e-6 m. Penalty springs
// carry the normal force in their gap alone, so their friction is iterated with the
// contact iterations (BlockSystem::follow_friction_normal_forces); the Augmented
// Lagrangian carries it in its multiplier. Fails with the friction of penalty contacts
// taken at the step's start (2.4e-5 m off from the first step), which is the default
// (numerics.friction_at_solution: false, docs/design_notes.md section 41).
void expect_friction_of_the_step(bool friction_at_solution) {
  constexpr double phi = 20.0;
  constexpr int n1 = 5, n2 = 5;
  const double a1 = analytical_acceleration(30.0, phi), a2 = analytical_acceleration(25.0, phi);
  ASSERT_GT(a2, 0.0);
  for (bool penalty : {true, false}) {
    const SlideRun run = slide(phi, false, {{n1, 30.0}, {n2, 25.0}}, penalty, friction_at_solution);
    for (int k = 1; k <= n1 + n2; ++k) {
      const double expected = 0.5 * kDt_s * kDt_s * (std::min(k, n1) * a1 + std::max(0, k - n1) * a2);
      EXPECT_NEAR(run.slip_m[k - 1], expected, slip_tolerance(k, false))
          << "step " << k << (penalty ? ", penalty" : ", Augmented Lagrangian");
    }
    EXPECT_EQ(run.sliding_ends, 2) << (penalty ? "penalty" : "Augmented Lagrangian");
    EXPECT_NEAR(run.normal_N, slider_mass_kg() * kGravity_m_s2 * std::cos(radians(25.0)), force_tolerance(false))
        << (penalty ? "penalty" : "Augmented Lagrangian");
  }
}

TEST(SlidingBlock, FrictionActsWithTheNormalForceOfItsStep) { expect_friction_of_the_step(true); }

// The default law (numerics.friction_at_solution: false) fails this for penalty contacts,
// from the first step: a known error kept to reproduce it.
TEST(SlidingBlock, DISABLED_FrictionOfTheStepStartLagsTheNormalForce) { expect_friction_of_the_step(false); }

// With numerics.friction_at_solution, a held (penalty) contact re-locks when its slip in
// the step reverses against the friction force, at the point it held when the step began
// (docs/design_notes.md section 41). With the older rule, re-locking only once the whole slip since the contact last
// locked was undone, the block was pulled back up the slope by its own friction (4.6 mm
// dynamic, 0.96 mm static, where it should stop and stay); the penalty test fails with
// that rule. Augmented Lagrangian contacts keep the older rule (locked back at the start,
// they stopped Mode II and mixed-mode verification runs on their multipliers), so their
// test stays disabled, a known failure kept to reproduce it.
void expect_block_stops(bool penalty, bool friction_at_solution) {
  // Phi = 20 deg; gravity at 30 deg to the joint's normal for 0.1 s (the block slides),
  // then at 15 deg (tan 15 < tan 20). Dynamic: the block decelerates at
  // a2 = g (sin 15 - cos 15 tan 20) and stops after v1 / |a2| = 0.199 s, mid-step, at
  // s1 + v1^2 / (2 |a2|), and stays. It stops within a step of the exact instant: up to
  // |a2| dt^2 / 2 from the exact point, besides the elastic terms of the header. Static:
  // every step starts from rest, so the block does not move once the driving shear is
  // below the limit. A sliding contact that did not lock would be pulled back up the
  // slope by its own friction.
  constexpr double phi = 20.0;
  constexpr int n1 = 10, n2 = 30;
  const double a1 = analytical_acceleration(30.0, phi);
  const double a2 = kGravity_m_s2 * (std::sin(radians(15.0)) - std::cos(radians(15.0)) * std::tan(radians(phi)));
  ASSERT_LT(a2, 0.0);
  const double t1 = n1 * kDt_s, v1 = a1 * t1;
  ASSERT_GT(n2 * kDt_s, v1 / -a2 + 2 * kDt_s);  // stops well before the end
  for (bool dynamic : {true, false}) {
    const SlideRun run = slide(phi, dynamic, {{n1, 30.0}, {n2, 15.0}}, penalty, friction_at_solution);
    const double s1 = dynamic ? 0.5 * a1 * t1 * t1 : n1 * 0.5 * a1 * kDt_s * kDt_s;
    const double rest = dynamic ? s1 + v1 * v1 / (-2.0 * a2) : s1;
    const double tolerance = slip_tolerance(n1 + n2, dynamic) + (dynamic ? -a2 * kDt_s * kDt_s : 0.0);
    const std::string label = std::string(dynamic ? "dynamic" : "static") + (penalty ? ", penalty" : ", ALM");
    std::printf("STOP %s: s after phase 1 %.6e m (analytical %.6e), at rest %.6e m (analytical %.6e, "
                "error %.2e m, tolerance %.1e m); %d sliding ends\n",
                label.c_str(), run.slip_m[n1 - 1], s1, run.slip_m.back(), rest, run.slip_m.back() - rest, tolerance,
                run.sliding_ends);
    EXPECT_NEAR(run.slip_m[n1 - 1], s1, slip_tolerance(n1, dynamic)) << label;
    EXPECT_NEAR(run.slip_m.back(), rest, tolerance) << label;
    // At rest for the last 5 steps.
    EXPECT_LT(std::abs(run.slip_m.back() - run.slip_m[n1 + n2 - 6]), 4.0 * kSettling_m) << label;
  }
}

TEST(SlidingBlockStops, WhenTheDrivingShearFallsBelowTheFrictionLimit) { expect_block_stops(true, true); }

TEST(SlidingBlockStops, DISABLED_WithAugmentedLagrangianContacts) { expect_block_stops(false, true); }

// The default law (numerics.friction_at_solution: false) pulls the block back (1.4 mm
// static): a known error kept to reproduce it.
TEST(SlidingBlockStops, DISABLED_WithTheDefaultLaw) { expect_block_stops(true, false); }

}  // namespace
}  // namespace hfdda::dda
