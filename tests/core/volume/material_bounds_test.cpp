#include "sculpt/core/volume/material_bounds.h"

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(MaterialBounds, EmptyHasNone) {
  EXPECT_FALSE(material_bounds(Volume(glm::ivec3(40), 0)).has_value());
}

TEST(MaterialBounds, IsTheTightBoxOfEveryVoxelWithDensity) {
  // A solid block (uniform bricks counted whole) and a single faint voxel
  // far off in a detailed brick: both bound the box, to the voxel.
  Volume v(glm::ivec3(100, 80, 60), 0, VolumeOptions{.brick_edge = 16, .levels = 4});
  v.write({32, 32, 16}, DenseGrid<uint8_t>(glm::ivec3(32, 16, 16), 255));
  DenseGrid<uint8_t> speck(glm::ivec3(1), 1);
  v.write({97, 3, 58}, speck);
  const auto bounds = material_bounds(v);
  ASSERT_TRUE(bounds.has_value());
  EXPECT_EQ(bounds->lo, glm::ivec3(32, 3, 16));
  EXPECT_EQ(bounds->hi, glm::ivec3(98, 48, 59));
}

TEST(MaterialBounds, AFullVolumeIsAllOfIt) {
  const auto bounds = material_bounds(Volume(glm::ivec3(37, 20, 9), 200));
  ASSERT_TRUE(bounds.has_value());
  EXPECT_EQ(bounds->lo, glm::ivec3(0));
  EXPECT_EQ(bounds->hi, glm::ivec3(37, 20, 9));
}

}  // namespace
}  // namespace sculpt::core
