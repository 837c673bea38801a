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

/// Pool threads started after this call first touch `bytes` of their heap
/// (warm_this_threads_heap, base/memory_reuse.h), as the window's own
/// threads do: their first loops then take no page faults (about 8 us each
/// on the virtual machines measured; the window's first big dabs were
/// meshed and sculpted beside 1,800 of them). 0 (the default) touches none.
void warm_pool_threads_when_started(size_t bytes);

/// Calls `body(i)` for every i in [0, count), spread over `threads` threads
/// (0 = default_threads()). Work is handed out in order, one index at a time,
/// so uneven items (uniform vs detailed bricks) balance themselves. `body` must
/// be safe to call concurrently for different i. A loop started inside
/// another loop's body runs serially on its thread; loops started by two
/// threads at once both run in parallel (the second on threads of its own).
void parallel_for(int64_t count, const std::function<void(int64_t)>& body, int threads = 0);

}  // namespace sculpt::core
