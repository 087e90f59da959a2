// hfdda: command-line front end.
//   hfdda run CASE.yaml --out DIR [--quiet] [--threads N] [--checkpoint-every N] [--trace-iterations] [--force | --restart]
//   hfdda check CASE.yaml                      validate the case and build its mesh
//   hfdda plot DIR [--times ...] [--out ...]   figures of a run directory (hfdda_plot.py)
//   hfdda network CASE.yaml --out DIR [--force] [--no-figure]
//                                              the case's generated fracture network
//   [mpirun -n N] hfdda ensemble CASE.yaml --out DIR [...]   Monte Carlo realisations and
//   hfdda ensemble merge --out DIR SOURCES...                their likelihood maps
// Exit codes: 0 success, 1 the run stopped (no convergence), 2 bad input or usage,
// 3 stopped by SIGINT/SIGTERM after a step, with a checkpoint to restart from.

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"
#include "cli/ensemble_command.hpp"
#include "core/errors.hpp"
#include "core/memory_policy.hpp"
#include "dda/thread_policy.hpp"
#include "io/case_config.hpp"
#include "simulation/checkpoint.hpp"
#include "simulation/model.hpp"
#include "simulation/network_outputs.hpp"
#include "simulation/run.hpp"

namespace {

constexpr const char* kUsage =
    "usage: hfdda run CASE.yaml --out DIR [--quiet] [--threads N] [--checkpoint-every N] [--trace-iterations] [--force | --restart]\n"
    "       hfdda check CASE.yaml\n"
    "       hfdda plot DIR [--times T1,T2,...] [--out FIGDIR]\n"
    "       hfdda network CASE.yaml --out DIR [--force] [--no-figure]\n"
    "       [mpirun -n N] hfdda ensemble CASE.yaml --out DIR [--shard K/N] ...   (hfdda ensemble --help)\n"
    "       hfdda ensemble merge --out DIR SOURCE_DIR...\n"
    "       hfdda --help | --version\n"
    "\n"
    "run    validates CASE.yaml, builds the mesh and runs the DDA time loop, writing\n"
    "       DIR/summary.json, DIR/history.csv, DIR/joints/*.csv and DIR/vtu/*.vtu (+ .pvd).\n"
    "       Shows progress on a terminal; --quiet shows nothing but errors.\n"
    "       --threads N: threads of the sparse factorisation (default: HFDDA_THREADS, else 1).\n"
    "       A DIR that holds a previous run is refused; --force empties it first.\n"
    "       --checkpoint-every N: write DIR/checkpoint.bin every N steps (default 10; 0: never).\n"
    "       --trace-iterations: also write DIR/iterations.csv, a row per open-close iteration of every\n"
    "       attempt at a step and per attempt's end (committed, or refused and cut, and why).\n"
    "       SIGINT or SIGTERM: the current step is abandoned at its next iteration (finished if a\n"
    "       cut half of it is already committed), a checkpoint of the last finished step written, exit 3.\n"
    "       --restart: continue the run in DIR from its checkpoint (same case file), with\n"
    "       the same results as a run that was never stopped.\n"
    "check  validates CASE.yaml and builds its mesh without writing anything.\n"
    "plot   draws a run directory's fracture map at the output nearest each time (default: the\n"
    "       last: natural fractures thin, open joints thick, closed joints with fluid light) and its\n"
    "       histories (inlet pressure, opened and invaded lengths by joint kind, the fluid mass\n"
    "       ledger), as PNG files in FIGDIR (default DIR/figures).\n"
    "network  builds the mesh of CASE.yaml and grows the natural fractures of its fracture_sets\n"
    "       (seed 5.3), without running anything, and writes DIR/network.csv (joints of each\n"
    "       fracture), DIR/network_fractures.csv, DIR/network_sets.csv, DIR/network.vtu (every\n"
    "       joint with its set) and DIR/network.png (--no-figure: none). A non-empty DIR is\n"
    "       refused; --force empties it first.\n"
    "ensemble  the Monte Carlo realisations of the case's `ensemble` section and their likelihood\n"
    "       maps (docs/ensembles.md); under mpirun the realisations are shared among the ranks.\n"
    "Case-file keys: docs/case_file.md. Exit: 0 ok, 1 run stopped, 2 bad input or unusable DIR,\n"
    "3 interrupted (checkpoint written).\n";

int usage_error(const std::string& message) {
  std::fprintf(stderr, "hfdda: %s\n%s", message.c_str(), kUsage);
  return 2;
}

/// DIR as an absolute path without "." and ".." parts or a trailing separator.
std::filesystem::path absolute_directory(const std::string& dir, std::error_code& ec) {
  std::filesystem::path p = std::filesystem::absolute(dir, ec).lexically_normal();
  if (!p.has_filename() && p.has_relative_path()) p = p.parent_path();
  return p;
}

/// The outermost directory of DIR's path that does not exist yet (empty: none), i.e. what
/// creating DIR would add to the file system.
std::filesystem::path outermost_missing_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path outermost;
  for (fs::path p = absolute_directory(dir, ec); !ec && !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    outermost = p;
    if (p == p.parent_path()) break;
  }
  return outermost;
}

