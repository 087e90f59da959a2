// Network scaling: time per coupled hydro-mechanical step against the number of wetted
// nodes, from about 100 to about 10,000, on a family of fracture networks already full
// of fluid, with the flow Newton's Jacobian dense, or S applied as an operator and the
// Newton steps solved by GMRES (krylov) or by a sparse LU of the augmented system
// (augmented).
//
// The network. The stochastic generator (fracture_sets) cannot start its fractures open
// and full of fluid (no fluid_filled key; its fractures take in fluid through w0 only once
// a neighbour is pressurised), so the family is a regular set of crossing fractures of
// the case file's `fractures` list, each initially open and fluid-filled: a "fishbone"
// tree on a structured mesh of 1 m cells, a vertical trunk through the centre crossed by
// `ribs` horizontal ribs 8 m apart, each rib crossed every 2 m by a 4 m branch. The
// domain grows with the number of ribs (inner square of half-width 4 ribs + 4 m), so the
// network keeps its density; wetted nodes = 24 ribs^2 + 1 (97 at 2 ribs, 10,585 at 21).
// A tree, not a grid: a grid of open fractures cuts the rock into islands held by nothing
// but their inertia, and the first step of a 225-node grid (5 x 5 lines 4 m apart, the
// settings below) stopped with the flow Newton not converged.
// The fluid starts at 0.1 MPa in the volume that pressure opens (initial_opening:
// elastic: the rock brought to equilibrium with it before t = 0, docs/design_notes.md
// section 31), so that no node starts at the corner of the rounded pressure max(y, 0)
// (section 19) and the timed steps are steps of a network in equilibrium with its
// fluid. Earlier starts: from the minimum width at zero pressure, the first step of the
// 385-node network took 1,654 Newton iterations and a cut, and that of the 1,177-node
// one had not ended after 13 minutes of CPU time; from joints 100 um wide at 0.1 MPa
// (wider than the rock holds them at that pressure), the first dozen steps squeezed the
// fluid out under the closing limit (217 nodes: 261, 468, 203 Newton iterations in
// steps 1-3 against 99, 22, 44 from the elastic start, 4-20 in later steps of either),
// and no size from 1,000 nodes finished its first steps within the cap. Joints are unbreakable, so the network, and
// with it the wetted-node count, does not change during the timed steps. Penalty
// contacts: with the augmented Lagrangian the 385-node network (minimum-width start)
// stopped in step 1 on the ALM iteration limit. No far-field stress: with 5 MPa in situ
// and the fluid at 5 MPa the flow Newton took 1,500 to 4,600 iterations per step at 97
// nodes.
//
// Two variants of the same networks (argument conjugate_frictionless). 0: the case as a
// user writes it, with the seed's integrated face load and the default friction of 30
// degrees. 1 ("-cf" paths): the fluid's face load lumped at the joint ends
// (numerics.fluid_load: lumped, the load work-conjugate to the lumped nodal volumes,
// docs/design_notes.md section 19) and frictionless faces (friction_angle: 0). Why: from
// 865 wetted nodes on, the first variant's flow Newton meets the fold of the
// non-conjugate pair (section 19), and from 1,177 nodes the steps before t = 0 do not
// settle: under the constant initial pressure, sliding contacts at the branches'
// junctions wind their normal forces up through friction (section 31). Neither is a cost
// of the coupled step; the -cf variant measures that cost where the iteration counts do
// not grow with those two defects, and the first variant shows where they stop it.
//
// Per size: one untimed warm-up step (the injection starts, contacts settle), then
// --timed_steps steps timed one by one (wall and process CPU time), then one
// factorisation of K (assemble_and_factorise on the last step's contact states) timed
// separately, the median of three. Counters per step: Newton iterations, Krylov
// iterations and products with S (krylov path; they cover the last attempt of a step
// that was cut), open-close iterations, factorisations; peak resident memory of the
// process that ran the size.
//
// Each size runs in a child process (fork), so that a size that takes too long can be
// stopped and its memory is its own: the child reports each phase (build, warm-up, each
// timed step) and the parent kills it once a phase has used more than --step_cap_s of
// CPU time (default 120 s; CPU time, because a busy neighbour on the shared machine
// stretches wall time), or 10 times that in wall time. The size is then reported as an
// error, and the larger sizes of the same path are not started. Peak memory is the
// child's ru_maxrss (wait4). With --trace_dir=DIR each size also writes its progress as
// it goes (DIR/trace_<path>_<ribs>.csv, class ProgressTrace), for a step that does not end
// within the cap.

