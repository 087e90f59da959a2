// Fracture criteria of the bonded joints (seed section 2.3, eq. 2.16 and items i, iii):
//   tension (Rankine):      a bond fails when N > T0 Lc;
//   shear (Mohr-Coulomb):   with shear failure of intact joints enabled, when
//                           |S| > C0 Lc + tan(phi) max(-N, 0);
//   rule (i):               only next to an open contact (the same joint's other end, or
//                           at the same point) and next to a pressurised point;
//   rule (iii):             of the bonds over their tensile strength only the most
//                           stressed (sigma_N = N / Lc) fails in an open-close round, and
//                           those within the tie tolerance of it fail with it.
// The tests load small block systems just below and just above these limits and check
// only whether bonds broke. Everything that touches the block-system API is in the
// helpers at the top of the file (Scenario, run, the outcome queries), so that moving the
// criteria elsewhere changes only those.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "coupling/coupled_step.hpp"
#include "coupling/prescribed_pressure.hpp"
#include "dda/block_system.hpp"
#include "fracture/fracture_criteria.hpp"
#include "mesh/mesh.hpp"

namespace hfdda::dda {
namespace {

// ------------------------------------------------------------------------------------
// System construction and queries (the only code that knows the BlockSystem API)

constexpr double kYoungs = 25.0e9;

/// A joint end: the joint from `a` to `b` (either order), at its end point `at`.
struct JointEnd {
  Vec2 a, b, at;
};

/// A small block system with its loads, built and stepped by run().
struct Scenario {
  mesh::Mesh mesh;
  MechanicsSettings settings;
  fracture::FractureRules rules;  ///< the failure rules of seed 2.3 under test
  Eigen::Matrix2d far_field = Eigen::Matrix2d::Zero();  ///< on every boundary edge
  bool in_situ = false;  ///< the far field is also the initial stress: at rest in equilibrium
  std::vector<Vec2> fixed_points;
  std::vector<std::pair<Vec2, Vec2>> point_loads;  ///< (where, force N/m)
  std::vector<std::pair<int, double>> fluid;       ///< (wetted joint, uniform pressure Pa)
  double dt_s = 0.01;
};

/// nx x ny square blocks of 1 m (quadrilaterals). Every joint starts bonded, closed and
/// unbreakable; tests make the joints under test breakable with set_joint().
Scenario grid(int nx, int ny) {
  mesh::StructuredMeshSpec spec;
  spec.outer = Rect{0.0, double(nx), 0.0, double(ny)};
  spec.cell_size_m = 1.0;
  spec.split = mesh::CellSplit::none;
  Scenario s;
  s.mesh = mesh::build_structured_mesh(spec);
  mesh::JointProperties unbreakable;
  unbreakable.breakable = false;
  unbreakable.tensile_strength_Pa = unbreakable.cohesion_Pa = 1e30;
  mesh::build_topology(s.mesh, unbreakable);
  // Converged Augmented Lagrangian: the contact forces are the blocks' internal forces.
  s.settings.normal_stiffness_N_m = s.settings.shear_stiffness_N_m = s.settings.fixed_point_stiffness_N_m =
      100.0 * kYoungs;
  s.settings.alm_force_tolerance = 1e-10;
  s.settings.max_alm_iterations = 500;
  s.rules.failure_needs_open_neighbour_and_fluid = false;
  s.rules.shear_failure_of_intact_joints = false;
  return s;
}

int joint_id(const mesh::Mesh& m, const Vec2& a, const Vec2& b) {
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
    const Vec2 p = m.points[m.joints[j].point_p], q = m.points[m.joints[j].point_q];
    if (((p - a).norm() < 1e-9 && (q - b).norm() < 1e-9) || ((p - b).norm() < 1e-9 && (q - a).norm() < 1e-9)) return j;
  }
  ADD_FAILURE() << "no joint from (" << a.transpose() << ") to (" << b.transpose() << ")";
  return -1;
}

/// A breakable bond of tensile strength T0, cohesion C0 and friction angle phi.
mesh::JointProperties bond(double tensile_Pa, double cohesion_Pa = 1e30, double friction_deg = 0.0) {
  mesh::JointProperties p;
  p.breakable = true;
  p.tensile_strength_Pa = tensile_Pa;
  p.cohesion_Pa = cohesion_Pa;
  p.friction_angle_rad = friction_deg * std::numbers::pi / 180.0;
  return p;
}
/// An initial fracture: open, unbonded from the start.
mesh::JointProperties initial_fracture() {
  mesh::JointProperties p;
  p.initially_open = true;
  p.breakable = false;
  return p;
}

void set_joint(Scenario& s, const Vec2& a, const Vec2& b, const mesh::JointProperties& p) {
  s.mesh.joints[joint_id(s.mesh, a, b)].properties = p;
}
/// Fluid at a uniform pressure on both faces of the joint a-b (both end points pressurised).
void fill_joint(Scenario& s, const Vec2& a, const Vec2& b, double pressure_Pa) {
  s.fluid.emplace_back(joint_id(s.mesh, a, b), pressure_Pa);
}

struct Outcome {
  std::unique_ptr<BlockSystem> system;
  StepStatistics stats;

