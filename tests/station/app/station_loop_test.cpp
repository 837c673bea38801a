// The station loop's own bounds on live input.

#include "sculpt/station/app/station_loop.h"

#include <gtest/gtest.h>

#include "sculpt/sim/session/command_limits.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {
namespace {

// Reproducer from the hardening review: a device held at full push with the
// tool pressed drove the pose toward infinity (a pose at 1e30 in a session
// did the same at once), and the stroke behind it sampled dabs all the way:
// memory grew until the machine ran out. The pose now stays within a tool's
// largest size of the volume, so the dabs of such a stroke are bounded too.
TEST(StationLoop, ADeviceHeldAtFullPushKeepsTheToolNearTheVolume) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(64);
  o.clay_margin = 8;
  o.mesh = false;
  StationLoop loop(o);
  hal::InputEvent press;
  press.kind = hal::InputKind::kButton;
  press.button = 0;
  press.pressed = true;
  loop.handle(press);
  hal::InputEvent push;
  push.kind = hal::InputKind::kMotion;
  for (int s = 1; s <= 3600; ++s) {  // an hour at full push, one sample a second
    push.t_ns = int64_t{s} * 1'000'000'000;
    push.axes[hal::kTx] = 1.0f;
    push.integral[hal::kTx] = static_cast<double>(s);
    loop.handle(push);
  }
  const float far = 64.0f + sim::kMaxToolSizeVox + 1.0f;
  EXPECT_LE(loop.pose().position.x, far);
  EXPECT_GT(loop.pose().position.x, 64.0f) << "the push did move the tool out";
  // The stroke from the centre to the bound, a dab every quarter of the
  // 16-voxel tool: its length over the spacing, not an hour of motion.
  EXPECT_LE(loop.counters().dabs, static_cast<int64_t>((far - 32.0f) / 4.0f) + 2);
}

TEST(StationLoop, TheToolVersionMovesWithTheToolOnly) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(48);
  o.mesh = false;
  StationLoop loop(o);
  const uint64_t start = loop.tool_version();
  sim::Command mode{sim::CommandKind::kMode, choice_of(core::SculptMode::kSubtract)};
  loop.handle(mode);
  loop.handle(sim::Command{sim::CommandKind::kPress});
  loop.handle(sim::Command{sim::CommandKind::kRelease});
  EXPECT_EQ(loop.tool_version(), start);  // a mode and a dab are not a new tool
  sim::Command cube{sim::CommandKind::kTool, choice_of(sim::ToolShape::kCube), {6.0f, 0.0f}};
  loop.handle(cube);
  EXPECT_GT(loop.tool_version(), start);
  EXPECT_EQ(loop.settings().shape, sim::ToolShape::kCube);
  EXPECT_EQ(loop.settings().mode, core::SculptMode::kSubtract);
}

}  // namespace
}  // namespace sculpt::station
