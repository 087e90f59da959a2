#pragma once
// The one thread setting of HFDDA: how many threads the sparse Cholesky factorisation
// (CHOLMOD, OpenMP) and the BLAS under it (OpenBLAS) may use. Programs call
// apply_thread_policy() once at start-up, with the value of `--threads N` or of the
// environment variable HFDDA_THREADS (default 1).
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

/// Caps CHOLMOD's OpenMP parallel regions and OpenBLAS at `threads` (>= 1). With 1, no
/// OpenMP region of CHOLMOD runs in parallel (max active levels 0). Returns what was set,
/// as one line for logs.
std::string apply_thread_policy(int threads);

}  // namespace hfdda::dda
