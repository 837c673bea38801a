#pragma once
// Keeping freed memory for reuse in a long-running interactive process.
//
// glibc's malloc gives a freed block of 128 KiB or more (a threshold that
// grows with use) back to the kernel, and trims the heap's top beyond
// 128 KiB. The next block of that size is then fresh pages, each a page
// fault on first touch, and on the virtual machines this station is
// measured on a fault costs about 8 us: a big tool's tables (27 MB) or a
// big dab's decoded bricks cost tens of milliseconds of faults, every time,
// on the sculpting thread. Kept, a freed block is reused already mapped.

#include <cstddef>

namespace sculpt {

/// Blocks up to 32 MiB (the most glibc allows) come from the heap, and up
/// to `keep_bytes` of free heap stay mapped. Returns whether malloc took
/// both settings. Call once, early, before the threads start.
bool keep_freed_memory(size_t keep_bytes);

}  // namespace sculpt
