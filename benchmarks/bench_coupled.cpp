// Time per coupled hydro-mechanical step (seed 2.4) on the chapter-3 cases: the KGD
// fracture at dx = 0.5 m (verification/kgd/base.yaml, 20 steps of 0.5 s; issue target:
// the whole run under 60 s on 2 cores) and free propagation in symmetric media
// (seed 3.4, 40 x 40 m inner domain, 2 m triangles, 30 steps of 1 s). Each benchmark
// runs the whole simulation once and reports per-step means: open-close (outer) and
// Newton (inner) iterations, factorisations of K, and the ratio of a step's time to
// one factorisation of K, the floor a step is compared against.
//
// Time per step at 1 and 2 threads: the KGD case at dx = 2, 1 and 0.5 m (2,186, 4,880
// and 5,188 blocks), steps 2 to 4 (step 1, which opens the first joints, runs untimed),
// with the process's CPU time (all threads) per step beside the wall time.
//
// Each benchmark runs once per repetition (Iterations(1)); --benchmark_repetitions is
// capped at kLongRepetitions for them, so that scripts/bench can ask the short DDA
// benchmarks for more repetitions without tripling this binary's run time.

#include "bench_support.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"

namespace {

using namespace hfdda;

const char* kSymmetricFree = R"(
title: "free propagation in symmetric media (seed 3.4), delta sigma = 0"
domain:
  outer: {xmin: -24, xmax: 24, ymin: -24, ymax: 24}
  inner: {xmin: -20, xmax: 20, ymin: -20, ymax: 20}
mesh: {type: structured, cell_size: 2.0, outer_growth: 1.0, split: four}
materials:
  - {name: rock, region: all, youngs_modulus: 25.0e9, poissons_ratio: 0.25, density: 2650}
  - {name: soft_outer, region: outer, youngs_modulus: 1.0e9, poissons_ratio: 0.0, density: 2650}
joints: {tensile_strength: 1.0e6, cohesion: 0, friction_angle: 30}
fractures:
  - {name: start, from: [-2, 0], to: [2, 0], initially_open: true, fluid_filled: true}
fluid: {density: 1000, bulk_modulus: 2.2e9, viscosity: 1.0e-3}
injections:
  - {at: [0, 0], mass_rate: 1.0}
far_field: {sxx: -5.0e6, syy: -5.0e6, sxy: 0, in_situ: true}
fixed_points: [[-24, -24], [24, -24], [24, 24], [-24, 24]]
time: {dt: 1.0, end_time: 30.0}
output: {every_steps: 0, vtu: false}
)";

void run_case(benchmark::State& state, const io::CaseConfig& config, double target_s) {
  const int steps = static_cast<int>(std::llround(config.time.end_time_s / config.time.dt_s));
  const bench::AdjacentCalibration calibration(state);
  StepStatistics total;
  int blocks = 0;
  for (auto _ : state) {
    state.PauseTiming();
    simulation::Model model = simulation::build_model(config);
    blocks = model.system->n_blocks();
    total = {};
    state.ResumeTiming();
    // The runner's step with cut-back, without its output.
    for (int s = 0; s < steps; ++s) total.accumulate(model.step->advance(config.time.dt_s, config.numerics.max_step_cuts));
  }
  state.counters["blocks"] = blocks;
  state.counters["steps"] = steps;
  state.counters["step_s"] = total.seconds_total / steps;
  state.counters["outer_per_step"] = double(total.open_close_iterations) / steps;
  state.counters["newton_per_step"] = double(total.flow_newton_iterations) / steps;
  state.counters["factorizations_per_step"] = double(total.factorizations) / steps;
  state.counters["low_rank_updates_per_step"] = double(total.low_rank_updates) / steps;
  state.counters["sensitivity_builds_per_step"] = double(total.sensitivity_builds) / steps;
  state.counters["sensitivity_corrections_per_step"] = double(total.sensitivity_corrections) / steps;
  state.counters["low_rank_terms_per_update"] = double(total.low_rank_terms) / std::max(1, total.low_rank_updates);
  const double factorize_s = total.seconds_factorization / std::max(1, total.factorizations);
  state.counters["factorize_s"] = factorize_s;
  state.counters["step_over_factorize"] = total.seconds_total / steps / factorize_s;
  state.counters["step_cuts"] = total.step_cuts;
  // Where a step's time goes: factorisations of K, S = J K^-1 B, flow solves (Newton
  // and the blocks' response to the pressures), the rest (assembly, ALM solves, states).
  state.counters["factorize_s_per_step"] = total.seconds_factorization / steps;
  state.counters["low_rank_s_per_step"] = total.seconds_low_rank / steps;
  state.counters["sensitivity_s_per_step"] = total.seconds_sensitivity / steps;
  state.counters["flow_s_per_step"] = total.seconds_flow / steps;
  if (target_s > 0) state.counters["target_s"] = target_s;
}

void BM_CoupledKgdDx05(benchmark::State& state) {
  run_case(state, io::load_case_file(std::string(HFDDA_SOURCE_DIR) + "/verification/kgd/base.yaml"), 60.0);
}

