#include "sculpt/station/view/lod_selector.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace sculpt::station {
namespace {

TEST(LodSelector, AVoxelOfTheLevelSpansAtMostThePixelError) {
  LodPolicy p;
  p.max_pixel_error = 1.0f;
  p.max_level = 4;
  const LodSelector lod(p);
  // A row of 16 bricks of 32 voxels along x, the eye 16 voxels before the
  // first; a focal length of 100 px: a voxel spans 100 / d pixels.
  const float focal = 100.0f;
  const std::vector<int> levels =
      lod.select({16, 1, 1}, 32, glm::vec3(-16.0f, 16.0f, 16.0f), focal);
  ASSERT_EQ(levels.size(), 16u);
  for (int i = 0; i < 16; ++i) {
    const float nearest = 16.0f + static_cast<float>(i) * 32.0f;  // the brick's nearest face
    const int level = levels[static_cast<size_t>(i)];
    // A coarser level's voxel (2^k voxels) spans at most a pixel there...
    if (level > 0) {
      EXPECT_LE(static_cast<float>(1 << level) * focal / nearest, 1.0f + 1e-5f) << "brick " << i;
    }
    // ...and the next coarser level's would not (or it is the coarsest).
    if (level < 4) {
      EXPECT_GT(static_cast<float>(2 << level) * focal / nearest, 1.0f) << "brick " << i;
    }
  }
  EXPECT_EQ(levels[0], 0);
  EXPECT_TRUE(std::is_sorted(levels.begin(), levels.end()));
  // A bigger viewport (twice the focal length) needs finer levels.
  const std::vector<int> finer =
      lod.select({16, 1, 1}, 32, glm::vec3(-16.0f, 16.0f, 16.0f), 200.0f);
  int coarse_sum = 0, fine_sum = 0;
  for (size_t i = 0; i < 16; ++i) {
    EXPECT_LE(finer[i], levels[i]) << i;
    coarse_sum += levels[i];
    fine_sum += finer[i];
  }
  EXPECT_LT(fine_sum, coarse_sum);
}

TEST(LodSelector, WithoutAFrameBudgetFrameTimesChangeNothing) {
  LodSelector lod;  // the default: no budget
  for (int i = 0; i < 100; ++i)
    EXPECT_FALSE(lod.frame_done(80.0));
  EXPECT_EQ(lod.bias(), 0.0f);
}

TEST(LodSelector, FixedLevelAndMaxLevelAreHonoured) {
  LodPolicy p;
  p.fixed_level = 5;
  p.max_level = 2;
  const std::vector<int> levels = LodSelector(p).select({4, 4, 4}, 32, glm::vec3(0.0f), 500.0f);
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
  const std::vector<int> levels = lod.select({1, 1, 1}, 32, glm::vec3(16.0f), 500.0f);
  EXPECT_EQ(levels[0], 1);
}

}  // namespace
}  // namespace sculpt::station
