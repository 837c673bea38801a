// The two conversions on their own: a force's direction all the way round,
// the level's rounding and clamping, an axis's range.

#include "backends/evdev_ff/constant_effect_mapping.h"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>

namespace sculpt::hal::evdev_ff {
namespace {

TEST(ConstantEffectForForce, TurnsOnceRoundAsTheForceDoes) {
  // 16 directions a sixteenth of a turn apart, 0x1000 each, from +y toward +x.
  for (int k = 0; k < 16; ++k) {
    const double a = 2.0 * M_PI * k / 16.0;
    const glm::vec3 f(float(2.0 * std::sin(a)), float(2.0 * std::cos(a)), 0.0f);
    const ConstantEffectCommand c = constant_effect_for_force(f, 4.0f, 0);
    EXPECT_EQ(c.direction, uint16_t(k * 0x1000)) << "k = " << k;
    EXPECT_NEAR(c.level, 16384, 1) << "k = " << k;
  }
}

TEST(ConstantEffectForForce, NeverExceedsTheFullLevel) {
  EXPECT_EQ(constant_effect_for_force({0.0f, 1e30f, 0.0f}, 4.0f, 0).level, kMaxConstantLevel);
  EXPECT_EQ(constant_effect_for_force({-4.0f, 0.0f, 0.0f}, 4.0f, 0).level, kMaxConstantLevel);
}

TEST(ConstantEffectForForce, NoForceKeepsTheDirectionItWasGiven) {
  const ConstantEffectCommand c = constant_effect_for_force(glm::vec3(0.0f), 4.0f, 0x1234);
  EXPECT_EQ(c.level, 0);
  EXPECT_EQ(c.direction, 0x1234);
  const ConstantEffectCommand n = constant_effect_for_force({INFINITY, 0.0f, 0.0f}, 4.0f, 0x4321);
  EXPECT_EQ(n.level, 0);
  EXPECT_EQ(n.direction, 0x4321);
}

input_absinfo range(int32_t minimum, int32_t maximum) {
  input_absinfo a{};
  a.minimum = minimum;
  a.maximum = maximum;
  return a;
}

TEST(NormalisedAxis, MapsTheRangeOntoMinusOneToOne) {
  EXPECT_FLOAT_EQ(normalised_axis(0, range(0, 255)), -1.0f);
  EXPECT_FLOAT_EQ(normalised_axis(255, range(0, 255)), 1.0f);
  EXPECT_FLOAT_EQ(normalised_axis(-32768, range(-32768, 32767)), -1.0f);
  // Asymmetric: 0 on -100..300 is a quarter of the way.
  EXPECT_FLOAT_EQ(normalised_axis(0, range(-100, 300)), -0.5f);
  // Outside the range (the input core does not clamp): clamped.
  EXPECT_FLOAT_EQ(normalised_axis(400, range(-100, 300)), 1.0f);
  EXPECT_FLOAT_EQ(normalised_axis(-101, range(-100, 300)), -1.0f);
  // The widest range does not overflow.
  EXPECT_FLOAT_EQ(normalised_axis(INT32_MAX, range(INT32_MIN, INT32_MAX)), 1.0f);
  // An empty range means nothing.
  EXPECT_FLOAT_EQ(normalised_axis(5, range(7, 7)), 0.0f);
  EXPECT_FLOAT_EQ(normalised_axis(5, range(9, 1)), 0.0f);
}

}  // namespace
}  // namespace sculpt::hal::evdev_ff
