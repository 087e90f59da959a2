// `hfdda ensemble` (ensemble_command.hpp).

#include "cli/ensemble_command.hpp"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_support.hpp"
#include "cli/ensemble_farm.hpp"
#include "core/errors.hpp"
#include "core/memory_policy.hpp"
#include "dda/thread_policy.hpp"
#include "ensemble/ensemble_run.hpp"
#include "io/case_config.hpp"
#include "simulation/run.hpp"

namespace hfdda::cli {

namespace {

constexpr const char* kEnsembleUsage =
    "usage: [mpirun -n N] hfdda ensemble CASE.yaml --out DIR [--shard K/N] [--force] [--quiet] [--threads N]\n"
    "                                   [--no-figures]\n"
    "       hfdda ensemble CASE.yaml --realisation I --out DIR [--force] [--quiet] [--trace-iterations]\n"
    "       hfdda ensemble merge --out DIR SOURCE_DIR... [--no-figures]\n"
    "\n"
    "Runs the realisations of the case's `ensemble` section (docs/ensembles.md), each written\n"
    "to DIR/realisations/ as soon as it is finished, then the likelihood maps of DIR\n"
    "(likelihood_*.csv, .vtu, .pvd, ensemble_summary.json, figures/). Realisation i draws from\n"
    "streams that depend only on the master seed and i. Under mpirun, rank 0 hands the\n"
    "realisations out one at a time; the maps are the same for any number of ranks.\n"
    "Re-running the same command resumes: finished realisations are skipped. SIGINT/SIGTERM\n"
    "drops the realisations in flight and exits 3. --force empties DIR first (but for CASE.yaml, if it is in DIR).\n"
    "--shard K/N: only the realisations with index % N == K (K from 0), for job arrays;\n"
    "then `hfdda ensemble merge --out DIR SHARD_DIR...` writes the maps over all of them.\n"
    "--threads N: threads per process (default: HFDDA_THREADS, else 1; keep 1 under mpirun).\n"
    "--realisation I: run realisation I alone, as `hfdda run` would, writing every output file\n"
    "(history.csv, joints, VTU, summary.json) to DIR: to look into one that failed; with\n"
    "--trace-iterations also DIR/iterations.csv, as `hfdda run --trace-iterations` writes it.\n";

int usage(const std::string& message) {
  std::fprintf(stderr, "hfdda ensemble: %s\n%s", message.c_str(), kEnsembleUsage);
  return 2;
}

bool parse_shard(const std::string& text, ensemble::Shard& shard) {
  const auto slash = text.find('/');
  if (slash == std::string::npos) return false;
  const std::string k = text.substr(0, slash), n = text.substr(slash + 1);
  auto whole = [](const std::string& s) {
    return !s.empty() && s.size() <= 6 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!whole(k) || !whole(n)) return false;
  shard.index = std::stoi(k), shard.count = std::stoi(n);
  return shard.count >= 1 && shard.index < shard.count;
}

int draw_figures(const std::string& dir) {
  const int code = run_python_script("ensemble", "hfdda_ensemble_plot.py", {dir, "--out", dir + "/figures"});
  if (code != 0) std::fprintf(stderr, "hfdda ensemble: the figures were not drawn (the maps were written)\n");
  return code;
}

void print_summary(const std::string& dir, const ensemble::EnsembleSummary& s) {
  std::fprintf(stderr, "ensemble: %d of %d realisations in %s: %d completed, %d failed", s.found, s.requested,
               dir.c_str(), s.completed, s.failed);
  if (!s.missing.empty()) std::fprintf(stderr, ", %zu not run (other shards, or stopped)", s.missing.size());
  std::fprintf(stderr, "; maps in %s\n", dir.c_str());
}

int merge_command(int argc, char** argv) {
  std::string out_dir;
  std::vector<std::string> sources;
  bool figures = true;
  for (int i = 3; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) out_dir = argv[++i];
    else if (arg == "--no-figures") figures = false;
    else if (!arg.empty() && arg[0] == '-') return usage("merge: unknown option '" + arg + "'");
    else sources.push_back(arg);
  }
  if (out_dir.empty()) return usage("merge needs --out DIR");
  if (sources.empty()) return usage("merge needs at least one ensemble directory");
  for (const std::string& dir : sources)
    if (!std::filesystem::exists(dir + "/ensemble.json"))
      return usage("merge: '" + dir + "' is not an ensemble directory (no ensemble.json)");
  const ensemble::EnsembleSummary s = ensemble::write_ensemble_maps(out_dir, sources);
  print_summary(out_dir, s);
  return figures ? (draw_figures(out_dir) == 0 ? 0 : 2) : 0;
}

/// Empties DIR for --force, except the case file itself when it lies in DIR: the case
/// an ensemble ran must stay beside its records (ensemble.json names it), so that
/// `--realisation I` can repeat any of them.
std::string empty_directory(const std::string& dir, const std::string& case_file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(dir, ec)) return "";
  if (!fs::is_directory(dir, ec)) return "'" + dir + "' exists and is not a directory";
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::error_code same_ec;
    if (fs::equivalent(entry.path(), case_file, same_ec)) continue;
    fs::remove_all(entry.path(), ec);
    if (ec) return "cannot empty '" + dir + "': " + ec.message();
  }
  return "";
}

