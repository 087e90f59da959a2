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
#include "io/case_config.hpp"
#include "mesh/mesh.hpp"
#include "simulation/model.hpp"

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


// Low-rank changes of K against a new factorisation (docs/design_notes.md section 26).
// A contact-state change adds or removes a few penalty springs k e e^T (e: 12 entries
// on two blocks): locked -> sliding removes a contact's two shear springs (rank 2), a
// joint opening removes 2 x (normal + shear) springs at each of its ends (rank 8).
// range(0): 0 the KGD case at dx = 0.5 m (verification/kgd/base.yaml, 5,188 blocks,
// K after 4 steps), 1 the 64-cell square of BM_DdaSteadyStep (16,384 blocks, after one
// step). Per round, in ms: (a) one supernodal numeric factorisation; (b) the copy and
// conversion of the factor to simplicial LDL' (the first downdate of rank 2 less a later
// one); (c) cholmod_updown of rank r = 2, 8, 32, downdate and update; (d) one solve and
// a 64-column solve with the supernodal and the simplicial factor, and r-column
// supernodal solves (the cost of the Woodbury identity's K^-1 C). resid_*: |K x - b| / |b|
// after a net downdate of rank 32 (the 8 nearest locked contacts opened), with the
// modified factor (updown, woodbury) and with a new factorisation of the same K (fresh).
// e_woodbury*: modify() with the Woodbury identity for rank r (W = K0^-1 C and M);
// d_solve*_woodbury32: solves with a rank-32 Woodbury correction.
struct LowRankCase {
  std::unique_ptr<DdaCase> square;
  std::unique_ptr<simulation::Model> kgd;
  const dda::BlockSystem& system() const { return kgd ? *kgd->system : *square->system; }
};

LowRankCase make_low_rank_case(int which) {
  LowRankCase c;
  if (which == 0) {
    const io::CaseConfig config = io::load_case_file(std::string(HFDDA_SOURCE_DIR) + "/verification/kgd/base.yaml");
    c.kgd = std::make_unique<simulation::Model>(simulation::build_model(config));
    for (int s = 0; s < 4; ++s) c.kgd->step->advance(config.time.dt_s, config.numerics.max_step_cuts);
  } else {
    c.square = make_system(64);
    c.square->step(1.0);
  }
  return c;
}

/// The spring terms of the locked joint contacts nearest the origin (where the crack is),
/// four per contact: normal and shear of its two springs, weight 1/2 each.
std::vector<dda::SpringTerm> nearest_locked_springs(const dda::BlockSystem& system, int count) {
  std::vector<std::pair<double, int>> by_distance;
  for (int ci = 0; ci < static_cast<int>(system.contacts().size()); ++ci) {
    const dda::Contact& c = system.contacts()[ci];
    if (c.joint >= 0 && c.state == dda::ContactState::locked)
      by_distance.emplace_back(system.mesh().points[c.point].norm(), ci);
  }
  std::sort(by_distance.begin(), by_distance.end());
  const double kn = system.settings().normal_stiffness_N_m, ks = system.settings().shear_stiffness_N_m;
  std::vector<dda::SpringTerm> terms;
  for (const auto& [distance, ci] : by_distance) {
    for (const auto& s : system.contacts()[ci].springs) {
      terms.push_back({s.vertex_block, s.edge_block, s.gap_vertex, s.gap_edge, 0.5 * kn});
      terms.push_back({s.vertex_block, s.edge_block, s.shear_vertex, s.shear_edge, 0.5 * ks});
    }
    if (static_cast<int>(terms.size()) >= count) break;
  }
  terms.resize(count);
  return terms;
}

double relative_residual(const dda::BlockSparseMatrix& k, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (k.multiply(x) - b).norm() / b.norm();
}

