// A force device at the station, end to end in real time: the simulated arm
// on its 1 kHz thread, pushed by a scripted hand onto a block of clay with
// its button held, while this thread plays the sculpting side. Counts and
// outcomes only (no timings): the tool rested on the clay, pushing carved a
// hole, the material pushed back, and the arm was left with no force.

#include "sculpt/station/haptics/haptic_station.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/hal/force/sim_arm.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {
namespace {

TEST(HapticStation, TheArmRestsOnTheClayAndPushingWithTheButtonCarvesAHole) {
  test::ScratchDir dir;
  ControllerOptions co;
  co.loop.mesh = false;
  co.loop.volume_dims = glm::ivec3(64);
  co.loop.clay_margin = 16;  // clay in [16, 48) on every axis
  co.project = dir.path() / "p.sculpt";
  co.autosave_seconds = 0;
  StationController controller(co);
  controller.set_tool(sim::ToolShape::kSphere, 6.0f, 6.0f, hal::monotonic_ns());
  controller.set_mode(core::SculptMode::kSubtract, hal::monotonic_ns());
  ASSERT_GT(controller.loop().volume().voxel({32, 46, 32}), 200);
  // Where the clay's top surface (density 127.5) crosses the centre column.
  float top_y = 0.0f;
  for (int y = 63; y > 0; --y) {
    const float a = controller.loop().volume().voxel({32, y, 32});
    const float b = controller.loop().volume().voxel({32, y - 1, 32});
    if (a < 127.5f && b >= 127.5f) {
      top_y = static_cast<float>(y) - (127.5f - a) / (b - a);
      break;
    }
  }
  ASSERT_GT(top_y, 44.0f);

  // The tool starts 8 voxels (4 mm) above the clay's top. The hand holds
  // still for 0.6 s, until the first patch of the clay has come (the
  // sculpting side built it in 291 ms under ThreadSanitizer on a slow
  // machine: a tool that reached the clay before it would go in unfelt),
  // goes down 10 mm (20 voxels) by 0.9 s, presses the button from 1.0 s to
  // 1.5 s, and the arm is unplugged at 1.8 s.
  hal::HandScript hand;
  hand.stiffness_n_per_mm = 0.8f;
  hand.path = {
      {0.0, glm::vec3(0.0f)}, {0.6, glm::vec3(0.0f)}, {0.9, glm::vec3(0.0f, -10.0f, 0.0f)}};
  hand.buttons = {{1.0, 1u}, {1.5, 0u}};
  hand.unplug_s = 1.8;
  auto arm = std::make_unique<hal::SimArm>(hand);
  const hal::SimArm& arm_view = *arm;
  HapticStationOptions options;
  options.thread.realtime_priority = 0;
  // CI runs this beside sanitized builds on two cores, where ticks come late
  // now and then: a watchdog trip would restart the ramp and leave too little
  // force to carve. The safety rules have their own tests (hal/force).
  options.loop.safety.watchdog_ns = 1'000'000'000;
  options.loop.safety.ramp_s = 0.05;
  HapticStation station(std::move(arm), options);
  station.start(glm::vec3(32.0f, 56.0f, 32.0f), 3.0f);

  float deepest_proxy_y = 1e9f;
  float deepest_device_y = 1e9f;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (station.running() && std::chrono::steady_clock::now() < give_up) {
    station.sculpting_side(controller, hal::monotonic_ns());
    // The arm's time is the loop's tick count (each tick is 1 ms of its physics).
    const int64_t ticks = station.figures().ticks;
    if (ticks > 850 && ticks < 990) {
      // Before the press: the tool rests on the clay (radius 3 above y = 48).
      deepest_proxy_y = std::min(deepest_proxy_y, station.contact().proxy_vox.y);
      deepest_device_y = std::min(deepest_device_y, station.contact().device_vox.y);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ASSERT_FALSE(station.running());
  const HapticFigures figures = station.figures();
  EXPECT_EQ(figures.ticks, 1800);
  EXPECT_GE(figures.patch.publishes, 1);
  // Resting, the hand's 0.8 N/mm spring 6 mm past the clay against its
  // 1 N/mm: 2.7 N.
  EXPECT_GT(figures.max_force_n, 2.0f);
  EXPECT_LE(figures.max_force_n, 8.0f);
  EXPECT_GE(figures.patch.builds, 1);
  EXPECT_GE(figures.patch.refreshes, 1);  // the carving reached the patch
  // Resting, the proxy stayed on the clay while the device sank well into it.
  EXPECT_GT(deepest_proxy_y, top_y + 3.0f - 0.2f);
  EXPECT_LT(deepest_device_y, top_y - 2.0f);  // at rest: 3.3 voxels under the top
  // Pushing carved: the clay under the tool is gone, the block's bottom is not.
  EXPECT_GT(controller.loop().counters().dabs, 0);
  EXPECT_LT(controller.loop().volume().voxel({32, 46, 32}), 128);
  EXPECT_GT(controller.loop().volume().voxel({32, 20, 32}), 200);
  EXPECT_EQ(arm_view.motor_force_n(), glm::vec3(0.0f));
}

}  // namespace
}  // namespace sculpt::station