#include "bench_support.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "simulation/model.hpp"

namespace {

using namespace hfdda;

/// numerics.flow_jacobian of each path, by the benchmark argument `jacobian`.
constexpr const char* kJacobianNames[] = {"dense", "krylov", "augmented"};
constexpr int kRibSpacingM = 8;     // distance between ribs
constexpr int kBranchSpacingM = 2;  // distance between branches along a rib
constexpr int kBranchHalfM = 2;     // half-length of a branch (< half the rib spacing: no cycles)
constexpr int kWarmUpSteps = 1;
constexpr int kFactorisationRepeats = 3;

struct Settings {
  double step_cap_s = 120.0;  // CPU seconds one phase (build, a step) may use
  int timed_steps = 2;
  std::string trace_dir;      // non-empty: each size writes its progress trace there
};
Settings settings;

/// Wetted nodes of the fishbone network with `ribs` ribs (all joints 1 m).
int expected_wetted_nodes(int ribs) { return 24 * ribs * ribs + 1; }

/// The case file of the network with `ribs` ribs (see the file comment).
std::string network_case(int ribs, int jacobian, bool conjugate_frictionless) {
  const int half_height = 4 * ribs;        // trunk and ribs reach +-4 ribs m
  const int inner = half_height + 4;       // inner (1 m cells) half-width
  const int outer = 2 * inner;             // coarser outer ring
  std::ostringstream yaml;
  const std::string fill = std::string("initially_open: true, fluid_filled: true, initial_opening: elastic, "
                                       "initial_pressure: 1.0e5") + (conjugate_frictionless ? ", friction_angle: 0" : "");
  auto fracture = [&](const std::string& name, int x0, int y0, int x1, int y1) {
    yaml << "  - {name: " << name << ", from: [" << x0 << ", " << y0 << "], to: [" << x1 << ", " << y1 << "], "
         << fill << "}\n";
  };
  yaml << "title: \"fishbone network, " << ribs << " ribs, " << expected_wetted_nodes(ribs) << " wetted nodes\"\n"
       << "domain:\n"
       << "  outer: {xmin: " << -outer << ", xmax: " << outer << ", ymin: " << -outer << ", ymax: " << outer << "}\n"
       << "  inner: {xmin: " << -inner << ", xmax: " << inner << ", ymin: " << -inner << ", ymax: " << inner << "}\n"
       << "mesh: {type: structured, cell_size: 1.0, outer_growth: 1.3, split: two}\n"
       << "materials:\n"
       << "  - {name: rock, youngs_modulus: 10.0e9, poissons_ratio: 0.22, density: 2650}\n"
       << "joints: {breakable: false}\n"
       << "fractures:\n";
  fracture("trunk", 0, -half_height, 0, half_height);
  for (int r = 0; r < ribs; ++r) {
    const int y = (2 * r - (ribs - 1)) * kRibSpacingM / 2;
    fracture("rib" + std::to_string(r), -half_height, y, half_height, y);
    for (int x = kBranchSpacingM; x < half_height; x += kBranchSpacingM)
      for (int side : {-1, 1})
        fracture("branch" + std::to_string(r) + "_" + std::to_string(side * x), side * x, y - kBranchHalfM, side * x,
                 y + kBranchHalfM);
  }
  yaml << "fluid: {density: 1000, bulk_modulus: 2.2e9, viscosity: 1.0e-3}\n"
       << "injections:\n"
       << "  - {at: [0, 0], mass_rate: 0.5}\n"
       << "fixed_points: [[" << -outer << ", " << -outer << "], [" << outer << ", " << -outer << "], [" << outer
       << ", " << outer << "], [" << -outer << ", " << outer << "]]\n"
       << "contact: {method: penalty}\n"
       << "numerics: {flow_jacobian: " << kJacobianNames[jacobian]
       << (conjugate_frictionless ? ", fluid_load: lumped" : "") << "}\n"
       << "time: {dt: 1.0, end_time: " << kWarmUpSteps + settings.timed_steps << ".0}\n"
       << "output: {every_steps: 0, vtu: false}\n";
  return yaml.str();
}

// --- child: runs one size and writes lines to the pipe ----------------------------------
// "P <phase>" at the start of each phase, "R <key> <value>" per result, "E <message>" on
// failure, "D" at the end.

class Reporter {
 public:
  explicit Reporter(int fd) : fd_(fd) {}
  void phase(const std::string& name) { write("P " + name); }
  void result(const std::string& key, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    write("R " + key + " " + buffer);
  }
  void error(std::string message) {
    std::replace(message.begin(), message.end(), '\n', ' ');
    write("E " + message);
  }
  void done() { write("D"); }

