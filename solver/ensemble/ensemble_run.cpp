// An ensemble's directory, records, work queue and maps (ensemble_run.hpp).

#include "ensemble/ensemble_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <vector>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/fingerprint.hpp"
#include "core/number_text.hpp"
#include "io/output.hpp"

namespace hfdda::ensemble {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string hash_text(const std::string& text) {
  Fingerprint f;
  f.add(text);
  return f.hex();
}

/// Fingerprint of the running executable's file (Linux /proc/self/exe; "unknown" where
/// it cannot be read); read once per ensemble.
std::string executable_hash() {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  if (!in) return "unknown";
  Fingerprint f;
  std::vector<char> buffer(1 << 20);
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
    f.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  return f.hex();
}

json grid_json(const MapGrid& g) {
  return {{"xmin", g.xmin}, {"ymin", g.ymin}, {"cell_m", g.cell_m}, {"nx", g.nx}, {"ny", g.ny}};
}

MapGrid grid_from(const json& j) {
  MapGrid g;
  g.xmin = j.at("xmin"), g.ymin = j.at("ymin"), g.cell_m = j.at("cell_m"), g.nx = j.at("nx"), g.ny = j.at("ny");
  return g;
}

json manifest_json(const EnsembleManifest& m) {
  return {{"format", "hfdda-ensemble-1"},
          {"case_file", m.case_file},
          {"case_hash", m.case_hash},
          {"solver_build", m.solver_build},
          {"realisations", m.realisations},
          {"master_seed", m.master_seed},
          {"resample", m.resample},
          {"map_times_s", m.map_times_s},
          {"grid", grid_json(m.grid)},
          {"mesh", {{"joints", m.mesh.joints}, {"hash", m.mesh.hash}}},
          {"shard", {{"index", m.shard.index}, {"count", m.shard.count}}}};
}

EnsembleManifest manifest_from(const json& j) {
  EnsembleManifest m;
  m.case_file = j.at("case_file");
  m.case_hash = j.at("case_hash");
  m.solver_build = j.value("solver_build", std::string("unrecorded"));
  m.realisations = j.at("realisations");
  m.master_seed = j.at("master_seed");
  m.resample = j.at("resample").get<std::vector<std::string>>();
  m.map_times_s = j.at("map_times_s").get<std::vector<double>>();
  m.grid = grid_from(j.at("grid"));
  m.mesh.joints = j.at("mesh").at("joints");
  m.mesh.hash = j.at("mesh").at("hash");
  m.shard.index = j.at("shard").at("index");
  m.shard.count = j.at("shard").at("count");
  return m;
}

EnsembleManifest read_manifest(const std::string& dir) {
  const std::string path = dir + "/ensemble.json";
  try {
    return manifest_from(json::parse(read_text(path)));
  } catch (const std::exception& e) {
    throw std::runtime_error("'" + path + "' is not an ensemble manifest: " + e.what());
  }
}

/// What differs between two manifests, ignoring the shard; empty when they agree.
std::string difference(const EnsembleManifest& a, const EnsembleManifest& b) {
  if (a.case_hash != b.case_hash) return "the case file differs (hash " + a.case_hash + " vs " + b.case_hash + ")";
  if (a.solver_build != b.solver_build)
    return "another build of the solver wrote it (executable hash " + a.solver_build + " vs " + b.solver_build +
           "): its realisations and this build's would mix";
  if (a.realisations != b.realisations)
    return "realisations " + std::to_string(a.realisations) + " vs " + std::to_string(b.realisations);
  if (a.master_seed != b.master_seed)
    return "master_seed " + std::to_string(a.master_seed) + " vs " + std::to_string(b.master_seed);
  if (a.resample != b.resample) return "the resampled groups differ";
  if (a.map_times_s != b.map_times_s) return "the map times differ";
  if (!(a.mesh == b.mesh)) return "the mesh differs";
  return "";
}

std::string record_name(long index) {
  char name[32];
  std::snprintf(name, sizeof name, "r%06ld.json", index);
  return name;
}

json ints(const std::vector<int>& v) { return json(v); }

json record_json(const RealisationRecord& r) {
  json j{{"index", r.index},         {"status", r.status},
         {"message", r.message},     {"stop_reason", r.stop_reason},
         {"steps", r.steps},         {"time_s", r.time_s},
         {"wall_s", r.wall_s},       {"natural_fractures", r.natural_fractures},
         {"mass_injected_kg", r.mass_injected_kg},
         {"open_length_m", r.open_length_m},
         {"wet_length_m", r.wet_length_m},
         {"peak_memory_mb", r.peak_memory_mb},
         {"schedule", {{"process", r.process}, {"started_unix_s", r.started_unix_s}, {"waited_s", r.waited_s}}},
         {"mesh", {{"joints", r.mesh.joints}, {"hash", r.mesh.hash}}}};
  if (r.quality.known)
    j["quality"] = {{"max_block_strain", r.quality.max_block_strain},
                    {"max_aperture_m", r.quality.max_aperture_m},
                    {"max_overlap_m", r.quality.max_overlap_m},
                    {"max_cycle_holds", r.quality.max_cycle_holds},
                    {"max_unbonded_tension_Pa", r.quality.max_unbonded_tension_Pa},
                    {"final_injection_pressure_Pa", r.quality.final_injection_pressure_Pa}};
  json& seeds = j["seeds"];
  for (const auto& [group, seed] : r.seeds.of_group) seeds[group] = seed;
  json& drawn = j["sampled_parameters"];
  drawn = json::array();
  for (const simulation::ParameterDraw& d : r.draws)
    drawn.push_back({{"key", d.key}, {"distribution", d.law}, {"per", d.per}, {"count", d.count},
                     {"min", d.min}, {"mean", d.mean}, {"max", d.max}});
  json& snaps = j["snapshots"];
  snaps = json::array();
  for (const MapSnapshot& s : r.maps.snapshots)
    snaps.push_back({{"open_joints", ints(s.open_joints)}, {"wet_joints", ints(s.wet_joints)},
                     {"open_cells", ints(s.open_cells)}, {"wet_cells", ints(s.wet_cells)}});
  return j;
}

RealisationRecord record_from(const json& j) {
  RealisationRecord r;
  r.index = j.at("index");
  r.status = j.at("status");
  if (r.status != "completed" && r.status != "failed") throw std::runtime_error("status '" + r.status + "'");
  r.message = j.at("message");
  r.stop_reason = j.at("stop_reason");
  r.steps = j.at("steps");
  r.time_s = j.at("time_s");
  r.wall_s = j.at("wall_s");
  r.natural_fractures = j.at("natural_fractures");
  r.mass_injected_kg = j.at("mass_injected_kg");
  r.open_length_m = j.at("open_length_m");
  r.wet_length_m = j.at("wet_length_m");
  r.peak_memory_mb = j.value("peak_memory_mb", 0.0);
  if (j.contains("quality")) {  // records written before it was kept have none
    const json& q = j.at("quality");
    r.quality.known = true;
    r.quality.max_block_strain = q.at("max_block_strain");
    r.quality.max_aperture_m = q.at("max_aperture_m");
    r.quality.max_overlap_m = q.at("max_overlap_m");
    r.quality.max_cycle_holds = q.at("max_cycle_holds");
    // Records written before it was kept have none.
    r.quality.max_unbonded_tension_Pa = q.value("max_unbonded_tension_Pa", std::numeric_limits<double>::quiet_NaN());
    r.quality.final_injection_pressure_Pa = q.at("final_injection_pressure_Pa");
  }
  if (j.contains("schedule")) {  // records written before it was kept have none
    const json& at = j.at("schedule");
    r.process = at.at("process");
    r.started_unix_s = at.at("started_unix_s");
    r.waited_s = at.at("waited_s");
  }
  r.mesh.joints = j.at("mesh").at("joints");
  r.mesh.hash = j.at("mesh").at("hash");
  r.seeds.index = r.index;
  for (const auto& [group, seed] : j.at("seeds").items()) r.seeds.of_group[group] = seed.get<std::uint64_t>();
  for (const json& d : j.at("sampled_parameters"))
    r.draws.push_back({d.at("key"), d.at("distribution"), d.at("per"), d.at("count"), d.at("min"), d.at("mean"),
                       d.at("max")});
  r.maps.index = r.index;
  for (const json& s : j.at("snapshots"))
    r.maps.snapshots.push_back({s.at("open_joints").get<std::vector<int>>(), s.at("wet_joints").get<std::vector<int>>(),
                                s.at("open_cells").get<std::vector<int>>(), s.at("wet_cells").get<std::vector<int>>()});
  return r;
}

void write_joint_geometry(const std::string& path, const std::vector<JointSegment>& joints) {
  std::string text = "x1,y1,x2,y2,natural\n";
  for (const JointSegment& s : joints)
    text += number_text(s.a.x()) + "," + number_text(s.a.y()) + "," + number_text(s.b.x()) + "," +
            number_text(s.b.y()) + "," + (s.natural ? "1" : "0") + "\n";
  io::write_file_atomically(path, text);
}

std::vector<JointSegment> read_joint_geometry(const std::string& path) {
  std::istringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  std::vector<JointSegment> joints;
  while (std::getline(in, line)) {
    double v[5];
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4]) != 5)
      throw std::runtime_error("'" + path + "': unreadable line '" + line + "'");
    joints.push_back({Vec2(v[0], v[1]), Vec2(v[2], v[3]), v[4] != 0.0});
  }
  return joints;
}

