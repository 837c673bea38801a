#include "sculpt/hal/haptics/haptic_thread.h"

#include <pthread.h>
#include <sched.h>

#include <cstring>
#include <string>
#include <vector>

#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {
namespace {

// A hint to the core that this is a polling loop (x86's PAUSE): it saves
// power and leaves the sibling hyper-thread its share.
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// The CPUs this process may run on, in order.
std::vector<int> allowed_cpus() {
  std::vector<int> cpus;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  return cpus;
}

}  // namespace

HapticThread::HapticThread(HapticLoop& loop, ForceDevice& device,
                           const HapticThreadOptions& options)
    : loop_(loop), device_(device), options_(options) {}

HapticThread::~HapticThread() {
  stop();
}

void HapticThread::start() {
  if (threads_[0].joinable()) return;
  stop_.store(false);
  started_.store(0);
  ended_.store(0);
  next_deadline_ns_ = monotonic_ns();
  // The last two cores the process may use (the first usually takes more of
  // the machine's interrupts); one thread, unpinned, without a second core.
  const std::vector<int> cpus = allowed_cpus();
  thread_count_ = options_.standby && cpus.size() >= 2 ? 2 : 1;
  running_.store(true, std::memory_order_release);
  for (int i = 0; i < thread_count_; ++i) {
    const int cpu = thread_count_ == 2 ? cpus[cpus.size() - 2 + static_cast<size_t>(i)] : -1;
    threads_[i] = std::thread([this, i, cpu] { run(i, cpu); });
  }
  // Wait until the threads have said whether they are real-time, so
  // realtime_note() is safe to read once start() returns. Asleep, not
  // yielding: the caller may be real-time itself (the window's sculpting
  // thread restarts the loop for a new tool), and a real-time thread that
  // yields keeps an ordinary one, as the new threads are until they make
  // themselves real-time, off its core (a restart then took up to a second).
  for (int n = started_.load(std::memory_order_acquire); n < thread_count_;
       n = started_.load(std::memory_order_acquire))
    started_.wait(n, std::memory_order_acquire);
}

void HapticThread::stop() {
  if (!threads_[0].joinable()) return;
  stop_.store(true, std::memory_order_release);
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
}

void HapticThread::run(int which, int cpu) {
  pthread_setname_np(pthread_self(), which == 0 ? "haptics" : "haptics-twin");
  if (cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    // Best effort: unpinned, the twin still helps whenever the scheduler
    // has put the two threads on different cores.
    (void)pthread_setaffinity_np(pthread_self(), sizeof set, &set);
  }
  bool realtime = false;
  std::string note;
  if (options_.realtime_priority > 0) {
    sched_param param{};
    param.sched_priority = options_.realtime_priority;
    const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (error == 0) {
      realtime = true;
    } else {
      note = std::string("haptic loop: no real-time priority (SCHED_FIFO ") +
             std::to_string(options_.realtime_priority) + ": " + std::strerror(error) +
             "); ticks may come late when the machine is busy (give the user rtprio " +
             "in /etc/security/limits.conf)";
    }
  } else {
    note = "haptic loop: real-time priority not asked for";
  }
  if (which == 0) {
    realtime_note_ = note;
    realtime_.store(realtime, std::memory_order_release);
  }
  started_.fetch_add(1, std::memory_order_acq_rel);
  started_.notify_all();

  int64_t deadline_ns = 0;
  {
    std::lock_guard<std::mutex> lock(tick_mutex_);
    deadline_ns = next_deadline_ns_;
  }
  while (!stop_.load(std::memory_order_acquire)) {
    sleep_until_ns(deadline_ns - options_.spin_ns);
    while (options_.spin_ns > 0 && monotonic_ns() < deadline_ns) {
      cpu_relax();
    }
    const int64_t woke_ns = monotonic_ns();
    std::lock_guard<std::mutex> lock(tick_mutex_);
    if (stop_.load(std::memory_order_acquire)) break;
    if (next_deadline_ns_ == deadline_ns) {
      // This deadline's tick is still to run: this thread woke first.
      if (!loop_.tick(monotonic_ns())) {
        stop_.store(true, std::memory_order_release);  // the device is gone: both end
        break;
      }
      int64_t next_ns = deadline_ns + options_.period_ns;
      const int64_t now_ns = monotonic_ns();
      if (now_ns >= next_ns) {
        // Past the next deadline already: take the first one still ahead.
        const int64_t behind = (now_ns - next_ns) / options_.period_ns + 1;
        skipped_.fetch_add(behind, std::memory_order_relaxed);
        next_ns += behind * options_.period_ns;
      }
      next_deadline_ns_ = next_ns;
    } else if (woke_ns - deadline_ns > options_.period_ns / 2) {
      // The twin ran this tick while this thread's wake-up came late.
      rescues_.fetch_add(1, std::memory_order_relaxed);
    }
    deadline_ns = next_deadline_ns_;
  }
  // The last thread to end leaves the device with zero force.
  if (ended_.fetch_add(1, std::memory_order_acq_rel) + 1 == thread_count_) {
    device_.zero();
    running_.store(false, std::memory_order_release);
  }
}

}  // namespace sculpt::hal