 private:
  void write(const std::string& line) {
    const std::string text = line + "\n";
    std::size_t sent = 0;
    while (sent < text.size()) {
      const ssize_t n = ::write(fd_, text.data() + sent, text.size() - sent);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) std::_Exit(3);  // parent gone
      sent += static_cast<std::size_t>(n);
    }
  }
  int fd_;
};

/// Progress of one size as it runs, for a step too long to wait for its counters: one
/// CSV line (flushed) at every check for a stop request, which the coupled step makes
/// before each open-close and contact iteration and the flow solve before each Newton
/// iteration, and one at the end of each open-close iteration and attempt. The
/// coupling's counters change only when a flow solve ends, so the Newton iterations of
/// a solve are the "check" lines between two changes of flow_solves, less the one before
/// the solve. A step cut in sub-steps stops checking once one of them is committed
/// (CoupledStep::interrupt_when), so its later sub-steps show only their iterations.
class ProgressTrace final : public coupling::IterationObserver {
 public:
  ProgressTrace(const std::string& path, const simulation::Model& model) : out_(path), model_(model) {
    if (!out_) throw std::runtime_error("cannot write the progress trace " + path);
    out_ << "cpu_s,wall_s,phase,event,detail,flow_solves,newton_iterations,krylov_iterations,s_products,"
            "inexact_solves,max_nodes\n" << std::flush;
  }
  void set_phase(const std::string& phase) { phase_ = phase; line("phase", ""); }
  void check() { line("check", ""); }
  void iteration(const coupling::IterationRecord& r) override {
    line("open_close", "iteration " + std::to_string(r.iteration) + " dt " + std::to_string(r.attempt_dt_s) +
                           " changes " + std::to_string(r.contact_changes) + "+" +
                           std::to_string(r.coupled_changes) + " first '" + r.first_change + "'");
  }
  void attempt_ended(double dt_s, int iterations, const std::string& refusal) override {
    line("attempt_end", "dt " + std::to_string(dt_s) + " iterations " + std::to_string(iterations) +
                            (refusal.empty() ? " committed" : " refused: " + refusal));
  }

 private:
  void line(const char* event, std::string detail) {
    std::replace(detail.begin(), detail.end(), ',', ';');
    std::replace(detail.begin(), detail.end(), '\n', ' ');
    const auto cpu = bench::ProcessCpu::now();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0_).count();
    const auto& c = model_.coupling->statistics();
    out_ << cpu.user_s + cpu.sys_s << ',' << wall << ',' << phase_ << ',' << event << ',' << detail << ','
         << c.flow_solves << ',' << c.newton_iterations << ',' << c.krylov_iterations << ','
         << c.sensitivity_products << ',' << c.inexact_linear_solves << ',' << c.max_nodes << '\n' << std::flush;
  }
  std::ofstream out_;
  const simulation::Model& model_;
  std::string phase_ = "build";
  const std::chrono::steady_clock::time_point wall0_ = std::chrono::steady_clock::now();
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
}

