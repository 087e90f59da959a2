#include "simulation/run.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "core/binary_io.hpp"
#include "core/errors.hpp"
#include "coupling/initial_opening.hpp"
#include "io/output.hpp"
#include "simulation/checkpoint.hpp"
#include "simulation/field_checks.hpp"
#include "simulation/iteration_trace.hpp"
#include "simulation/run_record.hpp"
#include "simulation/snapshots.hpp"
#include "simulation/stop_conditions.hpp"

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
    io::write_blocks_vtu(dir + "/" + blocks, block_frame(system, model.zone_of_material));
    io::write_joints_vtu(dir + "/" + joints, rows);
    blocks_pvd.add(time_s, blocks);
    joints_pvd.add(time_s, joints);
  }
};

}  // namespace

void write_summary(const Model& model, const RunOptions& options, const RunResult& r) {
  const auto& system = *model.system;
  nlohmann::json j;
  j["status"] = r.completed ? "completed" : r.interrupted ? "interrupted" : "failed";
  j["message"] = r.message;
  j["case_file"] = model.config.file;
  j["title"] = model.config.title;
  j["steps"] = r.steps;
  j["time_s"] = r.time_s;
  j["end_time_s"] = model.config.time.end_time_s;
  j["stop_reason"] = r.stop_reason;
  j["dt_s"] = model.config.time.dt_s;
  j["wall_time_s"] = r.wall_seconds;
  j["mesh"] = {{"blocks", system.n_blocks()},
               {"joints", system.mesh().joints.size()},
               {"points", system.mesh().points.size()},
               {"unknowns", 6 * system.n_blocks()},
               {"build_ms", model.mesh_seconds_ms}};
  {
    // What meshing changed of the fractures: digitised near-misses snapped, map rows cut.
    const mesh::Mesh& m = system.mesh();
    nlohmann::json snaps = nlohmann::json::array(), cuts = nlohmann::json::array();
    for (const mesh::FeatureSnap& s : m.feature_snaps)
      snaps.push_back({{"fracture", s.feature}, {"end", s.end == 0 ? "from" : "to"},
                       {"from", {s.from.x(), s.from.y()}}, {"to", {s.to.x(), s.to.y()}}, {"moved_m", s.moved_m}});
    for (const io::FractureConfig& f : model.config.fractures)
      if (f.clipped_length_m > 0.0) cuts.push_back({{"fracture", f.name}, {"removed_m", f.clipped_length_m}});
    if (m.has_feature_edges) {  // a Delaunay mesh: its fractures were made to meet
      j["mesh"]["snap_tolerance_m"] = m.feature_snap_tolerance_m;
      j["mesh"]["snapped_fracture_ends"] = snaps;
    }
    j["mesh"]["fracture_rows_cut_at_domain"] = cuts;
  }
  if (const auto& start = model.initial_opening) {
    // The steps before t = 0 that opened the `initial_opening: elastic` fractures.
    j["initial_opening"] = {{"steps", start->steps},
                            {"settled", start->settled},
                            {"stopped_on_growing_changes", start->growing},
                            {"settled_change", coupling::kSettledChange}};
    j["initial_opening"]["last_relative_change"] =
        std::isnan(start->last_relative_change) ? nlohmann::json(nullptr) : nlohmann::json(start->last_relative_change);
  }
  nlohmann::json& solver = j["solver"];
  solver["contact_method"] = system.settings().augmented_lagrangian ? "augmented_lagrangian" : "penalty";
  for (const SummaryField& f : summary_solver_fields()) {
    const double v = f.value(r.totals);
    solver[f.name] = f.integer ? nlohmann::json(static_cast<long long>(v)) : nlohmann::json(v);
  }
  if (!r.record.empty()) {
    // Fractures meeting others: each length and extent at the end and its largest value.
    nlohmann::json& fr = j["fractures"];
    for (const char* name : {"opened_length_rock_m", "opened_length_natural_m", "invaded_length_rock_m",
                             "invaded_length_natural_m", "slipped_length_rock_m", "slipped_length_natural_m",
                             "open_extent_m", "invaded_extent_m"}) {
      const std::vector<double> series = r.record.series(name);
      fr[name] = {{"final", series.back()}, {"max", *std::max_element(series.begin(), series.end())}};
    }
  }
  if (!model.parameter_draws.empty()) {
    // The keys given as distributions: what this run drew, reproducible from random_seed.
    j["random_seed"] = model.config.random_seed;
    nlohmann::json& drawn = j["sampled_parameters"];
    drawn = nlohmann::json::array();
    for (const ParameterDraw& d : model.parameter_draws) {
      nlohmann::json entry{{"key", d.key}, {"distribution", d.law}, {"per", d.per}, {"count", d.count}};
      if (d.per == "run")
        entry["value"] = d.min;
      else
        entry.update({{"min", d.min}, {"mean", d.mean}, {"max", d.max}});
      drawn.push_back(entry);
    }
  }
  if (const fluid::FlowNetwork* flow = model.flow.get()) {
    // Both mass checks: the ledger's (closes by construction) and the volume's (independent).
    double max_volume_error = 0.0;
    if (!r.record.empty())
      for (double e : r.record.series("mass_volume_error")) max_volume_error = std::max(max_volume_error, e);
    j["fluid"] = {{"mass_initial_kg", flow->initial_mass()},
                  {"mass_injected_kg", flow->injected_mass()},
                  {"mass_leaked_kg", flow->leaked_mass()},
                  {"mass_vented_kg", flow->vented_mass()},
                  {"mass_stored_kg", flow->stored_mass()},
                  {"mass_volume_kg", flow->volume_stored_mass()},
                  {"mass_balance_error", flow->mass_balance_error()},
                  {"mass_volume_error", flow->volume_balance_error()},
                  {"max_mass_volume_error", max_volume_error},
                  {"nodes", flow->n_nodes()}};
  }
  if (model.ramp) {
    const LoadRampOutcome& o = model.ramp->outcome();
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    j["load_ramp"] = {{"levels_solved", o.levels_solved},
                      {"last_level_Pa", number(o.last_level_Pa)},
                      {"predicted_first_failure_Pa", number(o.predicted_first_failure_Pa)},
                      {"jumped_to_Pa", number(o.jumped_to_Pa)},
                      {"first_failure_Pa", number(o.first_failure_Pa)},
                      {"first_failure_step", o.first_failure_step},
                      {"first_failure_at_jump", o.first_failure_at_jump},
                      {"jumps", o.jumps},
                      {"failures_at_jump", o.failures_at_jump},
                      {"first_joint_failure_Pa", number(o.first_joint_failure_Pa)},
                      {"stop_when", model.config.load_ramp->stop_when},
                      {"stop_reached", o.stop_reached},
                      {"stop_Pa", number(o.stop_Pa)},
                      {"stop_step", o.stop_step},
                      {"broken_fraction", o.broken_fraction}};
  }
  io::write_file_atomically(options.output_dir + "/summary.json", j.dump(2) + "\n");
}

