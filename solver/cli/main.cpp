// hfdda: command-line front end.
//   hfdda run CASE.yaml --out DIR [--quiet] [--threads N]   run a case, write the run directory
//   hfdda check CASE.yaml                      validate the case and build its mesh
// Exit codes: 0 success, 1 the run stopped (no convergence), 2 bad input or usage.

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "core/errors.hpp"
#include "dda/thread_policy.hpp"
#include "io/case_config.hpp"
#include "simulation/model.hpp"
#include "simulation/run.hpp"

namespace {

constexpr const char* kUsage =
    "usage: hfdda run CASE.yaml --out DIR [--quiet] [--threads N]\n"
    "       hfdda check CASE.yaml\n"
    "       hfdda --help | --version\n"
    "\n"
    "run    validates CASE.yaml, builds the mesh and runs the DDA time loop, writing\n"
    "       DIR/summary.json, DIR/history.csv, DIR/joints/*.csv and DIR/vtu/*.vtu (+ .pvd).\n"
    "       Shows progress on a terminal; --quiet shows nothing but errors.\n"
    "       --threads N: threads of the sparse factorisation (default: HFDDA_THREADS, else 1).\n"
    "check  validates CASE.yaml and builds its mesh without writing anything.\n"
    "Case-file keys: docs/case_file.md. Exit: 0 ok, 1 run stopped, 2 bad input.\n";

int usage_error(const std::string& message) {
  std::fprintf(stderr, "hfdda: %s\n%s", message.c_str(), kUsage);
  return 2;
}

int run_command(int argc, char** argv, bool check_only) {
  std::string case_file, out_dir;
  bool quiet = false;
  int threads = hfdda::dda::threads_from_environment();
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) out_dir = argv[++i];
    else if (arg == "--threads" && i + 1 < argc) {
      const std::string value = argv[++i];
      if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos || value.size() > 4 ||
          std::stoi(value) < 1)
        return usage_error("--threads needs a whole number from 1 to 9999 (got '" + value + "')");
      threads = std::stoi(value);
    }
    else if (arg == "--quiet" || arg == "-q") quiet = true;
    else if (!arg.empty() && arg[0] == '-') return usage_error("unknown option '" + arg + "'");
    else if (case_file.empty()) case_file = arg;
    else return usage_error("more than one case file given");
  }
  if (case_file.empty()) return usage_error("no case file given");
  if (!check_only && out_dir.empty()) return usage_error("run needs --out DIR");
  const std::string thread_note = hfdda::dda::apply_thread_policy(threads);
  if (!quiet && !check_only) std::fprintf(stderr, "%s\n", thread_note.c_str());

  const hfdda::io::CaseConfig config = hfdda::io::load_case_file(case_file);
  hfdda::simulation::Model model = hfdda::simulation::build_model(config);
  const auto& system = *model.system;
  if ((check_only || !quiet) && config.load_ramp)
    std::fprintf(stderr, "%s: %d blocks, %zu joints, %zu points, load ramp (%s), one static step of %g s per level\n",
                 case_file.c_str(), system.n_blocks(), system.mesh().joints.size(), system.mesh().points.size(),
                 config.load_ramp->history.empty() ? "uniform" : "history", config.time.dt_s);
  else if (check_only || !quiet)
    std::fprintf(stderr, "%s: %d blocks, %zu joints, %zu points, %d steps of %g s\n", case_file.c_str(),
                 system.n_blocks(), system.mesh().joints.size(), system.mesh().points.size(),
                 static_cast<int>(config.time.end_time_s / config.time.dt_s + 0.5), config.time.dt_s);
  if (check_only) return 0;

  const auto result = hfdda::simulation::run(model, {out_dir, quiet, true});
  if (!result.completed) {
    std::fprintf(stderr, "hfdda: run stopped at %s\nhfdda: outputs up to t = %g s are in %s\n", result.message.c_str(),
                 result.time_s, out_dir.c_str());
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
    return usage_error("unknown command '" + command + "'");
  } catch (const hfdda::InputError& e) {
    std::fprintf(stderr, "hfdda: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hfdda: error: %s\n", e.what());
    return 2;
  }
}
