#include "sculpt/base/memory_reuse.h"

#include <malloc.h>

#include <climits>

namespace sculpt {

bool keep_freed_memory(size_t keep_bytes) {
  // glibc's upper bound for the mmap threshold on 64-bit systems
  // (DEFAULT_MMAP_THRESHOLD_MAX); a larger value is refused.
  constexpr int kLargestHeapBlock = 32 << 20;
  const int keep =
      keep_bytes > static_cast<size_t>(INT_MAX) ? INT_MAX : static_cast<int>(keep_bytes);
  const bool mmap_ok = ::mallopt(M_MMAP_THRESHOLD, kLargestHeapBlock) == 1;
  const bool trim_ok = ::mallopt(M_TRIM_THRESHOLD, keep) == 1;
  return mmap_ok && trim_ok;
}

}  // namespace sculpt
