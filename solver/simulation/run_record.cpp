#include "simulation/run_record.hpp"

#include <algorithm>
#include <stdexcept>

namespace hfdda::simulation {

StepContext make_step_context(const Model& model, int step, double time_s, const StepStatistics& stats,
                              double elapsed_s) {
  StepContext c{model, step, time_s, stats, elapsed_s};
  const dda::BlockSystem& system = *model.system;
  const mesh::Mesh& m = system.mesh();
  for (std::size_t j = 0; j < m.joints.size(); ++j)
    for (int end = 0; end < 2; ++end) {
      c.open_joint_ends += system.joint_end_state(static_cast<int>(j), end) == dda::ContactState::open;
      const double gap = system.joint_gap(static_cast<int>(j), end);
      c.max_aperture_m = std::max(c.max_aperture_m, gap);
      c.max_overlap_m = std::max(c.max_overlap_m, -gap);
    }
  const fluid::FlowNetwork* flow = model.flow.get();
  c.inlet_point = flow && !model.injection_points.empty() ? model.injection_points.front() : -1;
  const Vec2 origin = c.inlet_point >= 0 ? m.points[c.inlet_point] : Vec2(0, 0);
  // Lengths per joint kind and extents, for fractures meeting others (seed 5.2-5.4).
  for (int j = 0; j < static_cast<int>(m.joints.size()); ++j) {
    const mesh::Joint& joint = m.joints[j];
    const int kind = joint.properties.natural ? 1 : 0;
    const double length = (m.points[joint.point_q] - m.points[joint.point_p]).norm();
    const bool open = system.joint_end_state(j, 0) == dda::ContactState::open ||
                      system.joint_end_state(j, 1) == dda::ContactState::open;
    const bool sliding = system.joint_end_state(j, 0) == dda::ContactState::sliding ||
                         system.joint_end_state(j, 1) == dda::ContactState::sliding;
    const bool invaded = flow && flow->wetted(j);
    c.opened_m[kind] += open ? length : 0.0;
    c.slipped_m[kind] += sliding ? length : 0.0;
    c.invaded_m[kind] += invaded ? length : 0.0;
    const double reach = std::max((m.points[joint.point_p] - origin).norm(), (m.points[joint.point_q] - origin).norm());
    if (open) c.open_extent_m = std::max(c.open_extent_m, reach);
    if (invaded) c.invaded_extent_m = std::max(c.invaded_extent_m, reach);
  }
  if (!flow) return c;
  for (int j = 0; j < flow->n_fractures(); ++j) {
    if (!flow->wetted(j)) continue;
    ++c.wetted_joints;
    for (int end = 0; end < 2; ++end) {
      const Vec2 r = m.points[end == 0 ? m.joints[j].point_p : m.joints[j].point_q] - origin;
      const bool open = system.joint_end_state(j, end) == dda::ContactState::open;
      if (open || !system.contacts()[system.joint_contacts(j)[end]].bonded)
        c.fracture_xmin_m = std::min(c.fracture_xmin_m, r.x()), c.fracture_xmax_m = std::max(c.fracture_xmax_m, r.x());
      if (!open) continue;
      c.open_xmin_m = std::min(c.open_xmin_m, r.x()), c.open_xmax_m = std::max(c.open_xmax_m, r.x());
      c.open_ymin_m = std::min(c.open_ymin_m, r.y()), c.open_ymax_m = std::max(c.open_ymax_m, r.y());
    }
  }
  return c;
}

namespace {

using Value = std::function<double(const StepContext&)>;

/// A column of the flow network: its value, or 0 for a case without one.
Value flow_value(std::function<double(const StepContext&, const fluid::FlowNetwork&)> f) {
  return [f = std::move(f)](const StepContext& c) { return c.model.flow ? f(c, *c.model.flow) : 0.0; };
}

/// A column of the flow network at the first injection point (0 without one).
Value inlet_value(double (fluid::FlowNetwork::*f)(int) const) {
  return flow_value([f](const StepContext& c, const fluid::FlowNetwork& flow) {
    return c.inlet_point >= 0 ? (flow.*f)(c.inlet_point) : 0.0;
  });
}

std::vector<OutputColumn> make_fixed_columns() {
  const std::string extent =
      " of the open ends of fluid-filled joints, relative to the injection point (a broken but dry joint does "
      "not count)";
  return {
      {"step", "-", "step number (1 for the first step)", [](const StepContext& c) { return double(c.step); }},
      {"time_s", "s", "simulated time at the end of the step", [](const StepContext& c) { return c.time_s; }},
      {"open_close_iterations", "-", "open-close (outer) iterations of the step",
       [](const StepContext& c) { return double(c.stats.open_close_iterations); }},
      {"alm_iterations", "-", "ALM iterations (linear solves of the contact iterations)",
       [](const StepContext& c) { return double(c.stats.alm_iterations); }},
      {"alm_stalls", "-",
       "ALM solves ended because the corrections stopped changing: a loop of closed contacts around a point "
       "whose reference points no longer close, by nanometres, after slips and rotations",
       [](const StepContext& c) { return double(c.stats.alm_stalls); }},
      {"cycle_holds", "-",
       "state changes refused to contacts caught in an open-close cycle (numerics.max_state_flips), each "
       "resolved by its most open state of the step (seed 5.1); > 0: the step ended on a cycle",
       [](const StepContext& c) { return double(c.stats.cycle_holds); }},
      {"mechanism_blocks", "-",
       "largest number of blocks held as a mechanism at one assembly of the stiffness matrix: groups that "
       "their closed contacts leave a rigid motion, given the inertia of numerics.mechanism_inertia_time",
       [](const StepContext& c) { return double(c.stats.max_mechanism_blocks); }},
      {"alm_stall_mismatch", "-",
       "largest gap or shear left at a stall, over the contact's length (a stall is accepted only below 1e-6)",
       [](const StepContext& c) { return c.stats.max_alm_stall_mismatch; }},
      {"alm_displacement_change", "-",
       "largest ||D(m+1) - D(m)|| / ||D(m+1)|| of the last inner iteration (erratum 2, docs/seed_errata.md: the "
       "inner iterations stop on the contact forces, this shows what that means for D)",
       [](const StepContext& c) { return c.stats.max_alm_displacement_change; }},
      {"factorizations", "-", "factorisations of the stiffness matrix",
       [](const StepContext& c) { return double(c.stats.factorizations); }},
      {"bonds_broken", "-", "bonds broken in the step", [](const StepContext& c) { return double(c.stats.bonds_broken); }},
      {"state_changes", "-", "contact state changes applied",
       [](const StepContext& c) { return double(c.stats.state_changes); }},
      {"vertex_vertex_activations", "-", "vertex-vertex contacts activated in the step",
       [](const StepContext& c) { return double(c.stats.vertex_vertex_activations); }},
      {"active_vertex_vertex", "-", "vertex-vertex contacts active at the end of the step",
       [](const StepContext& c) { return double(c.stats.active_vertex_vertex); }},
      {"open_joint_ends", "-", "joint ends in the open state", [](const StepContext& c) { return double(c.open_joint_ends); }},
      {"max_aperture_m", "m", "largest joint-end gap", [](const StepContext& c) { return c.max_aperture_m; }},
      {"max_penetration_m", "m", "largest penetration met in the step's contact iterations, iterates included",
       [](const StepContext& c) { return c.stats.max_penetration_m; }},
      {"max_overlap_m", "m", "largest overlap of joint faces in the committed state",
       [](const StepContext& c) { return c.max_overlap_m; }},
      {"max_block_strain", "-", "largest principal strain increment of a block in the step (a step above 0.1 is refused)",
       [](const StepContext& c) { return c.stats.max_block_strain; }},
      {"max_unbonded_tension_Pa", "Pa",
       "largest tension on a closed joint contact whose bond is broken (the contact law allows none: normally a "
       "contact held closed by the cycle rule; growing from step to step, it came before the collapses of design notes "
       "section 49)",
       [](const StepContext& c) { return c.stats.max_unbonded_tension_Pa; }},
      {"step_wall_s", "s", "wall time of the step", [](const StepContext& c) { return c.stats.seconds_total; }},
      {"elapsed_wall_s", "s", "wall time of the run so far", [](const StepContext& c) { return c.elapsed_s; }},
      {"step_cuts", "-", "halvings of the step after a failed attempt (0 without a flow network)",
       [](const StepContext& c) { return double(c.stats.step_cuts); }},
      {"fractures_wetted", "-", "joints that took in fluid during the step",
       [](const StepContext& c) { return double(c.stats.fractures_wetted); }},
      {"flow_newton_iterations", "-", "Newton iterations of the flow solves",
       [](const StepContext& c) { return double(c.stats.flow_newton_iterations); }},
      {"flow_newton_restarts", "-",
       "fallbacks used after the flow Newton stalled: full Newton steps, pseudo-transient continuation, restarts "
       "with the dry nodes at their neighbours' pressure, continuation in the step's inflows, the closing joints "
       "held open",
       [](const StepContext& c) { return double(c.stats.flow_newton_restarts); }},
      {"flow_krylov_iterations", "-",
       "GMRES iterations of the flow Newton (on the Krylov path, numerics.flow_jacobian krylov; 0 otherwise)",
       [](const StepContext& c) { return double(c.stats.flow_krylov_iterations); }},
      {"flow_inexact_linear_solves", "-",
       "GMRES solves that stopped at their iteration limit before their tolerance; Newton used them as inexact "
       "steps, its own convergence test being on the mass residual (krylov only)",
       [](const StepContext& c) { return double(c.stats.flow_inexact_linear_solves); }},
      {"flow_max_residual", "-", "largest relative mass residual of a flow solve",
       [](const StepContext& c) { return c.stats.max_flow_residual; }},
      {"wetted_joints", "-", "fluid-filled joints (0 without a flow network)",
       [](const StepContext& c) { return double(c.wetted_joints); }},
      {"injection_pressure_Pa", "Pa", "fluid pressure at the first injection point",
       inlet_value(&fluid::FlowNetwork::pressure)},
      {"injection_aperture_m", "m", "aperture at the first injection point",
       inlet_value(&fluid::FlowNetwork::aperture_at_point)},
      {"open_xmin_m", "m", "smallest x" + extent, [](const StepContext& c) { return c.open_xmin_m; }},
      {"open_xmax_m", "m", "largest x" + extent, [](const StepContext& c) { return c.open_xmax_m; }},
      {"open_ymin_m", "m", "smallest y" + extent, [](const StepContext& c) { return c.open_ymin_m; }},
      {"open_ymax_m", "m", "largest y" + extent, [](const StepContext& c) { return c.open_ymax_m; }},
      {"fracture_xmin_m", "m",
       "smallest x of the ends of fluid-filled joints that are open or no longer bonded there, relative to the "
       "injection point (a joint broken whole reaches its tip even where its faces touch there)",
       [](const StepContext& c) { return c.fracture_xmin_m; }},
      {"fracture_xmax_m", "m", "largest x of the same ends as fracture_xmin_m",
       [](const StepContext& c) { return c.fracture_xmax_m; }},
      {"opened_length_rock_m", "m", "length of rock joints (not natural) with an open end",
       [](const StepContext& c) { return c.opened_m[0]; }},
      {"opened_length_natural_m", "m", "length of natural-fracture joints with an open end",
       [](const StepContext& c) { return c.opened_m[1]; }},
      {"invaded_length_rock_m", "m", "length of rock joints holding fluid",
       [](const StepContext& c) { return c.invaded_m[0]; }},
      {"invaded_length_natural_m", "m", "length of natural-fracture joints holding fluid (open or not)",
       [](const StepContext& c) { return c.invaded_m[1]; }},
      {"slipped_length_rock_m", "m", "length of rock joints with a sliding end",
       [](const StepContext& c) { return c.slipped_m[0]; }},
      {"slipped_length_natural_m", "m", "length of natural-fracture joints with a sliding end",
       [](const StepContext& c) { return c.slipped_m[1]; }},
      {"open_extent_m", "m", "largest distance of an end of an open joint from the first injection point",
       [](const StepContext& c) { return c.open_extent_m; }},
      {"invaded_extent_m", "m", "largest distance of an end of an invaded joint from the first injection point",
       [](const StepContext& c) { return c.invaded_extent_m; }},
      {"mass_injected_kg", "kg", "fluid mass injected since t = 0",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.injected_mass(); })},
      {"mass_stored_kg", "kg", "fluid mass stored in the joints",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.stored_mass(); })},
      {"mass_leaked_kg", "kg", "fluid mass leaked off since t = 0",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.leaked_mass(); })},
      {"mass_vented_kg", "kg", "fluid mass that has left through a vented edge since t = 0 (fluid.edge)",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.vented_mass(); })},
      {"mass_balance_error", "-",
       "|initial + injected - stored - leaked - vented| / (initial + injected), stored as the ledger counts it: closes to "
       "round-off by construction, a check of the bookkeeping only",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.mass_balance_error(); })},
      {"mass_volume_kg", "kg",
       "fluid mass the committed state holds, from the apertures and pressures (or fill) of the nodes, without "
       "the ledger",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.volume_stored_mass(); })},
      {"mass_volume_error", "-",
       "|initial + injected - leaked - vented - mass_volume_kg| / (initial + injected): the sum of the last flow solve's "
       "mass residuals; large when the solve did not converge or fluid and apertures disagree",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return f.volume_balance_error(); })},
      {"flow_nodes", "-", "nodes of the flow network (points the fluid has reached)",
       flow_value([](const StepContext&, const fluid::FlowNetwork& f) { return double(f.n_nodes()); })},
  };
}

