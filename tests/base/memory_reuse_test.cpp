#include "sculpt/base/memory_reuse.h"

#include <malloc.h>

#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "sanitized.h"

namespace sculpt {
namespace {

// A sanitizer replaces malloc: mallopt() and mallinfo2() then speak of an
// allocator nobody uses (AddressSanitizer's mallopt() refuses every setting).
constexpr const char* kOwnAllocator = "a sanitizer's own allocator";

TEST(MemoryReuse, MallocTakesBothSettings) {
  if (test::kSanitized) GTEST_SKIP() << kOwnAllocator;
  EXPECT_TRUE(keep_freed_memory(size_t{64} << 20));
}

// A freed block of a size glibc would otherwise give back to the kernel
// (over its default 128 KiB mmap threshold) stays in the heap: mallinfo2
// counts it as free heap, not as unmapped.
TEST(MemoryReuse, AFreedBigBlockStaysInTheHeap) {
  if (test::kSanitized) GTEST_SKIP() << kOwnAllocator;
  ASSERT_TRUE(keep_freed_memory(size_t{64} << 20));
  constexpr size_t kBlock = size_t{4} << 20;
  const size_t mapped_before = ::mallinfo2().hblkhd;
  auto block = std::make_unique<unsigned char[]>(kBlock);
  block[0] = 1;
  block[kBlock - 1] = 1;
  EXPECT_EQ(::mallinfo2().hblkhd, mapped_before) << "the block was mapped on its own";
  block.reset();
  EXPECT_GE(::mallinfo2().fordblks, kBlock) << "the freed block went back to the kernel";
}

// Warmed, a thread's heap holds the reserve as free memory, still mapped:
// the heap's free bytes grow by about the reserve (a new thread's heap is
// its own arena, so nothing else frees or takes memory there meanwhile).
TEST(MemoryReuse, AWarmedHeapKeepsItsReserve) {
  if (test::kSanitized) GTEST_SKIP() << kOwnAllocator;
  ASSERT_TRUE(keep_freed_memory(size_t{256} << 20));
  constexpr size_t kReserve = size_t{8} << 20;
  std::thread([] {
    const size_t free_before = ::mallinfo2().fordblks;
    warm_this_threads_heap(kReserve);
    EXPECT_GE(::mallinfo2().fordblks, free_before + kReserve - (size_t{1} << 20));
  }).join();
}

// A reserve bigger than one of a thread arena's heaps (64 MiB) stays whole:
// blocks as a stroke's buffers and a change's bricks are (32 KiB), nearly
// the whole reserve of them, are taken without touching a new page. Before
// the newest heap was held, glibc unmapped it as the warming freed its
// blocks, and only the first 64 MiB stayed (6,400 faults here).
TEST(MemoryReuse, AWarmedReserveOverOneHeapStaysWhole) {
  if (test::kSanitized) GTEST_SKIP() << kOwnAllocator;
  ASSERT_TRUE(keep_freed_memory(size_t{256} << 20));
  constexpr size_t kReserve = size_t{96} << 20;
  std::thread([] {
    warm_this_threads_heap(kReserve);
    constexpr size_t kBlock = size_t{32} << 10;
    const size_t blocks = (kReserve - (size_t{4} << 20)) / kBlock;
    std::vector<std::vector<unsigned char>> taken;
    taken.reserve(blocks);
    const int64_t faults_before = this_threads_page_faults();
    for (size_t i = 0; i < blocks; ++i)
      taken.emplace_back(kBlock);  // zeroed: every page written
    // A few for the list itself and the odd page of glibc's bookkeeping.
    EXPECT_LT(this_threads_page_faults() - faults_before, 64);
  }).join();
}

}  // namespace
}  // namespace sculpt
