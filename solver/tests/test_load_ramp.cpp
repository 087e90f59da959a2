// Quasi-static load ramps (seed 4.2-4.4): the case keys and their checks, the margin
// and linear prediction of fracture/, and whole ramps on a small uniform block system
// whose answers are known exactly: a uniform tension s on a line of bonds of strength
// T0 breaks them all at s = T0.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "fracture/fracture_criteria.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "test_case_support.hpp"

namespace hfdda {
namespace {

using io::case_test::error_of_text;
using io::case_test::expect_error;

/// A 12 m x 12 m square of 1 m cells, a breakable horizontal line y = 0 (T0 = 1e5 Pa)
/// across it, everything else unbreakable; tension syy on top and bottom.
const std::string kRamp = R"(title: ramp
domain: {outer: {xmin: -6, xmax: 6, ymin: -6, ymax: 6}}
mesh: {type: structured, cell_size: 1, split: two}
joints: {tensile_strength: 1.0e5, breakable: false}
fractures:
  - {name: line, from: [-6, 0], to: [6, 0], breakable: true}
# No fixed point: the tractions are self-equilibrated and the inertia term of a static
# step keeps K definite, so the stress is exactly uniform.
output: {every_steps: 0, vtu: false}
load_ramp:
  syy: 1.0
  sides: [top, bottom]
  increment: 1.0e3
  maximum: 2.0e5
  stop_when: broken_fraction
  stop_joints: [line]
)";

simulation::RunResult run_text(const std::string& text, simulation::Model& model, const std::string& name) {
  model = simulation::build_model(io::load_case_text(text, name + ".yaml"));
  const std::string dir = (std::filesystem::temp_directory_path() / ("hfdda_test_ramp_" + name)).string();
  std::filesystem::remove_all(dir);
  return simulation::run(model, {dir, true, false});
}

TEST(LoadRampKeys, ParsesTheRampAndItsStop) {
  const io::CaseConfig c = io::load_case_text(kRamp, "ramp.yaml");
  ASSERT_TRUE(c.load_ramp);
  EXPECT_EQ(c.load_ramp->syy, 1.0);
  EXPECT_EQ(*c.load_ramp->increment_Pa, 1.0e3);
  EXPECT_EQ(c.load_ramp->stop_when, "broken_fraction");
  EXPECT_EQ(c.load_ramp->stop_fraction, 0.75);
  EXPECT_TRUE(c.load_ramp->predict_failures);
}

TEST(LoadRampKeys, RefusesWhatCannotMeanAnything) {
  expect_error(error_of_text(kRamp + "  history: [[0, 0], [10, 1.0e5]]\n"), "case.yaml", 13, "load_ramp.increment",
               "cannot be combined with load_ramp.history");
  std::string unknown = kRamp;
  unknown.replace(unknown.find("[line]"), 6, "[lines]");
  expect_error(error_of_text(unknown), "case.yaml", 16, "load_ramp.stop_joints[0]", "names no fracture");
  expect_error(error_of_text(kRamp + "time: {dt: 1, end_time: 10}\n"), "case.yaml", 17, "time.end_time",
               "not used with load_ramp");
  std::string zero = kRamp;
  zero.replace(zero.find("syy: 1.0"), 8, "syy: 0.0");
  expect_error(error_of_text(zero), "case.yaml", 11, "load_ramp.syy", "zero");
  std::string no_max = kRamp;
  no_max.replace(no_max.find("  maximum: 2.0e5\n"), 17, "");
  expect_error(error_of_text(no_max), "case.yaml", 10, "load_ramp.maximum", "required");
}

TEST(LoadRampPrediction, MarginAndZeroCrossing) {
  fracture::Bond b;
  b.length_m = 0.5;
  b.strength = {2.0e6, 1.0e6, 0.0};
  b.normal_N = 4.0e5;
  EXPECT_DOUBLE_EQ(fracture::failure_margin_N(b, false), 6.0e5);  // T0 Lc - N
  b.shear_N = -4.5e5;
  EXPECT_DOUBLE_EQ(fracture::failure_margin_N(b, true), 0.5e5);  // C0 Lc - |S|
  // Margin 1e6 at level 0 and 8e5 at level 1e5: zero at 5e5.
  EXPECT_DOUBLE_EQ(fracture::level_at_zero_margin(0.0, 1.0e6, 1.0e5, 8.0e5), 5.0e5);
  EXPECT_TRUE(std::isinf(fracture::level_at_zero_margin(0.0, 1.0e6, 1.0e5, 1.0e6)));
}

TEST(LoadRampRun, UniformTensionBreaksTheLineAtItsStrengthAfterOneJump) {
  simulation::Model model;
  const auto result = run_text(kRamp, model, "jump");
  ASSERT_TRUE(result.completed) << result.message;
  const auto& o = model.ramp->outcome();
  EXPECT_NEAR(o.predicted_first_failure_Pa, 1.0e5, 1.0);    // linear response, exact
  EXPECT_LT(o.jumped_to_Pa, 1.0e5 - 2.0e3 + 1.0);            // 2 increments below
  EXPECT_FALSE(o.first_failure_at_jump);
  EXPECT_NEAR(o.first_failure_Pa, 1.0e5, 1.0e3 + 1.0);       // within one increment
  EXPECT_TRUE(o.stop_reached);
  EXPECT_EQ(o.stop_Pa, o.first_failure_Pa);                   // all ties break together
  EXPECT_EQ(o.first_joint_failure_Pa, o.first_failure_Pa);
  EXPECT_LT(o.levels_solved, 10);                             // not 100 levels
  EXPECT_EQ(o.failures_at_jump, 0);
  EXPECT_EQ(result.record.series("load_level_Pa").back(), o.stop_Pa);
}

TEST(LoadRampRun, WithoutThePredictionEveryLevelIsSolvedAndTheAnswerIsTheSame) {
  simulation::Model model;
  std::string text = kRamp;
  text.replace(text.find("  increment: 1.0e3"), 18, "  increment: 1.0e4\n  predict_failures: false");
  const auto result = run_text(text, model, "climb");
  ASSERT_TRUE(result.completed) << result.message;
  const auto& o = model.ramp->outcome();
  EXPECT_TRUE(std::isnan(o.predicted_first_failure_Pa));
  EXPECT_NEAR(o.first_failure_Pa, 1.0e5, 1.0e4 + 1.0);
  EXPECT_EQ(o.levels_solved, static_cast<int>(std::lround(o.stop_Pa / 1.0e4)) + 1);
}

/// A centre crack (a = 2 m, initially open) under tension, failing by the toughness
/// criterion, on the plate of the LEFM study made smaller (1 m cells in a band around
/// the path, growing outwards). The open crack's end contacts sit at the tips, where its
/// two faces share the tip's point: on this mesh they close and open again by round-off
/// from level to level (on a uniform 24 m square of 1 m cells they do not), without force
/// either way.
const std::string kCrackRamp = R"(title: crack ramp
domain: {outer: {xmin: -40, xmax: 40, ymin: -40, ymax: 40}, inner: {xmin: -12, xmax: 12, ymin: -1, ymax: 1}}
mesh: {type: structured, cell_size: 1, split: four, outer_growth: 2.0}
joints: {tensile_strength: 1.0e7, breakable: false}
fractures:
  - {name: path, from: [-11, 0], to: [11, 0], breakable: true}
  - {name: crack, from: [-2, 0], to: [2, 0], initially_open: true}
fracture: {criterion: energy_release_rate, fracture_toughness: 886226.925}
contact: {method: alm, normal_stiffness: 100, shear_stiffness: 100}
output: {every_steps: 0, vtu: false}
load_ramp:
  syy: 1.0
  sides: [top, bottom]
  increment: 8.0e3
  maximum: 1.0e6
  stop_when: broken_fraction
  stop_joints: [path]
)";

