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

// A device `device`'s event at `t_ms`, its deflection integral along x at
// `integral_tx` (a motion sample moves the tool by the difference).
hal::InputEvent device_event(hal::InputKind kind, uint32_t device, int64_t t_ms,
                             double integral_tx) {
  hal::InputEvent e;
  e.kind = kind;
  e.device_id = device;
  e.t_ns = t_ms * 1'000'000;
  e.integral[hal::kTx] = integral_tx;
  return e;
}

// A 3D mouse unplugged and plugged back in reports through a new pipeline,
// its deflection integral from zero again: the tool goes on from where it
// is. (It was thrown back by everything the device had moved it before.)
TEST(StationLoop, ADevicePluggedBackInGoesOnFromWhereTheToolIs) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(128);
  o.mesh = false;
  StationLoop loop(o);
  loop.handle(device_event(hal::InputKind::kConnected, 0, 0, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 0, 1, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 0, 2, 0.1));  // pushed along x
  const float moved_to = loop.pose().position.x;
  loop.handle(device_event(hal::InputKind::kDisconnected, 0, 3, 0.0));
  loop.handle(device_event(hal::InputKind::kConnected, 0, 1000, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 0, 1001, 0.0));  // the new pipeline's first
  loop.handle(device_event(hal::InputKind::kMotion, 0, 1002, 0.0));
  EXPECT_EQ(loop.pose().position.x, moved_to);
  loop.handle(device_event(hal::InputKind::kMotion, 0, 1003, 0.1));
  EXPECT_NEAR(loop.pose().position.x - moved_to, moved_to - 64.0f, 1e-3);  // the same push again
}

// Two 3D mice: each one plugged in (again) starts its own stream; the
// other's goes on. (Both were restarted, and the two devices' integrals
// were differenced against each other.)
TEST(StationLoop, ASecondDevicePluggedInLeavesTheFirstsMotionAlone) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(128);
  o.mesh = false;
  StationLoop loop(o);
  loop.handle(device_event(hal::InputKind::kConnected, 1, 0, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 1, 1, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 1, 2, 0.1));  // pushed along x
  const float pushed = loop.pose().position.x - 64.0f;
  loop.handle(device_event(hal::InputKind::kConnected, 2, 3, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 2, 4, 0.0));  // the second's first: at rest
  loop.handle(device_event(hal::InputKind::kMotion, 1, 5, 0.2));  // the first pushes on
  EXPECT_NEAR(loop.pose().position.x - 64.0f, 2.0f * pushed, 1e-3);
  loop.handle(device_event(hal::InputKind::kMotion, 2, 6, 0.1));  // the second pushes
  EXPECT_NEAR(loop.pose().position.x - 64.0f, 3.0f * pushed, 1e-3);
  // The second one plugged in again: its new pipeline's integral from zero.
  loop.handle(device_event(hal::InputKind::kDisconnected, 2, 7, 0.0));
  loop.handle(device_event(hal::InputKind::kConnected, 2, 8, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 2, 9, 0.0));
  loop.handle(device_event(hal::InputKind::kMotion, 2, 10, 0.1));
  EXPECT_NEAR(loop.pose().position.x - 64.0f, 4.0f * pushed, 1e-3);
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

