#include "sculpt/core/tool/rotated_tool_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include <glm/gtc/quaternion.hpp>

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

// The exact rotation of a placement (the entry's sub-voxel offset, the
// caller's orientation unbinned), every voxel of `box` (zero outside its own).
std::vector<uint8_t> exact_voxels(const PreparedTool& tool, const glm::mat3& rotation,
                                  glm::vec3 offset, const Box& box) {
  const RotationFrame frame(tool, rotation, offset, Sampling::kTrilinear);
  std::vector<uint8_t> own(static_cast<size_t>(frame.box().voxel_count()));
  frame.sample_box(tool, own.data());
  std::vector<uint8_t> out;
  const glm::ivec3 n = frame.box().size();
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x) {
        const glm::ivec3 k = glm::ivec3(x, y, z) - frame.box().lo;
        const bool inside =
            glm::all(glm::greaterThanEqual(k, glm::ivec3(0))) && glm::all(glm::lessThan(k, n));
        out.push_back(inside ? own[(static_cast<size_t>(k.z) * n.y + k.y) * n.x + k.x] : 0);
      }
  return out;
}

TEST(RotatedToolCache, BinnedOrientationDiffersFromTheExactOneByAtMostOneDensityStep) {
  // Random orientations of each built-in shape (cubes, a flat cylinder like
  // the demo's, a ring, a cone): the cached placement, turned to its bin's
  // centre, against the exact orientation at the same offset.
  const Tool tools[] = {make_cube_tool(13.0f), make_cylinder_tool(18.0f, 11.0f),
                        make_ring_tool(12.0f, 4.0f), make_cone_tool(10.0f, 20.0f)};
  uint32_t seed = 12345;
  auto unit = [&] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / static_cast<float>(1u << 24);
  };
  for (const Tool& t : tools) {
    auto tool = std::make_shared<const PreparedTool>(t);
    RotatedToolCache cache(tool, Sampling::kTrilinear);
    for (int i = 0; i < 6; ++i) {
      const glm::quat q =
          glm::normalize(glm::quat(unit() - 0.5f, unit() - 0.5f, unit() - 0.5f, unit() - 0.5f));
      auto p = cache.acquire(q, {unit() * 4.0f, unit() * 4.0f, unit() * 4.0f});
      const Box exact_box =
          RotationFrame(*tool, glm::mat3_cast(q), p.entry->offset(), Sampling::kTrilinear).box();
      const Box box{glm::min(p.entry->box().lo, exact_box.lo),
                    glm::max(p.entry->box().hi, exact_box.hi)};
      const std::vector<uint8_t> exact =
          exact_voxels(*tool, glm::mat3_cast(q), p.entry->offset(), box);
      const std::vector<uint8_t> binned =
          exact_voxels(*tool, p.entry->rotation(), p.entry->offset(), box);
      int worst = 0;
      for (size_t k = 0; k < exact.size(); ++k)
        worst = std::max(worst, std::abs(int{exact[k]} - int{binned[k]}));
      EXPECT_LE(worst, 1) << "tool " << t.density.dims().x << " orientation " << i;
      // And what the entry hands out is that binned rotation.
      const Box& eb = p.entry->box();
      const std::vector<uint8_t> from_entry = all_voxels(*p.entry);
      EXPECT_EQ(from_entry, exact_voxels(*tool, p.entry->rotation(), p.entry->offset(), eb));
    }
  }
}

TEST(RotatedToolCache, OrientationsWithinOneBinShareAnEntry) {
  RotatedToolCache cache(cone(), Sampling::kTrilinear);
  const double step = orientation_bin_step(cache.tool().reach_vox());
  int32_t key[4];
  const glm::quat centre = bin_orientation(kTurn, step, key);
  (void)cache.acquire(centre, {0, 0, 0});
  // A drift a tenth of a bin either way, about each axis: the same bin.
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 a(0.0f);
      a[axis] = 1.0f;
      (void)cache.acquire(glm::angleAxis(sign * 0.1f * static_cast<float>(step), a) * centre,
                          {0, 0, 0});
    }
  EXPECT_EQ(cache.stats().placements, 7);
  EXPECT_EQ(cache.stats().placement_hits, 6);
  // Ten bins away is another entry.
  (void)cache.acquire(glm::angleAxis(20.0f * static_cast<float>(step), glm::vec3(0, 0, 1)) * centre,
                      {0, 0, 0});
  EXPECT_EQ(cache.stats().entries, 2u);
}

TEST(RotatedToolCache, BinStepShrinksWithTheToolsReach) {
  // A point at the reach moves at most kOrientationToleranceVox.
  EXPECT_DOUBLE_EQ(orientation_bin_step(10.0f) * 2.0 * 10.0,
                   static_cast<double>(kOrientationToleranceVox));
  EXPECT_DOUBLE_EQ(orientation_bin_step(40.0f) * 4.0, orientation_bin_step(10.0f));
}

}  // namespace
}  // namespace sculpt::core
