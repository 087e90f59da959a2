// Checkpoints and restarts (simulation/checkpoint.hpp): a run stopped after some step
// and continued from its checkpoint in a freshly built model gives the same history
// rows, block state, flow state and joint table, bit for bit, as a run never stopped;
// for a fluid-driven fracture (KGD, joints wetted after the checkpoint) and a load
// ramp (a jump and the bond failures after the checkpoint); also when the stop is asked
// inside a step, which is then abandoned.

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "core/binary_io.hpp"
#include "io/case_config.hpp"
#include "simulation/checkpoint.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"

namespace hfdda::simulation {
namespace {

namespace fs = std::filesystem;

fs::path test_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("hfdda_checkpoint_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

void expect_same_records(const RunRecord& a, const RunRecord& b) {
  ASSERT_EQ(a.columns(), b.columns());
  ASSERT_EQ(a.rows(), b.rows());
  for (std::size_t r = 0; r < a.rows(); ++r)
    for (std::size_t c = 0; c < a.columns().size(); ++c) {
      const std::string& name = a.columns()[c];
      if (name == "step_wall_s" || name == "elapsed_wall_s") continue;
      EXPECT_TRUE(same_bits(a.row(r)[c], b.row(r)[c]))
          << "row " << r << " column " << name << ": " << a.row(r)[c] << " vs " << b.row(r)[c];
    }
}

void expect_same_state(const Model& a, const Model& b) {
  const dda::BlockSystem& sa = *a.system;
  const dda::BlockSystem& sb = *b.system;
  for (int block = 0; block < sa.n_blocks(); ++block) {
    for (int k = 0; k < sa.n_corners(block); ++k) {
      EXPECT_TRUE(same_bits(sa.corner(block, k).x(), sb.corner(block, k).x())) << "block " << block;
      EXPECT_TRUE(same_bits(sa.corner(block, k).y(), sb.corner(block, k).y())) << "block " << block;
    }
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(same_bits(sa.stress(block)[i], sb.stress(block)[i])) << "block " << block;
  }
  for (std::size_t c = 0; c < sa.contacts().size(); ++c) {
    EXPECT_EQ(sa.contacts()[c].state, sb.contacts()[c].state) << "contact " << c;
    EXPECT_EQ(sa.contacts()[c].bonded, sb.contacts()[c].bonded) << "contact " << c;
    EXPECT_TRUE(same_bits(sa.contacts()[c].springs[0].normal_multiplier_N, sb.contacts()[c].springs[0].normal_multiplier_N));
  }
  ASSERT_EQ(a.flow != nullptr, b.flow != nullptr);
  if (!a.flow) return;
  for (int p = 0; p < a.flow->n_points(); ++p) EXPECT_TRUE(same_bits(a.flow->pressure(p), b.flow->pressure(p)));
  for (int f = 0; f < a.flow->n_fractures(); ++f) {
    EXPECT_EQ(a.flow->wetted(f), b.flow->wetted(f));
    if (a.flow->wetted(f))
      for (int end = 0; end < 2; ++end) EXPECT_TRUE(same_bits(a.flow->aperture(f, end), b.flow->aperture(f, end)));
  }
  EXPECT_TRUE(same_bits(a.flow->stored_mass(), b.flow->stored_mass()));
  EXPECT_TRUE(same_bits(a.flow->injected_mass(), b.flow->injected_mass()));
  EXPECT_TRUE(same_bits(a.flow->leaked_mass(), b.flow->leaked_mass()));
  EXPECT_TRUE(same_bits(a.flow->time(), b.flow->time()));
}

/// Runs the case through (the reference), and again with the stop that `stop` sets up,
/// which must end the run after `steps` steps with a checkpoint (`check` then looks at
/// the stopped run and its directory); the run continued from that checkpoint in a fresh
/// model must end as the reference did, bit for bit.
void expect_stopped_run_continues(const io::CaseConfig& config, const std::string& name, int steps,
                                  const std::function<void(RunOptions&)>& stop,
                                  const std::function<void(const RunResult&, const fs::path&)>& check = {}) {
  Model full = build_model(config);
  const fs::path full_dir = test_dir(name + "_full");
  const RunResult reference = run(full, {full_dir.string(), true, false});
  ASSERT_TRUE(reference.completed) << reference.message;
  ASSERT_GT(reference.steps, steps + 1);

  const fs::path dir = test_dir(name + "_restarted");
  Model first = build_model(config);
  RunOptions stopping{dir.string(), true, false};
  stop(stopping);
  const RunResult stopped = run(first, stopping);
  ASSERT_TRUE(stopped.interrupted) << stopped.message;
  EXPECT_FALSE(stopped.completed);
  EXPECT_EQ(stopped.steps, steps);
  ASSERT_TRUE(fs::exists(checkpoint_path(dir.string())));
  if (check) check(stopped, dir);

  Model second = build_model(config);
  RunOptions restarting{dir.string(), true, false};
  restarting.restart = true;
  const RunResult continued = run(second, restarting);
  ASSERT_TRUE(continued.completed) << continued.message;
  EXPECT_EQ(continued.steps, reference.steps);
  EXPECT_TRUE(same_bits(continued.time_s, reference.time_s));
  EXPECT_EQ(continued.totals.factorizations, reference.totals.factorizations);
  EXPECT_EQ(continued.totals.alm_iterations, reference.totals.alm_iterations);
  expect_same_records(reference.record, continued.record);
  expect_same_state(full, second);
  EXPECT_EQ(file_text(full_dir / "joints" / "joints_final.csv"), file_text(dir / "joints" / "joints_final.csv"));
  fs::remove_all(full_dir);
  fs::remove_all(dir);
}

/// Stopped after `stop_after` steps (asked after each step) and continued.
void expect_restart_matches(const io::CaseConfig& config, const std::string& name, int stop_after) {
  int asked = 0;
  expect_stopped_run_continues(config, name, stop_after, [&](RunOptions& o) {
    o.stop_requested = [&asked, stop_after] { return ++asked == stop_after; };
  });
}

/// A stop asked inside step 4 at the `ask`-th time it is asked: the step is abandoned,
/// rolled back to its start, and the checkpoint is that of step 3.
void expect_abandoned_step_restart_matches(const io::CaseConfig& config, const std::string& name, int ask) {
  int steps_done = 0, asked_in_step_4 = 0;
  expect_stopped_run_continues(
      config, name, 3,
      [&](RunOptions& o) {
        o.trace_iterations = true;
        o.after_step = [&steps_done](const Model&, int step, double) { steps_done = step; };
        o.abandon_step_requested = [&, ask] { return steps_done == 3 && ++asked_in_step_4 == ask; };
      },
      [&](const RunResult& stopped, const fs::path& dir) {
        EXPECT_EQ(asked_in_step_4, ask) << "the stop was asked inside step 4";
        EXPECT_NE(stopped.message.find("abandoned on request"), std::string::npos) << stopped.message;
        EXPECT_NE(file_text(dir / "iterations.csv").find("abandoned on request"), std::string::npos)
            << "the trace ends the abandoned attempt with the reason";
      });
}

TEST(Checkpoint, KgdContinuesBitForBit) {
  const io::CaseConfig config =
      io::load_case_file(std::string(HFDDA_TEST_DATA_DIR) + "/cases/restart_kgd.yaml");
  expect_restart_matches(config, "kgd_after_wetting", 3);  // joints were wetted in step 3
  expect_restart_matches(config, "kgd_before_wetting", 5);
}

TEST(Checkpoint, StepAbandonedMidwayRestartsBitForBit) {
  const io::CaseConfig config =
      io::load_case_file(std::string(HFDDA_TEST_DATA_DIR) + "/cases/restart_kgd.yaml");
  // How often step 4 asks (before each open-close and each later contact iteration).
  Model counting = build_model(config);
  RunOptions asking{"", true, false};
  asking.write_files = false;
  int steps_done = 0, asks = 0;
  asking.after_step = [&](const Model&, int step, double) { steps_done = step; };
  asking.abandon_step_requested = [&] { asks += steps_done == 3; return false; };
  const RunResult counted = run(counting, asking);
  ASSERT_TRUE(counted.completed);
  ASSERT_GE(asks, 4) << "step 4 must iterate for the late stop to follow contact changes";
  // The step asks before each open-close round and each later contact iteration (as
  // many as its contact iterations), and the flow solves before each Newton iteration.
  EXPECT_GT(asks, counted.record.value(3, "alm_iterations")) << "the flow solve does not ask";
  expect_abandoned_step_restart_matches(config, "abandoned_early", 2);    // in the first contact iterations
  expect_abandoned_step_restart_matches(config, "abandoned_late", asks);  // its last open-close round
}

/// A 12 m x 12 m square of 1 m cells pulled apart across a breakable line (T0 = 1e5 Pa):
/// the ramp jumps over its linear stretch and the line breaks at its strength.
const char* kRamp = R"(title: ramp
domain: {outer: {xmin: -6, xmax: 6, ymin: -6, ymax: 6}}
mesh: {type: structured, cell_size: 1, split: two}
joints: {tensile_strength: 1.0e5, breakable: false}
fractures:
  - {name: line, from: [-6, 0], to: [6, 0], breakable: true}
output: {every_steps: 0, vtu: false}
load_ramp:
  syy: 1.0
  sides: [top, bottom]
  increment: 1.0e3
  maximum: 1.2e5
)";

TEST(Checkpoint, LoadRampContinuesBitForBit) {
  const io::CaseConfig config = io::load_case_text(kRamp, "ramp.yaml");
  expect_restart_matches(config, "ramp_before_jump", 2);
  expect_restart_matches(config, "ramp_after_jump", 4);
  expect_restart_matches(config, "ramp_after_failures", 6);
}

TEST(Checkpoint, RefusesAnotherCaseAndDamagedFiles) {
  const io::CaseConfig config = io::load_case_text(kRamp, "ramp.yaml");
  const fs::path dir = test_dir("refusals");
  Model model = build_model(config);
  RunOptions stopping{dir.string(), true, false};
  stopping.stop_requested = [] { return true; };
  ASSERT_TRUE(run(model, stopping).interrupted);
  const std::string path = checkpoint_path(dir.string());

  std::string other_text = kRamp;
  other_text.replace(other_text.find("cell_size: 1"), 12, "cell_size: 2");
  Model other = build_model(io::load_case_text(other_text, "ramp.yaml"));
  EXPECT_THROW(read_checkpoint(path, other), std::runtime_error);

  const std::string bytes = file_text(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  Model fresh = build_model(config);
  try {
    read_checkpoint(path, fresh);
    ADD_FAILURE() << "a truncated checkpoint was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("end early"), std::string::npos) << e.what();
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << "not a checkpoint";
  EXPECT_THROW(read_checkpoint(path, fresh), std::runtime_error);
  fs::remove_all(dir);
}

TEST(BinaryIo, RoundTripsDoublesExactly) {
  BinaryWriter out;
  out.put(0.1);
  out.put(-0.0);
  out.put_vector(std::vector<double>{1e-300, 3.0});
  Eigen::VectorXd v(3);
  v << 1.0 / 3.0, 2.0, -7.5;
  out.put_matrix(v);
  out.put_string("x");
  BinaryReader in(out.bytes());
  EXPECT_TRUE(same_bits(in.get<double>(), 0.1));
  EXPECT_TRUE(same_bits(in.get<double>(), -0.0));
  std::vector<double> w;
  in.get_vector(w);
  EXPECT_EQ(w, (std::vector<double>{1e-300, 3.0}));
  Eigen::VectorXd u;
  in.get_matrix(u);
  EXPECT_EQ(u, v);
  EXPECT_EQ(in.get_string(), "x");
  EXPECT_EQ(in.remaining(), 0u);
  EXPECT_THROW(in.get<int>(), std::runtime_error);
}

}  // namespace
}  // namespace hfdda::simulation
