#pragma once
// The one thread setting of HFDDA: how many threads the sparse Cholesky factorisation
// (CHOLMOD, OpenMP) and the BLAS under it (OpenBLAS) may use. Programs call
// apply_thread_policy() once at start-up, with the value of `--threads N` or of the
// environment variable HFDDA_THREADS (default 1). It may be called again to change the
// setting for the whole process (the benchmarks compare 1 and 2 threads this way).
//
// Why the default is 1: CHOLMOD 3.0 (SuiteSparse 5.12) asks for 4 OpenMP threads in its supernodal
// factorisation whatever OMP_NUM_THREADS says, and idle OpenMP and OpenBLAS threads spin
// in futex and sched_yield calls. On the 2-core machines this code targets, a Mode I load
// ramp of 3,646 blocks spent 287 s in 216 factorisations with them and 33 s without
// (docs/design_notes.md, "Threads"). Several ranks sharing the cores run one thread each.

#include <string>

namespace hfdda::dda {

/// HFDDA_THREADS if set (a whole number >= 1), else 1. Throws std::invalid_argument
/// naming the variable for any other value.
int threads_from_environment();

/// Sets the OpenMP and OpenBLAS thread counts to `threads` (>= 1). With 1, no OpenMP
/// region of CHOLMOD runs in parallel (max active levels 0). With more, OpenBLAS runs
/// `threads` threads but CHOLMOD's OpenMP loops, which carry a num_threads(4) clause,
/// run 4 (measured: 5 threads in the process at 2; only OMP_THREAD_LIMIT, read at
/// program start, would cap them). Returns what was set, as one line for logs, with the
/// kernels OpenBLAS chose for the processor (OPENBLAS_CORETYPE overrides them). Call it
/// from the main thread; a later call replaces the setting.
std::string apply_thread_policy(int threads);

/// The value of the last apply_thread_policy() call, 0 before any.
int applied_threads();

/// The name of the kernels OpenBLAS runs ("Haswell", "Cooperlake", ...; set by the
/// processor or by OPENBLAS_CORETYPE), or "" when the BLAS is not OpenBLAS or does not
/// say. Results of long runs depend on them in the last bits (docs/design_notes.md
/// section 32), so verification results record them.
std::string blas_kernels();

}  // namespace hfdda::dda
