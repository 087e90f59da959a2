// The iteration trace (`hfdda run --trace-iterations`, DIR/iterations.csv): every
// open-close iteration and every attempt's end reach the observer, a refused attempt
// with its reason, and the CSV keeps text with commas and quotes in one field.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "coupling/coupled_step.hpp"
#include "dda/block_system.hpp"
#include "dda_test_support.hpp"
#include "io/case_config.hpp"
#include "simulation/iteration_trace.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"

namespace hfdda {
namespace {

struct Attempt {
  double dt_s;
  int iterations;
  std::string refusal;
  std::vector<coupling::IterationRecord> records;
};

/// Keeps what it is told, grouped by attempt.
class Recorder final : public coupling::IterationObserver {
 public:
  void iteration(const coupling::IterationRecord& r) override { pending_.push_back(r); }
  void attempt_ended(double dt_s, int iterations, const std::string& refusal) override {
    attempts.push_back({dt_s, iterations, refusal, std::move(pending_)});
    pending_.clear();
  }
  std::vector<Attempt> attempts;

 private:
  std::vector<coupling::IterationRecord> pending_;
};

TEST(IterationTrace, RefusedAttemptsAreReportedWithTheirReasonAndIterations) {
  auto system = dda::test_support::pulled_unit_block(0.25 * 25e9);
  Recorder recorder;
  coupling::CoupledStep step(*system, {});
  step.observe_iterations(&recorder);
  EXPECT_THROW(step.advance(1.0, 1), ConvergenceError);
  // The whole step refused, then its first half refused with no cut left.
  ASSERT_EQ(recorder.attempts.size(), 2u);
  EXPECT_DOUBLE_EQ(recorder.attempts[0].dt_s, 1.0);
  EXPECT_DOUBLE_EQ(recorder.attempts[1].dt_s, 0.5);
  for (const Attempt& a : recorder.attempts) {
    EXPECT_NE(a.refusal.find("would be strained"), std::string::npos) << a.refusal;
    ASSERT_EQ(static_cast<int>(a.records.size()), a.iterations);
    ASSERT_GE(a.iterations, 1);
    for (int i = 0; i < a.iterations; ++i) {
      EXPECT_EQ(a.records[i].iteration, i + 1);
      EXPECT_DOUBLE_EQ(a.records[i].attempt_dt_s, a.dt_s);
    }
    // The last iteration's trial is the state the guard refused: a strain of about 0.25.
    EXPECT_EQ(a.records.back().strain_block, 0);
    EXPECT_GT(a.records.back().block_strain, 0.2);
    EXPECT_EQ(a.records.back().contact_changes, 0);
  }
}

TEST(IterationTrace, ConvergedAttemptEndsCommittedWithTheStepsIterationCount) {
  auto system = dda::test_support::pulled_unit_block(0.0025 * 25e9);
  Recorder recorder;
  coupling::CoupledStep step(*system, {});
  step.observe_iterations(&recorder);
  const StepStatistics stats = step.advance(1.0, 2);
  ASSERT_EQ(recorder.attempts.size(), 1u);
  const Attempt& a = recorder.attempts[0];
  EXPECT_TRUE(a.refusal.empty()) << a.refusal;
  EXPECT_EQ(a.iterations, stats.open_close_iterations);
  ASSERT_EQ(static_cast<int>(a.records.size()), stats.open_close_iterations);
  EXPECT_NEAR(a.records.back().block_strain, stats.max_block_strain, 1e-15);
  EXPECT_LT(a.records.back().block_strain, 0.01);
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Commas outside double quotes.
int separators(const std::string& line) {
  int n = 0;
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) ++n;
  }
  return n;
}

TEST(IterationTrace, CsvKeepsTextWithCommasAndQuotesInOneFieldAndRestartsAfterItsCheckpoint) {
  const std::string path = (std::filesystem::path(testing::TempDir()) / "hfdda_iterations.csv").string();
  {
    simulation::IterationTrace trace(path);
    trace.begin_step(3, 2.5);
    coupling::IterationRecord r;
    r.attempt_dt_s = 0.5;
    r.iteration = 1;
    r.first_change = "joint 1 at (0, 1): open -> \"x\"";
    trace.iteration(r);
    trace.attempt_ended(0.5, 1, "faces overlap, 0.3 of the joint");
    trace.begin_step(4, 3.0);  // written after the checkpoint of step 3, then stopped
    trace.attempt_ended(0.5, 7, "");
  }
  {
    // Restarted after step 3: no second header, step 4's old row dropped, written again.
    simulation::IterationTrace again(path, 3);
    again.begin_step(4, 3.0);
    again.attempt_ended(0.5, 2, "");
  }
  const std::vector<std::string> lines = lines_of(path);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("step,step_start_s,attempt_dt_s,row,iteration,", 0), 0u);
  const int columns = separators(lines[0]) + 1;
  EXPECT_EQ(columns, 15);
  for (const std::string& line : lines) EXPECT_EQ(separators(line) + 1, columns) << line;
  EXPECT_EQ(lines[1].rfind("3,2.5,0.5,iteration,1,", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find(",\"joint 1 at (0, 1): open -> \"\"x\"\"\""), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find(",attempt,1,"), std::string::npos) << lines[2];
  EXPECT_NE(lines[2].find("\"faces overlap, 0.3 of the joint\""), std::string::npos) << lines[2];
  EXPECT_EQ(lines[3].rfind("4,3,0.5,attempt,2,", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find("\"committed\""), std::string::npos) << lines[3];
}

TEST(IterationTrace, RunWritesOneCommittedAttemptPerUncutStep) {
  // A block pressed by a boundary stress, three steps: each step one committed attempt,
  // preceded by as many iteration rows as its open-close iterations in history.csv.
  const std::string text = R"(
title: "iteration trace"
domain: {outer: {xmin: 0, xmax: 2, ymin: 0, ymax: 1}}
mesh: {type: structured, cell_size: 0.5, split: none}
materials: [{youngs_modulus: 25.0e9, poissons_ratio: 0.25}]
far_field: {sxx: -1.0e6, syy: 0, sxy: 0, sides: [right]}
fixed_points: [[0, 0], [0, 1]]
time: {dt: 1, end_time: 3}
output: {every_steps: 0, vtu: false}
)";
  simulation::Model model = simulation::build_model(io::load_case_text(text, "trace.yaml"));
  simulation::RunOptions options;
  options.output_dir = (std::filesystem::path(testing::TempDir()) / "hfdda_trace_run").string();
  std::filesystem::remove_all(options.output_dir);
  options.quiet = true;
  options.write_vtu = false;
  options.trace_iterations = true;
  const simulation::RunResult result = simulation::run(model, options);
  ASSERT_TRUE(result.completed) << result.message;
  const std::vector<std::string> lines = lines_of(options.output_dir + "/iterations.csv");
  int attempts = 0, iterations = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].find(",attempt,") != std::string::npos) {
      ++attempts;
      EXPECT_EQ(lines[i].rfind(std::to_string(attempts) + ",", 0), 0u) << "row of step " << attempts << ": " << lines[i];
      EXPECT_NE(lines[i].find("\"committed\""), std::string::npos) << lines[i];
    } else {
      ++iterations;
    }
  }
  EXPECT_EQ(attempts, result.steps);
  int expected = 0;
  for (std::size_t r = 0; r < result.record.rows(); ++r) expected += static_cast<int>(result.record.value(r, "open_close_iterations"));
  EXPECT_EQ(iterations, expected);
}

}  // namespace
}  // namespace hfdda
