#include "sculpt/station/view/lod_selector.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace sculpt::station {
namespace {

TEST(LodSelector, LevelGrowsByOneEachTimeTheDistanceDoubles) {
  LodPolicy p;
  p.full_detail_distance = 100.0f;
  p.max_level = 4;
  const LodSelector lod(p);
  // A row of 16 bricks of 32 voxels along x, eye at the first brick's centre.
  const std::vector<int> levels = lod.select({16, 1, 1}, 32, glm::vec3(16.0f, 16.0f, 16.0f));
  ASSERT_EQ(levels.size(), 16u);
  for (int i = 0; i < 16; ++i) {
    const float d = static_cast<float>(i) * 32.0f;
    const int expected = d < 200 ? 0 : d < 400 ? 1 : 2;
    EXPECT_EQ(levels[static_cast<size_t>(i)], expected) << "brick " << i;
  }
  EXPECT_TRUE(std::is_sorted(levels.begin(), levels.end()));
}

TEST(LodSelector, FixedLevelAndMaxLevelAreHonoured) {
  LodPolicy p;
  p.fixed_level = 5;
  p.max_level = 2;
  const std::vector<int> levels = LodSelector(p).select({4, 4, 4}, 32, glm::vec3(0.0f));
  EXPECT_EQ(levels.size(), 64u);
  for (int l : levels)
    EXPECT_EQ(l, 2);
}

TEST(LodSelector, SlowFramesCoarsenAndFastFramesRefineWithHysteresis) {
  LodPolicy p;
  p.frame_budget_ms = 16.0;
  p.max_level = 2;
  LodSelector lod(p);
  // One slow frame among fast ones changes nothing.
  EXPECT_FALSE(lod.frame_done(40.0));
  EXPECT_EQ(lod.bias(), 0.0f);
  int changes = 0;
  for (int i = 0; i < 100; ++i)
    changes += lod.frame_done(40.0);
  EXPECT_FLOAT_EQ(lod.bias(), 2.0f);  // capped at max_level
  EXPECT_EQ(changes, 8);              // 0.25 a step
  for (int i = 0; i < 100; ++i)
    lod.frame_done(12.0);  // within budget, not well under
  EXPECT_FLOAT_EQ(lod.bias(), 2.0f);
  for (int i = 0; i < 200; ++i)
    lod.frame_done(2.0);
  EXPECT_FLOAT_EQ(lod.bias(), 0.0f);
  // The bias shows in the levels chosen.
  for (int i = 0; i < 8; ++i)
    lod.frame_done(40.0);
  EXPECT_FLOAT_EQ(lod.bias(), 0.25f);
  for (int i = 0; i < 24; ++i)
    lod.frame_done(40.0);
  EXPECT_FLOAT_EQ(lod.bias(), 1.0f);
  const std::vector<int> levels = lod.select({1, 1, 1}, 32, glm::vec3(16.0f));
  EXPECT_EQ(levels[0], 1);
}

}  // namespace
}  // namespace sculpt::station