TEST(LoadRampRun, ContactsAtACracksTipDoNotStopThePrediction) {
  simulation::Model predicted_model, climbing_model;
  const auto predicted = run_text(kCrackRamp, predicted_model, "crack_predicted");
  ASSERT_TRUE(predicted.completed) << predicted.message;
  std::string text = kCrackRamp;
  text.replace(text.find("  increment: 8.0e3"), 18, "  increment: 8.0e3\n  predict_failures: false");
  const auto climbing = run_text(text, climbing_model, "crack_climbing");
  ASSERT_TRUE(climbing.completed) << climbing.message;
  const auto& p = predicted_model.ramp->outcome();
  const auto& c = climbing_model.ramp->outcome();
  EXPECT_GE(p.jumps, 1);
  EXPECT_EQ(p.failures_at_jump, 0);
  EXPECT_EQ(p.first_failure_Pa, c.first_failure_Pa);  // the level a level-by-level ramp finds
  EXPECT_LT(p.levels_solved * 4, c.levels_solved);
}

TEST(LoadRampRun, HistoryBelowTheStrengthBreaksNothing) {
  simulation::Model model;
  std::string text = kRamp;
  text.replace(text.find("  increment: 1.0e3\n  maximum: 2.0e5\n"), 35, "  history: [[0, 0], [4, 8.0e4]]\n");
  const auto result = run_text(text, model, "history");
  ASSERT_TRUE(result.completed) << result.message;
  EXPECT_EQ(result.steps, 4);
  EXPECT_DOUBLE_EQ(result.record.series("load_level_Pa").back(), 8.0e4);
  EXPECT_TRUE(std::isnan(model.ramp->outcome().first_failure_Pa));
  EXPECT_FALSE(model.ramp->outcome().stop_reached);
}

}  // namespace
}  // namespace hfdda