/// How the processes spent the time between the first realisation's start and the
/// last one's end: the realisations' own time, the waits for an index, and the idle
/// time at the end (a process done while another still runs its last realisation).
/// Records written before the schedule was kept have no start time and are left out.
json schedule_summary(const std::map<long, RealisationRecord>& by_index) {
  std::map<int, double> last_end_of_process;
  double first_start = 0.0, last_end = 0.0, waited = 0.0, busy = 0.0, longest_wait = 0.0;
  int timed = 0;
  for (const auto& [index, r] : by_index) {
    if (r.started_unix_s <= 0.0) continue;
    const double end = r.started_unix_s + r.wall_s;
    first_start = timed == 0 ? r.started_unix_s : std::min(first_start, r.started_unix_s);
    last_end = std::max(last_end, end);
    double& process_end = last_end_of_process[r.process];
    process_end = std::max(process_end, end);
    waited += r.waited_s;
    longest_wait = std::max(longest_wait, r.waited_s);
    busy += r.wall_s;
    ++timed;
  }
  double idle_at_end = 0.0;
  for (const auto& [process, end] : last_end_of_process) idle_at_end += last_end - end;
  return {{"realisations_timed", timed},
          {"processes_seen", last_end_of_process.size()},
          {"span_s", timed ? last_end - first_start : 0.0},
          {"busy_s", busy},
          {"waited_for_index_s", waited},
          {"longest_wait_s", longest_wait},
          {"idle_at_end_s", idle_at_end}};
}

}  // namespace