/// `--realisation I`: one realisation with the outputs of `hfdda run` (exit codes as run's).
int run_one_realisation(const io::CaseConfig& config, long index, const std::string& out_dir, bool quiet,
                        bool trace_iterations) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(out_dir + "/summary.json", ec) || fs::exists(out_dir + "/history.csv", ec)) {
    std::fprintf(stderr, "hfdda ensemble: '%s' holds a previous run; give --force to empty it first\n", out_dir.c_str());
    return 2;
  }
  simulation::Model model = ensemble::build_realisation_model(config, index);
  simulation::RunOptions options;
  options.output_dir = out_dir;
  options.quiet = quiet;
  options.trace_iterations = trace_iterations;
  options.stop_requested = stop_requested;
  options.abandon_step_requested = stop_requested;
  catch_stop_signals("\nhfdda ensemble: stop requested: the current step is abandoned at its next iteration "
                     "(signal again to stop at once)\n");
  const simulation::RunResult result = simulation::run(model, options);
  if (result.interrupted) return 3;
  if (!result.completed) {
    std::fprintf(stderr, "hfdda ensemble: realisation %ld stopped at %s\noutputs up to t = %g s are in %s\n", index,
                 result.message.c_str(), result.time_s, out_dir.c_str());
    return 1;
  }
  if (!quiet) std::fprintf(stderr, "realisation %ld: %d steps in %.2f s; outputs in %s\n", index, result.steps,
                           result.wall_seconds, out_dir.c_str());
  return 0;
}

