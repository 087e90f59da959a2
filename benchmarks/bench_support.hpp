#pragma once
// What the benchmark binaries share: the process's CPU time across all its threads, a
// thread count switched for one benchmark, the calibration benchmark that the baseline
// comparison of scripts/bench divides every time by, and the run's host context.

#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <time.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
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
/// measures the machine's speed at the moment, so that scripts/bench can compare runs
/// made while the shared machine was faster or slower. BM_Calibration times it once per
/// binary (the machine's speed in the report); AdjacentCalibration next to every
/// repetition of a benchmark (what the comparison divides by).
class CalibrationWork {
 public:
  CalibrationWork() : a_(kN * kN, kN * kN), b_(Eigen::VectorXd::Ones(kN * kN)) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) {
        const int k = i * kN + j;
        entries.emplace_back(k, k, 4.0);
        if (i > 0) entries.emplace_back(k, k - kN, -1.0);
        if (j > 0) entries.emplace_back(k, k - 1, -1.0);
        if (i + 1 < kN) entries.emplace_back(k, k + kN, -1.0);
        if (j + 1 < kN) entries.emplace_back(k, k + 1, -1.0);
      }
    a_.setFromTriplets(entries.begin(), entries.end());
    llt_.analyzePattern(a_);
  }
  void run() {
    llt_.factorize(a_);
    Eigen::VectorXd x = llt_.solve(b_);
    benchmark::DoNotOptimize(x.data());
  }

 private:
  static constexpr int kN = 96;
  Eigen::SparseMatrix<double> a_;
  Eigen::VectorXd b_;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt_;
};

inline void BM_Calibration(benchmark::State& state) {
  CalibrationWork work;
  for (auto _ : state) work.run();
}
BENCHMARK(BM_Calibration)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The calibration work timed next to a benchmark's own repetition, 10 runs before and
/// 10 after its timed loop: counters calibration_real_ms and calibration_cpu_ms, the
/// median run. A busy spell of the shared machine that lasts longer than a repetition
/// slows both, and their ratio does not move; the median ignores a few runs caught by a
/// shorter one (measured over a bench_dda run at a load of 2: relative spread of the
/// ratio 1.6 % with the median run, 2.0 % with the mean, 3.7 % for the time alone). The
/// CPU time is the calling thread's: threads of the benchmark still spinning would count
/// in the process's.
class AdjacentCalibration {
 public:
  explicit AdjacentCalibration(benchmark::State& state) : state_(state) { measure(); }
  ~AdjacentCalibration() {
    measure();
    state_.counters["calibration_real_ms"] = 1e3 * median(real_s_);
    state_.counters["calibration_cpu_ms"] = 1e3 * median(cpu_s_);
  }
  AdjacentCalibration(const AdjacentCalibration&) = delete;
  AdjacentCalibration& operator=(const AdjacentCalibration&) = delete;

 private:
  void measure() {
    static CalibrationWork work;
    constexpr int kRuns = 10;  // about 50 ms
    for (int i = 0; i < kRuns; ++i) {
      const double cpu0 = thread_cpu_s();
      const auto wall0 = std::chrono::steady_clock::now();
      work.run();
      real_s_.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
      cpu_s_.push_back(thread_cpu_s() - cpu0);
    }
  }
  static double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
  }
  static double thread_cpu_s() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
  benchmark::State& state_;
  std::vector<double> real_s_, cpu_s_;  // per run of the work
};

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
