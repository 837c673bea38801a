#include "sculpt/station/settings/command_codec.h"

#include <gtest/gtest.h>

namespace sculpt::station {
namespace {

TEST(CommandCodec, EveryModeAndShapeRoundTripsThroughItsChoiceByte) {
  for (uint8_t c = 0; c < sim::kFirstBallBrushMode; ++c) {
    const auto mode = sculpt_mode_of_choice(c);
    ASSERT_TRUE(mode.has_value());
    EXPECT_FALSE(ball_brush_of_choice(c).has_value());
    EXPECT_EQ(choice_of(*mode), c);
    EXPECT_EQ(to_core(to_session(*mode)), *mode);
    // The name a session file uses is the core's name for the same mode.
    EXPECT_EQ(sim::sculpt_mode_name(to_session(*mode)), core::sculpt_mode_name(*mode));
  }
  // The choices after the modes are the ball brushes, each one of them.
  for (uint8_t c = sim::kFirstBallBrushMode; c < sim::kSculptModeCount; ++c) {
    const auto brush = ball_brush_of_choice(c);
    ASSERT_TRUE(brush.has_value());
    EXPECT_FALSE(sculpt_mode_of_choice(c).has_value());
    EXPECT_EQ(choice_of(*brush), c);
  }
  EXPECT_EQ(sim::sculpt_mode_name(sim::SculptModeId::kClay), "clay");
  EXPECT_EQ(sim::sculpt_mode_name(sim::SculptModeId::kGrab), "grab");
  for (uint8_t c = 0; c < sim::kToolShapeCount; ++c) {
    const auto shape = tool_shape_of_choice(c);
    ASSERT_TRUE(shape.has_value());
    EXPECT_EQ(choice_of(*shape), c);
  }
}

TEST(CommandCodec, AChoiceOutOfRangeIsNoModeOrShape) {
  EXPECT_FALSE(sculpt_mode_of_choice(sim::kSculptModeCount).has_value());
  EXPECT_FALSE(sculpt_mode_of_choice(255).has_value());
  EXPECT_FALSE(ball_brush_of_choice(sim::kSculptModeCount).has_value());
  EXPECT_FALSE(ball_brush_of_choice(255).has_value());
  EXPECT_FALSE(tool_shape_of_choice(sim::kToolShapeCount).has_value());
  EXPECT_FALSE(tool_shape_of_choice(200).has_value());
}

}  // namespace
}  // namespace sculpt::station
