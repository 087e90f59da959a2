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
