#include "dda/thread_policy.hpp"

#include <dlfcn.h>
#include <omp.h>

#include <atomic>
#include <stdexcept>

#include "core/environment.hpp"

namespace hfdda::dda {

const char* serial_region_note();  // openmp_serial_regions.cpp

int threads_from_environment() { return core::whole_number_from_environment("HFDDA_THREADS", 1, 1024); }

namespace {
std::atomic<int> g_applied_threads{0};  // for applied_threads()
}  // namespace

std::string apply_thread_policy(int threads) {
  if (threads < 1) throw std::invalid_argument("the number of threads must be >= 1");
  g_applied_threads = threads;
  // A parallel region runs with one thread once the active-level limit is reached; with
  // a limit of 0 that is every region, including those with a num_threads clause.
  omp_set_max_active_levels(threads > 1 ? 1 : 0);
  omp_set_num_threads(threads);
  // OpenBLAS, when it is the BLAS CHOLMOD was linked with (looked up, not linked: any
  // other BLAS is single-threaded or has its own setting).
  using SetThreads = void (*)(int);
  std::string blas = "no OpenBLAS";
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) {
    set(threads);
    blas = "OpenBLAS " + std::to_string(threads);
    // The kernels OpenBLAS chose for this processor: long runs depend on them in the last
    // bits (docs/design_notes.md section 32), so logs and records name them.
    if (const std::string kernels = blas_kernels(); !kernels.empty()) blas += " with " + kernels + " kernels";
  }
  return "threads: " + std::to_string(threads) + " (CHOLMOD OpenMP " + std::to_string(threads) + ", " + blas +
         (threads == 1 ? std::string(", ") + serial_region_note() : std::string()) + ")";
}

int applied_threads() { return g_applied_threads; }

std::string blas_kernels() {
  using CoreName = char* (*)();
  const auto core = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  const char* name = core ? core() : nullptr;
  return name ? std::string(name) : std::string();
}

}  // namespace hfdda::dda
