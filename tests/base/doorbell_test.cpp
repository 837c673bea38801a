// The doorbell the device readers ring and the sculpting thread sleeps on
// (input_hub.cpp): a ring is never missed, and no ring means a sleep to
// the deadline. Nothing is timed: a sleep that a ring must end has a
// deadline ten seconds away, which only a lost ring reaches.

#include "sculpt/base/doorbell.h"

#include <chrono>
#include <latch>
#include <thread>

#include <gtest/gtest.h>

namespace sculpt {
namespace {

// CLOCK_MONOTONIC, the doorbell's deadlines' clock (libstdc++'s steady_clock).
int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

constexpr int64_t kPatienceNs = int64_t{10} * 1'000'000'000;

TEST(Doorbell, ARingBeforeTheWaitIsNotMissed) {
  Doorbell bell;
  const uint32_t seen = bell.rings();
  bell.ring();
  EXPECT_EQ(bell.rings(), seen + 1);
  const int64_t deadline = now_ns() + kPatienceNs;
  EXPECT_TRUE(bell.wait_until(seen, deadline));
  EXPECT_LT(now_ns(), deadline) << "the ring was lost: it slept to the deadline";
}

TEST(Doorbell, WithoutARingTheWaitEndsAtTheDeadline) {
  Doorbell bell;
  const int64_t deadline = now_ns() + 2'000'000;
  EXPECT_FALSE(bell.wait_until(bell.rings(), deadline));
  EXPECT_GE(now_ns(), deadline);
  EXPECT_FALSE(bell.wait_until(bell.rings(), now_ns() - 1));  // already past
}

TEST(Doorbell, ARingFromAnotherThreadWakesTheSleeper) {
  Doorbell bell;
  for (int round = 0; round < 20; ++round) {
    const uint32_t seen = bell.rings();
    std::latch ready(1);
    std::thread ringer([&] {
      ready.wait();
      // Every other round rings once the sleeper is most likely asleep.
      if (round % 2 == 1) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      bell.ring();
    });
    ready.count_down();
    // The ring may come before the sleep starts or during it: both wake it.
    const int64_t deadline = now_ns() + kPatienceNs;
    EXPECT_TRUE(bell.wait_until(seen, deadline));
    EXPECT_LT(now_ns(), deadline) << "the ring was lost: it slept to the deadline";
    ringer.join();
  }
  EXPECT_EQ(bell.rings(), 20u);
}

}  // namespace
}  // namespace sculpt