// A stroke in the station sweeps the tool between the sampler's dabs
// (core/sculpt/stroke.h): a groove cut with a ball at the default spacing (a
// quarter of the tool's size) has a flat floor. As a row of dabs it had
// ridges of 0.24 voxel between them.
TEST(StationLoop, AStrokeCutsAGrooveWithAFlatFloor) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(96);
  o.clay_margin = 8;  // clay up to z = 88
  o.mesh = false;
  StationLoop loop(o);
  loop.handle(
      sim::Command{sim::CommandKind::kTool, choice_of(sim::ToolShape::kSphere), {8.0f, 0.0f}});
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(core::SculptMode::kSubtract)});
  auto pose = [](float x) {
    return sim::Command{sim::CommandKind::kPointer, 0, {x, 48.0f, 84.0f, 1.0f, 0.0f, 0.0f, 0.0f}};
  };
  sim::Command start = pose(20.0f);
  start.kind = sim::CommandKind::kToolPose;
  loop.handle(start);
  loop.handle(sim::Command{sim::CommandKind::kPress});
  for (int x = 21; x <= 76; ++x)
    loop.handle(pose(static_cast<float>(x)));
  loop.handle(sim::Command{sim::CommandKind::kRelease});
  ASSERT_GT(loop.counters().dabs, 10);
  EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);  // one stroke, one undo step
  // The floor under the path: where the density rises through 127.5 going
  // down each column, to a sub-voxel height by linear interpolation.
  const core::Volume& v = loop.volume();
  float lowest = 1e9f, highest = -1e9f;
  for (int x = 30; x <= 66; ++x) {
    for (int z = 94; z > 60; --z) {
      const float above = v.voxel({x, 48, z}), below = v.voxel({x, 48, z - 1});
      if (above < 127.5f && below >= 127.5f) {
        const float floor_z = static_cast<float>(z) - (127.5f - above) / (below - above);
        lowest = std::min(lowest, floor_z);
        highest = std::max(highest, floor_z);
        break;
      }
    }
  }
  EXPECT_NEAR(lowest, 76.0f, 0.1f);    // the ball's lowest point passed at z = 76
  EXPECT_LE(highest - lowest, 0.02f);  // no scallop
}

// The hardness command remakes the built-in tool with that falloff: the same
// groove cut soft is shallower at its rim, and the setting holds for the
// next tool chosen.
TEST(StationLoop, HardnessSoftensTheBuiltInTools) {
  auto groove = [](float hardness) {
    StationLoop::Options o;
    o.volume_dims = glm::ivec3(64);
    o.clay_margin = 8;
    o.mesh = false;
    StationLoop loop(o);
    loop.handle(sim::Command{sim::CommandKind::kHardness, 0, {hardness}});
    loop.handle(
        sim::Command{sim::CommandKind::kTool, choice_of(sim::ToolShape::kSphere), {8.0f, 0.0f}});
    EXPECT_EQ(loop.settings().hardness, hardness);
    EXPECT_EQ(loop.tool().hardness, hardness);
    loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(core::SculptMode::kSubtract)});
    loop.handle(sim::Command{sim::CommandKind::kPress});
    for (int x = 20; x <= 44; ++x)
      loop.handle(sim::Command{sim::CommandKind::kPointer,
                               0,
                               {static_cast<float>(x), 32.0f, 56.0f, 1.0f, 0.0f, 0.0f, 0.0f}});
    loop.handle(sim::Command{sim::CommandKind::kRelease});
    int64_t removed = 0;  // density taken from the block
    for (int z = 0; z < 64; ++z)
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          removed += loop.volume().voxel({x, y, z});
    return removed;
  };
  const int64_t hard = groove(1.0f), soft = groove(0.0f);
  EXPECT_GT(soft, hard);  // a soft ball takes less: its falloff spends its outer part
}

// A mode or mirror change mid-press ends the swept stroke and starts the
// next at the tool, within the press's one undo step.
TEST(StationLoop, AModeChangeMidPressStaysOneUndoStep) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(64);
  o.clay_margin = 8;
  o.mesh = false;
  StationLoop loop(o);
  const uint64_t before = loop.volume().content_hash();
  auto at = [](float x) {
    return sim::Command{sim::CommandKind::kPointer, 0, {x, 32.0f, 56.0f, 1.0f, 0.0f, 0.0f, 0.0f}};
  };
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(core::SculptMode::kSubtract)});
  loop.handle(sim::Command{sim::CommandKind::kPress});
  for (int x = 20; x <= 30; ++x)
    loop.handle(at(static_cast<float>(x)));
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(core::SculptMode::kAdd)});
  loop.handle(sim::Command{sim::CommandKind::kMirror, 0, {32.0f}});
  for (int x = 31; x <= 40; ++x)
    loop.handle(at(static_cast<float>(x)));
  loop.handle(sim::Command{sim::CommandKind::kRelease});
  EXPECT_NE(loop.volume().content_hash(), before);
  EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);
  loop.handle(sim::Command{sim::CommandKind::kUndo});
  EXPECT_EQ(loop.volume().content_hash(), before);
}

}  // namespace
}  // namespace sculpt::station
