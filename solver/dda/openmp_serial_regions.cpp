// With the one-thread policy, CHOLMOD's OpenMP parallel regions run their body directly.
//
// Why: libgomp ends every parallel region with a barrier whose last arrival makes a
// futex wake system call, even when the team has a single thread. CHOLMOD's supernodal
// factorisation opens several regions per supernode, so a run with one thread still
// made hundreds of thousands of futex calls (a fifth of its CPU time in the kernel on
// small meshes; docs/design_notes.md, "Threads and kernel time").
//
// How: this definition of GOMP_parallel, the entry point GCC emits for `#pragma omp
// parallel`, is found before libgomp's by the dynamic linker. When the process runs one
// thread (apply_thread_policy(1) sets the active-level limit to 0, so libgomp itself
// would run the region with a team of one) it calls the region's function once on the
// calling thread, outside any team: omp_get_num_threads() is 1 and omp_get_thread_num()
// 0 there, worksharing loops take every iteration, and barriers return at once, as
// OpenMP specifies for code outside a parallel region. Otherwise it forwards to libgomp.

#include <dlfcn.h>
#include <omp.h>

#include <cstdio>
#include <cstdlib>

namespace {

using ParallelEntry = void (*)(void (*)(void*), void*, unsigned, unsigned);

ParallelEntry libgomp_parallel() {
  static const ParallelEntry next = [] {
    auto found = reinterpret_cast<ParallelEntry>(dlsym(RTLD_NEXT, "GOMP_parallel"));
    if (found == nullptr) {
      std::fprintf(stderr, "hfdda: GOMP_parallel not found in libgomp\n");
      std::abort();
    }
    return found;
  }();
  return next;
}

}  // namespace

extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  if (omp_get_max_active_levels() == 0 && omp_get_level() == 0) {
    fn(data);
    return;
  }
  libgomp_parallel()(fn, data, num_threads, flags);
}

namespace hfdda::dda {

// Referenced by apply_thread_policy() so that the linker keeps this file's
// GOMP_parallel in every program that sets the thread policy.
const char* serial_region_note() { return "one-thread regions run inline"; }

}  // namespace hfdda::dda
