#pragma once
// Runs a HapticLoop in real time (DESIGN.md §5a): its own thread, ticking on
// absolute deadlines of the monotonic clock (clock_nanosleep with
// TIMER_ABSTIME, so the period does not drift by the tick's own time), at
// real-time priority when the system grants it. A tick that misses its
// deadline is followed by the next deadline still ahead: the loop never
// bunches up ticks to catch up (a burst of stale forces is worse than a gap).
//
// On stop(), destruction, or the device going away, the device is left with
// zero force.
//
// Thread safety: start(), stop() and the accessors from the owning thread;
// the loop's own requests (enable, drop) from any thread.

#include <atomic>
#include <cstdint>
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

 private:
  void run();

  HapticLoop& loop_;
  ForceDevice& device_;
  HapticThreadOptions options_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, started_{false}, running_{false}, realtime_{false};
  std::atomic<int64_t> skipped_{0};
  std::string realtime_note_;  // written by the thread before running_ is set
};

}  // namespace sculpt::hal