RunResult run(Model& model, const RunOptions& options) {
  const auto start = Clock::now();
  const auto& time = model.config.time;
  const bool files = options.write_files;
  if (files) std::filesystem::create_directories(options.output_dir);
  const std::vector<OutputColumn> columns = history_columns(model);
  std::vector<std::string> names;
  for (const OutputColumn& c : columns) names.push_back(c.name);
  OutputSeries outputs(options.output_dir, files && options.write_vtu && model.config.output.vtu);
  const bool terminal = !options.quiet && isatty(fileno(stderr));

  RunResult result;
  result.record = RunRecord(names);
  double wall_before = 0.0;  // wall time of the parts of the run before a restart
  std::vector<std::vector<double>> kept_rows;
  if (options.restart) {
    if (!files) throw std::invalid_argument("run: a restart needs the run's files");
    RunProgress p = read_checkpoint(checkpoint_path(options.output_dir), model);
    if (p.record.columns() != names)
      throw std::runtime_error("checkpoint in '" + options.output_dir + "': its history columns differ");
    result.steps = p.step;
    result.time_s = p.time_s;
    result.totals = p.totals;
    result.record = std::move(p.record);
    wall_before = p.wall_s;
    for (std::size_t r = 0; r < result.record.rows(); ++r) kept_rows.push_back(result.record.row(r));
    outputs.blocks_pvd.restore(std::move(p.blocks_pvd));
    outputs.joints_pvd.restore(std::move(p.joints_pvd));
  }
  std::optional<io::HistoryCsv> history;
  if (files) history.emplace(options.output_dir + "/history.csv", names, kept_rows);
  std::optional<IterationTrace> trace;
  if (files && options.trace_iterations) {
    trace.emplace(options.output_dir + "/iterations.csv", options.restart ? result.steps : -1);
    model.step->observe_iterations(&*trace);
  }
  // A load ramp has moved to its next level before the step: its steps run to their end.
  model.step->interrupt_when(model.ramp ? std::function<bool()>{} : options.abandon_step_requested);
  struct StopObserving {  // the trace and the interruptions end with the run, even when a step throws
    Model& model;
    ~StopObserving() {
      model.step->observe_iterations(nullptr);
      model.step->interrupt_when({});
    }
  } stop_observing{model};
  auto progress_now = [&] {
    return RunProgress{result.steps, result.time_s,
                       wall_before + std::chrono::duration<double>(Clock::now() - start).count(), result.totals,
                       result.record, outputs.blocks_pvd.entries(), outputs.joints_pvd.entries()};
  };
  auto checkpoint = [&] { write_checkpoint(checkpoint_path(options.output_dir), model, progress_now()); };
  // A step abandoned on request is rolled back, but the flow network's warm start (its
  // last trial, kept in a checkpoint so that a restart repeats the same iterates) is the
  // abandoned attempt's last iterate: the network's state at the step's start is kept
  // (a few vectors per node and joint) and put back before the checkpoint is written.
  const bool keep_flow_start = files && options.abandon_step_requested && !model.ramp && model.flow;
  std::string flow_at_step_start;
  // Time stepping to end_time, or one step per load level of a load ramp.
  LoadRamp* ramp = model.ramp.get();
  const bool stop_at_edge = time.stop_when == "fluid_at_edge";
  const std::vector<char> edge_points =
      stop_at_edge ? inner_boundary_points(model.system->mesh(), model.config) : std::vector<char>{};
  const int n_steps = std::max(1, static_cast<int>(std::llround(time.end_time_s / time.dt_s)));
  if (files && !options.restart) outputs.write(model, 0, 0.0, false);
  for (int step = result.steps + 1; ramp ? ramp->has_next() : step <= n_steps; ++step) {
    const double t = step * time.dt_s;
    if (ramp) model.system->set_load_level(ramp->next_level());
    if (keep_flow_start) {
      BinaryWriter out(std::move(flow_at_step_start));
      model.flow->save_state(out);
      flow_at_step_start = out.take_bytes();
    }
    StepStatistics st;
    if (trace) trace->begin_step(step, t - time.dt_s);
    try {
      st = model.step->advance(time.dt_s, model.config.numerics.max_step_cuts);
      check_fields_finite(*model.system, model.flow.get(), step);
    } catch (const StepInterrupted&) {
      // The attempt was rolled back to the step's start; so is the flow's warm start.
      if (keep_flow_start) {
        BinaryReader in(flow_at_step_start);
        model.flow->restore_state(in);
      }
      if (files) checkpoint();
      result.interrupted = true;
      result.message = "step " + std::to_string(step) + ": abandoned on request; the state is that of step " +
                       std::to_string(result.steps) + (files ? ", checkpoint written" : "");
      break;
    } catch (const ConvergenceError& e) {
      char where[128];
      if (ramp)
        std::snprintf(where, sizeof where, "step %d (load level %g Pa): ", step, model.system->load_level());
      else
        std::snprintf(where, sizeof where, "step %d (t = %g s to %g s): ", step, t - time.dt_s, t);
      result.message = where + std::string(e.what());
      // Sub-steps of this step that converged before the failing one stay committed
      // (CoupledStep::advance): the state, and the outputs written from it, are then at
      // a time inside the step, which the run reports.
      const double partial_s = model.step->committed_time_s();
      if (partial_s > 0.0 && !ramp) {
        char reached[160];
        std::snprintf(reached, sizeof reached, " (the state is at t = %.9g s: the sub-steps of this step that "
                      "converged before it are committed)", t - time.dt_s + partial_s);
        result.message += reached;
        result.time_s = t - time.dt_s + partial_s;
      }
      break;
    }
    if (ramp) ramp->after_step(*model.system, step, st.bonds_broken);
    const bool at_edge = stop_at_edge && fluid_at_edge(*model.flow, model.system->mesh(), edge_points);
    if (at_edge) result.stop_reason = "fluid_at_edge";
    const bool last = at_edge || (ramp ? !ramp->has_next() : step == n_steps);
    result.steps = step;
    result.totals.accumulate(st);
    result.time_s = t;
    const double elapsed = wall_before + std::chrono::duration<double>(Clock::now() - start).count();
    const StepContext context = make_step_context(model, step, t, st, elapsed);
    std::vector<double> row;
    row.reserve(columns.size());
    for (const OutputColumn& c : columns) row.push_back(c.value(context));
    if (history) history->append(row);
    result.record.append(std::move(row));
    const int every = model.config.output.every_steps;
    if (files && (last || (every > 0 && step % every == 0))) outputs.write(model, step, t, last);
    if (options.after_step) options.after_step(model, step, t);
    const int shown_steps = ramp ? step : n_steps;
    if (terminal)
      std::fprintf(stderr, "\rstep %d/%d  t = %.4g s  open-close %d  ALM %d  elapsed %.1f s   ", step, shown_steps, t,
                   st.open_close_iterations, st.alm_iterations, elapsed);
    else if (!options.quiet)
      std::fprintf(stderr, "step %d/%d t=%.6g s open-close=%d alm=%d elapsed=%.3f s\n", step, shown_steps, t,
                   st.open_close_iterations, st.alm_iterations, elapsed);
    if (at_edge) break;
    if (last) continue;
    const bool stop = options.stop_requested && options.stop_requested();
    if (files && (stop || (options.checkpoint_every > 0 && step % options.checkpoint_every == 0))) checkpoint();
    if (stop) {
      result.interrupted = true;
      result.message = "step " + std::to_string(step) + ": stopped on request" + (files ? "; checkpoint written" : "");
      break;
    }
  }
  if (terminal) std::fprintf(stderr, "\n");
  result.completed = result.message.empty();
  if (result.completed && result.stop_reason.empty()) result.stop_reason = ramp ? "load_ramp" : "end_time";
  if (files && !result.completed && !result.interrupted) outputs.write(model, result.steps, result.time_s, true);
  result.wall_seconds = wall_before + std::chrono::duration<double>(Clock::now() - start).count();
  if (files) write_summary(model, options, result);
  return result;
}

}  // namespace hfdda::simulation
