#include "sculpt/core/haptics/press_dab.h"

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(PressDab, NothingUnderTheThresholdThenDeeperWithThePushUpToTheLimit) {
  const PressOptions press{.threshold_n = 1.0f, .depth_vox_per_n = 2.0f, .max_depth_vox = 3.0f};
  const glm::vec3 proxy(10, 10, 20), up(0, 0, 1);
  EXPECT_FALSE(pressed_dab_position(proxy, up, {0, 0, 0.9f}, true, press));
  EXPECT_FALSE(pressed_dab_position(proxy, up, {0, 0, 5.0f}, false, press));
  // Pulling away, or pushing sideways, is no press.
  EXPECT_FALSE(pressed_dab_position(proxy, up, {3.0f, 0, -2.0f}, true, press));
  EXPECT_EQ(*pressed_dab_position(proxy, up, {0.5f, 0, 1.5f}, true, press), glm::vec3(10, 10, 19));
  EXPECT_EQ(*pressed_dab_position(proxy, up, {0, 0, 9.0f}, true, press), glm::vec3(10, 10, 17));
}

}  // namespace
}  // namespace sculpt::core
