// Time of one DDA step (assembly, CHOLMOD factorisation, ALM solves, open-close checks)
// on triangulated meshes of about 1k, 4k and 16k blocks, and of one factorisation of K
// alone (the floor a step is compared against). Target: a 16k-block step < 1 s. The
// steady step and the factorisation run at 1 and 2 threads (the `threads` argument sets
// the thread policy for that benchmark); CPU time is the whole process's.
//
// Problem: a square of 4-triangle cells under 5 MPa vertical compression with a
// pressurised, initially open crack across its middle third (a Griffith-like load),
// all joints bonded, ALM contacts, fixed corners.

#include "bench_support.hpp"

#include <chrono>
#include <cmath>
#include <memory>

#include "coupling/coupled_step.hpp"
#include "coupling/prescribed_pressure.hpp"
#include "dda/block_system.hpp"
#include "mesh/mesh.hpp"

namespace {

using namespace hfdda;

/// The blocks, the crack's prescribed pressure and the step that drives them.
struct DdaCase {
  std::unique_ptr<dda::BlockSystem> system;
  std::unique_ptr<coupling::PrescribedPressure> pressure;
  std::unique_ptr<coupling::CoupledStep> stepper;
  StepStatistics step(double dt_s) { return stepper->advance(dt_s, 0); }
};

std::unique_ptr<DdaCase> make_system(int cells_per_side) {
  const double h = 1.0, half = 0.5 * cells_per_side * h;
  mesh::StructuredMeshSpec spec;
  spec.outer = Rect{-half, half, -half, half};
  spec.cell_size_m = h;
  spec.split = mesh::CellSplit::four;
  mesh::Mesh m = mesh::build_structured_mesh(spec);
  mesh::JointProperties unbreakable;
  unbreakable.friction_angle_rad = 0.5236;
  unbreakable.breakable = false;
  mesh::build_topology(m, unbreakable);
  const double crack = std::floor(half / 3.0);
  std::vector<double> pressure(m.points.size(), 0.0);
  std::vector<char> wetted(m.joints.size(), 0);
  for (int j : mesh::joints_on_segment(m, {-crack, 0.0}, {crack, 0.0}, 1e-9)) {
    m.joints[j].properties.initially_open = true;
    wetted[j] = 1;
    pressure[m.joints[j].point_p] = pressure[m.joints[j].point_q] = 9.81e6;
  }
  dda::MechanicsSettings settings;  // k = 100 E for E = 25 GPa
  auto system = std::make_unique<dda::BlockSystem>(m, std::vector<dda::Material>{dda::Material{}}, settings);
  for (double sx : {-half, half})
    for (double sy : {-half, half}) system->add_fixed_point({sx, sy});
  Eigen::Matrix2d far_field;
  far_field << 0.0, 0.0, 0.0, -5e6;
  for (int e = 0; e < static_cast<int>(m.boundary_edges.size()); ++e) {
    const auto& edge = m.boundary_edges[e];
    if (std::abs(std::abs(m.points[edge.point_p].y()) - half) < 1e-9 &&
        std::abs(std::abs(m.points[edge.point_q].y()) - half) < 1e-9)
      system->add_boundary_stress(e, far_field);
  }
  auto c = std::make_unique<DdaCase>();
  c->pressure = std::make_unique<coupling::PrescribedPressure>(system->mesh(), pressure, wetted);
  c->stepper = std::make_unique<coupling::CoupledStep>(*system, std::vector<coupling::FluidLoadModel*>{c->pressure.get()});
  c->system = std::move(system);
  return c;
}

void add_counters(benchmark::State& state, const dda::BlockSystem& system, const StepStatistics& last) {
  state.counters["blocks"] = system.n_blocks();
  state.counters["unknowns"] = 6.0 * system.n_blocks();
  state.counters["nnz_K_lower"] = static_cast<double>(system.stiffness().matrix().nonZeros());
  state.counters["open_close_iterations"] = last.open_close_iterations;
  state.counters["alm_iterations"] = last.alm_iterations;
  state.counters["factorize_s"] = last.seconds_factorization / std::max(1, last.factorizations);
  state.counters["assembly_s"] = last.seconds_assembly;
  state.counters["solve_s"] = last.seconds_solve;
}

// A first step from rest (loads applied, contacts settling): the realistic cost.
void BM_DdaFirstStep(benchmark::State& state) {
  const bench::AdjacentCalibration calibration(state);
  const int n = static_cast<int>(state.range(0));
  StepStatistics last;
  std::unique_ptr<DdaCase> system;
  for (auto _ : state) {
    state.PauseTiming();
    system = make_system(n);
    state.ResumeTiming();
    last = system->step(1.0);
  }
  add_counters(state, *system->system, last);
  if (4 * n * n >= 16000) state.counters["target_s"] = 1.0;
}

// A step from an equilibrated state (one open-close iteration, one ALM solve), at
// range(1) threads. The steps before it run untimed until the state is equilibrated, so
// that every thread count and repetition times the same kind of step.
void BM_DdaSteadyStep(benchmark::State& state) {
  const bench::AdjacentCalibration calibration(state);  // before the threads: measured at the process's setting
  const bench::ScopedThreads threads(static_cast<int>(state.range(1)));
  auto system = make_system(static_cast<int>(state.range(0)));
  StepStatistics last = system->step(1.0);
  int warm_up_steps = 1;
  for (; warm_up_steps < 10 && (last.open_close_iterations > 1 || last.alm_iterations > 1); ++warm_up_steps)
    last = system->step(1.0);
  state.counters["warm_up_steps"] = warm_up_steps;
  const auto cpu0 = bench::ProcessCpu::now();
  const auto wall0 = std::chrono::steady_clock::now();
  for (auto _ : state) last = system->step(1.0);
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - wall0;
  add_counters(state, *system->system, last);
  bench::add_step_counters(state, wall.count(), bench::ProcessCpu::now() - cpu0, static_cast<int>(state.iterations()));
}

// One numeric CHOLMOD factorisation of K (symbolic analysis reused): the floor.
void BM_FactorizeK(benchmark::State& state) {
  const bench::AdjacentCalibration calibration(state);
  const bench::ScopedThreads threads(static_cast<int>(state.range(1)));
  auto system = make_system(static_cast<int>(state.range(0)));
  system->step(1.0);
  dda::SpdSolver solver;
  solver.factorize(system->system->stiffness().matrix());  // symbolic analysis outside the loop
  const auto cpu0 = bench::ProcessCpu::now();
  for (auto _ : state) solver.factorize(system->system->stiffness().matrix());
  const auto cpu = bench::ProcessCpu::now() - cpu0;
  state.counters["sys_over_user"] = cpu.user_s > 0 ? cpu.sys_s / cpu.user_s : 0.0;
  state.counters["blocks"] = system->system->n_blocks();
  state.counters["nnz_K_lower"] = static_cast<double>(system->system->stiffness().matrix().nonZeros());
}

// Cells per side n gives 4 n^2 blocks: 16 -> 1024, 32 -> 4096, 64 -> 16384.
BENCHMARK(BM_DdaFirstStep)->ArgName("cells")->Arg(16)->Arg(32)->Arg(64)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DdaSteadyStep)->ArgNames({"cells", "threads"})->ArgsProduct({{16, 32, 64}, {1, 2}})
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_FactorizeK)->ArgNames({"cells", "threads"})->ArgsProduct({{16, 32, 64}, {1, 2}})
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

}  // namespace

int main(int argc, char** argv) {
  hfdda::bench::initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