EnsembleManifest make_manifest(const io::CaseConfig& config, const EnsembleGeometry& geometry, Shard shard) {
  const io::EnsembleConfig& e = *config.ensemble;
  EnsembleManifest m;
  m.case_file = config.file;
  // The top file, every base it extends and every fracture map it reads.
  std::string identity = config.source_text;
  for (const io::FractureMapConfig& map : config.fracture_maps) identity += map.path + "\n" + read_text(map.path) + "\n";
  m.case_hash = hash_text(identity);
  m.solver_build = executable_hash();
  m.realisations = e.realisations;
  m.master_seed = e.master_seed;
  m.resample = e.resample;
  m.map_times_s = geometry.map_times_s;
  m.grid = geometry.grid;
  m.mesh = geometry.mesh;
  m.shard = shard;
  return m;
}

void prepare_directory(const std::string& dir, const EnsembleManifest& manifest, const EnsembleGeometry& geometry) {
  const std::string path = dir + "/ensemble.json";
  if (fs::exists(path)) {
    const EnsembleManifest old = read_manifest(dir);
    std::string diff = difference(old, manifest);
    if (diff.empty() && (old.shard.index != manifest.shard.index || old.shard.count != manifest.shard.count))
      diff = "shard " + std::to_string(old.shard.index) + "/" + std::to_string(old.shard.count) + " vs " +
             std::to_string(manifest.shard.index) + "/" + std::to_string(manifest.shard.count);
    if (!diff.empty())
      throw std::runtime_error("'" + dir + "' holds another ensemble (" + diff + "); use another directory or --force");
    return;
  }
  fs::create_directories(dir + "/realisations");
  write_joint_geometry(dir + "/ensemble_joints.csv", geometry.joints);
  io::write_file_atomically(path, manifest_json(manifest).dump(2) + "\n");
}

