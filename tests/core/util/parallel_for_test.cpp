#include "sculpt/core/util/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
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

}  // namespace
}  // namespace sculpt::core
