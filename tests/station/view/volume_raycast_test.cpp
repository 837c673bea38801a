#include "sculpt/station/view/volume_raycast.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station {
namespace {

TEST(VolumeRaycast, HitsTheSphereOnItsNearSideToATenthOfAVoxel) {
  const core::Volume v = core::sphere_volume(64);  // centre 31.5, radius 22.4
  Ray r;
  r.origin = glm::vec3(31.5f, 31.5f, 200.0f);
  r.direction = glm::vec3(0, 0, -1);
  const auto hit = raycast_surface(v, r);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->z, 31.5f + 0.35f * 64, 1.0f);  // nearest-voxel sampling: within a voxel
  EXPECT_NEAR(hit->x, 31.5f, 1e-4f);
  EXPECT_GT(v.voxel(glm::ivec3(glm::floor(*hit + 0.5f))), 127);
}

TEST(VolumeRaycast, MissesWhenTheRayPassesBesideTheMaterialOrTheBlock) {
  const core::Volume v = core::sphere_volume(64);
  Ray beside;
  beside.origin = glm::vec3(2.0f, 2.0f, 200.0f);
  beside.direction = glm::vec3(0, 0, -1);
  EXPECT_FALSE(raycast_surface(v, beside).has_value());
  Ray away;
  away.origin = glm::vec3(31.5f, 31.5f, 200.0f);
  away.direction = glm::vec3(0, 0, 1);
  EXPECT_FALSE(raycast_surface(v, away).has_value());
  Ray outside;
  outside.origin = glm::vec3(-10.0f, 500.0f, 0.0f);
  outside.direction = glm::vec3(1, 0, 0);
  EXPECT_FALSE(raycast_surface(v, outside).has_value());
}

TEST(VolumeRaycast, StartsInsideTheBlock) {
  const core::Volume v = core::sphere_volume(64);
  Ray r;
  r.origin = glm::vec3(31.5f, 31.5f, 60.0f);
  r.direction = glm::normalize(glm::vec3(0, 0.1f, -1));
  const auto hit = raycast_surface(v, r);
  ASSERT_TRUE(hit.has_value());
  EXPECT_LT(hit->z, 60.0f);
}

}  // namespace
}  // namespace sculpt::station
