#pragma once
// A fork-join loop over an index range, for whole-volume work (encoding
// every brick, extracting a level) and for the few bricks a dab touches. The
// calling thread takes part; the others come from a pool of threads that
// sleep between loops, so a loop costs a wake-up, not a thread start.

#include <cstddef>
#include <cstdint>
#include <functional>

namespace sculpt::core {

/// Number of threads the machine offers (at least 1).
int hardware_threads();

/// Threads that whole-volume work uses when a call asks for 0 ("all"):
/// hardware_threads() unless set. Results never depend on it; tests and
/// `--threads` use it to prove that.
int default_threads();
/// Sets default_threads() (0 restores the hardware count).
void set_default_threads(int threads);

/// Starts the pool's threads now, each first touching `warm_heap_bytes` of
/// its heap (warm_this_threads_heap, base/memory_reuse.h), as the window's
/// own threads do, and so does any pool thread started later: their first
/// loops then take no page faults (about 8 us each on the virtual machines
/// measured; the window's first big dabs were meshed and sculpted beside
/// 1,800 of them). Without this call threads start at their first loop,
/// unwarmed.
void start_pool_threads(size_t warm_heap_bytes);

/// Calls `body(i)` for every i in [0, count), spread over `threads` threads
/// (0 = default_threads()). Work is handed out in order, one index at a time,
/// so uneven items (uniform vs detailed bricks) balance themselves. `body` must
/// be safe to call concurrently for different i. A loop started inside
/// another loop's body runs serially on its thread; loops started by
/// several threads at once all run in parallel, each on a crew of pool
/// threads of its own (three crews; a fourth loop at once starts threads
/// for itself).
void parallel_for(int64_t count, const std::function<void(int64_t)>& body, int threads = 0);

}  // namespace sculpt::core
