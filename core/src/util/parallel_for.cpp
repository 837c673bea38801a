#include "sculpt/core/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace sculpt::core {

namespace {
std::atomic<int> g_default_threads{0};
}  // namespace

int hardware_threads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

int default_threads() {
  const int n = g_default_threads.load(std::memory_order_relaxed);
  return n > 0 ? n : hardware_threads();
}

void set_default_threads(int threads) {
  g_default_threads.store(std::max(threads, 0), std::memory_order_relaxed);
}

void parallel_for(int64_t count, const std::function<void(int64_t)>& body, int threads) {
  if (threads <= 0) threads = default_threads();
  const int64_t workers = std::min<int64_t>(threads, count);
  if (workers <= 1) {
    for (int64_t i = 0; i < count; ++i)
      body(i);
    return;
  }
  std::atomic<int64_t> next{0};
  auto work = [&] {
    for (int64_t i = next.fetch_add(1, std::memory_order_relaxed); i < count;
         i = next.fetch_add(1, std::memory_order_relaxed)) {
      body(i);
    }
  };
  std::vector<std::jthread> pool;
  pool.reserve(static_cast<size_t>(workers - 1));
  for (int64_t t = 1; t < workers; ++t)
    pool.emplace_back(work);
  work();
}

}  // namespace sculpt::core
