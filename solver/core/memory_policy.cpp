#include "core/memory_policy.hpp"

#include <malloc.h>

namespace hfdda::core {

std::string retain_freed_memory() {
  constexpr int kMmapThresholdBytes = 256 << 20;  // larger blocks still get their own mapping
  constexpr int kTrimThresholdBytes = 1 << 30;    // freed heap kept before trimming
  constexpr int kTopPadBytes = 64 << 20;          // heap grown in 64 MiB steps
  const bool ok = mallopt(M_MMAP_THRESHOLD, kMmapThresholdBytes) == 1 &&
                  mallopt(M_TRIM_THRESHOLD, kTrimThresholdBytes) == 1 && mallopt(M_TOP_PAD, kTopPadBytes) == 1;
  return ok ? "memory: freed blocks up to 256 MiB kept for reuse (trim above 1 GiB)"
            : "memory: allocator defaults (mallopt refused the retention settings)";
}

}  // namespace hfdda::core