/// Creates DIR (and its parents) and checks that a file can be written in it; the reason
/// if not. On a failed creation `created` is cleared: nothing to take back, or only what
/// the failed call left, which is kept rather than guessed at.
std::string create_writable_directory(const std::string& dir, std::filesystem::path& created) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    created.clear();
    return "cannot create output directory '" + dir + "': " + ec.message();
  }
  const std::string probe = dir + "/.hfdda-write-test." + std::to_string(::getpid());
  std::FILE* file = std::fopen(probe.c_str(), "wb");
  if (file == nullptr) return "output directory '" + dir + "' is not writable: " + std::strerror(errno);
  std::fclose(file);
  std::remove(probe.c_str());
  return {};
}

/// Makes DIR ready for a run; the reason if it cannot be used. A directory holding a
/// previous run is refused unless `force` (then emptied); a restart needs its checkpoint.
/// `created` is set to the outermost directory this call created (empty: none), so that
/// a run that stops before writing anything can leave the file system as it found it.
std::string prepare_output_directory(const std::string& dir, bool force, bool restart, std::filesystem::path& created) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(dir);
  created = outermost_missing_directory(dir);
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) return "output '" + dir + "' exists and is not a directory";
  const std::string checkpoint = hfdda::simulation::checkpoint_path(dir);
  if (restart) {
    if (!fs::is_regular_file(checkpoint, ec)) return "--restart: no checkpoint '" + checkpoint + "'";
    // Temporary files of writes a kill interrupted (io::write_file_atomically's "NAME.tmp.PID").
    for (const auto& entry : fs::recursive_directory_iterator(path, ec))
      if (entry.is_regular_file(ec) && entry.path().filename().string().find(".tmp.") != std::string::npos)
        fs::remove(entry.path(), ec);
  } else if (fs::is_directory(path, ec)) {
    bool previous = false;
    for (const char* name : {"summary.json", "history.csv", "checkpoint.bin", "joints", "vtu", "blocks.pvd"})
      previous = previous || fs::exists(path / name, ec);
    if (previous && !force)
      return "output directory '" + dir +
             "' holds a previous run; give --force to empty it first, or --restart to continue it";
    if (previous)
      for (const auto& entry : fs::directory_iterator(path, ec)) {
        fs::remove_all(entry.path(), ec);
        if (ec) return "cannot empty '" + dir + "': " + entry.path().string() + ": " + ec.message();
      }
  }
  return create_writable_directory(dir, created);
}

