// One realisation of an ensemble (realisation.hpp).

#include "ensemble/realisation.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/fingerprint.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"
#include "stochastic/scalar_distribution.hpp"

namespace hfdda::ensemble {

namespace {

bool resampled(const io::EnsembleConfig& e, const std::string& group) {
  return std::find(e.resample.begin(), e.resample.end(), group) != e.resample.end();
}

/// Fingerprint of the joints' end points.
MeshSignature mesh_signature(const mesh::Mesh& m) {
  Fingerprint f;
  for (const mesh::Joint& j : m.joints)
    for (int point : {j.point_p, j.point_q}) f.add(m.points[point].x()), f.add(m.points[point].y());
  return {static_cast<int>(m.joints.size()), f.hex()};
}

/// The case as realisation `seeds` runs it: its own network seed.
io::CaseConfig realisation_case(const io::CaseConfig& config, const RealisationSeeds& seeds) {
  io::CaseConfig c = config;
  if (!c.fracture_sets.empty()) c.network_seed = seeds.network_seed();
  return c;
}

MapSnapshot snapshot(const simulation::Model& model, const EnsembleGeometry& geometry) {
  const dda::BlockSystem& s = *model.system;
  MapSnapshot snap;
  std::vector<char> open_cell(geometry.grid.cells(), 0), wet_cell(geometry.grid.cells(), 0);
  for (int j = 0; j < geometry.mesh.joints; ++j) {
    const bool open =
        s.joint_end_state(j, 0) == dda::ContactState::open || s.joint_end_state(j, 1) == dda::ContactState::open;
    const bool wet = model.flow && model.flow->wetted(j);
    if (open) snap.open_joints.push_back(j);
    if (wet) snap.wet_joints.push_back(j);
    for (int cell : geometry.cells_of_joint[j]) {
      if (open) open_cell[cell] = 1;
      if (wet) wet_cell[cell] = 1;
    }
  }
  for (int c = 0; c < geometry.grid.cells(); ++c) {
    if (open_cell[c]) snap.open_cells.push_back(c);
    if (wet_cell[c]) snap.wet_cells.push_back(c);
  }
  return snap;
}

}  // namespace

RealisationSeeds realisation_seeds(const io::EnsembleConfig& ensemble, long index) {
  RealisationSeeds seeds;
  seeds.index = index;
  const auto master = static_cast<std::uint64_t>(ensemble.master_seed);
  for (const std::string& group : parameter_groups()) {
    const std::string stream =
        resampled(ensemble, group) ? "realisation " + std::to_string(index) + " " + group : "held " + group;
    seeds.of_group[group] = stochastic::stream_seed(master, stream);
  }
  return seeds;
}

std::vector<double> map_times(const io::EnsembleConfig& ensemble, double end_time_s) {
  std::vector<double> times;
  const double every = ensemble.map_every_s;
  const long n = static_cast<long>(std::floor(end_time_s / every * (1.0 + 1e-9)));
  for (long k = 1; k <= n; ++k) times.push_back(std::min(k * every, end_time_s));
  if (times.empty() || times.back() < end_time_s * (1.0 - 1e-9)) times.push_back(end_time_s);
  return times;
}

EnsembleGeometry ensemble_geometry(const io::CaseConfig& config) {
  if (!config.ensemble) throw std::invalid_argument("ensemble_geometry: the case has no ensemble section");
  const io::EnsembleConfig& e = *config.ensemble;
  EnsembleGeometry g;
  // The held network's natural fractures are drawn in the maps; a resampled one differs
  // from realisation to realisation and is not.
  const io::CaseConfig c = realisation_case(config, realisation_seeds(e, 0));
  const simulation::FracturedMesh fractured = simulation::build_fractured_mesh(c);
  const mesh::Mesh& m = fractured.mesh;
  const bool network_held = !resampled(e, "network");
  const Rect& out = config.domain.outer;
  g.grid = MapGrid::covering(out.xmin, out.xmax, out.ymin, out.ymax, e.grid_cell_m);
  for (const mesh::Joint& j : m.joints) {
    const Vec2 a = m.points[j.point_p], b = m.points[j.point_q];
    const bool generated = j.properties.natural;
    g.joints.push_back({a, b, network_held ? generated : false});
    g.cells_of_joint.push_back(cells_crossed(g.grid, a, b));
  }
  g.mesh = mesh_signature(m);
  g.map_times_s = map_times(e, config.time.end_time_s);
  return g;
}

namespace {

/// The largest of each quality column over the run's committed steps.
RealisationQuality realisation_quality(const simulation::RunRecord& history) {
  RealisationQuality q;
  q.known = true;
  if (history.empty()) return q;
  const auto largest = [&](const char* column) {
    const std::vector<double> values = history.series(column);
    return *std::max_element(values.begin(), values.end());
  };
  q.max_block_strain = largest("max_block_strain");
  q.max_aperture_m = largest("max_aperture_m");
  q.max_overlap_m = largest("max_overlap_m");
  q.max_cycle_holds = static_cast<int>(largest("cycle_holds"));
  q.max_unbonded_tension_Pa = largest("max_unbonded_tension_Pa");
  if (history.has("injection_pressure_Pa"))
    q.final_injection_pressure_Pa = history.value(history.rows() - 1, "injection_pressure_Pa");
  return q;
}

}  // namespace

simulation::Model build_realisation_model(const io::CaseConfig& config, long index) {
  if (!config.ensemble) throw std::invalid_argument("build_realisation_model: the case has no ensemble section");
  const RealisationSeeds seeds = realisation_seeds(*config.ensemble, index);
  simulation::ParameterSampler sampler(seeds.of_group);
  return simulation::build_model(realisation_case(config, seeds), sampler);
}

std::optional<RealisationRecord> run_realisation(const io::CaseConfig& config, const EnsembleGeometry& geometry,
                                                 long index, const std::function<bool()>& stop_requested,
                                                 const std::function<void()>& after_step) {
  const auto start = std::chrono::steady_clock::now();  // building the model counts too
  RealisationRecord record;
  record.index = index;
  record.seeds = realisation_seeds(*config.ensemble, index);
  record.maps.index = index;
  simulation::Model model = build_realisation_model(config, index);
  record.draws = model.parameter_draws;
  record.natural_fractures = static_cast<int>(model.network.fractures.size());
  record.mesh = mesh_signature(model.system->mesh());
  if (!(record.mesh == geometry.mesh))
    throw std::runtime_error("realisation " + std::to_string(index) + ": its mesh differs from the ensemble's (" +
                             std::to_string(record.mesh.joints) + " joints, hash " + record.mesh.hash + ")");

  const std::vector<double>& times = geometry.map_times_s;
  simulation::RunOptions options;
  options.quiet = true;
  options.write_files = false;
  options.stop_requested = stop_requested;
  options.abandon_step_requested = stop_requested;  // a realisation in flight is dropped anyway
  options.after_step = [&](const simulation::Model& m, int, double t) {
    while (record.maps.snapshots.size() < times.size() && t >= times[record.maps.snapshots.size()] * (1.0 - 1e-9))
      record.maps.snapshots.push_back(snapshot(m, geometry));
    if (after_step) after_step();
  };
  const simulation::RunResult result = simulation::run(model, options);
  if (result.interrupted) return std::nullopt;
  record.status = result.completed ? "completed" : "failed";
  record.message = result.message;
  record.stop_reason = result.stop_reason;
  record.steps = result.steps;
  record.time_s = result.time_s;
  record.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (model.flow) record.mass_injected_kg = model.flow->injected_mass();
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) record.peak_memory_mb = usage.ru_maxrss / 1024.0;  // KiB on Linux
  const MapSnapshot last = snapshot(model, geometry);
  for (int j : last.open_joints) record.open_length_m += (geometry.joints[j].b - geometry.joints[j].a).norm();
  for (int j : last.wet_joints) record.wet_length_m += (geometry.joints[j].b - geometry.joints[j].a).norm();
  record.quality = realisation_quality(result.record);
  return record;
}

bool completed_with_strained_blocks(const RealisationRecord& r) {
  return r.status == "completed" && r.quality.known && r.quality.max_block_strain > kImplausibleStepStrain;
}

}  // namespace hfdda::ensemble
