// Making threads nicer and real-time: the window puts a dab's path ahead of
// drawing, and drawing behind sculpting and meshing, this way
// (station_window.cpp).

#include "sculpt/base/thread_priority.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <latch>
#include <string>
#include <thread>

#include <pthread.h>
#include <sched.h>

#include <gtest/gtest.h>

namespace sculpt {
namespace {

// A thread that runs until released, and says its kernel id.
class ParkedThread {
 public:
  explicit ParkedThread(const char* name = nullptr)
      : thread_([this, name] {
          if (name != nullptr) pthread_setname_np(pthread_self(), name);
          id_.store(this_thread_id());
          started_.count_down();
          release_.wait();
          if (on_release_) on_release_();
        }) {
    started_.wait();
  }
  // Runs `f` on the thread when it is released (before the destructor
  // joins it).
  void on_release(std::function<void()> f) { on_release_ = std::move(f); }
  ~ParkedThread() {
    release_.count_down();
    thread_.join();
  }
  int id() const { return id_.load(); }

 private:
  std::atomic<int> id_{0};
  std::latch started_{1};
  std::latch release_{1};
  std::function<void()> on_release_;
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

TEST(ThreadPriority, FindsThreadsByName) {
  ParkedThread reader("tp-reader"), other("tp-other");
  EXPECT_EQ(threads_named("tp-reader"), std::vector<int>{reader.id()});
  EXPECT_TRUE(threads_named("tp-none").empty());
}

TEST(ThreadPriority, MakesThreadsRealtimeButNotTheThreadsTheyStart) {
  std::atomic<int> child_policy{-1};
  {
    ParkedThread sculpting, drawing;
    const int ids[] = {sculpting.id()};
    if (const std::string why_not = make_threads_realtime(ids, 1); !why_not.empty())
      GTEST_SKIP() << "no real-time priority here: " << why_not;
    EXPECT_EQ(thread_scheduling(sculpting.id()), (ThreadScheduling{SCHED_FIFO, 1}));
    const ThreadScheduling ordinary{SCHED_OTHER, 0};
    EXPECT_EQ(thread_scheduling(drawing.id()), ordinary);  // only the threads named
    EXPECT_EQ(this_thread_scheduling(), ordinary);
    // A thread the real-time one starts is ordinary: a long job started
    // from the sculpting thread must not keep the frames off the cores.
    sculpting.on_release(
        [&] { std::thread([&] { child_policy.store(this_thread_scheduling().policy); }).join(); });
  }  // released: the child is started and joined
  EXPECT_EQ(child_policy.load(), SCHED_OTHER);
}

TEST(ThreadPriority, AThreadTakesOnAndLeavesAScheduling) {
  const ThreadScheduling ordinary = this_thread_scheduling();
  ASSERT_EQ(ordinary.policy, SCHED_OTHER);
  EXPECT_EQ(ordinary.priority, 0);
  std::atomic<bool> took = false, left = false;
  ThreadScheduling seen;
  std::thread([&] {
    if (!set_this_thread_scheduling({SCHED_FIFO, 1})) return;
    took = true;
    seen = this_thread_scheduling();
    left = set_this_thread_scheduling(ordinary) && this_thread_scheduling() == ordinary;
  }).join();
  if (!took) GTEST_SKIP() << "no real-time priority here";
  EXPECT_EQ(seen, (ThreadScheduling{SCHED_FIFO, 1}));
  EXPECT_TRUE(left);
}

}  // namespace
}  // namespace sculpt
