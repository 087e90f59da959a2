// Bond failures judged on settled contact states (fracture::FractureRules::
// failures_on_settled_contacts, docs/design_notes.md section 34): in an open-close round
// that changes a contact, no bond fails; the failures of that round wait for the next.

#include <gtest/gtest.h>

#include <string>

#include "coupling/coupled_step.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace hfdda::coupling {
namespace {

/// A 4 m crack under tension syy = 0.6 MPa (its tip bonds, T0 = 1 MPa on joints of
/// 0.5 m, fail from about 0.36 MPa; the path runs one joint beyond each tip), and, 8 m
/// away, an initially open vertical joint that sxx = -1 MPa closes. Both happen in the
/// first open-close round of the step.
simulation::Model crack_and_closing_joint() {
  const std::string text = R"(
title: "a crack that grows while another joint closes"
domain:
  outer: {xmin: -20, xmax: 20, ymin: -20, ymax: 20}
  inner: {xmin: -12, xmax: 12, ymin: -3, ymax: 3}
mesh: {type: structured, cell_size: 0.5, outer_growth: 2.0, split: four}
materials:
  - {name: rock, youngs_modulus: 25.0e9, poissons_ratio: 0.25, density: 2650}
joints: {tensile_strength: 1.0e6, cohesion: 1.0e12, breakable: false}
fractures:
  - {name: path, from: [-2.5, 0], to: [2.5, 0], breakable: true}
  - {name: crack, from: [-2, 0], to: [2, 0], initially_open: true}
  - {name: gap, from: [8, -2], to: [8, 2], initially_open: true}
far_field: {syy: 0.6e6, sxx: -1.0e6, sides: [left, right, top, bottom]}
contact: {method: alm, normal_stiffness: 100, shear_stiffness: 100}
time: {dt: 1.0, end_time: 1.0}
output: {every_steps: 0, vtu: false}
)";
  return simulation::build_model(io::load_case_text(text, "settled.yaml"));
}

TEST(SettledFailures, BondsWaitForTheRoundThatChangesNoContact) {
  StepStatistics seeds_rounds, settled_rounds;
  for (const bool settled : {false, true}) {
    simulation::Model model = crack_and_closing_joint();
    fracture::FractureRules rules;
    rules.failure_needs_open_neighbour_and_fluid = false;  // no fluid here
    rules.failures_on_settled_contacts = settled;
    (settled ? settled_rounds : seeds_rounds) = CoupledStep(*model.system, {}, rules).advance(1.0, 0);
  }
  // The same bonds break, but the settled rule spends more rounds: its first one closes
  // the gap alone, and every round in which a contact still changes defers the failures.
  // (The seed's rounds fail the tip bonds in the first round, beside the gap's closing.)
  ASSERT_GT(seeds_rounds.bonds_broken, 0);
  EXPECT_EQ(settled_rounds.bonds_broken, seeds_rounds.bonds_broken);
  EXPECT_GT(settled_rounds.open_close_iterations, seeds_rounds.open_close_iterations);
}

}  // namespace
}  // namespace hfdda::coupling
