#pragma once
// Where a process's CPU time went, thread by thread: the station's --stats
// says how much the frame, the mesher, the worker pool, the device readers
// and the software renderer's own threads (Mesa's llvmpipe-N) each took.
// Threads are told apart by name, so the station names the ones it starts.
//
// Linux only (/proc/self/task). Thread safe.

#include <string>
#include <vector>

namespace sculpt {

/// Names the calling thread as `top` and other tools show it. Linux keeps
/// 15 bytes of a name; the rest is dropped.
void name_this_thread(const std::string& name);

struct ThreadGroupTime {
  std::string name;  ///< the threads' name without a trailing number ("llvmpipe")
  int threads = 0;   ///< threads of that name running now
  double cpu_s = 0;  ///< user and system time, seconds, since each started
};

/// The CPU time of this process's running threads, summed by name (digits
/// and a '-' or '_' before them dropped, so llvmpipe-0 and llvmpipe-1 are
/// one group), largest first, then the time of threads that already ended
/// as "ended" (the process's total less the running threads'). Empty when
/// /proc cannot be read.
std::vector<ThreadGroupTime> thread_cpu_times();

}  // namespace sculpt
