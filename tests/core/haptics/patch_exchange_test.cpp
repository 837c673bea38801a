#include "sculpt/core/haptics/patch_exchange.h"

#include <atomic>
#include <thread>

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(PatchExchange, TheReaderGetsWholeSnapshotsInOrderWhileTheWriterNeverWaits) {
  constexpr int kEdge = 8;
  constexpr uint64_t kPublishes = 20000;
  PatchExchange exchange(kEdge);
  EXPECT_TRUE(exchange.acquire().empty());
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (uint64_t v = 1; v <= kPublishes; ++v) {
      PatchSnapshot& s = exchange.back();
      s.edge = kEdge;
      s.version = v;
      s.phi.assign(size_t(kEdge) * kEdge * kEdge, float(v));
      exchange.publish();
    }
    done = true;
  });
  uint64_t last = 0, reads = 0;
  while (!done || last < kPublishes) {
    const PatchSnapshot& s = exchange.acquire();
    if (s.empty()) continue;
    ASSERT_GE(s.version, last);
    // Every value comes from the same publish as the version.
    for (const float v : s.phi)
      ASSERT_EQ(v, float(s.version));
    last = s.version;
    ++reads;
  }
  writer.join();
  EXPECT_EQ(last, kPublishes);
  EXPECT_GT(reads, 0u);
}

TEST(PatchExchange, CopyingIntoASnapshotReusesItsMemory) {
  PatchExchange exchange(4);
  PatchSnapshot patch;
  patch.edge = 4;
  patch.phi.assign(64, 1.5f);
  const float* before = exchange.back().phi.data();
  copy_snapshot(patch, exchange.back());
  EXPECT_EQ(exchange.back().phi.data(), before);
  EXPECT_EQ(exchange.back().phi, patch.phi);
}

}  // namespace
}  // namespace sculpt::core
