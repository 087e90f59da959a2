#include "simulation/run.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "io/output.hpp"
#include "simulation/snapshots.hpp"

namespace hfdda::simulation {

namespace {

using Clock = std::chrono::steady_clock;

std::string step_tag(int step) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%06d", step);
  return buffer;
}

struct OutputSeries {
  std::string dir;
  bool vtu;
  io::PvdSeries blocks_pvd, joints_pvd;
  OutputSeries(const std::string& d, bool write_vtu)
      : dir(d), vtu(write_vtu), blocks_pvd(d + "/blocks.pvd"), joints_pvd(d + "/joints.pvd") {}

  void write(const dda::BlockSystem& system, int step, double time_s, bool final) {
    const auto rows = joint_rows(system);
    io::write_joints_csv(dir + "/joints/joints_" + step_tag(step) + ".csv", rows);
    if (final) io::write_joints_csv(dir + "/joints/joints_final.csv", rows);
    if (!vtu) return;
    const std::string blocks = "vtu/blocks_" + step_tag(step) + ".vtu";
    const std::string joints = "vtu/joints_" + step_tag(step) + ".vtu";
    io::write_blocks_vtu(dir + "/" + blocks, block_frame(system));
    io::write_joints_vtu(dir + "/" + joints, rows);
    blocks_pvd.add(time_s, blocks);
    joints_pvd.add(time_s, joints);
  }
};

const std::vector<std::string> kHistoryColumns{
    "step", "time_s", "open_close_iterations", "alm_iterations", "factorizations", "bonds_broken",
    "state_changes", "vertex_vertex_activations", "active_vertex_vertex", "open_joint_ends",
    "max_aperture_m", "max_penetration_m", "step_wall_s", "elapsed_wall_s"};

std::vector<double> history_row(const dda::BlockSystem& system, int step, double time_s,
                                 const dda::StepStatistics& st, double elapsed) {
  int open_ends = 0;
  double max_aperture = 0.0;
  for (std::size_t j = 0; j < system.mesh().joints.size(); ++j)
    for (int end = 0; end < 2; ++end) {
      open_ends += system.contacts()[2 * j + end].state == dda::ContactState::open;
      max_aperture = std::max(max_aperture, system.joint_gap(static_cast<int>(j), end));
    }
  return {double(step), time_s, double(st.open_close_iterations), double(st.alm_iterations),
          double(st.factorizations), double(st.bonds_broken), double(st.state_changes),
          double(st.vertex_vertex_activations), double(st.active_vertex_vertex), double(open_ends),
          max_aperture, st.max_penetration_m, st.seconds_total, elapsed};
}

void write_summary(const Model& model, const RunOptions& options, const RunResult& r) {
  const auto& system = *model.system;
  nlohmann::json j;
  j["status"] = r.completed ? "completed" : "failed";
  j["message"] = r.message;
  j["case_file"] = model.config.file;
  j["title"] = model.config.title;
  j["steps"] = r.totals.steps;
  j["time_s"] = r.time_s;
  j["end_time_s"] = model.config.time.end_time_s;
  j["dt_s"] = model.config.time.dt_s;
  j["wall_time_s"] = r.wall_seconds;
  j["mesh"] = {{"blocks", system.n_blocks()},
               {"joints", system.mesh().joints.size()},
               {"points", system.mesh().points.size()},
               {"unknowns", 6 * system.n_blocks()},
               {"build_ms", model.mesh_seconds_ms}};
  j["solver"] = {{"contact_method", system.settings().augmented_lagrangian ? "augmented_lagrangian" : "penalty"},
                 {"open_close_iterations", r.totals.open_close_iterations},
                 {"alm_iterations", r.totals.alm_iterations},
                 {"factorizations", r.totals.factorizations},
                 {"bonds_broken", r.totals.bonds_broken},
                 {"vertex_vertex_activations", r.totals.vertex_vertex_activations},
                 {"max_active_vertex_vertex", r.totals.max_active_vertex_vertex},
                 {"seconds_assembly", r.totals.seconds_assembly},
                 {"seconds_factorization", r.totals.seconds_factorization},
                 {"seconds_solve", r.totals.seconds_solve}};
  io::write_file_atomically(options.output_dir + "/summary.json", j.dump(2) + "\n");
}

}  // namespace

RunResult run(Model& model, const RunOptions& options) {
  const auto start = Clock::now();
  dda::BlockSystem& system = *model.system;
  const auto& time = model.config.time;
  std::filesystem::create_directories(options.output_dir);
  io::HistoryCsv history(options.output_dir + "/history.csv", kHistoryColumns);
  OutputSeries outputs(options.output_dir, options.write_vtu && model.config.output.vtu);
  const bool terminal = !options.quiet && isatty(fileno(stderr));

  RunResult result;
  const int n_steps = std::max(1, static_cast<int>(std::llround(time.end_time_s / time.dt_s)));
  outputs.write(system, 0, 0.0, false);
  for (int step = 1; step <= n_steps; ++step) {
    const double t = step * time.dt_s;
    dda::StepStatistics st;
    try {
      st = system.step(time.dt_s);
    } catch (const ConvergenceError& e) {
      char where[96];
      std::snprintf(where, sizeof where, "step %d (t = %g s to %g s): ", step, t - time.dt_s, t);
      result.message = where + std::string(e.what());
      break;
    }
    auto& tot = result.totals;
    tot.steps = step;
    tot.open_close_iterations += st.open_close_iterations;
    tot.alm_iterations += st.alm_iterations;
    tot.factorizations += st.factorizations;
    tot.bonds_broken += st.bonds_broken;
    tot.vertex_vertex_activations += st.vertex_vertex_activations;
    tot.max_active_vertex_vertex = std::max(tot.max_active_vertex_vertex, st.active_vertex_vertex);
    tot.seconds_assembly += st.seconds_assembly;
    tot.seconds_factorization += st.seconds_factorization;
    tot.seconds_solve += st.seconds_solve;
    result.time_s = t;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    history.append(history_row(system, step, t, st, elapsed));
    const int every = model.config.output.every_steps;
    if (step == n_steps || (every > 0 && step % every == 0)) outputs.write(system, step, t, step == n_steps);
    if (terminal)
      std::fprintf(stderr, "\rstep %d/%d  t = %.4g s  open-close %d  ALM %d  elapsed %.1f s   ", step, n_steps, t,
                   st.open_close_iterations, st.alm_iterations, elapsed);
    else if (!options.quiet)
      std::fprintf(stderr, "step %d/%d t=%.6g s open-close=%d alm=%d elapsed=%.3f s\n", step, n_steps, t,
                   st.open_close_iterations, st.alm_iterations, elapsed);
  }
  if (terminal) std::fprintf(stderr, "\n");
  result.completed = result.message.empty();
  if (!result.completed) outputs.write(system, result.totals.steps, result.time_s, true);
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  write_summary(model, options, result);
  return result;
}

}  // namespace hfdda::simulation