void run_size(int ribs, int jacobian, bool conjugate_frictionless, Reporter& out) {
  out.phase("building the model");
  const auto build_cpu0 = bench::ProcessCpu::now();
  const io::CaseConfig config =
      io::load_case_text(network_case(ribs, jacobian, conjugate_frictionless), "network_scaling.yaml");
  simulation::Model model = simulation::build_model(config);
  const auto build_cpu = bench::ProcessCpu::now() - build_cpu0;
  std::unique_ptr<ProgressTrace> trace;
  if (!settings.trace_dir.empty()) {
    trace = std::make_unique<ProgressTrace>(settings.trace_dir + "/trace_" + kJacobianNames[jacobian] +
                                                (conjugate_frictionless ? "-cf" : "") + "_" + std::to_string(ribs) +
                                                ".csv",
                                            model);
    model.step->observe_iterations(trace.get());
    model.step->interrupt_when([t = trace.get()] {
      t->check();
      return false;
    });
  }
  auto phase = [&](const std::string& name) {
    out.phase(name);
    if (trace) trace->set_phase(name);
  };
  const double dt_s = config.time.dt_s;
  const int cuts = config.numerics.max_step_cuts;
  const auto warm_up_cpu0 = bench::ProcessCpu::now();
  StepStatistics warm_up;
  for (int s = 0; s < kWarmUpSteps; ++s) {
    phase("warm-up step " + std::to_string(s + 1));
    warm_up.accumulate(model.step->advance(dt_s, cuts));
  }
  const auto warm_up_cpu = bench::ProcessCpu::now() - warm_up_cpu0;
  const int nodes_before = model.flow->n_nodes();

  StepStatistics total;
  double wall_s = 0.0, cpu_s = 0.0, max_step_cpu_s = 0.0;
  long krylov_iterations = 0, sensitivity_products = 0;
  for (int s = 0; s < settings.timed_steps; ++s) {
    phase("timed step " + std::to_string(s + 1));
    const auto cpu0 = bench::ProcessCpu::now();
    const auto wall0 = std::chrono::steady_clock::now();
    total.accumulate(model.step->advance(dt_s, cuts));
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const auto cpu = bench::ProcessCpu::now() - cpu0;
    cpu_s += cpu.user_s + cpu.sys_s;
    max_step_cpu_s = std::max(max_step_cpu_s, cpu.user_s + cpu.sys_s);
    // The coupling's counters cover the step's last attempt (reset by each begin_step).
    krylov_iterations += model.coupling->statistics().krylov_iterations;
    sensitivity_products += model.coupling->statistics().sensitivity_products;
  }

  // One factorisation of K on the contact states the last step ended with.
  phase("factorisation of K");
  std::vector<double> factorise_wall_s, factorise_cpu_s, factorisation_only_s;
  for (int r = 0; r < kFactorisationRepeats; ++r) {
    StepStatistics stats;
    const auto cpu0 = bench::ProcessCpu::now();
    const auto wall0 = std::chrono::steady_clock::now();
    model.system->assemble_and_factorise(stats);
    factorise_wall_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
    const auto cpu = bench::ProcessCpu::now() - cpu0;  // all threads, as for the steps
    factorise_cpu_s.push_back(cpu.user_s + cpu.sys_s);
    factorisation_only_s.push_back(stats.seconds_factorization);
  }

  const int steps = settings.timed_steps;
  out.result("build_cpu_s", build_cpu.user_s + build_cpu.sys_s);
  out.result("warm_up_cpu_s", (warm_up_cpu.user_s + warm_up_cpu.sys_s) / kWarmUpSteps);
  out.result("warm_up_newton_per_step", double(warm_up.flow_newton_iterations) / kWarmUpSteps);
  out.result("wetted_nodes", model.flow->n_nodes());
  out.result("wetted_nodes_after_warm_up", nodes_before);
  out.result("blocks", model.system->n_blocks());
  out.result("steps", steps);
  out.result("step_s", wall_s / steps);
  out.result("step_cpu_s", cpu_s / steps);
  out.result("max_step_cpu_s", max_step_cpu_s);
  out.result("factorize_s", median(factorise_wall_s));
  out.result("factorize_cpu_s", median(factorise_cpu_s));
  out.result("factorization_only_s", median(factorisation_only_s));
  out.result("newton_per_step", double(total.flow_newton_iterations) / steps);
  out.result("krylov_per_step", double(krylov_iterations) / steps);
  out.result("s_products_per_step", double(sensitivity_products) / steps);
  out.result("flow_solves_per_step", double(total.flow_solves) / steps);
  out.result("outer_per_step", double(total.open_close_iterations) / steps);
  out.result("factorizations_per_step", double(total.factorizations) / steps);
  out.result("step_cuts", total.step_cuts);
  out.result("sensitivity_s_per_step", total.seconds_sensitivity / steps);
  out.result("flow_s_per_step", total.seconds_flow / steps);
}

