// Monte Carlo ensembles (seed 5.5, 5.6; W. E. Morgan, PhD dissertation, Georgia Institute
// of Technology, 2014, Figures 5.20-5.44). Each variant is a whole ensemble, run by the
// CLI (`hfdda ensemble`, under `mpirun -n <ranks>` when the variant has ranks > 1 and
// mpirun is installed) into runs/<variant>/; the metrics read its likelihood maps and
// summary at the last map time: band half-widths across y (the minimum-stress direction)
// and along x, expected open and invaded areas, per-joint likelihoods for comparisons,
// realisation counts and times. Checks and their reasons are in study.yaml.

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "harness.hpp"

namespace hfdda::verification {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `args` (no shell), its exit code; -1 if it could not be started.
int run_program(const std::vector<std::string>& args) {
  std::vector<char*> c_args;
  std::vector<std::string> copy = args;
  for (std::string& a : copy) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    execvp(c_args[0], c_args.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (!dir.empty() && access((dir + "/" + program).c_str(), X_OK) == 0) return true;
  return false;
}

/// Processes an ensemble variant runs on: its `ranks` (default 2) when mpirun is there.
int processes_of(const VariantSpec& v) {
  const int ranks = v.has("ranks") ? static_cast<int>(v.number("ranks")) : 2;
  return ranks > 1 && on_path("mpirun") ? ranks : 1;
}

/// The ensemble of the variant, by the CLI next to this runner. The ensemble completes
/// when every realisation has a record (failed ones included: they are counted).
void run_ensemble(VariantRun& r, const std::string& case_path, const std::string& run_dir) {
  const VariantSpec& v = *r.variant;
  const int processes = processes_of(v);
  std::error_code ec;
  const fs::path hfdda = fs::read_symlink("/proc/self/exe", ec).parent_path() / "hfdda";
  std::vector<std::string> args;
  if (processes > 1) {
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);  // CI containers run as root
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 0);  // containers forbid cross-memory attach
    args = {"mpirun", "--oversubscribe", "-n", std::to_string(processes)};
  } else if (v.has("ranks") && v.number("ranks") > 1) {
    r.note("mpirun not found: one process");
  }
  // --force: a verification run starts afresh (a resumed ensemble would report the wall
  // time of its missing realisations only, and could hold records of an older build).
  for (const std::string& a : {hfdda.string(), std::string("ensemble"), case_path, std::string("--out"), run_dir,
                               std::string("--no-figures"), std::string("--quiet"), std::string("--force")})
    args.push_back(a);
  const auto start = std::chrono::steady_clock::now();
  const int code = run_program(args);
  r.run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.built = true;
  r.completed = code == 0;
  if (code != 0) r.note("hfdda ensemble exited with " + std::to_string(code));
}

/// Rows of a likelihood CSV at its last map time: column name -> values, in file order.
struct LastTime {
  double time_s = kNaN;
  std::map<std::string, std::vector<double>> columns;
  std::size_t rows() const { return columns.empty() ? 0 : columns.begin()->second.size(); }
};

LastTime read_last_time(const std::string& path) {
  LastTime t;
  std::istringstream in(read_text(path));
  std::string line;
  if (!std::getline(in, line)) return t;
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::vector<std::vector<double>> rows;
  double last = -std::numeric_limits<double>::infinity();
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::strtod(cell.c_str(), nullptr));
    if (row.size() != names.size()) continue;
    if (row[0] > last) last = row[0], rows.clear();
    if (row[0] == last) rows.push_back(std::move(row));
  }
  t.time_s = last;
  for (std::size_t c = 0; c < names.size(); ++c)
    for (const auto& row : rows) t.columns[names[c]].push_back(row[c]);
  return t;
}

/// Largest |coordinate| + half a cell over the cells whose `column` exceeds `level`
/// (0 when none does): how far the band reaches from the injection point.
double half_width(const LastTime& grid, const std::string& column, double level, const char* axis, double cell_m) {
  double reach = 0.0;
  const auto& p = grid.columns.at(column);
  const auto& c = grid.columns.at(axis);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p[i] > level) reach = std::max(reach, std::abs(c[i]) + 0.5 * cell_m);
  return reach;
}

