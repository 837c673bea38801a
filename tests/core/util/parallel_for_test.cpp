#include "sculpt/core/util/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace sculpt::core {
namespace {

TEST(ParallelFor, VisitsEveryIndexExactlyOnce) {
  for (int threads : {1, 2, 7}) {
    std::vector<std::atomic<int>> hits(1000);
    parallel_for(
        1000, [&](int64_t i) { hits[static_cast<size_t>(i)].fetch_add(1); }, threads);
    for (const auto& h : hits)
      ASSERT_EQ(h.load(), 1);
  }
  int calls = 0;
  parallel_for(0, [&](int64_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

// The pool's threads are reused: many short loops in a row, as a stroke of
// dabs makes them, each see every index once.
TEST(ParallelFor, ManyShortLoopsInARowEachVisitEveryIndex) {
  for (int loop = 0; loop < 2000; ++loop) {
    const int64_t count = 1 + loop % 9;
    std::vector<std::atomic<int>> hits(static_cast<size_t>(count));
    parallel_for(
        count, [&](int64_t i) { hits[static_cast<size_t>(i)].fetch_add(1); }, 4);
    for (const auto& h : hits)
      ASSERT_EQ(h.load(), 1) << "loop " << loop;
  }
}

// The loop really runs on more than one thread when asked to, from the very
// first loop of the process (ctest runs this test alone): each index waits
// for the other to arrive. The wait gives up after a minute so that a loop
// left to one thread fails instead of hanging.
TEST(ParallelFor, UsesMoreThanTheCallingThread) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  std::atomic<int> arrived{0};
  std::mutex m;
  std::set<std::thread::id> ids;
  parallel_for(
      2,
      [&](int64_t) {
        {
          std::lock_guard lock(m);
          ids.insert(std::this_thread::get_id());
        }
        arrived.fetch_add(1);
        while (arrived.load() < 2 && std::chrono::steady_clock::now() < give_up)
          std::this_thread::yield();
      },
      2);
  EXPECT_EQ(ids.size(), 2u);
}

TEST(ParallelFor, ALoopInsideALoopRunsAndCompletes) {
  std::vector<std::atomic<int>> hits(16 * 16);
  parallel_for(
      16,
      [&](int64_t i) {
        parallel_for(
            16, [&](int64_t j) { hits[static_cast<size_t>(i * 16 + j)].fetch_add(1); }, 4);
      },
      4);
  for (const auto& h : hits)
    ASSERT_EQ(h.load(), 1);
}

// Two threads that start loops at once (say a replay and a distance
// transform in one process) both finish with every index visited.
TEST(ParallelFor, LoopsFromTwoThreadsAtOnceBothComplete) {
  std::vector<std::atomic<int>> a(5000), b(5000);
  auto run = [](std::vector<std::atomic<int>>& hits) {
    for (int round = 0; round < 50; ++round)
      parallel_for(
          static_cast<int64_t>(hits.size() / 50),
          [&](int64_t i) { hits[static_cast<size_t>(round * 100 + i)].fetch_add(1); }, 3);
  };
  std::thread other([&] { run(b); });
  run(a);
  other.join();
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].load(), 1);
    ASSERT_EQ(b[i].load(), 1);
  }
}

// An exception thrown on the calling thread reaches the caller after the
// workers have let go of the body, and the pool still works afterwards.
TEST(ParallelFor, AnExceptionOnTheCallingThreadReachesTheCaller) {
  // A worker holds its first index until the caller has thrown, so the
  // caller is sure to take one.
  const auto caller = std::this_thread::get_id();
  std::atomic<bool> thrown{false};
  EXPECT_THROW(parallel_for(
                   1000,
                   [&](int64_t) {
                     if (std::this_thread::get_id() == caller) {
                       thrown.store(true);
                       throw std::runtime_error("stop");
                     }
                     while (!thrown.load())
                       std::this_thread::yield();
                   },
                   2),
               std::runtime_error);
  std::vector<std::atomic<int>> hits(100);
  parallel_for(
      100, [&](int64_t i) { hits[static_cast<size_t>(i)].fetch_add(1); }, 2);
  for (const auto& h : hits)
    ASSERT_EQ(h.load(), 1);
}

}  // namespace
}  // namespace sculpt::core