std::string escape_cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

const std::vector<OutputColumn>& fixed_history_columns() {
  static const std::vector<OutputColumn> columns = make_fixed_columns();
  return columns;
}

std::vector<OutputColumn> probe_columns(const std::string& name, std::size_t index) {
  return {{"probe_" + name + "_pressure_Pa", "Pa", "fluid pressure at probe `" + name + "` (0 without a flow network)",
           [index](const StepContext& c) {
             return c.model.flow ? c.model.flow->pressure(c.model.probe_points[index]) : 0.0;
           }},
          {"probe_" + name + "_aperture_m", "m",
           "hydraulic aperture at probe `" + name +
               "`: mean aperture of the fluid-filled joints meeting at its mesh point (as the flow uses it, at "
               "least the minimum width); 0 where none meets there and without a flow network",
           [index](const StepContext& c) {
             return c.model.flow ? c.model.flow->aperture_at_point(c.model.probe_points[index]) : 0.0;
           }}};
}

std::vector<OutputColumn> load_ramp_columns() {
  return {{"load_level_Pa", "Pa", "load level s of the load ramp in the step (load_ramp cases only)",
           [](const StepContext& c) { return c.model.system->load_level(); }},
          {"broken_fraction", "-",
           "broken length of the load ramp's stop_joints over their length (load_ramp cases with stop_when: "
           "broken_fraction only)",
           [](const StepContext& c) { return c.model.ramp ? c.model.ramp->broken_fraction() : 0.0; }}};
}