Metrics variant_metrics(const VariantRun& r) {
  Metrics m;
  const std::string dir = r.out_dir + "/runs/" + r.variant->name;
  const int processes = processes_of(*r.variant);
  m.numbers["processes"] = processes;
  m.numbers["wall_s"] = r.run.wall_seconds;
  if (!r.built || !fs::exists(dir + "/ensemble_summary.json")) return m;
  const nlohmann::json s = nlohmann::json::parse(read_text(dir + "/ensemble_summary.json"));
  const double requested = s.at("realisations_requested"), completed = s.at("completed"), failed = s.at("failed");
  const double per_realisation = s.at("wall_s_per_realisation");
  m.numbers["realisations"] = requested;
  m.numbers["realisations_completed"] = completed;
  m.numbers["realisations_failed"] = failed;
  m.numbers["completed_fraction"] = requested > 0 ? completed / requested : kNaN;
  m.numbers["records_missing"] = s.at("missing");
  // Completed runs that passed the solver's guards with blocks strained by percents;
  // NaN for summaries written before it was counted.
  m.numbers["completed_with_strained_blocks"] =
      s.contains("plausibility") ? double(s.at("plausibility").at("completed_with_strained_blocks")) : kNaN;
  m.numbers["wall_s_per_realisation"] = per_realisation;
  m.numbers["peak_memory_mb_per_process"] = s.value("peak_memory_mb_per_process", 0.0);
  // Busy time of the realisations over the processes' elapsed time.
  m.numbers["parallel_efficiency"] =
      r.run.wall_seconds > 0 ? double(s.at("wall_s_total")) / (processes * r.run.wall_seconds) : kNaN;
  // Where the rest of processes x elapsed went (ensemble_run.cpp, schedule_summary).
  for (const char* key : {"waited_for_index_s", "longest_wait_s", "idle_at_end_s", "outside_realisations_s"})
    m.numbers[key] = kNaN;  // unless every record of this run says when and where it ran
  if (s.contains("schedule") && s.at("schedule").at("realisations_timed") == requested) {
    const nlohmann::json& at = s.at("schedule");
    m.numbers["waited_for_index_s"] = at.at("waited_for_index_s");
    m.numbers["longest_wait_s"] = at.at("longest_wait_s");
    m.numbers["idle_at_end_s"] = at.at("idle_at_end_s");
    m.numbers["outside_realisations_s"] = processes * r.run.wall_seconds - double(at.at("busy_s")) -
                                          double(at.at("waited_for_index_s")) - double(at.at("idle_at_end_s"));
  }
  m.json["failures"] = s.at("failures");

  const nlohmann::json manifest = nlohmann::json::parse(read_text(dir + "/ensemble.json"));
  const double cell = manifest.at("grid").at("cell_m");
  const LastTime grid = read_last_time(dir + "/likelihood_grid.csv");
  if (grid.rows() == 0) return m;
  m.numbers["map_time_s"] = grid.time_s;
  m.numbers["realisations_at_map_time"] = grid.columns.at("realisations").front();
  for (const char* field : {"p_open", "p_wet"}) {
    const std::string kind = std::string(field) == "p_open" ? "open" : "wet";
    for (double level : {0.25, 0.5}) {
      const std::string pct = level == 0.25 ? "25" : "50";
      m.numbers[kind + "_halfwidth_y_" + pct + "_m"] = half_width(grid, field, level, "y_centre", cell);
      m.numbers[kind + "_halfwidth_x_" + pct + "_m"] = half_width(grid, field, level, "x_centre", cell);
    }
    double area = 0.0;
    for (double p : grid.columns.at(field)) area += p * cell * cell;
    m.numbers[kind + "_expected_area_m2"] = area;  // sum over cells of likelihood x cell area
  }
  char line[200];
  std::snprintf(line, sizeof line, "%.0f/%.0f completed, %.1f s each; >25 %% open band +-%.0f m across y, "
                "+-%.0f m along x; >50 %% wet +-%.0f m across y",
                completed, requested, per_realisation, m.numbers["open_halfwidth_y_25_m"],
                m.numbers["open_halfwidth_x_25_m"], m.numbers["wet_halfwidth_y_50_m"]);
  m.summary = line;
  return m;
}

/// Per-joint open likelihood at the last map time: joint id -> (p, length).
std::map<long, std::pair<double, double>> joint_likelihoods(const std::string& dir) {
  const LastTime t = read_last_time(dir + "/likelihood_joints.csv");
  std::map<long, std::pair<double, double>> out;
  if (t.rows() == 0) return out;
  const auto &id = t.columns.at("joint"), &p = t.columns.at("p_open");
  const auto &x1 = t.columns.at("x1"), &y1 = t.columns.at("y1"), &x2 = t.columns.at("x2"), &y2 = t.columns.at("y2");
  for (std::size_t i = 0; i < id.size(); ++i)
    out[std::lround(id[i])] = {p[i], std::hypot(x2[i] - x1[i], y2[i] - y1[i])};
  return out;
}

