#pragma once
// A thread that works on a timer, woken early when there is work: the
// window's sculpting thread polls the devices once a millisecond, and a
// report that came just after a poll waited for the next one, half a
// millisecond on average before anything sculpted it. Each device reader
// rings when it has pushed a report; the sculpting thread sleeps until its
// next poll is due or a ring, whichever comes first.
//
// A futex on a ring count (Linux): ringing never blocks and costs one system
// call, so a real-time reader can ring at every report; the waiter cannot
// miss a ring that came between its last look and its sleep, as it sleeps
// only while the count is still the one it saw.

#include <atomic>
#include <cstdint>

namespace sculpt {

class Doorbell {
 public:
  /// Wakes a thread in wait_until(). Any thread; never blocks.
  void ring();
  /// How many times it has rung: read before looking for work, then given
  /// to wait_until(), so a ring while looking is not missed.
  uint32_t rings() const { return rings_.load(std::memory_order_acquire); }
  /// Sleeps until the count differs from `seen` (a ring since it was read)
  /// or CLOCK_MONOTONIC reaches `deadline_ns`. Returns whether it rang.
  bool wait_until(uint32_t seen, int64_t deadline_ns) const;

 private:
  std::atomic<uint32_t> rings_{0};
};

}  // namespace sculpt
