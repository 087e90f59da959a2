#include "simulation/run.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

  void write(const Model& model, int step, double time_s, bool final) {
    const dda::BlockSystem& system = *model.system;
    const auto rows = joint_rows(system, model.flow.get());
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

/// State of the flow network (zeros without one). Extent: open ends of fluid-filled
/// joints, relative to the (first) injection point.
const std::vector<std::string> kNetworkColumns{
    "wetted_joints",  "injection_pressure_Pa", "injection_aperture_m", "open_xmin_m",    "open_xmax_m",
    "open_ymin_m",    "open_ymax_m",           "mass_injected_kg",     "mass_stored_kg", "mass_leaked_kg",
    "mass_balance_error"};

std::vector<std::string> history_columns(const Model& model) {
  std::vector<std::string> columns{
      "step", "time_s", "open_close_iterations", "alm_iterations", "alm_stalls", "alm_stall_mismatch", "alm_displacement_change", "factorizations", "bonds_broken",
      "state_changes", "vertex_vertex_activations", "active_vertex_vertex", "open_joint_ends",
      "max_aperture_m", "max_penetration_m", "step_wall_s", "elapsed_wall_s",
      "step_cuts", "fractures_wetted", "flow_newton_iterations", "flow_newton_restarts", "flow_max_residual"};
  columns.insert(columns.end(), kNetworkColumns.begin(), kNetworkColumns.end());
  for (const auto& probe : model.config.probes) {
    columns.push_back("probe_" + probe.name + "_pressure_Pa");
    columns.push_back("probe_" + probe.name + "_aperture_m");
  }
  return columns;
}

std::vector<double> history_row(const Model& model, int step, double time_s, const StepStatistics& st,
                                double elapsed) {
  const dda::BlockSystem& system = *model.system;
  int open_ends = 0;
  double max_aperture = 0.0;
  for (std::size_t j = 0; j < system.mesh().joints.size(); ++j)
    for (int end = 0; end < 2; ++end) {
      open_ends += system.contacts()[2 * j + end].state == dda::ContactState::open;
      max_aperture = std::max(max_aperture, system.joint_gap(static_cast<int>(j), end));
    }
  std::vector<double> row{double(step), time_s, double(st.open_close_iterations), double(st.alm_iterations),
                          double(st.alm_stalls), st.max_alm_stall_mismatch, st.max_alm_displacement_change,
                          double(st.factorizations), double(st.bonds_broken), double(st.state_changes),
                          double(st.vertex_vertex_activations), double(st.active_vertex_vertex), double(open_ends),
                          max_aperture, st.max_penetration_m, st.seconds_total, elapsed,
                          double(st.step_cuts), double(st.fractures_wetted),
                          double(st.flow_newton_iterations), double(st.flow_newton_restarts),
                          st.max_flow_residual};
  const fluid::FlowNetwork* flow = model.flow.get();
  if (!flow) {
    row.resize(row.size() + kNetworkColumns.size(), 0.0);
  } else {
    const auto& m = system.mesh();
    const int inlet = model.injection_points.empty() ? -1 : model.injection_points.front();
    const Vec2 origin = inlet >= 0 ? m.points[inlet] : Vec2(0, 0);
    int wetted = 0;
    double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
    for (int j = 0; j < flow->n_fractures(); ++j) {
      if (!flow->wetted(j)) continue;
      ++wetted;
      for (int end = 0; end < 2; ++end) {
        if (system.contacts()[2 * j + end].state != dda::ContactState::open) continue;
        const Vec2 r = m.points[end == 0 ? m.joints[j].point_p : m.joints[j].point_q] - origin;
        xmin = std::min(xmin, r.x()), xmax = std::max(xmax, r.x());
        ymin = std::min(ymin, r.y()), ymax = std::max(ymax, r.y());
      }
    }
    row.insert(row.end(), {double(wetted), inlet >= 0 ? flow->pressure(inlet) : 0.0,
                           inlet >= 0 ? flow->aperture_at_point(inlet) : 0.0, xmin, xmax, ymin, ymax,
                           flow->injected_mass(), flow->stored_mass(), flow->leaked_mass(),
                           flow->mass_balance_error()});
  }
  for (std::size_t i = 0; i < model.config.probes.size(); ++i) {
    const int point = model.probe_points[i];
    row.push_back(flow ? flow->pressure(point) : 0.0);
    row.push_back(flow ? flow->aperture_at_point(point) : 0.0);
  }
  return row;
}

}  // namespace

void write_summary(const Model& model, const RunOptions& options, const RunResult& r) {
  const auto& system = *model.system;
  nlohmann::json j;
  j["status"] = r.completed ? "completed" : "failed";
  j["message"] = r.message;
  j["case_file"] = model.config.file;
  j["title"] = model.config.title;
  j["steps"] = r.steps;
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
                 {"alm_stalls", r.totals.alm_stalls},
                 {"max_alm_stall_mismatch", r.totals.max_alm_stall_mismatch},
                 {"factorizations", r.totals.factorizations},
                 {"bonds_broken", r.totals.bonds_broken},
                 {"vertex_vertex_activations", r.totals.vertex_vertex_activations},
                 {"max_active_vertex_vertex", r.totals.max_active_vertex_vertex},
                 {"seconds_assembly", r.totals.seconds_assembly},
                 {"seconds_factorization", r.totals.seconds_factorization},
                 {"seconds_solve", r.totals.seconds_solve}};
  io::write_file_atomically(options.output_dir + "/summary.json", j.dump(2) + "\n");
}

RunResult run(Model& model, const RunOptions& options) {
  const auto start = Clock::now();
  const auto& time = model.config.time;
  std::filesystem::create_directories(options.output_dir);
  io::HistoryCsv history(options.output_dir + "/history.csv", history_columns(model));
  OutputSeries outputs(options.output_dir, options.write_vtu && model.config.output.vtu);
  const bool terminal = !options.quiet && isatty(fileno(stderr));

  RunResult result;
  const int n_steps = std::max(1, static_cast<int>(std::llround(time.end_time_s / time.dt_s)));
  outputs.write(model, 0, 0.0, false);
  for (int step = 1; step <= n_steps; ++step) {
    const double t = step * time.dt_s;
    StepStatistics st;
    try {
      st = model.step->advance(time.dt_s, model.config.numerics.max_step_cuts);
    } catch (const ConvergenceError& e) {
      char where[96];
      std::snprintf(where, sizeof where, "step %d (t = %g s to %g s): ", step, t - time.dt_s, t);
      result.message = where + std::string(e.what());
      break;
    }
    result.steps = step;
    result.totals.accumulate(st);
    result.time_s = t;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    history.append(history_row(model, step, t, st, elapsed));
    const int every = model.config.output.every_steps;
    if (step == n_steps || (every > 0 && step % every == 0)) outputs.write(model, step, t, step == n_steps);
    if (terminal)
      std::fprintf(stderr, "\rstep %d/%d  t = %.4g s  open-close %d  ALM %d  elapsed %.1f s   ", step, n_steps, t,
                   st.open_close_iterations, st.alm_iterations, elapsed);
    else if (!options.quiet)
      std::fprintf(stderr, "step %d/%d t=%.6g s open-close=%d alm=%d elapsed=%.3f s\n", step, n_steps, t,
                   st.open_close_iterations, st.alm_iterations, elapsed);
  }
  if (terminal) std::fprintf(stderr, "\n");
  result.completed = result.message.empty();
  if (!result.completed) outputs.write(model, result.steps, result.time_s, true);
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  write_summary(model, options, result);
  return result;
}

}  // namespace hfdda::simulation