/// Length-weighted distance of two per-joint likelihood maps on one mesh:
/// sum |pa - pb| L / sum max(pa, pb) L (0: the same map, 1: disjoint); NaN if both empty.
double likelihood_distance(const std::string& a_dir, const std::string& b_dir) {
  const auto a = joint_likelihoods(a_dir), b = joint_likelihoods(b_dir);
  double diff = 0.0, total = 0.0;
  auto add = [&](double pa, double pb, double length) {
    diff += std::abs(pa - pb) * length;
    total += std::max(pa, pb) * length;
  };
  for (const auto& [id, pl] : a) {
    const auto it = b.find(id);
    add(pl.first, it == b.end() ? 0.0 : it->second.first, pl.second);
  }
  for (const auto& [id, pl] : b)
    if (!a.count(id)) add(0.0, pl.first, pl.second);
  return total > 0.0 ? diff / total : kNaN;
}

void study_metrics(StudyOutcome& st) {
  auto dir_of = [&](const VariantOutcome* v) { return v->run.out_dir + "/runs/" + v->variant().name; };
  auto number = [](const VariantOutcome* v, const std::string& name) {
    if (!v) return kNaN;
    const auto it = v->metrics.numbers.find(name);
    return it == v->metrics.numbers.end() ? kNaN : it->second;
  };
  // Rank invariance: the same maps, byte for byte, from one process and from two ranks.
  const VariantOutcome *one = st.find("tiny_1"), *two = st.find("tiny_2");
  if (one && two) {
    bool same = one->run.completed && two->run.completed;
    for (const char* name : {"likelihood_joints.csv", "likelihood_grid.csv", "likelihood_convergence.csv"})
      same = same && read_text(dir_of(one) + "/" + name) == read_text(dir_of(two) + "/" + name) &&
             !read_text(dir_of(one) + "/" + name).empty();
    st.metrics.numbers["maps_identical_1_and_2_ranks"] = same ? 1.0 : 0.0;
  }
  // Each study comes in two sizes: the full tier's few realisations (suffix _few) and
  // the ensemble tier's 50; compare whichever ran.
  auto find = [&](const std::string& name) {
    const VariantOutcome* v = st.find(name + "_few");
    return v ? v : st.find(name);
  };
  const VariantOutcome *s0 = find("s55_s0"), *s12 = find("s55_s12");
  const VariantOutcome *held = find("s55_fluid_held"), *all = find("s55_fluid_all");
  const VariantOutcome *m_base = find("s56_base"), *m_mu = find("s56_mu1000");
  auto set = [&](const std::string& name, double value) {
    st.metrics.numbers[name] = value;
    st.metrics.json[name] = finite_or_null(value);
  };
  if (s0 && s12)
    set("s55_open_halfwidth_y_25_s0_minus_s12_m",
        number(s0, "open_halfwidth_y_25_m") - number(s12, "open_halfwidth_y_25_m"));
  if (s0 && s12 && held && all) {
    const double stress = likelihood_distance(dir_of(s0), dir_of(s12));
    const double fluid = likelihood_distance(dir_of(held), dir_of(all));
    set("s55_distance_stress", stress);
    set("s55_distance_fluid", fluid);
    set("s55_distance_fluid_minus_stress", fluid - stress);
  }
  if (m_base) {
    const double open50 = number(m_base, "open_halfwidth_y_50_m"), wet50 = number(m_base, "wet_halfwidth_y_50_m");
    set("s56_open_halfwidth_y_50_m", open50);
    set("s56_wet_over_open_halfwidth_y_50", open50 > 0 ? wet50 / open50 : kNaN);
  }
  if (m_base && m_mu)
    set("s56_wet_area_mu1000_minus_base_m2",
        number(m_mu, "wet_expected_area_m2") - number(m_base, "wet_expected_area_m2"));
  // One table of every band width for the report.
  std::ostringstream table;
  table << "variant,realisations,completed,failed,wall_s,s_per_realisation,open_y25,open_x25,open_y50,open_x50,"
           "wet_y25,wet_x25,wet_y50,wet_x50,open_area_m2,wet_area_m2\n";
  for (const VariantOutcome& o : st.variants) {
    table << o.variant().name;
    for (const char* k : {"realisations", "realisations_completed", "realisations_failed", "wall_s",
                          "wall_s_per_realisation", "open_halfwidth_y_25_m", "open_halfwidth_x_25_m",
                          "open_halfwidth_y_50_m", "open_halfwidth_x_50_m", "wet_halfwidth_y_25_m",
                          "wet_halfwidth_x_25_m", "wet_halfwidth_y_50_m", "wet_halfwidth_x_50_m",
                          "open_expected_area_m2", "wet_expected_area_m2"})
      table << "," << number(&o, k);
    table << "\n";
  }
  st.metrics.files["ensembles.csv"] = table.str();
}

}  // namespace

CaseDefinition case_definition() {
  CaseDefinition d;
  d.metrics = variant_metrics;
  d.study_metrics = study_metrics;
  d.run = run_ensemble;
  d.variants_share_cores = false;  // its variants run MPI ranks and time their speed-up
  return d;
}

}  // namespace hfdda::verification