/// Takes back the directories prepare_output_directory created, from DIR up to
/// `created`, when the run stops before writing into them. Only empty directories are
/// removed: one that holds anything, or existed before, is left alone.
void remove_created_directories(const std::string& dir, const std::filesystem::path& created) {
  namespace fs = std::filesystem;
  if (created.empty()) return;
  std::error_code ec;
  for (fs::path p = absolute_directory(dir, ec); !ec && !p.empty(); p = p.parent_path()) {
    if (!fs::remove(p, ec) || ec) return;  // fs::remove takes only an empty directory
    if (p == created || p == p.parent_path()) return;
  }
}

bool whole_number(const std::string& value, int min) {
  return !value.empty() && value.find_first_not_of("0123456789") == std::string::npos && value.size() <= 9 &&
         std::stoi(value) >= min;
}

int run_command(int argc, char** argv, bool check_only) {
  std::string case_file, out_dir;
  bool quiet = false, force = false, restart = false, trace_iterations = false;
  int checkpoint_every = 10;
  int threads = hfdda::dda::threads_from_environment();
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) out_dir = argv[++i];
    else if (arg == "--threads" && i + 1 < argc) {
      const std::string value = argv[++i];
      if (!whole_number(value, 1) || value.size() > 4)
        return usage_error("--threads needs a whole number from 1 to 9999 (got '" + value + "')");
      threads = std::stoi(value);
    }
    else if (arg == "--checkpoint-every" && i + 1 < argc) {
      const std::string value = argv[++i];
      if (!whole_number(value, 0)) return usage_error("--checkpoint-every needs a whole number >= 0 (got '" + value + "')");
      checkpoint_every = std::stoi(value);
    }
    else if (arg == "--force") force = true;
    else if (arg == "--trace-iterations") trace_iterations = true;
    else if (arg == "--restart") restart = true;
    else if (arg == "--quiet" || arg == "-q") quiet = true;
    else if (!arg.empty() && arg[0] == '-') return usage_error("unknown option '" + arg + "'");
    else if (case_file.empty()) case_file = arg;
    else return usage_error("more than one case file given");
  }
  if (case_file.empty()) return usage_error("no case file given");
  if (!check_only && out_dir.empty()) return usage_error("run needs --out DIR");
  if (force && restart) return usage_error("--force and --restart exclude each other");
  const std::string thread_note = hfdda::dda::apply_thread_policy(threads);
  const std::string memory_note = hfdda::core::retain_freed_memory();
  if (!quiet && !check_only) std::fprintf(stderr, "%s; %s\n", thread_note.c_str(), memory_note.c_str());

  const hfdda::io::CaseConfig config = hfdda::io::load_case_file(case_file);
  std::filesystem::path created;  // outermost directory made for the outputs (empty: none)
  if (!check_only) {
    // Before the model is built: an unusable DIR is refused without waiting for the mesh.
    const std::string problem = prepare_output_directory(out_dir, force, restart, created);
    if (!problem.empty()) {
      std::fprintf(stderr, "hfdda: %s\n", problem.c_str());
      return 2;
    }
  }
  hfdda::simulation::Model model = [&] {
    try {
      return hfdda::simulation::build_model(config);
    } catch (...) {
      remove_created_directories(out_dir, created);
      throw;
    }
  }();
  const auto& system = *model.system;
  if ((check_only || !quiet) && config.load_ramp)
    std::fprintf(stderr, "%s: %d blocks, %zu joints, %zu points, load ramp (%s), one static step of %g s per level\n",
                 case_file.c_str(), system.n_blocks(), system.mesh().joints.size(), system.mesh().points.size(),
                 config.load_ramp->history.empty() ? "uniform" : "history", config.time.dt_s);
  else if (check_only || !quiet)
    std::fprintf(stderr, "%s: %d blocks, %zu joints, %zu points, %d steps of %g s\n", case_file.c_str(),
                 system.n_blocks(), system.mesh().joints.size(), system.mesh().points.size(),
                 static_cast<int>(config.time.end_time_s / config.time.dt_s + 0.5), config.time.dt_s);
  if (const std::string note = hfdda::simulation::fracture_adjustments_note(config, system.mesh());
      !note.empty() && (check_only || !quiet))
    std::fprintf(stderr, "%s: %s\n", case_file.c_str(), note.c_str());
  if (const std::string note = hfdda::simulation::initial_opening_note(model); !note.empty() && (check_only || !quiet))
    std::fprintf(stderr, "%s: %s\n", case_file.c_str(), note.c_str());
  if (check_only) return 0;

  hfdda::simulation::RunOptions options{out_dir, quiet, true};
  options.checkpoint_every = checkpoint_every;
  options.restart = restart;
  options.trace_iterations = trace_iterations;
  options.stop_requested = hfdda::cli::stop_requested;
  options.abandon_step_requested = hfdda::cli::stop_requested;
  hfdda::cli::catch_stop_signals(
      "\nhfdda: stop requested: the current step is abandoned at its next iteration and a checkpoint of the "
      "last finished step written (signal again to stop at once, keeping the last checkpoint)\n");
  const auto result = hfdda::simulation::run(model, options);
  if (result.interrupted) {
    std::fprintf(stderr, "hfdda: stopped after step %d (t = %g s) on a signal; checkpoint %s\n"
                 "hfdda: continue with: hfdda run %s --out %s --restart\n",
                 result.steps, result.time_s, hfdda::simulation::checkpoint_path(out_dir).c_str(), case_file.c_str(),
                 out_dir.c_str());
    return 3;
  }
  if (!result.completed) {
    std::fprintf(stderr, "hfdda: run stopped at %s\nhfdda: outputs up to t = %g s are in %s\n", result.message.c_str(),
                 result.time_s, out_dir.c_str());
    if (!trace_iterations)
      std::fprintf(stderr, "hfdda: to see how the step's open-close iterations went, run again with --trace-iterations "
                           "(DIR/iterations.csv; `hfdda plot DIR` draws it)\n");
    return 1;
  }
  if (!quiet) {
    std::fprintf(stderr, "done: %d steps in %.2f s (%d factorisations); outputs in %s\n", result.steps,
                 result.wall_seconds, result.totals.factorizations, out_dir.c_str());
    if (result.totals.alm_stalls > 0)
      std::fprintf(stderr,
                   "note: %d contact solves ended as ALM stalls (loops of closed contacts that cannot all close); "
                   "largest gap left %.2g of a contact length (accepted below 1e-6)\n",
                   result.totals.alm_stalls, result.totals.max_alm_stall_mismatch);
  }
  return 0;
}

}  // namespace