void BM_LowRankK(benchmark::State& state) {
  const bench::AdjacentCalibration calibration(state);
  const LowRankCase low_rank = make_low_rank_case(static_cast<int>(state.range(0)));
  const dda::BlockSystem& system = low_rank.system();
  const dda::BlockSparseMatrix& k = system.stiffness();
  const std::vector<dda::SpringTerm> springs = nearest_locked_springs(system, 32);
  auto first = [&](int r) { return std::vector<dda::SpringTerm>(springs.begin(), springs.begin() + r); };
  auto removed = [&](int r) {
    std::vector<dda::SpringTerm> terms = first(r);
    for (auto& t : terms) t.stiffness = -t.stiffness;
    return terms;
  };
  const int n = 6 * system.n_blocks();
  const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
  const Eigen::MatrixXd b64 = Eigen::MatrixXd::Random(n, 64);
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::time_point start) { return 1e3 * std::chrono::duration<double>(Clock::now() - start).count(); };
  auto timed = [&](const char* name, auto&& work) {
    const auto start = Clock::now();
    work();
    state.counters[name] += ms(start);
  };
  dda::SpdSolver solver;
  solver.factorize(k.matrix());  // symbolic analysis outside the rounds
  for (auto _ : state) {
    timed("a_factorize_ms", [&] { solver.factorize(k.matrix()); });
    timed("d_solve1_super_ms", [&] { benchmark::DoNotOptimize(solver.solve(b)); });
    timed("d_solve64_super_ms", [&] { benchmark::DoNotOptimize(solver.solve(b64)); });
    timed("d_solve8_super_ms", [&] { benchmark::DoNotOptimize(solver.solve(Eigen::MatrixXd(b64.leftCols(8)))); });
    timed("d_solve32_super_ms", [&] { benchmark::DoNotOptimize(solver.solve(Eigen::MatrixXd(b64.leftCols(32)))); });
    double first_downdate_ms = 0.0;
    {
      const auto start = Clock::now();
      solver.modify(removed(2), dda::LowRankMethod::updown);
      first_downdate_ms = ms(start);
    }
    solver.modify(first(2), dda::LowRankMethod::updown);
    for (int r : {2, 8, 32}) {
      const std::string rank = std::to_string(r);
      const auto start = Clock::now();
      solver.modify(removed(r), dda::LowRankMethod::updown);
      const double downdate_ms = ms(start);
      state.counters["c_downdate" + rank + "_ms"] += downdate_ms;
      if (r == 2) state.counters["b_convert_ms"] += first_downdate_ms - downdate_ms;
      timed(("c_update" + rank + "_ms").c_str(), [&] { solver.modify(first(r), dda::LowRankMethod::updown); });
    }
    timed("d_solve1_simplicial_ms", [&] { benchmark::DoNotOptimize(solver.solve(b)); });
    timed("d_solve64_simplicial_ms", [&] { benchmark::DoNotOptimize(solver.solve(b64)); });
    state.counters["resid_restored"] += relative_residual(k, solver.solve(b), b);
    // Woodbury: the supernodal factor kept, W = K0^-1 C by one r-column solve.
    for (int r : {2, 8, 32}) {
      solver.factorize(k.matrix());
      timed(("e_woodbury" + std::to_string(r) + "_ms").c_str(), [&] { solver.modify(removed(r)); });
    }
    timed("d_solve1_woodbury32_ms", [&] { benchmark::DoNotOptimize(solver.solve(b)); });
    timed("d_solve64_woodbury32_ms", [&] { benchmark::DoNotOptimize(solver.solve(b64)); });
  }
  for (const char* name : {"a_factorize_ms", "b_convert_ms", "c_downdate2_ms", "c_update2_ms", "c_downdate8_ms",
                           "c_update8_ms", "c_downdate32_ms", "c_update32_ms", "d_solve1_super_ms",
                           "d_solve64_super_ms", "d_solve8_super_ms", "d_solve32_super_ms", "d_solve1_simplicial_ms",
                           "d_solve64_simplicial_ms", "resid_restored", "e_woodbury2_ms", "e_woodbury8_ms",
                           "e_woodbury32_ms", "d_solve1_woodbury32_ms", "d_solve64_woodbury32_ms"})
    state.counters[name] = benchmark::Counter(state.counters[name], benchmark::Counter::kAvgIterations);

  // Accuracy of a net downdate against a new factorisation of the same matrix.
  dda::BlockSparseMatrix opened = k;
  for (const dda::SpringTerm& t : springs) {
    opened.add_diagonal(t.block_a, -t.stiffness * t.row_a.transpose() * t.row_a);
    opened.add_diagonal(t.block_b, -t.stiffness * t.row_b.transpose() * t.row_b);
    opened.add_coupling(opened.coupling_slot(t.block_a, t.block_b), t.block_a, t.block_b,
                        -t.stiffness * t.row_a.transpose() * t.row_b);
  }
  for (auto method : {dda::LowRankMethod::updown, dda::LowRankMethod::woodbury}) {
    solver.factorize(k.matrix());
    solver.modify(removed(32), method);
    state.counters[method == dda::LowRankMethod::updown ? "resid_updown" : "resid_woodbury"] =
        relative_residual(opened, solver.solve(b), b);
  }
  dda::SpdSolver fresh;
  fresh.factorize(opened.matrix());
  state.counters["resid_fresh"] = relative_residual(opened, fresh.solve(b), b);
  state.counters["blocks"] = system.n_blocks();
  state.counters["nnz_K_lower"] = static_cast<double>(k.matrix().nonZeros());
}

// Cells per side n gives 4 n^2 blocks: 16 -> 1024, 32 -> 4096, 64 -> 16384.
BENCHMARK(BM_DdaFirstStep)->ArgName("cells")->Arg(16)->Arg(32)->Arg(64)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_DdaSteadyStep)->ArgNames({"cells", "threads"})->ArgsProduct({{16, 32, 64}, {1, 2}})
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_FactorizeK)->ArgNames({"cells", "threads"})->ArgsProduct({{16, 32, 64}, {1, 2}})
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_LowRankK)->ArgName("square16k")->DenseRange(0, 1)->Iterations(5)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  hfdda::bench::initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
