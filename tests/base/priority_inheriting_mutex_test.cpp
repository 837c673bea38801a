// The window's turn between the real-time sculpting thread and the frame's
// thread (input_hub.h): while the sculpting thread waits for the turn, the
// frame's thread holding it runs at the sculpting thread's priority, ahead
// of the real-time mesher that would otherwise keep it off the core.

#include "sculpt/base/priority_inheriting_mutex.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include <pthread.h>
#include <sched.h>

#include <gtest/gtest.h>

#include "sculpt/base/thread_priority.h"

namespace sculpt {
namespace {

TEST(PriorityInheritingMutex, IsALockableMutex) {
  PriorityInheritingMutex m;
  {
    std::unique_lock lock(m);
    EXPECT_TRUE(lock.owns_lock());
    std::thread other([&] { EXPECT_FALSE(m.try_lock()); });
    other.join();
  }
  EXPECT_TRUE(m.try_lock());
  m.unlock();
  // Two threads counting under it lose no count.
  int64_t count = 0;
  auto add = [&] {
    for (int i = 0; i < 100000; ++i) {
      std::lock_guard lock(m);
      ++count;
    }
  };
  std::thread a(add), b(add);
  a.join();
  b.join();
  EXPECT_EQ(count, 200000);
}

// Pins the calling thread to `cpu`.
bool pin_to(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

// The inversion itself, on one core: a low thread (ordinary) holds the
// mutex, a middle one (SCHED_FIFO 1) spins, a high one (SCHED_FIFO 2) asks
// for the mutex. Without inheritance the low thread never runs while the
// middle one spins, so the high one gets the mutex only after the middle
// one gives up. With it the low thread runs at the high one's priority,
// lets go, and the high one has the mutex microseconds later, while the
// middle one still spins. The middle one's bound (300 ms) stays under the
// kernel's real-time throttling (sched_rt_runtime_us: real-time threads get
// at most 950 ms of each second), which would let the low thread run.
TEST(PriorityInheritingMutex, TheHolderRunsAheadOfAMiddlePriorityThread) {
  PriorityInheritingMutex m;
  ASSERT_TRUE(m.inherits_priority());
  if (!set_this_thread_scheduling({SCHED_FIFO, 1})) GTEST_SKIP() << "no real-time priority here";
  ASSERT_TRUE(set_this_thread_scheduling({SCHED_OTHER, 0}));
  // Two of the cores this process may use: the test's own thread stays on
  // the first, so it can start the threads whatever spins on the second.
  cpu_set_t saved;
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof saved, &saved), 0);
  int cpus[2] = {-1, -1};
  for (int c = 0, found = 0; c < CPU_SETSIZE && found < 2; ++c)
    if (CPU_ISSET(c, &saved)) cpus[found++] = c;
  if (cpus[1] < 0) GTEST_SKIP() << "needs two cores";
  ASSERT_TRUE(pin_to(cpus[0]));
  const int shared = cpus[1];

  std::atomic<bool> low_holds{false}, high_waits{false}, high_has_it{false};
  std::atomic<bool> middle_spins{false}, middle_gave_up{false};
  std::thread low([&] {
    EXPECT_TRUE(pin_to(shared));
    std::unique_lock lock(m);
    low_holds = true;
    while (!high_waits)
      std::this_thread::yield();
    lock.unlock();
  });
  while (!low_holds)
    std::this_thread::yield();
  std::thread middle([&] {
    // Real-time first, then onto the shared core (an ordinary thread
    // moved there would wait behind the spinning one).
    EXPECT_TRUE(set_this_thread_scheduling({SCHED_FIFO, 1}));
    EXPECT_TRUE(pin_to(shared));
    middle_spins = true;
    const auto bound = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
    while (!high_has_it && std::chrono::steady_clock::now() < bound) {
    }
    middle_gave_up = !high_has_it;
  });
  while (!middle_spins)
    std::this_thread::yield();
  std::thread high([&] {
    EXPECT_TRUE(set_this_thread_scheduling({SCHED_FIFO, 2}));
    EXPECT_TRUE(pin_to(shared));
    high_waits = true;
    std::lock_guard lock(m);
    high_has_it = true;
  });
  high.join();
  middle.join();
  low.join();
  pthread_setaffinity_np(pthread_self(), sizeof saved, &saved);
  EXPECT_TRUE(high_has_it);
  EXPECT_FALSE(middle_gave_up) << "the holder waited behind the middle-priority thread";
}

}  // namespace
}  // namespace sculpt
