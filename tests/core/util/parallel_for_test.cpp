#include "sculpt/core/util/parallel_for.h"

#include <gtest/gtest.h>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "sanitized.h"
#include "sculpt/base/memory_reuse.h"
#include "sculpt/base/thread_priority.h"

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

// The scheduling a pool thread runs one index of a two-index loop with: the
// caller holds its own index until the other has been run elsewhere.
ThreadScheduling a_helpers_scheduling() {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<bool> seen{false};
  ThreadScheduling helper{-1, -1};
  parallel_for(
      2,
      [&](int64_t) {
        if (std::this_thread::get_id() != caller) {
          helper = this_thread_scheduling();
          seen.store(true);
          return;
        }
        while (!seen.load() && std::chrono::steady_clock::now() < give_up)
          std::this_thread::yield();
      },
      2);
  return helper;
}

// A loop's helpers run it with its caller's scheduling: a real-time thread's
// loop (the mesher's) on real-time helpers, not on threads the drawing keeps
// off the cores; an ordinary thread's loop next on ordinary ones again.
TEST(ParallelFor, HelpersRunALoopWithItsCallersScheduling) {
  const ThreadScheduling ordinary = this_thread_scheduling();
  std::optional<ThreadScheduling> realtime_helper;
  std::thread([&] {
    if (!set_this_thread_scheduling({SCHED_FIFO, 1})) return;
    realtime_helper = a_helpers_scheduling();
  }).join();
  if (!realtime_helper) GTEST_SKIP() << "no real-time priority here";
  EXPECT_EQ(*realtime_helper, (ThreadScheduling{SCHED_FIFO, 1}));
  EXPECT_EQ(a_helpers_scheduling(), ordinary);
}

// In a process of its own (the pool is process-wide and its threads start
// once): the page faults a pool thread takes touching 16 MiB of fresh heap
// blocks in its first loop, with pool threads asked to warm `warm_bytes` of
// their heap when they start. Exits 0 when `warm` and it took almost none,
// or when not `warm` and it took a fault a page (the measurement works).
[[noreturn]] void exit_on_a_pool_threads_faults(bool warm) {
  (void)keep_freed_memory(size_t{256} << 20);
  start_pool_threads(warm ? size_t{32} << 20 : 0);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<long> faults{-1};
  parallel_for(
      2,
      [&](int64_t) {
        if (std::this_thread::get_id() == caller) {
          // Holds its index, so the other goes to the pool's thread.
          while (faults.load() < 0 && std::chrono::steady_clock::now() < give_up)
            std::this_thread::yield();
          return;
        }
        rusage before{}, after{};
        getrusage(RUSAGE_THREAD, &before);
        constexpr size_t kBlock = size_t{64} << 10, kBlocks = 256;  // under the mmap threshold
        std::vector<std::unique_ptr<volatile char[]>> blocks;
        for (size_t b = 0; b < kBlocks; ++b) {
          blocks.emplace_back(new volatile char[kBlock]);
          for (size_t at = 0; at < kBlock; at += 4096)
            blocks.back()[at] = 1;
        }
        getrusage(RUSAGE_THREAD, &after);
        faults.store(after.ru_minflt - before.ru_minflt);
      },
      2);
  const long pages = static_cast<long>((size_t{16} << 20) / 4096);
  const long took = faults.load();
  std::exit(took >= 0 && (warm ? took < pages / 16 : took > pages / 2) ? 0 : 1);
}

TEST(ParallelFor, PoolThreadsAskedToWarmTheirHeapTakeNoFaultsInTheirFirstLoop) {
  if (test::kSanitized) GTEST_SKIP() << "a sanitizer's own allocator keeps no warmed heap";
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // a fresh process: no pool threads yet
  EXPECT_EXIT(exit_on_a_pool_threads_faults(false), testing::ExitedWithCode(0), "");
  EXPECT_EXIT(exit_on_a_pool_threads_faults(true), testing::ExitedWithCode(0), "");
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

// The station's three loop owners (the sculpting thread, the mesher, the
// refiner) may each run a loop at once: each gets a crew of sleeping pool
// threads, and none starts threads of its own ("pool-extra"). Each loop's
// first index waits until all three loops hold their crews.
TEST(ParallelFor, ThreeLoopsAtOnceEachRunOnACrewOfPoolThreads) {
  constexpr int kLoops = 3;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  std::atomic<int> holding{0};
  std::mutex m;
  std::set<std::string> names;
  std::vector<std::atomic<int>> hits(kLoops * 64);
  auto loop = [&](int l) {
    std::atomic<bool> first{true};
    parallel_for(
        64,
        [&](int64_t i) {
          if (first.exchange(false)) {
            holding.fetch_add(1);
            while (holding.load() < kLoops && std::chrono::steady_clock::now() < give_up)
              std::this_thread::yield();
          }
          char name[16] = {};
          pthread_getname_np(pthread_self(), name, sizeof name);
          {
            std::lock_guard lock(m);
            names.insert(name);
          }
          hits[static_cast<size_t>(l * 64 + i)].fetch_add(1);
        },
        2);
  };
  std::vector<std::thread> owners;
  for (int l = 0; l < kLoops; ++l)
    owners.emplace_back(loop, l);
  for (std::thread& t : owners)
    t.join();
  EXPECT_EQ(holding.load(), kLoops);  // all three were running at once
  for (const auto& h : hits)
    ASSERT_EQ(h.load(), 1);
  EXPECT_EQ(names.count("pool-extra"), 0u);
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