std::vector<OutputColumn> history_columns(const Model& model) {
  std::vector<OutputColumn> columns = fixed_history_columns();
  if (model.ramp)
    for (OutputColumn& c : load_ramp_columns()) columns.push_back(std::move(c));
  for (std::size_t i = 0; i < model.config.probes.size(); ++i)
    for (OutputColumn& c : probe_columns(model.config.probes[i].name, i)) columns.push_back(std::move(c));
  return columns;
}

std::string history_columns_markdown() {
  std::string text = "| column | unit | meaning |\n|---|---|---|\n";
  std::vector<OutputColumn> columns = fixed_history_columns();
  for (OutputColumn& c : probe_columns("<name>", 0)) columns.push_back(std::move(c));
  for (OutputColumn& c : load_ramp_columns()) columns.push_back(std::move(c));
  for (const OutputColumn& c : columns)
    text += "| `" + c.name + "` | " + c.unit + " | " + escape_cell(c.description) + " |\n";
  return text;
}

RunRecord::RunRecord(std::vector<std::string> columns) : columns_(std::move(columns)) {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (!index_.emplace(columns_[i], i).second)
      throw std::invalid_argument("RunRecord: column '" + columns_[i] + "' appears twice");
}

std::size_t RunRecord::column(const std::string& name) const {
  const auto it = index_.find(name);
  if (it != index_.end()) return it->second;
  std::string known;
  for (const std::string& c : columns_) known += (known.empty() ? "" : ", ") + c;
  throw std::out_of_range("run record has no column '" + name + "'; known columns: " + known);
}

