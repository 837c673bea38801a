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
//
// The first use still faults: a session's first big stroke (a 66-voxel ball
// over 92 bricks) touches about 17 MB of new pages, 35 ms of faults. So a
// thread that must answer at once warms its heap when it starts, as
// real-time Linux programs do (the Linux Foundation's real-time wiki,
// "Memory for Real-time Applications": keep trimming off, then touch a
// heap reserve so that later allocations never fault).

#include <cstddef>
#include <cstdint>

namespace sculpt {

/// Blocks up to 32 MiB (the most glibc allows) come from the heap, and up
/// to `keep_bytes` of free heap stay mapped. Returns whether malloc took
/// both settings. Call once, early, before the threads start.
bool keep_freed_memory(size_t keep_bytes);

/// Allocates about `bytes` from the calling thread's heap, touches every
/// page and frees it again, but for its last MiB, held for the thread's life
/// (else glibc unmaps a thread heap past the first 64 MiB as soon as it is
/// wholly free): with keep_freed_memory() in force the pages stay mapped,
/// and the thread's next allocations up to that size do not fault. Costs a
/// page fault a page, once (70 to 135 ms for 32 MiB here).
void warm_this_threads_heap(size_t bytes);

/// The calling thread's page faults so far that needed no disk (a fresh
/// page's first touch): what a warmed heap spares a thread.
int64_t this_threads_page_faults();

}  // namespace sculpt