// The same run with numerics.low_rank_updates: contact-spring changes applied to the
// step's factorisation of K instead of new factorisations (docs/design_notes.md section 26).
void BM_CoupledKgdDx05LowRank(benchmark::State& state) {
  io::CaseConfig config = io::load_case_file(std::string(HFDDA_SOURCE_DIR) + "/verification/kgd/base.yaml");
  config.numerics.low_rank_updates = true;
  run_case(state, config, 60.0);
}

void BM_CoupledSymmetricFree(benchmark::State& state) {
  run_case(state, io::load_case_text(kSymmetricFree, "symmetric_free.yaml"), 0.0);
}

// The two fracture criteria on the same runs (docs/formulation.md section 5), range(0):
// 0 the seed's strength rule, 1 the energy release rate at crack tips with the toughness
// the strength stands for, K_IC = T0 sqrt(pi L / 2) (seed eq. 4.13). Target: the energy
// criterion costs at most 20 % more time per step.
io::CaseConfig with_criterion(io::CaseConfig config, bool energy, double toughness_Pa_sqrt_m) {
  if (energy) {
    config.fracture.criterion = io::FailureCriterionKind::energy_release_rate;
    config.fracture.fracture_toughness_Pa_sqrt_m = toughness_Pa_sqrt_m;
  }
  return config;
}

void BM_CriterionSymmetricFree(benchmark::State& state) {
  // T0 = 1 MPa on the 2 m joints of the structured mesh.
  const double toughness = 1.0e6 * std::sqrt(std::numbers::pi * 2.0 / 2.0);
  run_case(state, with_criterion(io::load_case_text(kSymmetricFree, "symmetric_free.yaml"), state.range(0) == 1, toughness), 0.0);
}

void BM_CriterionKgdToughness(benchmark::State& state) {
  // verification/kgd_toughness/l1_k0886.yaml: K_IC = 0.886 MPa m^0.5 on L = 1 m joints.
  const io::CaseConfig config =
      io::load_case_file(std::string(HFDDA_SOURCE_DIR) + "/verification/kgd_toughness/l1_k0886.yaml");
  run_case(state, with_criterion(config, state.range(0) == 1, 0.886e6), 0.0);
}

constexpr int kKgdWarmUpSteps = 1, kKgdTimedSteps = 3;

// range(0): dx in cm (200, 100, 50); range(1): threads.
void BM_CoupledKgdStep(benchmark::State& state) {
  const bench::AdjacentCalibration calibration(state);
  const bench::ScopedThreads threads(static_cast<int>(state.range(1)));
  const std::string file = state.range(0) == 50 ? "base" : "dx" + std::to_string(state.range(0) / 100);
  const io::CaseConfig config = io::load_case_file(std::string(HFDDA_SOURCE_DIR) + "/verification/kgd/" + file + ".yaml");
  StepStatistics total;
  bench::ProcessCpu cpu;
  double wall_s = 0.0;
  int blocks = 0, steps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    simulation::Model model = simulation::build_model(config);
    blocks = model.system->n_blocks();
    for (int s = 0; s < kKgdWarmUpSteps; ++s) model.step->advance(config.time.dt_s, config.numerics.max_step_cuts);
    state.ResumeTiming();
    const auto cpu0 = bench::ProcessCpu::now();
    const auto wall0 = std::chrono::steady_clock::now();
    for (int s = 0; s < kKgdTimedSteps; ++s) total.accumulate(model.step->advance(config.time.dt_s, config.numerics.max_step_cuts));
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    cpu += bench::ProcessCpu::now() - cpu0;
    steps += kKgdTimedSteps;
  }
  state.counters["blocks"] = blocks;
  state.counters["steps"] = kKgdTimedSteps;
  bench::add_step_counters(state, wall_s, cpu, steps);
  state.counters["outer_per_step"] = double(total.open_close_iterations) / steps;
  state.counters["factorizations_per_step"] = double(total.factorizations) / steps;
  state.counters["factorize_s"] = total.seconds_factorization / std::max(1, total.factorizations);
}

}  // namespace

int main(int argc, char** argv) {
  // Registered here, once the command line is known, to cap their repetitions.
  constexpr int kLongRepetitions = 3;
  const int repetitions = std::min(hfdda::bench::requested_repetitions(argc, argv), kLongRepetitions);
  hfdda::bench::initialize(&argc, argv);
  auto long_benchmark = [&](const char* name, void (*function)(benchmark::State&)) {
    return benchmark::RegisterBenchmark(name, function)
        ->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(repetitions)->MeasureProcessCPUTime();
  };
  long_benchmark("BM_CoupledKgdDx05", BM_CoupledKgdDx05);
  long_benchmark("BM_CoupledKgdDx05LowRank", BM_CoupledKgdDx05LowRank);
  long_benchmark("BM_CoupledSymmetricFree", BM_CoupledSymmetricFree);
  long_benchmark("BM_CriterionSymmetricFree", BM_CriterionSymmetricFree)->ArgName("energy")->DenseRange(0, 1);
  long_benchmark("BM_CriterionKgdToughness", BM_CriterionKgdToughness)->ArgName("energy")->DenseRange(0, 1);
  long_benchmark("BM_CoupledKgdStep", BM_CoupledKgdStep)
      ->ArgNames({"dx_cm", "threads"})->ArgsProduct({{200, 100, 50}, {1, 2}})->UseRealTime();
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
