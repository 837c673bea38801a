// The sculpting side's patch: after dabs and moves, at full resolution and at
// a coarser level of the pyramid, what the haptic loop receives equals a
// patch built from scratch on the material as it is then.

#include "sculpt/core/haptics/patch_keeper.h"

#include <gtest/gtest.h>

#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/tool/tool.h"

namespace sculpt::core {
namespace {

// A block holding a slab of clay inset by `margin` voxels, with a
// 2-voxel density ramp at its faces.
Volume clay_block(glm::ivec3 dims, int margin) {
  DenseGrid<uint8_t> g(dims);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const glm::vec3 p(x, y, z);
        const glm::vec3 lo(static_cast<float>(margin));
        const glm::vec3 hi = glm::vec3(dims - margin) - 1.0f;
        const glm::vec3 d = glm::max(lo - p, p - hi);  // > 0 outside the slab
        g.at(x, y, z) = density_from_distance(std::max(d.x, std::max(d.y, d.z)));
      }
  return Volume::from_dense(g);
}

// The snapshot a from-scratch build on `volume` (at `level`) gives.
PatchSnapshot fresh(const Volume& volume, int level, const DistancePatchOptions& options,
                    glm::vec3 centre_vox) {
  DistancePatch patch(options);
  if (level == 0) {
    patch.build(volume, centre_vox);
  } else {
    const Volume coarse = Volume::from_dense(volume.to_dense(level), VolumeOptions{16, 1, 1});
    patch.build(coarse, SpherePatch{level, {}}.to_patch(centre_vox));
  }
  return patch.snapshot();
}

void expect_same(const PatchSnapshot& a, const PatchSnapshot& b) {
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
  Volume volume = clay_block(glm::ivec3(128), 32);  // clay in [32, 96)
  const DistancePatchOptions options{48, band_for_sphere(3.0f), 1};
  PatchExchange exchange(options.edge);
  PatchKeeper keeper(exchange, options, level);
  const float scale = static_cast<float>(1 << level);
  glm::vec3 centre(64.0f, 96.0f + 3.0f * scale, 64.0f);
  ASSERT_TRUE(keeper.update(volume, 1, centre));
  expect_same(exchange.acquire(), fresh(volume, level, options, centre));
  EXPECT_FALSE(keeper.update(volume, 1, centre));  // nothing changed: nothing published

  // Dabs under the patch, and one far away (which the level's mirror must
  // follow all the same, for when the patch gets there).
  Sculptor sculptor(volume);
  sculptor.set_tool(make_sphere_tool(6.0f));
  for (const glm::vec3 at : {glm::vec3(64, 96, 64), glm::vec3(70, 94, 60), glm::vec3(30, 60, 100)})
    sculptor.dab({at, glm::quat(1, 0, 0, 0), SculptMode::kSubtract, 1.0f});
  ASSERT_TRUE(keeper.update(volume, 1, centre));
  expect_same(exchange.acquire(), fresh(volume, level, options, centre));
  EXPECT_GE(keeper.figures().refreshes, 1);

  // The proxy moves far off the centre: the patch follows.
  centre += glm::vec3(20.0f * scale, 0.0f, 0.0f);
  ASSERT_TRUE(keeper.update(volume, 1, centre));
  expect_same(exchange.acquire(), fresh(volume, level, options, centre));
  EXPECT_GE(keeper.figures().recentres, 1);

  // A new volume (a project opened): built again.
  Volume other = clay_block(glm::ivec3(128), 40);
  ASSERT_TRUE(keeper.update(other, 2, centre));
  expect_same(exchange.acquire(), fresh(other, level, options, centre));
  EXPECT_EQ(keeper.figures().builds, 2);
}

INSTANTIATE_TEST_SUITE_P(Levels, PatchKeeperAtLevel, testing::Values(0, 1, 3));

}  // namespace
}  // namespace sculpt::core