std::vector<long> pending_realisations(const std::string& dir, const EnsembleManifest& manifest) {
  std::vector<long> pending;
  for (long i = 0; i < manifest.realisations; ++i)
    if (manifest.shard.contains(i) && !fs::exists(dir + "/realisations/" + record_name(i))) pending.push_back(i);
  return pending;
}

void write_record(const std::string& dir, const RealisationRecord& record) {
  io::write_file_atomically(dir + "/realisations/" + record_name(record.index), record_json(record).dump() + "\n");
}

RealisationRecord read_record(const std::string& path) {
  try {
    return record_from(json::parse(read_text(path)));
  } catch (const std::exception& e) {
    throw std::runtime_error("'" + path + "' is not a realisation record: " + e.what());
  }
}

std::vector<RealisationRecord> read_records(const std::string& dir) {
  std::vector<std::string> paths;
  const std::string folder = dir + "/realisations";
  if (!fs::is_directory(folder)) return {};
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 6 && name[0] == 'r' && name.ends_with(".json")) paths.push_back(entry.path().string());
  }
  std::vector<RealisationRecord> records;
  for (const std::string& p : paths) records.push_back(read_record(p));
  std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
  return records;
}

SerialQueue::SerialQueue(std::vector<long> pending, bool show_progress)
    : pending_(std::move(pending)), show_progress_(show_progress) {}

std::optional<long> SerialQueue::next(const std::optional<Outcome>& finished) {
  if (finished) {
    ++done_;
    failed_ += finished->failed;
    wall_s_ += finished->wall_s;
  }
  if (show_progress_)
    std::fprintf(stderr, "%s\n",
                 progress_text(done_, failed_, cursor_ < pending_.size() ? 1 : 0, static_cast<int>(pending_.size()),
                               done_ > 0 ? wall_s_ / done_ : 0.0, 1)
                     .c_str());
  if (cursor_ >= pending_.size()) return std::nullopt;
  return pending_[cursor_++];
}

std::string progress_text(int done, int failed, int running, int total, double mean_wall_s, int processes) {
  char text[200];
  const int left = std::max(0, total - done);
  if (done == 0) {
    std::snprintf(text, sizeof text, "ensemble: %d/%d done, %d failed, %d running", done, total, failed, running);
  } else {
    const double eta = mean_wall_s * left / std::max(1, processes);
    std::snprintf(text, sizeof text, "ensemble: %d/%d done, %d failed, %d running, %.1f s each, about %.0f s left",
                  done, total, failed, running, mean_wall_s, eta);
  }
  return text;
}

bool run_realisations(const io::CaseConfig& config, const EnsembleGeometry& geometry, const std::string& dir,
                      WorkQueue& queue, const std::function<bool()>& stop_requested) {
  std::optional<Outcome> finished;
  using Clock = std::chrono::steady_clock;
  for (;;) {
    const Clock::time_point asked = Clock::now();
    const std::optional<long> index = queue.next(finished);
    if (!index) break;
    const double waited_s = std::chrono::duration<double>(Clock::now() - asked).count();
    const double started_unix_s =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    std::optional<RealisationRecord> record;
    try {
      record = run_realisation(config, geometry, *index, stop_requested, [&queue] { queue.serve(); });
    } catch (const std::exception& e) {
      // A model that cannot be built (a draw the mechanics refuses) is a failed
      // realisation with its reason, not the end of the ensemble.
      record = RealisationRecord{};
      record->index = *index;
      record->seeds = realisation_seeds(*config.ensemble, *index);
      record->maps.index = *index;
      record->status = "failed";
      record->message = std::string("the model could not be built: ") + e.what();
      record->mesh = geometry.mesh;
    }
    if (!record) return false;
    record->process = queue.process();
    record->started_unix_s = started_unix_s;
    record->waited_s = waited_s;
    write_record(dir, *record);
    finished = Outcome{record->status == "failed", record->wall_s};
    if (stop_requested && stop_requested()) return false;
  }
  queue.finish();
  return true;
}

