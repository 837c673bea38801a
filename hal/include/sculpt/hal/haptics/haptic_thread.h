#pragma once
// Runs a HapticLoop in real time (DESIGN.md §5a): its own thread, ticking on
// absolute deadlines of the monotonic clock (clock_nanosleep with
// TIMER_ABSTIME, so the period does not drift by the tick's own time), at
// real-time priority when the system grants it. A tick that misses its
// deadline is followed by the next deadline still ahead: the loop never
// bunches up ticks to catch up (a burst of stale forces is worse than a gap).
//
// A standby twin: on a machine with two cores or more, a second thread,
// pinned to another core than the first, sleeps until the same deadlines,
// and whichever wakes first runs the tick (one at a time, under a mutex; the
// other finds the deadline taken and sleeps until the next). A real-time
// thread's wake-up is late when its core is held by something that cannot be
// preempted there: on a kernel without preemption, a kernel thread or a
// system call that runs for milliseconds (measured on the 2-core CI machines:
// a memory monitor, kdamond, for up to 4.7 ms at a time). Both cores are
// seldom held at once, so a tick is late only then.
//
// On stop(), destruction, or the device going away, the device is left with
// zero force.
//
// Thread safety: start(), stop() and the accessors from the owning thread;
// the loop's own requests (enable, drop) from any thread.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "sculpt/hal/haptics/haptic_loop.h"

namespace sculpt::hal {

struct HapticThreadOptions {
  int64_t period_ns = 1'000'000;
  /// SCHED_FIFO priority asked for (1..99); 0 asks for none.
  int realtime_priority = 80;
  /// The thread sleeps until this long before each deadline, then polls the
  /// clock up to it (0: sleeps to the deadline). The kernel's wake-up now
  /// and then comes late (on a virtual machine whose kernel is not
  /// preemptible, 0.15% of ticks came over half a period late); waking
  /// early absorbs that much of it, for this share of the period of one
  /// core spent polling.
  int64_t spin_ns = 0;
  /// Run the standby twin (above) when the process may use two cores or more.
  bool standby = true;
};

class HapticThread {
 public:
  HapticThread(HapticLoop& loop, ForceDevice& device, const HapticThreadOptions& options = {});
  ~HapticThread();
  HapticThread(const HapticThread&) = delete;
  HapticThread& operator=(const HapticThread&) = delete;

  void start();
  /// Stops ticking and zeroes the device's force; returns when the thread has ended.
  void stop();
  /// True while ticking: false after stop() or once the device went away.
  bool running() const { return running_.load(std::memory_order_acquire); }

  /// Whether the thread got real-time priority, and if not, one line saying
  /// why (for the log, once). Valid once the first tick has run.
  bool realtime() const { return realtime_.load(std::memory_order_acquire); }
  const std::string& realtime_note() const { return realtime_note_; }
  /// Deadlines passed over because a tick ran past the next one.
  int64_t skipped_deadlines() const { return skipped_.load(std::memory_order_relaxed); }
  /// Threads ticking, or that ticked: 2 with the standby twin, else 1 (0
  /// before start()).
  int threads() const { return thread_count_; }
  /// Ticks one thread ran on time while the other woke over half a period
  /// late: the late ticks the twin spared.
  int64_t standby_rescues() const { return rescues_.load(std::memory_order_relaxed); }

 private:
  // Thread `which` (0, or 1 the twin), pinned to `cpu` (-1: not pinned).
  void run(int which, int cpu);

  HapticLoop& loop_;
  ForceDevice& device_;
  HapticThreadOptions options_;
  std::thread threads_[2];
  int thread_count_ = 0;
  std::atomic<bool> stop_{false}, running_{false}, realtime_{false};
  std::atomic<int> started_{0}, ended_{0};
  std::atomic<int64_t> skipped_{0}, rescues_{0};
  std::string realtime_note_;  // written by thread 0 before it counts as started
  std::mutex tick_mutex_;
  int64_t next_deadline_ns_ = 0;  // the deadline of the next tick; guarded by tick_mutex_
};

}  // namespace sculpt::hal
