// Two-tier contacts (seed 5.1; dda/block_system.hpp, MechanicsSettings::intact_stiffness_ratio):
// the intact contacts' springs only set the pace of the Augmented Lagrangian iterations,
// so stiffening them must leave each step's converged state unchanged and cut the
// iterations. The case: a small naturally fractured block under an anisotropic in-situ
// stress, fluid injected into a short open fracture (the Marcellus case of seed 5.4 at a
// quarter of its size), where intact contacts meet the penalty contacts of the natural
// fractures and, at one stiffness for both tiers, converge by about one seventh per
// iteration.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"

namespace hfdda::simulation {
namespace {

std::string fractured_block(double intact_stiffness_ratio) {
  return R"(
domain:
  outer: {xmin: -40, xmax: 40, ymin: -40, ymax: 40}
mesh: {type: delaunay, max_area_inner: 16}
materials:
  - {name: shale, youngs_modulus: 33.47e9, poissons_ratio: 0.17, density: 2500}
joints: {tensile_strength: 9.02e6, cohesion: 0, friction_angle: 30}
network_seed: 3
fracture_sets:
  - {name: J1, azimuth: 90, azimuth_tolerance: 5, seed_fraction: 0.2, length: {distribution: uniform, min: 10, max: 25},
     tensile_strength: 0, cohesion: 0, friction_angle: 30, hydraulic_width: 1.0e-4}
  - {name: J2, azimuth: 0, azimuth_tolerance: 5, seed_fraction: 0.15, length: {distribution: uniform, min: 10, max: 25},
     tensile_strength: 0, cohesion: 0, friction_angle: 30, hydraulic_width: 1.0e-4}
fractures:
  - {name: injection_joints, from: [-2, 0], to: [2, 0], segment_length: 2, initially_open: true, fluid_filled: true}
fluid: {density: 1000, bulk_modulus: 2.2e9, viscosity: 0.02, reference_pressure: 0, leak_off_coefficient: 0}
injections:
  - {name: well, at: [0, 0], mass_rate: 0.5, start_time: 0}
probes:
  - {name: inlet, at: [0, 0]}
far_field: {sxx: -32.0e6, syy: -10.0e6, sxy: 0, in_situ: true, sides: [left, right, bottom, top]}
fixed_points: [[-40, -40], [40, -40], [40, 40], [-40, 40]]
contact: {method: alm, normal_stiffness: 30, shear_stiffness: 30, two_tier: true, intact_stiffness_ratio: )" +
         std::to_string(intact_stiffness_ratio) + R"(}
time: {dt: 60, end_time: 60}
)";
}

struct TwoTierRun {
  RunResult result;
  std::vector<double> pressure_Pa;  // per point
  double stored_mass_kg = 0.0;
};

TwoTierRun run_block(double ratio) {
  Model model = build_model(io::load_case_text(fractured_block(ratio), "two_tier.yaml"));
  RunOptions options;
  options.quiet = true;
  options.write_files = false;
  TwoTierRun r;
  r.result = run(model, options);
  if (model.flow) {
    for (int p = 0; p < model.flow->n_points(); ++p) r.pressure_Pa.push_back(model.flow->pressure(p));
    r.stored_mass_kg = model.flow->stored_mass();
  }
  return r;
}

TEST(TwoTierContacts, StifferIntactSpringsConvergeFasterToTheSameState) {
  const TwoTierRun seed_like = run_block(1.0);
  const TwoTierRun stiff = run_block(100.0);
  ASSERT_TRUE(seed_like.result.completed) << seed_like.result.message;
  ASSERT_TRUE(stiff.result.completed) << stiff.result.message;
  ASSERT_EQ(seed_like.pressure_Pa.size(), stiff.pressure_Pa.size());

  // The same converged state: pressures agree to the iterations' tolerance (both stop
  // on contact forces within 1e-7 of the largest), far below what a state change
  // (a joint opening, wetting or slipping) would move. One step: in the next, the
  // seed-like run ends its contact iterations on stalls and open-close cycles, and the
  // two runs part (there the stiff run opens 3.9 m of natural fracture, the other none).
  double largest = 0.0, difference = 0.0;
  for (std::size_t p = 0; p < stiff.pressure_Pa.size(); ++p) {
    largest = std::max(largest, std::abs(seed_like.pressure_Pa[p]));
    difference = std::max(difference, std::abs(seed_like.pressure_Pa[p] - stiff.pressure_Pa[p]));
  }
  ASSERT_GT(largest, 1.0e6);  // the fluid did load the block
  EXPECT_LT(difference, 1.0e-5 * largest);
  EXPECT_NEAR(seed_like.stored_mass_kg, stiff.stored_mass_kg, 1.0e-9 * seed_like.stored_mass_kg);
  const auto wetted_a = seed_like.result.record.series("wetted_joints");
  const auto wetted_b = stiff.result.record.series("wetted_joints");
  EXPECT_EQ(wetted_a, wetted_b);

  // The pace: at one stiffness for both tiers the intact contacts next to the natural
  // fractures' penalty springs converge slowly; 100 times stiffer, in a third of the
  // iterations or fewer.
  EXPECT_LE(3 * stiff.result.totals.alm_iterations, seed_like.result.totals.alm_iterations)
      << "ALM iterations: " << stiff.result.totals.alm_iterations << " (ratio 100) against "
      << seed_like.result.totals.alm_iterations << " (ratio 1)";
}

}  // namespace
}  // namespace hfdda::simulation
