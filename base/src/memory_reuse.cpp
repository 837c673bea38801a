#include "sculpt/base/memory_reuse.h"

#include <malloc.h>

#include <climits>
#include <memory>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

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

void warm_this_threads_heap(size_t bytes) {
  // Blocks of 1 MiB: under the mmap threshold, so they come from the
  // thread's heap and coalesce into its top when freed.
  constexpr size_t kBlock = size_t{1} << 20;
  const size_t page = static_cast<size_t>(::sysconf(_SC_PAGESIZE));
  std::vector<std::unique_ptr<volatile unsigned char[]>> blocks;
  for (size_t n = 0; n < bytes; n += kBlock) {
    auto& block = blocks.emplace_back(new volatile unsigned char[kBlock]);
    for (size_t at = 0; at < kBlock; at += page)
      block[at] = 0;
  }
  // A thread's arena grows in heaps of at most 64 MiB, and glibc unmaps the
  // newest heap as soon as it is wholly free, whatever the trim threshold:
  // with every block freed, a reserve over 64 MiB kept only its first
  // 64 MiB (92 MB of 32 KiB blocks after warming 96 MiB: 6,400 faults).
  // The last block, held for the thread's life, keeps its heap in use.
  thread_local std::unique_ptr<volatile unsigned char[]> newest_heap_kept;
  if (!blocks.empty()) newest_heap_kept = std::move(blocks.back());
}

int64_t this_threads_page_faults() {
  rusage usage{};
  ::getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

}  // namespace sculpt
