#include "sculpt/hal/force/force_safety.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace sculpt::hal {
namespace {

constexpr int64_t kMs = 1'000'000;

TEST(ForceSafety, NoForceUntilEnabledThenALinearRampOverHalfASecond) {
  ForceSafety safety(sim_arm_limits());
  const glm::vec3 push(2.0f, 0.0f, 0.0f);
  for (int64_t t = 0; t < 10; ++t)
    EXPECT_EQ(safety.filter(push, t * kMs), glm::vec3(0.0f));
  safety.enable();
  const int64_t on = 10 * kMs;
  EXPECT_EQ(safety.filter(push, on), glm::vec3(0.0f));  // the ramp starts at zero
  float previous = 0.0f;
  for (int64_t t = 1; t <= 600; ++t) {
    const float x = safety.filter(push, on + t * kMs).x;
    EXPECT_GE(x, previous) << t;
    if (t <= 500) {
      EXPECT_NEAR(x, 2.0f * static_cast<float>(t) / 500.0f, 1e-4f) << t;
    }
    previous = x;
  }
  EXPECT_FLOAT_EQ(previous, 2.0f);
}

TEST(ForceSafety, DropIsImmediateAndEnableRampsAgain) {
  ForceSafety safety(sim_arm_limits(), {0.0, 3 * kMs});  // no ramp: full force at once
  safety.enable();
  const glm::vec3 push(0.0f, 3.0f, 0.0f);
  EXPECT_EQ(safety.filter(push, 0), push);
  safety.drop();
  EXPECT_EQ(safety.filter(push, kMs), glm::vec3(0.0f));
  EXPECT_EQ(safety.counters().drops, 1);
  ForceSafety ramped(sim_arm_limits());
  ramped.enable();
  for (int64_t t = 0; t <= 500; ++t)
    ramped.filter(push, t * kMs);
  ramped.drop();
  EXPECT_EQ(ramped.filter(push, 501 * kMs), glm::vec3(0.0f));
  ramped.enable();
  EXPECT_EQ(ramped.filter(push, 502 * kMs), glm::vec3(0.0f));
  for (int64_t t = 503; t < 752; ++t)
    ramped.filter(push, t * kMs);
  EXPECT_NEAR(ramped.filter(push, 752 * kMs).y, 1.5f, 1e-4f);
}

TEST(ForceSafety, ALateTickZeroesTheForceAndRestartsTheRamp) {
  ForceSafety safety(sim_arm_limits());
  safety.enable();
  const glm::vec3 push(0.0f, 0.0f, 4.0f);
  int64_t t = 0;
  for (; t <= 600 * kMs; t += kMs)
    safety.filter(push, t);
  EXPECT_FLOAT_EQ(safety.filter(push, t).z, 4.0f);
  // 3 ms is still on time; 3 ms and a nanosecond is not.
  t += 3 * kMs;
  EXPECT_FLOAT_EQ(safety.filter(push, t).z, 4.0f);
  t += 3 * kMs + 1;
  EXPECT_EQ(safety.filter(push, t), glm::vec3(0.0f));
  EXPECT_EQ(safety.counters().watchdog_trips, 1);
  for (int64_t i = 1; i < 250; ++i)
    safety.filter(push, t + i * kMs);
  EXPECT_NEAR(safety.filter(push, t + 250 * kMs).z, 2.0f, 1e-4f);
}

TEST(ForceSafety, TheLimitClampsKeepingTheDirectionAndNonFiniteForcesAreZero) {
  ForceSafety safety(sim_arm_limits(), {0.0, 3 * kMs});
  safety.enable();
  const glm::vec3 f = safety.filter(glm::vec3(30.0f, 40.0f, 0.0f), 0);
  EXPECT_NEAR(glm::length(f), 8.0f, 1e-5f);
  EXPECT_NEAR(f.x / f.y, 0.75f, 1e-6f);
  EXPECT_EQ(safety.counters().clamped, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(safety.filter(glm::vec3(1.0f, nan, 0.0f), kMs), glm::vec3(0.0f));
  EXPECT_EQ(safety.filter(glm::vec3(std::numeric_limits<float>::infinity()), 2 * kMs),
            glm::vec3(0.0f));
  EXPECT_EQ(safety.counters().non_finite, 2);
}

}  // namespace
}  // namespace sculpt::hal
