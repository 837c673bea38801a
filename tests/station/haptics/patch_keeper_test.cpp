// The sculpting side's patch: after dabs and moves, at full resolution and at
// a coarser level of the pyramid, what the haptic loop receives equals a
// patch built from scratch on the material as it is then.

#include "sculpt/station/haptics/patch_keeper.h"

#include <gtest/gtest.h>

#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {
namespace {

// The snapshot a from-scratch build on `volume` (at `level`) gives.
core::PatchSnapshot fresh(const core::Volume& volume, int level,
                          const core::DistancePatchOptions& options, glm::vec3 centre_vox) {
  const float scale = static_cast<float>(1 << level);
  core::DistancePatch patch(options);
  if (level == 0) {
    patch.build(volume, centre_vox);
  } else {
    const core::Volume coarse =
        core::Volume::from_dense(volume.to_dense(level), core::VolumeOptions{16, 1, 1});
    patch.build(coarse, centre_vox / scale);
  }
  return patch.snapshot();
}

void expect_same(const core::PatchSnapshot& a, const core::PatchSnapshot& b) {
  ASSERT_EQ(a.origin, b.origin);
  ASSERT_EQ(a.edge, b.edge);
  ASSERT_EQ(a.phi.size(), b.phi.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.phi.size(); ++i)
    differ += a.phi[i] != b.phi[i];
  EXPECT_EQ(differ, 0u);
}

class PatchKeeperAtLevel : public testing::TestWithParam<int> {};

TEST_P(PatchKeeperAtLevel, WhatItPublishesEqualsAFreshBuildAfterDabsAndMoves) {
  const int level = GetParam();
  core::Volume volume = clay_block(glm::ivec3(128), 32);  // clay in [32, 96)
  const core::DistancePatchOptions options{48, core::band_for_sphere(3.0f), 1};
  core::PatchExchange exchange(options.edge);
  PatchKeeper keeper(exchange, options, level);
  const float scale = static_cast<float>(1 << level);
  glm::vec3 centre(64.0f, 96.0f + 3.0f * scale, 64.0f);
  ASSERT_TRUE(keeper.update(volume, 1, centre));
  expect_same(exchange.acquire(), fresh(volume, level, options, centre));
  EXPECT_FALSE(keeper.update(volume, 1, centre));  // nothing changed: nothing published

  // Dabs under the patch, and one far away (which the level's mirror must
  // follow all the same, for when the patch gets there).
  core::Sculptor sculptor(volume);
  sculptor.set_tool(core::make_sphere_tool(6.0f));
  for (const glm::vec3 at : {glm::vec3(64, 96, 64), glm::vec3(70, 94, 60), glm::vec3(30, 60, 100)})
    sculptor.dab({at, glm::quat(1, 0, 0, 0), core::SculptMode::kSubtract, 1.0f});
  ASSERT_TRUE(keeper.update(volume, 1, centre));
  expect_same(exchange.acquire(), fresh(volume, level, options, centre));
  EXPECT_GE(keeper.figures().refreshes, 1);

  // The proxy moves far off the centre: the patch follows.
  centre += glm::vec3(20.0f * scale, 0.0f, 0.0f);
  ASSERT_TRUE(keeper.update(volume, 1, centre));
  expect_same(exchange.acquire(), fresh(volume, level, options, centre));
  EXPECT_GE(keeper.figures().recentres, 1);

  // A new volume (a project opened): built again.
  core::Volume other = clay_block(glm::ivec3(128), 40);
  ASSERT_TRUE(keeper.update(other, 2, centre));
  expect_same(exchange.acquire(), fresh(other, level, options, centre));
  EXPECT_EQ(keeper.figures().builds, 2);
}

INSTANTIATE_TEST_SUITE_P(Levels, PatchKeeperAtLevel, testing::Values(0, 1, 3));

}  // namespace
}  // namespace sculpt::station
