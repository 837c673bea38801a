#include "sculpt/core/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "sculpt/base/memory_reuse.h"
#include "sculpt/base/thread_priority.h"
#include "sculpt/base/thread_times.h"

namespace sculpt::core {

namespace {

std::atomic<int> g_default_threads{0};
std::atomic<size_t> g_pool_warm_bytes{0};

// Depth of parallel_for calls on this thread: a body that calls parallel_for
// again runs the inner loop serially rather than waiting on workers that are
// busy with the outer one.
thread_local int t_loop_depth = 0;

// Hands out indices in order until the range is used up.
void drain(std::atomic<int64_t>& next, int64_t count, const std::function<void(int64_t)>& body) {
  for (int64_t i = next.fetch_add(1, std::memory_order_relaxed); i < count;
       i = next.fetch_add(1, std::memory_order_relaxed)) {
    body(i);
  }
}

// A loop's helpers take on its caller's scheduling (thread_priority.h) while
// they run it: a real-time thread's loop must not wait on helpers that the
// drawing's threads keep off the cores, and an ordinary thread's loop must
// not run ahead of them. The system call is made only when it changes.
void adopt_scheduling(const ThreadScheduling& loop, ThreadScheduling& mine) {
  if (loop != mine && set_this_thread_scheduling(loop)) mine = loop;
}

// Threads kept asleep between loops. Starting threads for every call cost
// about as much as re-meshing a brick, and a dab's re-mesh is a few bricks;
// waking a sleeping worker costs far less.
class WorkerPool {
 public:
  explicit WorkerPool(const char* name) : name_(name) {}

  // Runs the loop with up to `helpers` pool threads beside the caller, or
  // returns false at once if another thread's loop holds the pool.
  bool try_run(int64_t count, const std::function<void(int64_t)>& body, int helpers) {
    bool expected = false;
    if (!busy_.compare_exchange_strong(expected, true, std::memory_order_acquire)) return false;
    {
      std::lock_guard lock(mutex_);
      // A new thread must count this loop as unseen: it takes the lock only
      // after the generation below has moved on.
      start_locked(helpers);
      scheduling_ = this_thread_scheduling();
      body_ = &body;
      count_ = count;
      next_.store(0, std::memory_order_relaxed);
      seats_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    std::exception_ptr error;
    try {
      drain(next_, count, body);
    } catch (...) {
      error = std::current_exception();
      next_.store(count, std::memory_order_relaxed);  // hand out nothing more
    }
    {
      // Workers that have not taken a seat yet must not start on a body that
      // is about to go out of scope.
      std::unique_lock lock(mutex_);
      seats_ = 0;
      finished_.wait(lock, [this] { return seated_ == 0; });
      body_ = nullptr;
    }
    busy_.store(false, std::memory_order_release);
    if (error) std::rethrow_exception(error);
    return true;
  }

  // Starts threads until the crew has `helpers`.
  void start(int helpers) {
    std::lock_guard lock(mutex_);
    start_locked(helpers);
  }

 private:
  void start_locked(int helpers) {
    while (static_cast<int>(threads_.size()) < helpers)
      threads_.emplace_back([this, seen = generation_] { work(seen); });
  }

  void work(uint64_t seen) {
    name_this_thread(name_);
    // Before taking a seat: the loop that started this thread goes on
    // without it meanwhile.
    if (const size_t bytes = g_pool_warm_bytes.load(std::memory_order_relaxed); bytes > 0)
      warm_this_threads_heap(bytes);
    t_loop_depth = 1;
    ThreadScheduling mine = this_thread_scheduling();
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return generation_ != seen && seats_ > 0; });
      seen = generation_;
      --seats_;
      ++seated_;
      const std::function<void(int64_t)>& body = *body_;
      const int64_t count = count_;
      const ThreadScheduling loop = scheduling_;
      lock.unlock();
      adopt_scheduling(loop, mine);
      drain(next_, count, body);
      lock.lock();
      if (--seated_ == 0) finished_.notify_one();
    }
  }

  const char* name_;
  std::atomic<bool> busy_{false};
  std::mutex mutex_;  // guards everything below but next_
  std::condition_variable wake_;
  std::condition_variable finished_;
  std::vector<std::thread> threads_;
  const std::function<void(int64_t)>* body_ = nullptr;
  int64_t count_ = 0;
  ThreadScheduling scheduling_;  // the current loop's caller's
  std::atomic<int64_t> next_{0};
  int seats_ = 0;   // workers that may still join the current loop
  int seated_ = 0;  // workers running the current loop
  uint64_t generation_ = 0;
};

// Crews of sleeping threads, one taken per loop. The station runs loops
// from three threads at once (the sculpting thread's big dabs, the mesher's
// updates, the refiner's passes); with one crew the second loop started
// threads of its own each time, whose first allocations faulted in fresh
// pages beside the loops they shared the cores with. Never destroyed: their
// threads sleep until the process ends, and a static destructor elsewhere
// may still run a loop.
constexpr int kCrews = 3;
WorkerPool& worker_pool(int crew) {
  static constexpr const char* kNames[kCrews] = {"pool", "pool-2", "pool-3"};
  static WorkerPool* pools[kCrews] = {new WorkerPool(kNames[0]), new WorkerPool(kNames[1]),
                                      new WorkerPool(kNames[2])};
  return *pools[crew];
}

// Every crew is in use by other threads: start threads for this loop alone.
void run_on_fresh_threads(int64_t count, const std::function<void(int64_t)>& body,
                          int64_t workers) {
  std::atomic<int64_t> next{0};
  const ThreadScheduling loop = this_thread_scheduling();
  auto work = [&] {
    name_this_thread("pool-extra");
    ThreadScheduling mine = this_thread_scheduling();
    adopt_scheduling(loop, mine);
    t_loop_depth = 1;
    drain(next, count, body);
  };
  std::vector<std::jthread> pool;
  pool.reserve(static_cast<size_t>(workers - 1));
  for (int64_t t = 1; t < workers; ++t)
    pool.emplace_back(work);
  drain(next, count, body);
}

}  // namespace

int hardware_threads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

int default_threads() {
  const int n = g_default_threads.load(std::memory_order_relaxed);
  return n > 0 ? n : hardware_threads();
}

void start_pool_threads(size_t warm_heap_bytes) {
  g_pool_warm_bytes.store(warm_heap_bytes, std::memory_order_relaxed);
  for (int crew = 0; crew < kCrews; ++crew)
    worker_pool(crew).start(hardware_threads() - 1);
}

void set_default_threads(int threads) {
  g_default_threads.store(std::max(threads, 0), std::memory_order_relaxed);
}

void parallel_for(int64_t count, const std::function<void(int64_t)>& body, int threads) {
  if (threads <= 0) threads = default_threads();
  const int64_t workers = std::min<int64_t>(threads, count);
  if (workers <= 1 || t_loop_depth > 0) {
    for (int64_t i = 0; i < count; ++i)
      body(i);
    return;
  }
  struct Depth {
    Depth() { ++t_loop_depth; }
    ~Depth() { --t_loop_depth; }
  } depth;
  for (int crew = 0; crew < kCrews; ++crew)
    if (worker_pool(crew).try_run(count, body, static_cast<int>(workers - 1))) return;
  run_on_fresh_threads(count, body, workers);
}

}  // namespace sculpt::core
