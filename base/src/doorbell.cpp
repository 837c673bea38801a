#include "sculpt/base/doorbell.h"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <ctime>

namespace sculpt {
namespace {

int64_t monotonic_now_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec;
}

// The futex word: the low 32 bits of the count, which is what a futex holds.
uint32_t* word(const std::atomic<uint32_t>& a) {
  static_assert(sizeof(std::atomic<uint32_t>) == sizeof(uint32_t) &&
                std::atomic<uint32_t>::is_always_lock_free);
  return reinterpret_cast<uint32_t*>(const_cast<std::atomic<uint32_t>*>(&a));
}

}  // namespace

void Doorbell::ring() {
  rings_.fetch_add(1, std::memory_order_release);
  // Woken whether or not anyone sleeps: a flag saying so would need the
  // same ordering care as the count, for a system call saved per report.
  syscall(SYS_futex, word(rings_), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
}

bool Doorbell::wait_until(uint32_t seen, int64_t deadline_ns) const {
  // FUTEX_WAIT_BITSET takes an absolute CLOCK_MONOTONIC deadline: no
  // relative timeout recomputed after each spurious wake.
  const timespec deadline{static_cast<time_t>(deadline_ns / 1'000'000'000),
                          static_cast<long>(deadline_ns % 1'000'000'000)};
  while (rings() == seen) {
    if (monotonic_now_ns() >= deadline_ns) return false;
    const long r = syscall(SYS_futex, word(rings_), FUTEX_WAIT_BITSET_PRIVATE, seen, &deadline,
                           nullptr, FUTEX_BITSET_MATCH_ANY);
    if (r == -1 && errno == ETIMEDOUT) return rings() != seen;
    // 0 (woken), EAGAIN (it rang before the sleep) or EINTR: look again.
  }
  return true;
}

}  // namespace sculpt
