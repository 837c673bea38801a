#include "sculpt/hal/haptics/haptic_thread.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <cerrno>
#include <cstring>

#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {
namespace {

constexpr int64_t kNsPerS = 1'000'000'000;

// A hint to the core that this is a polling loop (x86's PAUSE): it saves
// power and leaves the sibling hyper-thread its share.
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

timespec to_timespec(int64_t ns) {
  return {static_cast<time_t>(ns / kNsPerS), static_cast<long>(ns % kNsPerS)};
}

}  // namespace

HapticThread::HapticThread(HapticLoop& loop, ForceDevice& device,
                           const HapticThreadOptions& options)
    : loop_(loop), device_(device), options_(options) {}

HapticThread::~HapticThread() {
  stop();
}

void HapticThread::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  started_.store(false);
  thread_ = std::thread([this] { run(); });
  // Wait until the thread has said whether it is real-time, so
  // realtime_note() is safe to read once start() returns.
  while (!started_.load(std::memory_order_acquire))
    std::this_thread::yield();
}

void HapticThread::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true, std::memory_order_release);
  thread_.join();
}

void HapticThread::run() {
  pthread_setname_np(pthread_self(), "haptics");
  if (options_.realtime_priority > 0) {
    sched_param param{};
    param.sched_priority = options_.realtime_priority;
    const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (error == 0) {
      realtime_.store(true, std::memory_order_release);
    } else {
      realtime_note_ = std::string("haptic loop: no real-time priority (SCHED_FIFO ") +
                       std::to_string(options_.realtime_priority) + ": " + std::strerror(error) +
                       "); ticks may come late when the machine is busy (give the user rtprio " +
                       "in /etc/security/limits.conf)";
    }
  } else {
    realtime_note_ = "haptic loop: real-time priority not asked for";
  }
  running_.store(true, std::memory_order_release);
  started_.store(true, std::memory_order_release);

  int64_t deadline_ns = monotonic_ns();
  while (!stop_.load(std::memory_order_acquire)) {
    if (!loop_.tick(monotonic_ns())) break;
    deadline_ns += options_.period_ns;
    const int64_t now_ns = monotonic_ns();
    if (now_ns >= deadline_ns) {
      // Past the next deadline already: take the first one still ahead.
      const int64_t behind = (now_ns - deadline_ns) / options_.period_ns + 1;
      skipped_.fetch_add(behind, std::memory_order_relaxed);
      deadline_ns += behind * options_.period_ns;
    }
    const timespec at = to_timespec(deadline_ns - options_.spin_ns);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &at, nullptr) == EINTR) {
    }
    while (options_.spin_ns > 0 && monotonic_ns() < deadline_ns) {
      cpu_relax();
    }
  }
  device_.zero();
  running_.store(false, std::memory_order_release);
}

}  // namespace sculpt::hal