EnsembleSummary write_ensemble_maps(const std::string& out_dir, const std::vector<std::string>& dirs) {
  if (dirs.empty()) throw std::invalid_argument("write_ensemble_maps: no directory");
  const EnsembleManifest first = read_manifest(dirs.front());
  std::map<long, RealisationRecord> by_index;
  for (const std::string& dir : dirs) {
    const EnsembleManifest m = read_manifest(dir);
    const std::string diff = difference(first, m);
    if (!diff.empty())
      throw std::runtime_error("'" + dir + "' holds another ensemble than '" + dirs.front() + "' (" + diff + ")");
    for (RealisationRecord& r : read_records(dir)) {
      if (r.index < 0 || r.index >= first.realisations)
        throw std::runtime_error("'" + dir + "': realisation " + std::to_string(r.index) + " is outside the ensemble");
      if (!(r.mesh == first.mesh))
        throw std::runtime_error("'" + dir + "': realisation " + std::to_string(r.index) + " ran on another mesh");
      by_index.emplace(r.index, std::move(r));  // the same index twice: same seeds, same record; keep the first
    }
  }
  const std::vector<JointSegment> segments = read_joint_geometry(dirs.front() + "/ensemble_joints.csv");
  LikelihoodAccumulator maps(first.map_times_s, first.mesh.joints, first.grid);
  std::vector<RealisationMaps> all;
  EnsembleSummary summary;
  summary.requested = first.realisations;
  json failures = json::array();
  json strained = json::array();
  int quality_unknown = 0;
  double wall = 0.0, peak_memory_mb = 0.0;
  for (const auto& [index, r] : by_index) {
    peak_memory_mb = std::max(peak_memory_mb, r.peak_memory_mb);
    maps.add(r.maps);
    all.push_back(r.maps);
    ++summary.found;
    wall += r.wall_s;
    if (r.status == "completed") {
      ++summary.completed;
      if (!r.quality.known) ++quality_unknown;
      if (completed_with_strained_blocks(r)) {
        ++summary.completed_with_strained_blocks;
        strained.push_back({{"index", index},
                            {"max_block_strain", r.quality.max_block_strain},
                            {"max_aperture_m", r.quality.max_aperture_m},
                            {"final_injection_pressure_Pa", r.quality.final_injection_pressure_Pa}});
      }
    } else {
      ++summary.failed;
      failures.push_back({{"index", index}, {"time_s", r.time_s}, {"message", r.message}});
    }
  }
  for (long i = 0; i < first.realisations; ++i)
    if (!by_index.count(i)) summary.missing.push_back(i);
  const json schedule = schedule_summary(by_index);
  std::vector<std::vector<ConvergencePoint>> convergence;
  for (std::size_t t = 0; t < first.map_times_s.size(); ++t)
    convergence.push_back(grid_convergence(all, first.grid, static_cast<int>(t)));
  fs::create_directories(out_dir);
  write_likelihood_maps(out_dir, maps, segments, convergence);
  if (fs::absolute(out_dir).lexically_normal() != fs::absolute(dirs.front()).lexically_normal())
    write_joint_geometry(out_dir + "/ensemble_joints.csv", segments);

  json s{{"case_file", first.case_file},
         {"case_hash", first.case_hash},
         {"master_seed", first.master_seed},
         {"realisations_requested", summary.requested},
         {"records_found", summary.found},
         {"completed", summary.completed},
         {"failed", summary.failed},
         {"missing", summary.missing.size()},
         {"failures", failures},
         {"plausibility",
          {{"step_strain_limit", kImplausibleStepStrain},
           {"completed_with_strained_blocks", summary.completed_with_strained_blocks},
           {"completed_quality_unknown", quality_unknown},
           {"strained", strained}}},
         {"wall_s_total", wall},
         {"wall_s_per_realisation", summary.found ? wall / summary.found : 0.0},
         {"peak_memory_mb_per_process", peak_memory_mb},
         {"schedule", schedule},
         {"sources", dirs}};
  json& per_time = s["maps"];
  per_time = json::array();
  for (std::size_t t = 0; t < first.map_times_s.size(); ++t)
    per_time.push_back({{"time_s", first.map_times_s[t]}, {"realisations", maps.realisations_at(static_cast<int>(t))}});
  io::write_file_atomically(out_dir + "/ensemble_summary.json", s.dump(2) + "\n");
  return summary;
}

}  // namespace hfdda::ensemble