/// `hfdda plot DIR [--times ...] [--out ...]`: runs hfdda_plot.py.
int plot_command(int argc, char** argv) {
  if (argc < 3) return usage_error("plot: give the run directory");
  return hfdda::cli::run_python_script("plot", "hfdda_plot.py", std::vector<std::string>(argv + 2, argv + argc));
}

/// Makes DIR ready for `hfdda network`: created if missing; refused if it is not a
/// directory, or holds anything unless `force` (then emptied). The reason if unusable.
std::string prepare_network_directory(const std::string& dir, bool force, std::filesystem::path& created) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(dir);
  created = outermost_missing_directory(dir);
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) return "output '" + dir + "' exists and is not a directory";
  if (fs::is_directory(path, ec) && !fs::is_empty(path, ec)) {
    if (!force) return "output directory '" + dir + "' is not empty; give --force to empty it first";
    for (const auto& entry : fs::directory_iterator(path, ec)) {
      fs::remove_all(entry.path(), ec);
      if (ec) return "cannot empty '" + dir + "': " + entry.path().string() + ": " + ec.message();
    }
  }
  return create_writable_directory(dir, created);
}

/// `hfdda network CASE.yaml --out DIR [--force] [--no-figure]`: the mesh and the generated
/// fracture network of a case, written without building the block system or any fluid.
int network_command(int argc, char** argv) {
  std::string case_file, out_dir;
  bool force = false, figure = true;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) out_dir = argv[++i];
    else if (arg == "--force") force = true;
    else if (arg == "--no-figure") figure = false;
    else if (!arg.empty() && arg[0] == '-') return usage_error("network: unknown option '" + arg + "'");
    else if (case_file.empty()) case_file = arg;
    else return usage_error("network: more than one case file given");
  }
  if (case_file.empty()) return usage_error("network: no case file given");
  if (out_dir.empty()) return usage_error("network needs --out DIR");
  const auto start = std::chrono::steady_clock::now();
  const hfdda::io::CaseConfig config = hfdda::io::load_case_file(case_file);
  if (config.fracture_sets.empty())
    throw hfdda::InputError(case_file, 0, "fracture_sets",
                            "hfdda network needs at least one fracture set (the case has none)");
  std::filesystem::path created;
  const std::string problem = prepare_network_directory(out_dir, force, created);
  if (!problem.empty()) {
    std::fprintf(stderr, "hfdda: %s\n", problem.c_str());
    return 2;
  }
  const hfdda::simulation::FracturedMesh fractured = [&] {
    try {
      return hfdda::simulation::build_fractured_mesh(config);
    } catch (...) {
      remove_created_directories(out_dir, created);
      throw;
    }
  }();
  hfdda::simulation::write_network_outputs(out_dir, config, fractured);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%s: %zu blocks, %zu joints; network seed %d\n", case_file.c_str(),
               fractured.mesh.blocks.size(), fractured.mesh.joints.size(), config.network_seed);
  if (const std::string note = hfdda::simulation::fracture_adjustments_note(config, fractured.mesh); !note.empty())
    std::fprintf(stderr, "%s: %s\n", case_file.c_str(), note.c_str());
  for (std::size_t k = 0; k < config.fracture_sets.size(); ++k) {
    const auto& s = fractured.network.sets[k];
    std::fprintf(stderr,
                 "  set %s (azimuth %g deg): %d candidates, %d seeds (%d on joints already taken), %d fractures "
                 "(%d reached their length), %d joints, %.1f m\n",
                 config.fracture_sets[k].name.c_str(), config.fracture_sets[k].azimuth_deg, s.candidates, s.seeds,
                 s.absorbed_seeds, s.fractures, s.fractures_reaching_target, s.joints, s.total_length_m);
  }
  std::fprintf(stderr, "case, mesh, network and files in %.3f s; files in %s\n", seconds, out_dir.c_str());
  if (!figure) return 0;
  const hfdda::Rect& d = config.domain.outer;
  char domain[160];
  std::snprintf(domain, sizeof domain, "%.17g,%.17g,%.17g,%.17g", d.xmin, d.xmax, d.ymin, d.ymax);
  const std::string title = std::filesystem::path(case_file).filename().string() + ", network seed " +
                            std::to_string(config.network_seed);
  const int code = hfdda::cli::run_python_script("network", "hfdda_network_plot.py", {out_dir, std::string("--domain=") + domain, "--title=" + title});
  if (code != 0) std::fprintf(stderr, "hfdda: network: the figure was not drawn (the other files were written)\n");
  return code == 0 ? 0 : 2;
}

int main(int argc, char** argv) {
  if (argc < 2) return usage_error("no command given");
  const std::string command = argv[1];
  if (command == "--help" || command == "-h") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (command == "--version") {
    std::puts("hfdda 0.1.0");
    return 0;
  }
  try {
    if (command == "run") return run_command(argc, argv, false);
    if (command == "check") return run_command(argc, argv, true);
    if (command == "plot") return plot_command(argc, argv);
    if (command == "network") return network_command(argc, argv);
    if (command == "ensemble") return hfdda::cli::ensemble_command(argc, argv);
    return usage_error("unknown command '" + command + "'");
  } catch (const hfdda::InputError& e) {
    std::fprintf(stderr, "hfdda: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hfdda: error: %s\n", e.what());
    return 2;
  }
}
