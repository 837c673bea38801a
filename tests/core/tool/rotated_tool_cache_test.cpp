#include "sculpt/core/tool/rotated_tool_cache.h"

#include <gtest/gtest.h>

#include <vector>

namespace sculpt::core {
namespace {

std::shared_ptr<const PreparedTool> cone() {
  return std::make_shared<const PreparedTool>(make_cone_tool(6.0f, 10.0f));
}

// Every voxel of the entry's box, requested row by row.
std::vector<uint8_t> all_voxels(RotatedToolEntry& e) {
  std::vector<uint8_t> out;
  const Box& b = e.box();
  for (int z = b.lo.z; z < b.hi.z; ++z)
    for (int y = b.lo.y; y < b.hi.y; ++y) {
      const uint8_t* r = e.row(y, z, b.lo.x, b.hi.x);
      out.insert(out.end(), r, r + (b.hi.x - b.lo.x));
    }
  return out;
}

const glm::quat kTurn = glm::normalize(glm::quat(0.9f, 0.2f, -0.3f, 0.1f));

TEST(RotatedToolCache, HitAfterAnIntegerMoveReturnsIdenticalVoxelsWithoutRotating) {
  RotatedToolCache cache(cone(), Sampling::kTrilinear);
  auto a = cache.acquire(kTurn, {20.3f, 11.6f, 7.0f});
  const std::vector<uint8_t> first = all_voxels(*a.entry);
  const int64_t rotated = cache.stats().voxels_rotated;
  EXPECT_EQ(rotated, static_cast<int64_t>(first.size()));
  auto b = cache.acquire(kTurn, {25.3f, 9.6f, 8.0f});
  EXPECT_EQ(cache.stats().placement_hits, 1);
  EXPECT_EQ(b.anchor - a.anchor, glm::ivec3(5, -2, 1));
  EXPECT_EQ(all_voxels(*b.entry), first);
  EXPECT_EQ(cache.stats().voxels_rotated, rotated);
  EXPECT_DOUBLE_EQ(cache.stats().voxel_hit_rate(), 0.5);
}

TEST(RotatedToolCache, EntryMatchesAFreshRotationOfTheSamePlacement) {
  auto tool = cone();
  RotatedToolCache cache(tool, Sampling::kNearest);
  auto p = cache.acquire(kTurn, {3.7f, 4.2f, 5.9f});
  const RotationFrame frame(*tool, p.entry->rotation(), p.entry->offset(), Sampling::kNearest);
  ASSERT_EQ(frame.box(), p.entry->box());
  std::vector<uint8_t> fresh(static_cast<size_t>(frame.box().voxel_count()));
  frame.sample_box(*tool, fresh.data());
  EXPECT_EQ(all_voxels(*p.entry), fresh);
}

TEST(RotatedToolCache, TurningBackHitsAndNewOrientationsMiss) {
  RotatedToolCache cache(cone(), Sampling::kTrilinear);
  const glm::quat other = glm::normalize(glm::quat(0.5f, 0.5f, 0.5f, 0.1f));
  (void)cache.acquire(kTurn, {0, 0, 0});
  (void)cache.acquire(other, {0, 0, 0});
  (void)cache.acquire(-kTurn, {0, 0, 0});    // the same rotation
  (void)cache.acquire(kTurn, {0.5f, 0, 0});  // another sub-voxel offset
  EXPECT_EQ(cache.stats().placements, 4);
  EXPECT_EQ(cache.stats().placement_hits, 1);
  EXPECT_EQ(cache.stats().entries, 3u);
}

TEST(RotatedToolCache, OnlyRequestedVoxelsAreRotated) {
  RotatedToolCache cache(cone(), Sampling::kTrilinear);
  auto p = cache.acquire(kTurn, {0, 0, 0});
  const Box& b = p.entry->box();
  const int y = (b.lo.y + b.hi.y) / 2, z = (b.lo.z + b.hi.z) / 2;
  (void)p.entry->row(y, z, b.lo.x + 2, b.lo.x + 5);
  EXPECT_EQ(cache.stats().voxels_rotated, 3);
  // Widening the stretch rotates only the new voxels.
  (void)p.entry->row(y, z, b.lo.x, b.lo.x + 7);
  EXPECT_EQ(cache.stats().voxels_rotated, 7);
  (void)p.entry->row(y, z, b.lo.x + 1, b.lo.x + 6);
  EXPECT_EQ(cache.stats().voxels_rotated, 7);
}

TEST(RotatedToolCache, MemoryStaysUnderItsCap) {
  auto tool = cone();
  std::vector<glm::quat> turns;
  for (int i = 0; i < 10; ++i)
    turns.push_back(glm::angleAxis(0.1f * static_cast<float>(i), glm::vec3(0, 0, 1)));
  RotatedToolCache probe(tool, Sampling::kNearest);
  size_t smallest = SIZE_MAX, largest = 0;
  for (const glm::quat& q : turns) {
    const size_t b = probe.acquire(q, {0, 0, 0}).entry->memory_bytes();
    smallest = std::min(smallest, b);
    largest = std::max(largest, b);
  }
  const size_t cap = largest * 3 + largest / 2;
  RotatedToolCache cache(tool, Sampling::kNearest, cap);
  for (const glm::quat& q : turns) {
    (void)cache.acquire(q, {0, 0, 0});
    EXPECT_LE(cache.stats().bytes, cap);
  }
  EXPECT_GE(cache.stats().entries, 3u);
  EXPECT_LE(cache.stats().entries, cap / smallest);
  EXPECT_EQ(cache.stats().evictions, static_cast<int64_t>(turns.size() - cache.stats().entries));
  // The most recent is still there.
  (void)cache.acquire(turns.back(), {0, 0, 0});
  EXPECT_EQ(cache.stats().placement_hits, 1);
}

}  // namespace
}  // namespace sculpt::core
