#include "sculpt/core/haptics/tool_proxy.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

PatchSnapshot floor_patch(glm::vec3 lo, glm::vec3 hi) {
  const Volume volume = Volume::from_dense(box_density(glm::ivec3(64), lo, hi));
  DistancePatch patch({.edge = 64, .band_vox = 4.0f});
  patch.build(volume, glm::vec3(32.0f));
  return patch.snapshot();
}

// The deepest shell point below the material's surface, voxels (0: none).
float deepest(const ToolProxy& proxy, const PatchSnapshot& field) {
  float d = 0.0f;
  const glm::mat3 r = glm::mat3_cast(proxy.state().orientation);
  for (const glm::vec3& p : proxy.shell().points)
    d = std::min(d, field.sample(proxy.state().position_vox + r * p).phi_vox);
  return -d;
}

TEST(PointShell, LiesOnTheToolSurfaceWithOutwardNormals) {
  const PointShell shell = make_point_shell(make_sphere_tool(10.0f));
  ASSERT_GT(shell.points.size(), 1000u);
  for (size_t i = 0; i < shell.points.size(); ++i) {
    EXPECT_NEAR(glm::length(shell.points[i]), 10.0f, 0.1f);
    EXPECT_GT(glm::dot(shell.normals[i], glm::normalize(shell.points[i])), 0.98f);
  }
  EXPECT_NEAR(shell.reach_vox, 10.0f, 0.1f);
}

TEST(ToolProxy, ACubePressedOnAFloorRestsOnItWithForceUpAndNoTorque) {
  const PatchSnapshot field = floor_patch(glm::vec3(2, 2, 2), glm::vec3(62, 62, 30));
  ToolProxy proxy(make_point_shell(make_cube_tool(8.0f)));
  const glm::quat level(1, 0, 0, 0);
  proxy.reset(glm::vec3(32, 32, 40), level);
  for (float z = 40.0f; z >= 31.0f; z -= 0.25f)
    (void)proxy.update(field, glm::vec3(32, 32, z), level);
  for (int i = 0; i < 50; ++i)
    (void)proxy.update(field, glm::vec3(32, 32, 31), level);
  const ToolTick& t = proxy.state();
  EXPECT_TRUE(t.contact);
  EXPECT_LT(deepest(proxy, field), 0.5f);
  EXPECT_GT(t.position_vox.z, 33.5f);  // the cube's bottom (4 below its centre) stays near 30
  EXPECT_GT(t.force_n.z, 0.5f);
  EXPECT_LT(std::hypot(t.force_n.x, t.force_n.y), 0.05f * t.force_n.z);
  EXPECT_LT(glm::length(t.torque_nm), 1e-3f);
}

TEST(ToolProxy, ContactOnOneSideTwistsTheToolAndTheDeviceFeelsIt) {
  // A floor under x > 32 only: the cube, centred on its edge, touches with
  // its +x half, so the push up there turns it about -y.
  const PatchSnapshot field = floor_patch(glm::vec3(32, 2, 2), glm::vec3(62, 62, 30));
  ToolProxy proxy(make_point_shell(make_cube_tool(8.0f)));
  const glm::quat level(1, 0, 0, 0);
  proxy.reset(glm::vec3(32, 32, 40), level);
  for (float z = 40.0f; z >= 32.0f; z -= 0.25f)
    (void)proxy.update(field, glm::vec3(32, 32, z), level);
  const ToolTick& t = proxy.state();
  EXPECT_TRUE(t.contact);
  EXPECT_GT(t.force_n.z, 0.0f);
  EXPECT_LT(t.torque_nm.y, -1e-4f);
  EXPECT_LT(std::abs(t.torque_nm.x), 0.1f * std::abs(t.torque_nm.y));
  EXPECT_LT(deepest(proxy, field), 0.5f);
}

TEST(ToolProxy, FreeMotionKeepsUpWithTheHandAndFeelsNothing) {
  const PatchSnapshot field = floor_patch(glm::vec3(2, 2, 2), glm::vec3(62, 62, 10));
  ToolProxy proxy(make_point_shell(make_sphere_tool(4.0f)));
  const glm::quat level(1, 0, 0, 0);
  proxy.reset(glm::vec3(20, 20, 40), level);
  const ToolTick& t = proxy.update(field, glm::vec3(24, 20, 40), level);
  EXPECT_FALSE(t.contact);
  EXPECT_EQ(t.force_n, glm::vec3(0.0f));
  EXPECT_NEAR(t.position_vox.x, 24.0f, 0.01f);
}

}  // namespace
}  // namespace sculpt::core