[[noreturn]] void child_main(int ribs, int jacobian, bool conjugate_frictionless, int fd) {
  Reporter out(fd);
  try {
    run_size(ribs, jacobian, conjugate_frictionless, out);
    out.done();
  } catch (const std::exception& e) {
    out.error(e.what());
  }
  ::close(fd);
  std::_Exit(0);  // no destructors of the parent's objects, no benchmark output
}

// --- parent: watches the child --------------------------------------------------------

/// User + system CPU time of a running process [s] (/proc/PID/stat fields 14 and 15).
double process_cpu_s(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');  // the command name may hold spaces
  if (close == std::string::npos) return 0.0;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  return double(utime + stime) / double(sysconf(_SC_CLK_TCK));
}

struct ChildOutcome {
  std::map<std::string, double> results;
  std::string error;       // empty: completed
  bool capped = false;     // killed at the time cap
  double peak_rss_mb = 0;  // ru_maxrss of the child
};

ChildOutcome run_in_child(int ribs, int jacobian, bool conjugate_frictionless) {
  ChildOutcome outcome;
  int fds[2];
  if (pipe(fds) != 0) {
    outcome.error = std::string("pipe: ") + std::strerror(errno);
    return outcome;
  }
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    outcome.error = std::string("fork: ") + std::strerror(errno);
    return outcome;
  }
  if (pid == 0) {
    ::close(fds[0]);
    child_main(ribs, jacobian, conjugate_frictionless, fds[1]);
  }
  ::close(fds[1]);

  std::string phase = "starting", pending;
  bool done = false, eof = false;
  double phase_cpu0 = 0.0;
  auto phase_wall0 = std::chrono::steady_clock::now();
  while (!eof) {
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, 200);
    if (ready > 0) {
      char buffer[4096];
      const ssize_t n = read(fds[0], buffer, sizeof buffer);
      if (n <= 0) {
        eof = true;
      } else {
        pending.append(buffer, static_cast<std::size_t>(n));
        for (auto newline = pending.find('\n'); newline != std::string::npos; newline = pending.find('\n')) {
          const std::string line = pending.substr(0, newline);
          pending.erase(0, newline + 1);
          if (line.rfind("P ", 0) == 0) {
            phase = line.substr(2);
            phase_cpu0 = process_cpu_s(pid);
            phase_wall0 = std::chrono::steady_clock::now();
          } else if (line.rfind("R ", 0) == 0) {
            std::istringstream fields(line.substr(2));
            std::string key;
            double value = 0.0;
            fields >> key >> value;
            outcome.results[key] = value;
          } else if (line.rfind("E ", 0) == 0) {
            outcome.error = phase + " failed: " + line.substr(2);
          } else if (line == "D") {
            done = true;
          }
        }
      }
    } else if (ready < 0 && errno != EINTR) {
      eof = true;
    }
    const double phase_cpu = process_cpu_s(pid) - phase_cpu0;
    const double phase_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - phase_wall0).count();
    if (!eof && (phase_cpu > settings.step_cap_s || phase_wall > 10.0 * settings.step_cap_s)) {
      kill(pid, SIGKILL);
      char message[256];
      std::snprintf(message, sizeof message,
                    "over the time cap: %s used %.0f s CPU (%.0f s wall), cap %.0f s CPU per phase; stopped",
                    phase.c_str(), phase_cpu, phase_wall, settings.step_cap_s);
      outcome.error = message;  // the peak memory until the stop is added below
      outcome.capped = true;
      break;
    }
  }
  ::close(fds[0]);
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  outcome.peak_rss_mb = double(usage.ru_maxrss) / 1024.0;  // kB on Linux
  if (outcome.capped)
    outcome.error += " (peak resident memory until then " + std::to_string(std::lround(outcome.peak_rss_mb)) + " MB)";
  if (outcome.error.empty() && !done) {
    outcome.error = phase + ": the child process ended without results (" +
                    (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                         : "exit " + std::to_string(WEXITSTATUS(status))) + ")";
  }
  return outcome;
}

// Per path (jacobian, conjugate_frictionless), the smallest size that went over the cap:
// larger ones are not started.
std::map<std::pair<int, bool>, int> capped_at;

