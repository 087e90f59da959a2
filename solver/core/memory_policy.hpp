#pragma once
// How the process keeps the memory it frees. A time step allocates and frees the same
// large arrays again and again (CHOLMOD's transposed copy of K and its update matrices,
// contact and flow work arrays). With glibc's defaults, blocks above a dynamic threshold
// (at most 32 MiB) are returned to the kernel when freed, and the next allocation makes
// the kernel fault in and zero fresh pages: on large meshes that was a third of the
// kernel time of a run (docs/design_notes.md, "Threads and kernel time").

#include <string>

namespace hfdda::core {

/// Serves allocations up to 256 MiB from the heap and keeps up to 1 GiB of freed heap
/// in the process instead of returning it to the kernel. Call once at start-up, before
/// large allocations. Returns what was set, as one line for logs.
std::string retain_freed_memory();

}  // namespace hfdda::core
