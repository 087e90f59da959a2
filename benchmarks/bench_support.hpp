#pragma once
// What the benchmark binaries share: the process's CPU time across all its threads, a
// thread count switched for one benchmark, the calibration benchmark that the baseline
// comparison of scripts/bench divides every time by, and the run's host context.

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "dda/thread_policy.hpp"

namespace hfdda::bench {

/// User and system CPU time of the whole process, all threads [s]. Benchmark's own CPU
/// time is the main thread's unless MeasureProcessCPUTime() is set, and has no split.
struct ProcessCpu {
  double user_s = 0.0, sys_s = 0.0;

  static ProcessCpu now() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return {seconds(usage.ru_utime), seconds(usage.ru_stime)};
  }
  ProcessCpu& operator+=(const ProcessCpu& o) { user_s += o.user_s; sys_s += o.sys_s; return *this; }
  ProcessCpu operator-(const ProcessCpu& o) const { return {user_s - o.user_s, sys_s - o.sys_s}; }
};

/// Per-step wall and CPU time. cpu_over_wall is the number of busy cores; sys_over_user
/// shows idle threads spinning in the kernel (futex, sched_yield).
inline void add_step_counters(benchmark::State& state, double wall_s, const ProcessCpu& cpu, int steps) {
  state.counters["step_s"] = wall_s / steps;
  state.counters["cpu_s"] = (cpu.user_s + cpu.sys_s) / steps;
  state.counters["cpu_over_wall"] = wall_s > 0 ? (cpu.user_s + cpu.sys_s) / wall_s : 0.0;
  state.counters["sys_over_user"] = cpu.user_s > 0 ? cpu.sys_s / cpu.user_s : 0.0;
}

/// The thread policy at `threads` while the object lives, then the previous setting
/// again, so that benchmarks without a thread argument keep the process's setting
/// whatever order they run in (--benchmark_enable_random_interleaving).
class ScopedThreads {
 public:
  explicit ScopedThreads(int threads) : previous_(dda::applied_threads()) { dda::apply_thread_policy(threads); }
  ~ScopedThreads() { dda::apply_thread_policy(previous_ > 0 ? previous_ : 1); }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;

 private:
  int previous_;
};

/// Fixed work that touches none of HFDDA's code: a sparse Cholesky factorisation and
/// solve of the 5-point Laplacian on a 96 x 96 grid (Eigen, one thread). Its time
/// measures the machine's speed at the moment; scripts/bench divides every benchmark's
/// time by it to compare runs made while the shared machine was faster or slower.
inline void BM_Calibration(benchmark::State& state) {
  const int n = 96, unknowns = n * n;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int k = i * n + j;
      entries.emplace_back(k, k, 4.0);
      if (i > 0) entries.emplace_back(k, k - n, -1.0);
      if (j > 0) entries.emplace_back(k, k - 1, -1.0);
      if (i + 1 < n) entries.emplace_back(k, k + n, -1.0);
      if (j + 1 < n) entries.emplace_back(k, k + 1, -1.0);
    }
  Eigen::SparseMatrix<double> a(unknowns, unknowns);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(unknowns);
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt;
  llt.analyzePattern(a);
  for (auto _ : state) {
    llt.factorize(a);
    Eigen::VectorXd x = llt.solve(b);
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(BM_Calibration)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The CPU's model name (/proc/cpuinfo), to tell whether a baseline came from this host.
inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

/// The value of --benchmark_repetitions on the command line, 1 without it.
inline int requested_repetitions(int argc, char** argv) {
  int repetitions = 1;
  const char* flag = "--benchmark_repetitions=";
  for (int i = 1; i < argc; ++i)
    if (std::strncmp(argv[i], flag, std::strlen(flag)) == 0) repetitions = std::max(1, std::atoi(argv[i] + std::strlen(flag)));
  return repetitions;
}

/// Initialises the library with the context every binary reports: build type, CPU
/// model and the process's thread setting (HFDDA_THREADS).
inline void initialize(int* argc, char** argv) {
  benchmark::AddCustomContext("hfdda_build_type", HFDDA_BUILD_TYPE);
  benchmark::AddCustomContext("cpu_model", cpu_model());
  benchmark::AddCustomContext("hfdda_threads", dda::apply_thread_policy(dda::threads_from_environment()));
  benchmark::Initialize(argc, argv);
}

}  // namespace hfdda::bench
