// Touch mode: a 3D mouse gets the contact a force device gets, without the
// force. Driven through the station loop as a device drives it, so what is
// tested is what a user gets (and a replay reproduces).

#include "sculpt/station/app/touch_mode.h"

#include <gtest/gtest.h>

#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {
namespace {

sim::Command command(sim::CommandKind kind, uint8_t choice = 0,
                     std::initializer_list<float> values = {}) {
  sim::Command c{kind, choice, {}};
  std::copy(values.begin(), values.end(), c.values);
  return c;
}

// The clay's top: where its density crosses 127.5 on the centre column.
float top_of(const core::Volume& v, int x, int z) {
  for (int y = v.dims().y - 1; y > 0; --y) {
    const float a = v.voxel({x, y, z}), b = v.voxel({x, y - 1, z});
    if (a < 127.5f && b >= 127.5f) return static_cast<float>(y) - (127.5f - a) / (b - a);
  }
  return 0.0f;
}

// A 3D mouse in rate control, one sample a millisecond.
struct Mouse {
  StationLoop& loop;
  hal::InputEvent e;
  int64_t t_ns = 0;
  explicit Mouse(StationLoop& l) : loop(l) { e.kind = hal::InputKind::kMotion; }
  // Holds the cap at (tx, ty, tz) for `ms` milliseconds.
  void push(float tx, float ty, float tz, int ms) {
    for (int i = 0; i < ms; ++i) {
      t_ns += 1'000'000;
      e.t_ns = t_ns;
      e.axes = {tx, ty, tz, 0, 0, 0};
      e.integral[hal::kTx] += tx * 1e-3;
      e.integral[hal::kTy] += ty * 1e-3;
      e.integral[hal::kTz] += tz * 1e-3;
      loop.handle(e);
    }
  }
  void button(bool pressed) {
    hal::InputEvent b;
    b.kind = hal::InputKind::kButton;
    b.button = 0;
    b.pressed = pressed;
    b.t_ns = t_ns;
    loop.handle(b);
  }
};

StationLoop clay_loop() {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(96);
  o.clay_margin = 24;  // clay in [24, 72)
  o.mesh = false;
  return StationLoop(o);
}

void start_above_the_clay(StationLoop& loop, float radius) {
  loop.handle(command(sim::CommandKind::kTool, choice_of(sim::ToolShape::kSphere), {radius, 0.0f}));
  loop.handle(command(sim::CommandKind::kMode, choice_of(core::SculptMode::kSubtract)));
  loop.handle(command(sim::CommandKind::kToolPose, 0, {48, 84, 48, 1, 0, 0, 0}));
  loop.handle(command(sim::CommandKind::kTouch, 1));
}

TEST(TouchMode, TheToolStopsOnTheClayHoweverHardTheCapIsPushed) {
  StationLoop loop = clay_loop();
  const float top = top_of(loop.volume(), 48, 48);
  start_above_the_clay(loop, 4.0f);
  Mouse mouse(loop);
  mouse.push(0.0f, -1.0f, 0.0f, 500);  // 100 voxels down at full speed
  EXPECT_NEAR(loop.pose().position.y, top + 4.0f, 0.2f);
  // Sideways it slides along the top.
  mouse.push(0.5f, -1.0f, 0.0f, 100);
  EXPECT_GT(loop.pose().position.x, 55.0f);
  EXPECT_NEAR(loop.pose().position.y, top + 4.0f, 0.2f);
  // Pulling the cap back lifts it at once: the device point did not sink.
  mouse.push(0.0f, 0.5f, 0.0f, 20);
  EXPECT_GT(loop.pose().position.y, top + 4.0f + 1.0f);
  EXPECT_EQ(loop.counters().dabs, 0);
  // Without touch mode the same push goes through.
  loop.handle(command(sim::CommandKind::kTouch, 0));
  mouse.push(0.0f, -1.0f, 0.0f, 200);
  EXPECT_LT(loop.pose().position.y, top - 10.0f);
}

TEST(TouchMode, WithTheButtonHeldOnlyAPushPastTheThresholdCarves) {
  StationLoop loop = clay_loop();
  const uint64_t untouched = loop.volume().content_hash();
  start_above_the_clay(loop, 4.0f);
  Mouse mouse(loop);
  mouse.push(0.0f, -1.0f, 0.0f, 300);  // down onto the clay
  mouse.push(0.0f, -0.1f, 0.0f, 50);   // resting on it
  mouse.button(true);
  // A light push (0.1 of full: 0.4 N, under the 1 N threshold): nothing carved.
  mouse.push(0.0f, -0.1f, 0.0f, 300);
  EXPECT_EQ(loop.counters().dabs, 0);
  EXPECT_EQ(loop.volume().content_hash(), untouched);
  // A full push (4 N): it carves, the tool going down with the clay it takes.
  const float top = top_of(loop.volume(), 48, 48);
  mouse.push(0.0f, -1.0f, 0.0f, 300);
  mouse.button(false);
  EXPECT_GT(loop.counters().dabs, 0);
  EXPECT_LT(top_of(loop.volume(), 48, 48), top - 2.0f);
  EXPECT_EQ(loop.counters().strokes, 1);
}

TEST(TouchMode, ABigToolTouchesThroughACoarsePatchAndRestsOnTheClayToo) {
  StationLoop loop = clay_loop();
  const float top = top_of(loop.volume(), 48, 48);
  start_above_the_clay(loop, 20.0f);  // level 2 of the pyramid
  loop.handle(command(sim::CommandKind::kToolPose, 0, {48, 94, 48, 1, 0, 0, 0}));
  Mouse mouse(loop);
  mouse.push(0.0f, -1.0f, 0.0f, 500);
  // Within a coarse voxel's tenth or so of resting on the top.
  EXPECT_NEAR(loop.pose().position.y, top + 20.0f, 1.0f);
}

}  // namespace
}  // namespace sculpt::station
