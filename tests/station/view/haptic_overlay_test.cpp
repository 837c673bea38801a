#include "sculpt/station/view/haptic_overlay.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace sculpt::station {
namespace {

TEST(HapticOverlay, TheProxyIsASphereOfTheToolsRadiusAndTheGhostOnlyShowsWhenApart) {
  HapticOverlayInput in;
  in.proxy_vox = {10, 20, 30};
  in.device_vox = in.proxy_vox + glm::vec3(0.0f, -0.2f, 0.0f);
  in.radius_vox = 6.0f;
  HapticOverlay o = haptic_overlay(in);
  ASSERT_EQ(o.proxy.size() % 2, 0u);
  ASSERT_FALSE(o.proxy.empty());
  for (const glm::vec3& p : o.proxy)
    EXPECT_NEAR(glm::length(p - in.proxy_vox), 6.0f, 1e-4f);
  EXPECT_TRUE(o.ghost.empty());
  EXPECT_TRUE(o.force.empty());
  in.device_vox = in.proxy_vox + glm::vec3(0.0f, -3.0f, 0.0f);
  o = haptic_overlay(in);
  ASSERT_EQ(o.ghost.size(), o.proxy.size());
  for (const glm::vec3& p : o.ghost)
    EXPECT_NEAR(glm::length(p - in.device_vox), 6.0f, 1e-4f);
  // The device's cross is centred on it.
  glm::vec3 mean(0.0f);
  for (const glm::vec3& p : o.device)
    mean += p;
  EXPECT_LT(glm::length(mean / float(o.device.size()) - in.device_vox), 1e-4f);
}

TEST(HapticOverlay, TheForceArrowLeavesTheProxyAlongTheForceScaledPerNewton) {
  HapticOverlayInput in;
  in.proxy_vox = {0, 0, 0};
  in.radius_vox = 2.0f;
  in.force_n = {0.0f, 2.5f, 0.0f};
  in.arrow_vox_per_n = 4.0f;
  const HapticOverlay o = haptic_overlay(in);
  ASSERT_GE(o.force.size(), 2u);
  EXPECT_NEAR(glm::length(o.force[0] - glm::vec3(0, 2, 0)), 0.0f, 1e-5f);   // tail on the sphere
  EXPECT_NEAR(glm::length(o.force[1] - glm::vec3(0, 12, 0)), 0.0f, 1e-5f);  // 2.5 N * 4 vox/N
  // The head's strokes point back from the tip.
  for (size_t i = 2; i + 1 < o.force.size(); i += 2) {
    EXPECT_EQ(o.force[i], o.force[1]);
    EXPECT_LT(o.force[i + 1].y, o.force[1].y);
  }
}

}  // namespace
}  // namespace sculpt::station