double RunRecord::value(std::size_t row, const std::string& name) const {
  const std::size_t c = column(name);
  if (row >= rows_.size())
    throw std::out_of_range("run record has " + std::to_string(rows_.size()) + " rows; row " + std::to_string(row) +
                            " requested (column '" + name + "')");
  return rows_[row][c];
}

std::vector<double> RunRecord::series(const std::string& name) const {
  const std::size_t c = column(name);
  std::vector<double> out;
  out.reserve(rows_.size());
  for (const auto& r : rows_) out.push_back(r[c]);
  return out;
}

void RunRecord::append(std::vector<double> row) {
  if (row.size() != columns_.size())
    throw std::invalid_argument("RunRecord::append: " + std::to_string(row.size()) + " values for " +
                                std::to_string(columns_.size()) + " columns");
  rows_.push_back(std::move(row));
}

const std::vector<SummaryField>& summary_solver_fields() {
  static const std::vector<SummaryField> fields{
      {"open_close_iterations", "open-close iterations of the run",
       [](const StepStatistics& t) { return double(t.open_close_iterations); }, true},
      {"alm_iterations", "ALM iterations of the run", [](const StepStatistics& t) { return double(t.alm_iterations); },
       true},
      {"alm_stalls", "ALM solves ended by the stall test", [](const StepStatistics& t) { return double(t.alm_stalls); },
       true},
      {"friction_iterations_frozen", "contact solves whose sliding friction was frozen before its normal force settled",
       [](const StepStatistics& t) { return double(t.friction_iterations_frozen); }, true},
      {"max_unbonded_tension_Pa", "largest tension on a closed contact whose bond is broken [Pa]",
       [](const StepStatistics& t) { return t.max_unbonded_tension_Pa; }},
      {"max_alm_stall_mismatch", "largest mismatch accepted at a stall",
       [](const StepStatistics& t) { return t.max_alm_stall_mismatch; }},
      {"steps_with_cycles", "(sub-)steps that ended with a contact held on an open-close cycle",
       [](const StepStatistics& t) { return double(t.steps_with_cycles); }, true},
      {"factorizations", "factorisations of the stiffness matrix",
       [](const StepStatistics& t) { return double(t.factorizations); }, true},
      {"bonds_broken", "bonds broken", [](const StepStatistics& t) { return double(t.bonds_broken); }, true},
      {"vertex_vertex_activations", "vertex-vertex contacts activated",
       [](const StepStatistics& t) { return double(t.vertex_vertex_activations); }, true},
      {"max_active_vertex_vertex", "largest number of active vertex-vertex contacts at the end of a step",
       [](const StepStatistics& t) { return double(t.max_active_vertex_vertex); }, true},
      {"seconds_assembly", "wall time of the assembly [s]", [](const StepStatistics& t) { return t.seconds_assembly; }},
      {"seconds_factorization", "wall time of the factorisations [s]",
       [](const StepStatistics& t) { return t.seconds_factorization; }},
      {"seconds_solve", "wall time of the solves [s]", [](const StepStatistics& t) { return t.seconds_solve; }},
  };
  return fields;
}

}  // namespace hfdda::simulation
