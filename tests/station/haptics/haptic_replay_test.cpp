// A force device's session, recorded live and replayed: the simulated arm on
// its real 1 kHz thread presses onto clay and carves while the station
// records; the replay runs every tick again on patches built from the
// replayed material and must give the recorded force bit for bit, and the
// same sculpture.

#include "sculpt/station/haptics/haptic_replay.h"

#include <chrono>
#include <filesystem>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/hal/force/sim_arm.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/haptics/haptic_station.h"

namespace sculpt::station {
namespace {

ControllerOptions clay_station(const test::ScratchDir& dir) {
  ControllerOptions co;
  co.loop.mesh = false;
  co.loop.volume_dims = glm::ivec3(64);
  co.loop.clay_margin = 16;  // clay in [16, 48) on every axis
  co.project = dir.path() / "p.sculpt";
  co.autosave_seconds = 0;
  return co;
}

// Replays the session at `path` into `replayed`, its force device's loops
// too; each tick run again goes to `on_tick`.
HapticReplayFigures replay_forces(const std::filesystem::path& path, StationLoop& replayed,
                                  std::function<void(const ReplayedTick&)> on_tick = {}) {
  auto session = sim::read_session_file(path);
  EXPECT_TRUE(session.ok()) << session.error().message();
  if (!session.ok()) return {};
  HapticReplay haptics(replayed, path.filename().string());
  haptics.on_tick = std::move(on_tick);
  ReplayOptions ro;
  ro.fast = true;
  ro.on_haptic = [&](const sim::HapticRecord& r) { return haptics.handle(r); };
  auto result = replay_session(*session, path.filename().string(), replayed, ro);
  EXPECT_TRUE(result.ok()) << result.error().message();
  return haptics.figures();
}

TEST(HapticReplay, ALiveForceSessionReplaysEveryTickBitForBit) {
  test::ScratchDir dir;
  StationController controller(clay_station(dir));
  const auto session_path = dir.path() / "touch.scs";
  ASSERT_TRUE(controller.start_recording(session_path, hal::monotonic_ns()).ok());
  controller.set_tool(sim::ToolShape::kSphere, 6.0f, 6.0f, hal::monotonic_ns());
  controller.set_mode(core::SculptMode::kSubtract, hal::monotonic_ns());

  // A second at rest (the sculpting side builds the clay's patch meanwhile:
  // under ThreadSanitizer on a slow machine the first one came so late that
  // the press met little or no clay), then down onto the clay, a press with
  // the button that carves, a slide along the hole, with the clutch key held
  // for a moment, then unplugged.
  constexpr double kRestS = 1.0;
  // The clutch held for 50 ticks of the 1 kHz loop during the slide.
  constexpr int64_t kClutchTick = static_cast<int64_t>(kRestS * 1000) + 850;
  hal::HandScript hand;
  hand.stiffness_n_per_mm = 0.8f;
  hand.path = {{kRestS, glm::vec3(0.0f)},
               {kRestS + 0.3, glm::vec3(0.0f, -10.0f, 0.0f)},
               {kRestS + 0.9, glm::vec3(4.0f, -10.0f, 0.0f)}};
  hand.buttons = {{kRestS + 0.4, 1u}, {kRestS + 0.8, 0u}};
  hand.unplug_s = kRestS + 1.0;
  HapticStationOptions options;
  options.thread.realtime_priority = 0;
  options.loop.safety.ramp_s = 0.05;
  HapticStation station(std::make_unique<hal::SimArm>(hand), options);
  station.start(glm::vec3(32.0f, 56.0f, 32.0f), 3.0f);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool clutched = false;
  while (station.running() && std::chrono::steady_clock::now() < give_up) {
    station.sculpting_side(controller, hal::monotonic_ns());
    const int64_t ticks = station.figures().ticks;
    if (ticks > kClutchTick && ticks < kClutchTick + 50 && !clutched)
      station.set_clutch(clutched = true);
    if (ticks >= kClutchTick + 50 && clutched) station.set_clutch(clutched = false);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ASSERT_FALSE(station.running());
  station.sculpting_side(controller, hal::monotonic_ns());  // the last ticks
  // The loop dropped no record of a tick: the recording holds every one.
  EXPECT_EQ(station.figures().records_dropped, 0);
  ASSERT_TRUE(controller.stop_recording().ok());
  const uint64_t live_hash = controller.loop().volume().content_hash();
  ASSERT_GT(controller.loop().counters().dabs, 0);

  StationLoop replayed(StationLoop::Options{.mesh = false});
  int64_t ticks_seen = 0;
  int64_t forceful = 0;
  const HapticReplayFigures f = replay_forces(session_path, replayed, [&](const ReplayedTick& t) {
    ++ticks_seen;
    if (glm::length(t.tick.force_n) > 0.5f) ++forceful;
  });
  EXPECT_EQ(f.loops, 1);
  // Every tick of the loop's two seconds of life, recorded and run again:
  // about two thousand, fewer when the machine is loaded (the arm's script
  // runs on the clock; 981 of a thousand was seen beside a CI run), so the
  // bound is loose and the test's point is that none was dropped (above)
  // and each one replays.
  EXPECT_GE(f.ticks, 1000);
  EXPECT_EQ(f.ticks, ticks_seen);
  EXPECT_EQ(f.unverified_ticks, 0);
  EXPECT_EQ(f.force_mismatches, 0);
  EXPECT_GE(f.patches, 2);  // built, then refreshed as the press carved
  EXPECT_EQ(f.patch_mismatches, 0);
  // It rested and pressed: the forces are not all zero (706-869 ticks over
  // 0.5 N under ThreadSanitizer on a slow machine once the arm rested
  // first; 0-35 when it pressed at once, before the clay's patch came).
  EXPECT_GT(forceful, 200);
  EXPECT_GT(f.max_force_n, 0.5f);
  EXPECT_LE(f.max_force_n, 8.0f);
  EXPECT_EQ(replayed.volume().content_hash(), live_hash);
}

// The bundled force session: the simulated arm's touch.hand, recorded by the
// window. A change to the contact law, the proxy or the safety rules changes
// its forces, and this test says so; record it again with `sculpt run
// --haptic sim-arm:sim/sessions/touch.hand --record sim/sessions/touch.scs
// --until-replayed` (under xvfb-run without a display).
TEST(HapticReplay, TheBundledTouchSessionReplaysEveryTickBitForBit) {
  StationLoop replayed(StationLoop::Options{.mesh = false});
  const HapticReplayFigures f = replay_forces(sim::bundled_session_path("touch"), replayed);
  EXPECT_EQ(f.loops, 1);
  EXPECT_EQ(f.ticks, 6200);  // the hand unplugs the arm at 6.2 s
  EXPECT_EQ(f.unverified_ticks, 0);
  EXPECT_EQ(f.force_mismatches, 0);
  EXPECT_EQ(f.patch_mismatches, 0);
  EXPECT_GT(f.max_force_n, 2.0f);
  EXPECT_GT(replayed.counters().dabs, 100);  // it carved a groove
}

TEST(HapticReplay, ATickRecordWithoutItsLoopsStartIsCountedNotRun) {
  StationLoop material(StationLoop::Options{.mesh = false});
  HapticReplay haptics(material, "orphan.scs");
  sim::HapticRecord tick;
  tick.type = sim::HapticRecord::Type::kTick;
  tick.flags = sim::kTickHomed;
  ASSERT_TRUE(haptics.handle(tick).ok());
  EXPECT_EQ(haptics.figures().ticks, 0);
  EXPECT_EQ(haptics.figures().unverified_ticks, 1);
}

TEST(HapticReplay, ALoopSetUpRoundTripsAndABadOneNamesTheSetting) {
  HapticLoopSetup setup;
  setup.contact.haptic.coupling.stiffness_n_per_mm = 2.75f;
  setup.contact.workspace_scale = 3.0f;
  setup.loop.safety.watchdog_ns = 4'000'000;
  setup.placed = true;
  setup.placed_device_mm = glm::vec3(0.1f, -7.25f, 3.0f);
  setup.volume_levels = 4;
  const sim::HapticRecord record = start_record(setup);
  auto back = parse_loop_setup(record, "s.scs");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(start_record(*back), record);  // every setting, bit for bit
  EXPECT_EQ(back->contact.haptic.coupling.stiffness_n_per_mm, 2.75f);
  EXPECT_EQ(back->placed_device_mm.y, -7.25f);

  sim::HapticRecord bad = record;
  bad.settings = "coupling.stiffnes_n_per_mm = 1\n";
  EXPECT_EQ(parse_loop_setup(bad, "s.scs").error().message(),
            "s.scs: haptic loop set-up: unknown setting coupling.stiffnes_n_per_mm");
  bad.settings = "patch_level = 2.5\n";
  EXPECT_EQ(parse_loop_setup(bad, "s.scs").error().message(),
            "s.scs: haptic loop set-up: patch_level = 2.500000 is out of range");
  bad.settings = "voxel_mm = 1e300\n";
  EXPECT_FALSE(parse_loop_setup(bad, "s.scs").ok());
}

}  // namespace
}  // namespace sculpt::station
