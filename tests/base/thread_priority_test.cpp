// Making threads nicer: the window puts drawing behind sculpting and meshing
// this way (station_window.cpp).

#include "sculpt/base/thread_priority.h"

#include <algorithm>
#include <atomic>
#include <latch>
#include <thread>

#include <gtest/gtest.h>

namespace sculpt {
namespace {

// A thread that runs until released, and says its kernel id.
class ParkedThread {
 public:
  ParkedThread()
      : thread_([this] {
          id_.store(this_thread_id());
          started_.count_down();
          release_.wait();
        }) {
    started_.wait();
  }
  ~ParkedThread() {
    release_.count_down();
    thread_.join();
  }
  int id() const { return id_.load(); }

 private:
  std::atomic<int> id_{0};
  std::latch started_{1};
  std::latch release_{1};
  std::thread thread_;
};

TEST(ThreadPriority, FindsTheThreadsStartedInBetween) {
  const std::vector<int> before = process_thread_ids();
  ASSERT_TRUE(std::is_sorted(before.begin(), before.end()));
  ASSERT_TRUE(std::binary_search(before.begin(), before.end(), this_thread_id()));
  ParkedThread started;
  const std::vector<int> now = process_thread_ids();
  EXPECT_EQ(threads_started(before, now), std::vector<int>{started.id()});
  EXPECT_TRUE(threads_started(now, now).empty());
}

TEST(ThreadPriority, MakesThreadsNicerAndNeverLessNice) {
  const int base = thread_niceness(this_thread_id());
  ASSERT_GT(base, -100);
  if (base >= 17) GTEST_SKIP() << "already running at niceness " << base;
  ParkedThread drawing, sculpting;
  ASSERT_EQ(thread_niceness(drawing.id()), base);  // inherited from this thread
  const int nicer = base + 2;
  const int ids[] = {drawing.id()};
  EXPECT_EQ(make_threads_nicer(ids, nicer), 1);
  EXPECT_EQ(thread_niceness(drawing.id()), nicer);
  EXPECT_EQ(thread_niceness(sculpting.id()), base);    // only the threads named
  EXPECT_EQ(thread_niceness(this_thread_id()), base);  // nor the caller
  EXPECT_EQ(make_threads_nicer(ids, base + 1), 0);     // a nicer thread keeps its niceness
  EXPECT_EQ(thread_niceness(drawing.id()), nicer);
}

TEST(ThreadPriority, SkipsAThreadThatEnded) {
  int ended = 0;
  std::thread([&] { ended = this_thread_id(); }).join();
  EXPECT_EQ(thread_niceness(ended), -100);
  const int ids[] = {ended};
  // Nothing to change (setpriority would fail on it as well): no error, 0.
  EXPECT_EQ(make_threads_nicer(ids, 19), 0);
}

}  // namespace
}  // namespace sculpt