  int contact(const JointEnd& e) const {
    const int j = joint_id(system->mesh(), e.a, e.b);
    for (int ci : system->joint_contacts(j))
      if ((system->mesh().points[system->contacts()[ci].point] - e.at).norm() < 1e-9) return ci;
    ADD_FAILURE() << "joint end at (" << e.at.transpose() << ") not found";
    return 0;
  }
  bool broken(const JointEnd& e) const {
    const Contact& c = system->contacts()[contact(e)];
    return !c.bonded || c.state != ContactState::locked;
  }
  bool open(const JointEnd& e) const { return system->contacts()[contact(e)].state == ContactState::open; }
  bool sliding(const JointEnd& e) const { return system->contacts()[contact(e)].state == ContactState::sliding; }
  /// Normal (tension positive) and shear force of the joint end [N per m].
  std::pair<double, double> forces(const JointEnd& e) const { return system->contact_forces(contact(e)); }
  /// Length of the contact (half the joint) [m].
  double contact_length(const JointEnd& e) const { return system->contacts()[contact(e)].length_m; }
};

/// Builds the system and runs one time step.
Outcome run(const Scenario& s) {
  Outcome out;
  out.system = std::make_unique<BlockSystem>(s.mesh, std::vector<Material>{Material{kYoungs, 0.25, 2650.0}}, s.settings);
  BlockSystem& system = *out.system;
  if (!s.far_field.isZero())
    for (int e = 0; e < static_cast<int>(s.mesh.boundary_edges.size()); ++e) system.add_boundary_stress(e, s.far_field);
  if (s.in_situ) system.set_in_situ_stress(s.far_field);
  for (const Vec2& p : s.fixed_points) system.add_fixed_point(p);
  for (const auto& [at, force] : s.point_loads) system.add_point_load(at, force);
  // Fluid at prescribed pressures on the wetted joints, through the coupled step.
  std::vector<double> pressure(s.mesh.points.size(), 0.0);
  std::vector<char> wetted(s.mesh.joints.size(), 0);
  for (auto [j, p] : s.fluid) {
    wetted[j] = 1;
    pressure[s.mesh.joints[j].point_p] = pressure[s.mesh.joints[j].point_q] = p;
  }
  coupling::PrescribedPressure fluid(system.mesh(), pressure, wetted);
  std::vector<coupling::FluidLoadModel*> fluids;
  if (!s.fluid.empty()) fluids.push_back(&fluid);
  out.stats = coupling::CoupledStep(system, fluids, s.rules).advance(s.dt_s, 0);
  return out;
}

Eigen::Matrix2d stress(double sxx, double syy, double sxy) {
  Eigen::Matrix2d m;
  m << sxx, sxy, sxy, syy;
  return m;
}

// ------------------------------------------------------------------------------------
// The configurations

// Two blocks stacked, bonded along y = 1 (joint length 1 m, two contacts of Lc = 0.5 m),
// in a uniform stress state at rest (far field = initial stress): each joint end carries
// exactly N = syy Lc and |S| = |sxy| Lc.
const Vec2 kStackA{0, 1}, kStackB{1, 1};
const JointEnd kStackEnd0{kStackA, kStackB, kStackA}, kStackEnd1{kStackA, kStackB, kStackB};

Scenario stacked_pair(const mesh::JointProperties& joint, const Eigen::Matrix2d& far_field) {
  Scenario s = grid(1, 2);
  set_joint(s, kStackA, kStackB, joint);
  s.far_field = far_field;
  s.in_situ = true;
  s.fixed_points = {{0.0, 0.0}};
  s.dt_s = 1e-3;  // small motion after a failure (the loads are then out of balance)
  return s;
}

// 2 x 2 blocks; points (0,1), (1,1), (2,1) on the middle line. The joint under test is one
// half of the middle line, the other half or the upper vertical joint is an initial
// fracture that may carry fluid. All other joints are unbreakable.
const Vec2 kLeft{0, 1}, kCentre{1, 1}, kRight{2, 1}, kTop{1, 2};
const JointEnd kRightTip{kCentre, kRight, kCentre}, kRightFar{kCentre, kRight, kRight};
const JointEnd kLeftTip{kLeft, kCentre, kCentre};

Scenario square_of_four() {
  Scenario s = grid(2, 2);
  s.fixed_points = {{0.0, 0.0}};
  return s;
}

double tan_deg(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

// ------------------------------------------------------------------------------------
// Tension (Rankine, eq. 2.16): N > T0 Lc

TEST(FractureTension, BondHoldsJustBelowAndBreaksJustAboveTensileStrength) {
  // Closed form: N = syy Lc. Rule (i) is off (no fluid anywhere).
  const double t0 = 1.0e6;
  {
    const Outcome o = run(stacked_pair(bond(t0), stress(0, 0.99 * t0, 0)));
    EXPECT_NEAR(o.forces(kStackEnd0).first, 0.99 * t0 * o.contact_length(kStackEnd0), 1e-6 * t0);  // the set-up
    EXPECT_EQ(o.stats.bonds_broken, 0);
    EXPECT_FALSE(o.broken(kStackEnd0));
    EXPECT_FALSE(o.broken(kStackEnd1));
  }
  {
    const Outcome o = run(stacked_pair(bond(t0), stress(0, 1.01 * t0, 0)));
    EXPECT_EQ(o.stats.bonds_broken, 2);  // both ends, equally stressed
    EXPECT_TRUE(o.broken(kStackEnd0));
    EXPECT_TRUE(o.broken(kStackEnd1));
    EXPECT_TRUE(o.open(kStackEnd0));
  }
}

TEST(FractureTension, StrengthScalesWithContactLength) {
  // The same stress in a 2 m x 2 m pair of blocks (Lc = 1 m): still just below / above.
  const double t0 = 1.0e6;
  for (double ratio : {0.99, 1.01}) {
    Scenario s = stacked_pair(bond(t0), stress(0, ratio * t0, 0));
    for (Vec2& p : s.mesh.points) p *= 2.0;
    s.fixed_points = {{0.0, 0.0}};
    const Outcome o = run(s);
    const JointEnd end{2 * kStackA, 2 * kStackB, 2 * kStackA};
    EXPECT_NEAR(o.contact_length(end), 1.0, 1e-12);
    EXPECT_EQ(o.broken(end), ratio > 1.0) << "load / strength " << ratio;
  }
}

// Tension next to a fluid-filled initial fracture (the left half of the middle line, at
// 1 MPa): the bond at its tip is pulled open. The load is fixed and the strength set
// from the tip's force in a run with an unbreakable bond: T0 = N / (ratio Lc). Rule (i)
// is on, and satisfied (open fracture and pressurised point at the tip).
TEST(FractureTension, BondAtTipOfPressurisedFractureHoldsBelowAndBreaksAboveStrength) {
  auto scenario = [](const mesh::JointProperties& tested) {
    Scenario s = square_of_four();
    s.rules.failure_needs_open_neighbour_and_fluid = true;
    set_joint(s, kLeft, kCentre, initial_fracture());
    fill_joint(s, kLeft, kCentre, 1.0e6);
    set_joint(s, kCentre, kRight, tested);
    return s;
  };
  const Outcome calibration = run(scenario(bond(1e30)));
  const double n = calibration.forces(kRightTip).first, lc = calibration.contact_length(kRightTip);
  ASSERT_EQ(calibration.stats.bonds_broken, 0);
  ASSERT_GT(n, 1e4);  // the fluid does pull the tip
  {
    const Outcome o = run(scenario(bond(n / (0.99 * lc))));
    EXPECT_EQ(o.stats.bonds_broken, 0);
    EXPECT_FALSE(o.broken(kRightTip));
  }
  {
    const Outcome o = run(scenario(bond(n / (1.01 * lc))));
    EXPECT_GE(o.stats.bonds_broken, 1);
    EXPECT_TRUE(o.broken(kRightTip));
  }
}

// ------------------------------------------------------------------------------------
// Shear (Mohr-Coulomb, eq. 2.16): |S| > C0 Lc + tan(phi) max(-N, 0)

TEST(FractureShear, BondHoldsJustBelowAndBreaksJustAboveMohrCoulombLimit) {
  // Closed form: N = -2 MPa Lc, |S| = sxy Lc; limit sxy = C0 + tan(30 deg) 2 MPa, of which
  // friction is more than half. Rule (i) off.
  const double c0 = 1.0e6, sn = 2.0e6, phi = 30.0;
  const double limit = c0 + tan_deg(phi) * sn;
  for (double ratio : {0.99, 1.01}) {
    Scenario s = stacked_pair(bond(1e6, c0, phi), stress(0, -sn, ratio * limit));
    s.rules.shear_failure_of_intact_joints = true;
    const Outcome o = run(s);
    const bool above = ratio > 1.0;
    EXPECT_EQ(o.stats.bonds_broken, above ? 2 : 0) << "load / strength " << ratio;
    EXPECT_EQ(o.broken(kStackEnd0), above) << "load / strength " << ratio;
    EXPECT_EQ(o.broken(kStackEnd1), above) << "load / strength " << ratio;
    if (above) EXPECT_TRUE(o.sliding(kStackEnd0) || o.open(kStackEnd0));
  }
}

TEST(FractureShear, IntactBondsDoNotFailInShearUnlessEnabled) {
  // Seed 2.3 (ii): by default bonds fail in tension first; shear over the limit holds.
  const double c0 = 1.0e6, sn = 2.0e6, phi = 30.0;
  const Outcome o = run(stacked_pair(bond(1e6, c0, phi), stress(0, -sn, 1.5 * (c0 + tan_deg(phi) * sn))));
  EXPECT_EQ(o.stats.bonds_broken, 0);
  EXPECT_FALSE(o.broken(kStackEnd0));
}

// Shear next to a fluid-filled initial fracture: the upper vertical joint (1,1)-(1,2) at
// 2 MPa pushes the two upper blocks apart against 1 MPa of horizontal and 3 MPa of
// vertical far-field compression, shearing the compressed left half of the middle line
// at its end (1,1). Calibrated like the tension test: phi so that friction is half the
// force, then C0 Lc = |S| / ratio - tan(phi) |N|. Rule (i) on and satisfied.
TEST(FractureShear, BondNextToPressurisedFractureHoldsBelowAndBreaksAboveMohrCoulombLimit) {
  auto scenario = [](const mesh::JointProperties& tested) {
    Scenario s = square_of_four();
    s.rules.failure_needs_open_neighbour_and_fluid = true;
    s.rules.shear_failure_of_intact_joints = true;
    s.far_field = stress(-1.0e6, -3.0e6, 0.0);
    set_joint(s, kCentre, kTop, initial_fracture());
    fill_joint(s, kCentre, kTop, 2.0e6);
    set_joint(s, kLeft, kCentre, tested);
    return s;
  };
  const Outcome calibration = run(scenario(bond(1e30, 1e30, 0.0)));
  ASSERT_EQ(calibration.stats.bonds_broken, 0);
  const auto [n, shear] = calibration.forces(kLeftTip);
  const double lc = calibration.contact_length(kLeftTip);
  ASSERT_LT(n, -1e4);                   // compressed: friction matters
  ASSERT_GT(std::abs(shear), 1e4);      // and sheared by the fluid
  const double tan_phi = 0.5 * std::abs(shear) / std::abs(n);
  const double phi_deg = std::atan(tan_phi) * 180.0 / std::numbers::pi;
  for (double ratio : {0.99, 1.01}) {
    const double c0 = (std::abs(shear) / ratio - tan_phi * std::abs(n)) / lc;
    ASSERT_GT(c0, 0.0);
    const Outcome o = run(scenario(bond(1e30, c0, phi_deg)));
    const bool above = ratio > 1.0;
    EXPECT_EQ(o.broken(kLeftTip), above) << "load / strength " << ratio;
    if (above)
      EXPECT_GE(o.stats.bonds_broken, 1);
    else
      EXPECT_EQ(o.stats.bonds_broken, 0);
  }
}

// ------------------------------------------------------------------------------------
// Rule (i): a bond may fail only next to an open contact (same joint or same point) and
// next to a pressurised point. The right half of the middle line is pulled at twice its
// strength by a vertical far-field tension; each case is run with the rule on and off.

enum class Neighbour { closed_dry, open_dry, closed_pressurised, open_pressurised };

Outcome pulled_middle_line(Neighbour left_half, bool rule) {
  const double t0 = 0.5e6;
  Scenario s = square_of_four();
  s.rules.failure_needs_open_neighbour_and_fluid = rule;
  s.far_field = stress(0.0, 2.0 * t0, 0.0);
  set_joint(s, kCentre, kRight, bond(t0));
  if (left_half == Neighbour::open_dry || left_half == Neighbour::open_pressurised)
    set_joint(s, kLeft, kCentre, initial_fracture());
  if (left_half == Neighbour::closed_pressurised || left_half == Neighbour::open_pressurised)
    fill_joint(s, kLeft, kCentre, 0.2e6);
  return run(s);
}

/// The bond holds with the rule on and, as the control that it is over its strength,
/// breaks with the rule off.
void expect_held_only_by_the_rule(Neighbour left_half) {
  const Outcome with_rule = pulled_middle_line(left_half, true);
  EXPECT_EQ(with_rule.stats.bonds_broken, 0);
  EXPECT_FALSE(with_rule.broken(kRightTip));
  EXPECT_FALSE(with_rule.broken(kRightFar));
  const Outcome without_rule = pulled_middle_line(left_half, false);
  EXPECT_TRUE(without_rule.broken(kRightTip));
  EXPECT_GE(without_rule.stats.bonds_broken, 1);
}

TEST(FractureRuleOpenNeighbourAndFluid, OverstressedBondWithoutOpenNeighbourOrFluidHolds) {
  expect_held_only_by_the_rule(Neighbour::closed_dry);
}

TEST(FractureRuleOpenNeighbourAndFluid, OverstressedBondNextToDryOpenFractureHolds) {
  expect_held_only_by_the_rule(Neighbour::open_dry);
}

TEST(FractureRuleOpenNeighbourAndFluid, OverstressedBondAtPressurisedPointWithoutOpenNeighbourHolds) {
  // The left half is closed and bonded but carries fluid: (1,1) is pressurised.
  expect_held_only_by_the_rule(Neighbour::closed_pressurised);
}

TEST(FractureRuleOpenNeighbourAndFluid, OverstressedBondNextToOpenPressurisedFractureBreaks) {
  const Outcome o = pulled_middle_line(Neighbour::open_pressurised, true);
  // The tip fails next to the open fracture end at the same point; then the far end
  // fails next to the open other end of its own joint (pressurised point at (1,1)).
  EXPECT_TRUE(o.broken(kRightTip));
  EXPECT_TRUE(o.broken(kRightFar));
  EXPECT_EQ(o.stats.bonds_broken, 2);
}

// ------------------------------------------------------------------------------------
// Rule (iii): a column of three blocks, the bottom one fixed, pulled up by point loads at
// the centroids of the top (F_top) and middle (F_mid) blocks. The lower joint carries
// F_top + F_mid, the upper one F_top (sigma_N = force / (2 Lc), Lc = 0.5 m), both over
// T0 = 0.75 F_top. If only the lower joint breaks, the two upper blocks move off together
// and the upper joint is relieved (its force drops to (F_top - F_mid) / 2 < T0): it
// survives the step only if it did not break in the same round.

const Vec2 kLowA{0, 1}, kLowB{1, 1}, kUpA{0, 2}, kUpB{1, 2};

struct ColumnResult {
  int lower_broken = 0, upper_broken = 0, bonds_broken = 0;
};

ColumnResult pulled_column(double f_top, double f_mid, double tie_tolerance) {
  Scenario s = grid(1, 3);
  s.rules.tie_tolerance = tie_tolerance;
  s.fixed_points = {{0.0, 0.0}, {1.0, 0.0}};
  s.point_loads = {{{0.5, 2.5}, {0.0, f_top}}, {{0.5, 1.5}, {0.0, f_mid}}};
  s.dt_s = 0.1;  // inertia ~1e-5 of the forces: equal loads give equal stresses
  set_joint(s, kLowA, kLowB, bond(0.75 * f_top));
  set_joint(s, kUpA, kUpB, bond(0.75 * f_top));
  const Outcome o = run(s);
  ColumnResult r;
  for (const Vec2& at : {kLowA, kLowB}) r.lower_broken += o.broken({kLowA, kLowB, at});
  for (const Vec2& at : {kUpA, kUpB}) r.upper_broken += o.broken({kUpA, kUpB, at});
  r.bonds_broken = o.stats.bonds_broken;
  return r;
}

TEST(FractureRuleMostStressedFails, OnlyTheMostStressedOfTwoOverstressedBondsBreaks) {
  // Stresses 2 F and F, both over T0 = 0.75 F.
  const ColumnResult r = pulled_column(1.0e4, 1.0e4, 1e-3);
  EXPECT_EQ(r.lower_broken, 2);
  EXPECT_EQ(r.upper_broken, 0);
  EXPECT_EQ(r.bonds_broken, 2);
}

TEST(FractureRuleMostStressedFails, EquallyStressedBondsBreakTogether) {
  // Both joints carry F: all four joint ends fail in the same round.
  const ColumnResult r = pulled_column(1.0e4, 0.0, 1e-3);
  EXPECT_EQ(r.lower_broken, 2);
  EXPECT_EQ(r.upper_broken, 2);
  EXPECT_EQ(r.bonds_broken, 4);
}

TEST(FractureRuleMostStressedFails, TieToleranceIsRelativeToTheLargestStress) {
  // Stresses 1.05 F and F: a tie within a 10 % tolerance, not within 1 %.
  const ColumnResult within = pulled_column(1.0e4, 0.05e4, 0.1);
  EXPECT_EQ(within.lower_broken, 2);
  EXPECT_EQ(within.upper_broken, 2);
  const ColumnResult outside = pulled_column(1.0e4, 0.05e4, 0.01);
  EXPECT_EQ(outside.lower_broken, 2);
  EXPECT_EQ(outside.upper_broken, 0);
}

}  // namespace
}  // namespace hfdda::dda
