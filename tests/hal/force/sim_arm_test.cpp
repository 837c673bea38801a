#include "sculpt/hal/force/sim_arm.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace sculpt::hal {
namespace {

HandScript hand_at(glm::vec3 target_mm, double unplug_s = -1.0) {
  HandScript hand;
  hand.path.push_back({0.0, target_mm});
  hand.unplug_s = unplug_s;
  return hand;
}

TEST(SimArm, TheHandBringsTheGripToItsTargetAndTheEncodersCountInSteps) {
  SimArm arm(hand_at({3.0f, -2.0f, 1.234567f}));
  ForceDeviceState state;
  for (int i = 0; i < 2000; ++i)
    ASSERT_EQ(arm.read(state), ForceIo::kOk);
  EXPECT_NEAR(arm.t_s(), 2.0, 1e-9);
  EXPECT_NEAR(glm::length(arm.position_mm() - glm::vec3(3.0f, -2.0f, 1.234567f)), 0.0f, 1e-3f);
  EXPECT_LT(glm::length(arm.velocity_mm_per_s()), 0.1f);
  // The reading is a whole number of 0.01 mm counts, within half a count.
  for (int axis = 0; axis < 3; ++axis) {
    const float counts = state.position_mm[axis] / 0.01f;
    EXPECT_NEAR(counts, std::round(counts), 1e-3f) << axis;
    EXPECT_LE(std::abs(state.position_mm[axis] - arm.position_mm()[axis]), 0.005f + 1e-5f);
  }
}

TEST(SimArm, AForceReachesTheMotorsOneTickLateAndClampedToTheLimit) {
  SimArm arm(hand_at(glm::vec3(0.0f)));
  ForceDeviceState state;
  ASSERT_EQ(arm.read(state), ForceIo::kOk);
  ASSERT_EQ(arm.write(glm::vec3(0.0f, 20.0f, 0.0f)), ForceIo::kOk);  // at tick 1
  ASSERT_EQ(arm.read(state), ForceIo::kOk);                          // tick 2: not yet moving
  EXPECT_EQ(arm.velocity_mm_per_s(), glm::vec3(0.0f));
  EXPECT_NEAR(arm.motor_force_n().y, 8.0f, 1e-5f);  // clamped, and at the motors from now
  ASSERT_EQ(arm.read(state), ForceIo::kOk);         // tick 3: moved by 8 N
  EXPECT_GT(arm.velocity_mm_per_s().y, 0.0f);
  // 8 N on 0.15 kg for 1 ms, less a little hand and friction: about 53 mm/s.
  EXPECT_NEAR(arm.velocity_mm_per_s().y, 8.0f / 0.15f, 2.0f);
}

TEST(SimArm, UnpluggedItSaysRemovedFromThenOn) {
  SimArm arm(hand_at(glm::vec3(0.0f), 0.0105));
  ForceDeviceState state;
  int ok = 0;
  while (arm.read(state) == ForceIo::kOk)
    ++ok;
  EXPECT_EQ(ok, 10);
  EXPECT_EQ(arm.read(state), ForceIo::kRemoved);
  EXPECT_EQ(arm.write(glm::vec3(1.0f)), ForceIo::kRemoved);
  EXPECT_EQ(arm.motor_force_n(), glm::vec3(0.0f));
}

}  // namespace
}  // namespace sculpt::hal