// range(0): ribs; range(1): the flow Jacobian, index into kJacobianNames (0 dense,
// 1 krylov, 2 augmented); range(2): 1 for the lumped face load and frictionless faces
// (see the file comment).
void BM_NetworkScaling(benchmark::State& state) {
  const int ribs = static_cast<int>(state.range(0));
  const int jacobian = static_cast<int>(state.range(1));
  const bool conjugate_frictionless = state.range(2) != 0;
  const std::pair<int, bool> path{jacobian, conjugate_frictionless};
  state.SetLabel(std::string(kJacobianNames[jacobian]) + (conjugate_frictionless ? "-cf" : ""));
  state.counters["ribs"] = ribs;
  state.counters["expected_wetted_nodes"] = expected_wetted_nodes(ribs);
  state.counters["step_cap_s"] = settings.step_cap_s;
  for (auto _ : state) {
    if (capped_at.count(path) && ribs > capped_at[path]) {
      state.SkipWithError(("not run: over the time cap at a smaller size (" + std::to_string(capped_at[path]) +
                           " ribs, " + std::to_string(expected_wetted_nodes(capped_at[path])) + " wetted nodes)")
                              .c_str());
      break;
    }
    const ChildOutcome outcome = run_in_child(ribs, jacobian, conjugate_frictionless);
    state.counters["peak_rss_mb"] = outcome.peak_rss_mb;
    if (!outcome.error.empty()) {
      if (outcome.capped) capped_at[path] = ribs;
      state.SkipWithError(outcome.error.c_str());
      break;
    }
    for (const auto& [key, value] : outcome.results) state.counters[key] = value;
    // The ratio in CPU time, which a busy neighbour on the shared machine stretches least.
    state.counters["step_over_factorize"] = outcome.results.at("step_cpu_s") / outcome.results.at("factorize_cpu_s");
    state.SetIterationTime(outcome.results.at("step_s"));  // the real-time column: wall time per timed step
  }
}

/// Removes --step_cap_s=X, --timed_steps=N and --trace_dir=DIR from the command line
/// (the benchmark library refuses flags it does not know).
bool take_own_flags(int* argc, char** argv) {
  int kept = 1;
  for (int i = 1; i < *argc; ++i) {
    const std::string arg = argv[i];
    auto value_of = [&](const char* flag) -> const char* {
      const std::size_t n = std::strlen(flag);
      return arg.compare(0, n, flag) == 0 ? argv[i] + n : nullptr;
    };
    if (const char* v = value_of("--step_cap_s=")) {
      settings.step_cap_s = std::atof(v);
      if (!(settings.step_cap_s > 0)) return false;
    } else if (const char* v = value_of("--trace_dir=")) {
      settings.trace_dir = v;
      if (settings.trace_dir.empty()) return false;
    } else if (const char* v = value_of("--timed_steps=")) {
      settings.timed_steps = std::atoi(v);
      if (settings.timed_steps < 1) return false;
    } else {
      argv[kept++] = argv[i];
    }
  }
  *argc = kept;
  argv[kept] = nullptr;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (!take_own_flags(&argc, argv)) {
    std::fprintf(stderr, "bench_network_scaling: --step_cap_s needs a number > 0, "
                         "--timed_steps a whole number >= 1, --trace_dir a directory\n");
    return 2;
  }
  hfdda::bench::initialize(&argc, argv);
  char cap[32];
  std::snprintf(cap, sizeof cap, "%g", settings.step_cap_s);
  benchmark::AddCustomContext("step_cap_s", cap);
  benchmark::AddCustomContext("timed_steps", std::to_string(settings.timed_steps));
  // 2 to 21 ribs: 97 to 10,585 wetted nodes; per variant the dense path first, sizes in
  // increasing order.
  const std::vector<int> ribs = {2, 3, 4, 5, 6, 7, 9, 11, 14, 17, 21};
  auto* bench = benchmark::RegisterBenchmark("BM_NetworkScaling", BM_NetworkScaling);
  for (int conjugate_frictionless : {0, 1})
    for (int jacobian : {0, 1, 2})
      for (int r : ribs) bench->Args({r, jacobian, conjugate_frictionless});
  bench->ArgNames({"ribs", "jacobian", "conjugate_frictionless"})->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