int run_ensemble(int argc, char** argv, const ProcessGroup& group) {
  std::string case_file, out_dir;
  long only = -1;
  ensemble::Shard shard;
  bool force = false, quiet = false, figures = true, trace_iterations = false;
  int threads = dda::threads_from_environment();
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) out_dir = argv[++i];
    else if (arg == "--shard" && i + 1 < argc) {
      const std::string value = argv[++i];
      if (!parse_shard(value, shard)) return usage("--shard needs K/N with 0 <= K < N (got '" + value + "')");
    } else if (arg == "--threads" && i + 1 < argc) {
      const std::string value = argv[++i];
      if (value.empty() || value.size() > 4 || value.find_first_not_of("0123456789") != std::string::npos ||
          std::stoi(value) < 1)
        return usage("--threads needs a whole number from 1 to 9999 (got '" + value + "')");
      threads = std::stoi(value);
    } else if (arg == "--realisation" && i + 1 < argc) {
      const std::string value = argv[++i];
      if (value.empty() || value.size() > 9 || value.find_first_not_of("0123456789") != std::string::npos)
        return usage("--realisation needs a whole number >= 0 (got '" + value + "')");
      only = std::stol(value);
    } else if (arg == "--force") force = true;
    else if (arg == "--quiet" || arg == "-q") quiet = true;
    else if (arg == "--no-figures") figures = false;
    else if (arg == "--trace-iterations") trace_iterations = true;
    else if (!arg.empty() && arg[0] == '-') return usage("unknown option '" + arg + "'");
    else if (case_file.empty()) case_file = arg;
    else return usage("more than one case file given");
  }
  if (case_file.empty()) return usage("no case file given");
  if (out_dir.empty()) return usage("ensemble needs --out DIR");
  if (trace_iterations && only < 0) return usage("--trace-iterations goes with --realisation I (one realisation)");
  const bool lead = group.rank == 0;
  const std::string thread_note = dda::apply_thread_policy(threads);
  core::retain_freed_memory();
  const io::CaseConfig config = io::load_case_file(case_file);
  if (!config.ensemble)
    throw InputError(case_file, 0, "ensemble", "hfdda ensemble needs an `ensemble` section (docs/case_file.md)");
  if (only >= 0) {
    if (group.size > 1) return usage("--realisation runs on one process, not under mpirun");
    if (only >= config.ensemble->realisations)
      return usage("--realisation " + std::to_string(only) + ": the ensemble has realisations 0 to " +
                   std::to_string(config.ensemble->realisations - 1));
    if (force) {
      const std::string problem = empty_directory(out_dir, case_file);
      if (!problem.empty()) return usage(problem);
    }
    return run_one_realisation(config, only, out_dir, quiet, trace_iterations);
  }
  const ensemble::EnsembleGeometry geometry = ensemble::ensemble_geometry(config);
  const ensemble::EnsembleManifest manifest = ensemble::make_manifest(config, geometry, shard);

  // Rank 0 prepares DIR (or finds the ensemble to resume in it); the others wait for its word.
  std::vector<long> pending;
  std::string problem;
  if (lead) {
    if (force) problem = empty_directory(out_dir, case_file);
    if (problem.empty()) try {
        ensemble::prepare_directory(out_dir, manifest, geometry);
        pending = ensemble::pending_realisations(out_dir, manifest);
      } catch (const std::exception& e) {
        problem = e.what();
      }
    if (!problem.empty()) std::fprintf(stderr, "hfdda ensemble: %s\n", problem.c_str());
  }
  if (share_from_rank0(group, problem.empty() ? 0 : 1) != 0) return 2;
  if (lead && !quiet) {
    const int total = (config.ensemble->realisations - shard.index + shard.count - 1) / shard.count;
    std::fprintf(stderr, "%s: %d joints, %zu map times, %d x %d grid cells of %g m; %d of %d realisations to run on %d "
                 "process(es) (%s)\n",
                 case_file.c_str(), geometry.mesh.joints, geometry.map_times_s.size(), geometry.grid.nx,
                 geometry.grid.ny, geometry.grid.cell_m, static_cast<int>(pending.size()), total, group.size,
                 thread_note.c_str());
  }
  // Under mpirun every rank gets the signal: the first rank alone says what happens.
  catch_stop_signals(lead ? "\nhfdda ensemble: stop requested: finished realisations are kept, those in flight "
                            "stop at their next iteration and are dropped (signal again to stop at once)\n"
                          : "");
  const auto queue = make_work_queue(group, std::move(pending), lead && !quiet, stop_requested);
  const bool finished = ensemble::run_realisations(config, geometry, out_dir, *queue, stop_requested);
  if (!finished) {
    if (lead)
      std::fprintf(stderr, "\nhfdda ensemble: stopped on a signal; the finished realisations are in %s/realisations; "
                   "run the same command again to go on\n", out_dir.c_str());
    return 3;
  }
  if (!lead) return 0;
  const ensemble::EnsembleSummary s = ensemble::write_ensemble_maps(out_dir, {out_dir});
  if (!quiet) print_summary(out_dir, s);
  return figures && draw_figures(out_dir) != 0 ? 2 : 0;
}

}  // namespace

int ensemble_command(int argc, char** argv) {
  if (argc >= 3 && std::string(argv[2]) == "merge") return merge_command(argc, argv);
  if (argc >= 3 && (std::string(argv[2]) == "--help" || std::string(argv[2]) == "-h")) {
    std::fputs(kEnsembleUsage, stdout);
    return 0;
  }
  const ProcessGroup group = start_processes(&argc, &argv);
  int code = 2;
  try {
    code = run_ensemble(argc, argv, group);
  } catch (...) {
    end_processes(group);
    throw;
  }
  end_processes(group);
  return code;
}

}  // namespace hfdda::cli
