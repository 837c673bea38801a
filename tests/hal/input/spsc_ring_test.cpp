// The ring's correctness under real concurrency. Run under ThreadSanitizer in
// CI (-DSCULPT_SANITIZE=thread): a data race in the ring is reported there
// even when the values below happen to come out right.

#include "sculpt/hal/input/spsc_ring.h"

#include <thread>

#include <gtest/gtest.h>

#include "sculpt/hal/types/input_event.h"

namespace sculpt::hal {
namespace {

TEST(SpscRing, FullAndEmptyAtCapacity) {
  SpscRing<int> ring(3);
  int v = 0;
  EXPECT_FALSE(ring.try_pop(v));
  EXPECT_TRUE(ring.try_push(1));
  EXPECT_TRUE(ring.try_push(2));
  EXPECT_TRUE(ring.try_push(3));
  EXPECT_FALSE(ring.try_push(4)) << "a full ring refuses, never overwrites";
  EXPECT_EQ(ring.size_approx(), 3u);
  ASSERT_TRUE(ring.try_pop(v));
  EXPECT_EQ(v, 1);
  EXPECT_TRUE(ring.try_push(4));  // wraps around
  for (int want : {2, 3, 4}) {
    ASSERT_TRUE(ring.try_pop(v));
    EXPECT_EQ(v, want);
  }
  EXPECT_FALSE(ring.try_pop(v));
}

TEST(SpscRing, StressEveryItemArrivesOnceInOrder) {
  // Small ring, many items: the producer constantly meets a full ring and the
  // consumer an empty one, exercising both index caches.
  constexpr int64_t kItems = 2'000'000;
  SpscRing<InputEvent> ring(64);
  std::thread producer([&] {
    InputEvent e;
    for (int64_t i = 0; i < kItems; ++i) {
      e.t_ns = i;
      e.axes[0] = static_cast<float>(i % 1000);
      e.button = static_cast<int>(i % 7);
      while (!ring.try_push(e))
        std::this_thread::yield();
    }
  });
  int64_t expected = 0;
  int64_t mismatches = 0;
  InputEvent e;
  while (expected < kItems) {
    if (!ring.try_pop(e)) {
      std::this_thread::yield();
      continue;
    }
    mismatches += e.t_ns != expected || e.axes[0] != static_cast<float>(expected % 1000) ||
                  e.button != static_cast<int>(expected % 7);
    ++expected;
  }
  producer.join();
  EXPECT_EQ(mismatches, 0);
  EXPECT_FALSE(ring.try_pop(e));
}

}  // namespace
}  // namespace sculpt::hal
