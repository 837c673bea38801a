// A tracker driving the station through the one StationLoop path: the tool
// follows its poses from where the tool was, a lost tracker ends the stroke,
// and finding it again moves nothing until the tracker moves.

#include <gtest/gtest.h>

#include <cmath>

#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {
namespace {

StationLoop::Options small_block() {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(64);
  o.clay_margin = 8;
  o.mesh = false;
  o.pose.tracker_filter.enabled = false;  // exact positions; the filter has its own test
  return o;
}

hal::InputEvent pose_at(double x_mm, double y_mm, double z_mm, int64_t t_ns) {
  hal::InputEvent e;
  e.kind = hal::InputKind::kMotion;
  e.absolute = true;
  e.has_pose = true;
  e.pose.position_mm = {x_mm, y_mm, z_mm};
  e.t_ns = t_ns;
  return e;
}

hal::InputEvent button0(bool pressed, int64_t t_ns) {
  hal::InputEvent e;
  e.kind = hal::InputKind::kButton;
  e.button = 0;
  e.pressed = pressed;
  e.t_ns = t_ns;
  return e;
}

hal::InputEvent tracking_lost(int64_t t_ns) {
  hal::InputEvent e;
  e.kind = hal::InputKind::kTrackingLost;
  e.t_ns = t_ns;
  return e;
}

TEST(StationTracker, TheToolFollowsTheTrackerFromWhereItWas) {
  StationLoop loop(small_block());
  const glm::vec3 start = loop.pose().position;
  // The tracker's origin is a metre away: the first pose still moves nothing.
  loop.handle(pose_at(1000, -400, 250, 1));
  EXPECT_EQ(loop.pose().position, start);
  loop.handle(pose_at(1010, -400, 245, 2));
  EXPECT_FLOAT_EQ(loop.pose().position.x, start.x + 10.0f);  // 1 voxel per mm by default
  EXPECT_FLOAT_EQ(loop.pose().position.z, start.z - 5.0f);
  EXPECT_EQ(loop.counters().motion_samples, 2);
}

TEST(StationTracker, APressedTrackerSculptsAlongItsPath) {
  StationLoop loop(small_block());
  loop.handle(pose_at(0, 0, 0, 1));
  loop.handle(button0(true, 2));
  const int64_t at_press = loop.counters().dabs;
  for (int i = 1; i <= 10; ++i)
    loop.handle(pose_at(i, 0, 0, 2 + i));
  EXPECT_GT(loop.counters().dabs, at_press);
  EXPECT_TRUE(loop.pressed());
}

TEST(StationTracker, LosingTrackingEndsTheStrokeAndFindingItAgainNeverJumps) {
  StationLoop loop(small_block());
  loop.handle(pose_at(0, 0, 0, 1));
  loop.handle(button0(true, 2));
  loop.handle(pose_at(4, 0, 0, 3));
  const glm::vec3 last_seen = loop.pose().position;
  loop.handle(tracking_lost(4));
  EXPECT_FALSE(loop.pressed()) << "the stroke ends where the tracker was last seen";
  EXPECT_EQ(loop.counters().strokes, 1);
  EXPECT_EQ(loop.counters().tracking_losses, 1);
  const int64_t dabs = loop.counters().dabs;
  // Found again 200 mm away (the user walked while it was lost).
  loop.handle(pose_at(204, 0, 0, 5));
  EXPECT_EQ(loop.pose().position, last_seen);
  EXPECT_EQ(loop.counters().dabs, dabs) << "no streak across the sculpture";
  loop.handle(pose_at(207, 0, 0, 6));
  EXPECT_FLOAT_EQ(loop.pose().position.x, last_seen.x + 3.0f);
  // The button still held on the device starts a new stroke only when pressed again.
  EXPECT_EQ(loop.counters().dabs, dabs);
  loop.handle(button0(true, 7));
  EXPECT_EQ(loop.counters().strokes, 2);
}

sim::Command command(sim::CommandKind kind, uint8_t choice, std::initializer_list<float> values) {
  sim::Command c{kind, choice};
  int i = 0;
  for (const float v : values)
    c.values[i++] = v;
  return c;
}

hal::InputEvent button(int index, bool pressed, int64_t t_ns) {
  hal::InputEvent e = button0(pressed, t_ns);
  e.button = index;
  return e;
}

TEST(StationTracker, TheClutchKeyOrGripButtonLetsTheHandMoveBackWithoutTheTool) {
  StationLoop loop(small_block());
  const glm::vec3 start = loop.pose().position;
  loop.handle(pose_at(0, 0, 0, 1));
  loop.handle(pose_at(10, 0, 0, 2));
  EXPECT_FLOAT_EQ(loop.pose().position.x, start.x + 10.0f);
  // The key (a recorded command): the hand goes back 30 mm, the tool stays.
  loop.handle(command(sim::CommandKind::kClutch, 1, {}));
  EXPECT_TRUE(loop.clutched());
  loop.handle(pose_at(-20, 0, 0, 3));
  EXPECT_FLOAT_EQ(loop.pose().position.x, start.x + 10.0f);
  loop.handle(command(sim::CommandKind::kClutch, 0, {}));
  EXPECT_FALSE(loop.clutched());
  loop.handle(pose_at(-20, 0, 0, 4));  // re-anchors here
  loop.handle(pose_at(-15, 0, 0, 5));
  EXPECT_FLOAT_EQ(loop.pose().position.x, start.x + 15.0f);
  // The grip button (the device's third) does the same, and either held holds.
  loop.handle(button(StationLoop::kClutchButton, true, 6));
  loop.handle(command(sim::CommandKind::kClutch, 1, {}));
  loop.handle(button(StationLoop::kClutchButton, false, 7));
  EXPECT_TRUE(loop.clutched()) << "the key is still held";
  loop.handle(pose_at(-40, 0, 0, 8));
  EXPECT_FLOAT_EQ(loop.pose().position.x, start.x + 15.0f);
  loop.handle(command(sim::CommandKind::kClutch, 0, {}));
  loop.handle(pose_at(-40, 0, 0, 9));
  EXPECT_FLOAT_EQ(loop.pose().position.x, start.x + 15.0f);
}

TEST(StationTracker, ATrackerCommandScalesAndTurnsWhatFollowsAndIsASetting) {
  StationLoop loop(small_block());
  loop.handle(pose_at(0, 0, 0, 1));
  // 0.5 voxel per mm, the tracker's x is the sculpture's -z (a quarter turn
  // about +y: w = x = cos 45 deg on y).
  const float h = std::sqrt(0.5f);
  loop.handle(command(sim::CommandKind::kTracker, 0, {0.5f, h, 0, h, 0}));
  EXPECT_EQ(loop.settings().tracker.scale_vox_per_mm, 0.5);
  const glm::vec3 at = loop.pose().position;
  loop.handle(pose_at(0, 0, 0, 2));  // re-anchors: no jump
  EXPECT_EQ(loop.pose().position, at);
  loop.handle(pose_at(20, 0, 0, 3));
  EXPECT_NEAR(loop.pose().position.z, at.z - 10.0f, 1e-4f);
  EXPECT_NEAR(loop.pose().position.x, at.x, 1e-4f);
}

}  // namespace
}  // namespace sculpt::station
