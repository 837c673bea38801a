// The sculpting thread: a session played as a live device through the hub
// ends on its replay's volume, with the render thread taking its turns with
// the controller meanwhile (run under ThreadSanitizer in CI).

#include "sculpt/station/app/input_hub.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "scratch_dir.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/hal/backends/feed_backend.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/sim/replay/sim_backend.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_loading.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/session_start.h"

#include "../replay_fast.h"
#include "plug_in_and_out.h"

namespace sculpt::station {
namespace {

struct LiveSession {
  std::unique_ptr<hal::DeviceRegistry> registry;
  sim::SimBackend* sim = nullptr;
  std::string normalizer;
};

// The session as a device, as the window plays it (`sculpt run --device sim:`),
// its raw reports tapped into `recorder`'s recording when given.
LiveSession play_live(const std::string& name, double speed, StationController* recorder = nullptr,
                      bool wait_for_start = false) {
  auto session = load_session(sim::bundled_session_path(name));
  EXPECT_TRUE(session.ok());
  auto config = hal::parse_normalizer_config(session->header.normalizer_config, name);
  EXPECT_TRUE(config.ok());
  LiveSession live;
  live.normalizer = hal::to_text(*config);
  hal::ReaderOptions reader_options;
  if (recorder != nullptr)
    reader_options.on_raw = [recorder](const hal::RawEvent& e) { recorder->raw_report(e); };
  live.registry = std::make_unique<hal::DeviceRegistry>(
      std::vector<std::unique_ptr<hal::Backend>>{}, *config, reader_options);
  auto backend =
      std::make_unique<sim::SimBackend>(std::move(session).value(), sim::bundled_session_path(name),
                                        speed, /*loop=*/false, wait_for_start);
  live.sim = backend.get();
  live.registry->add_backend(std::move(backend), /*first=*/true);
  EXPECT_TRUE(live.registry->open_device("sim").ok());
  return live;
}

uint64_t replayed_hash(const std::string& name, int64_t* dabs) {
  auto session = load_session(sim::bundled_session_path(name));
  StationLoop loop(StationLoop::Options{});
  EXPECT_TRUE(test::replay_fast(*session, name, loop).ok());
  *dabs = loop.counters().dabs;
  return loop.volume().content_hash();
}

// The recording at `path`, replayed from its start, ends on the live volume.
void expect_replays_to_the_live_volume(const std::filesystem::path& path,
                                       const StationController& controller) {
  auto recorded = load_session(path.string());
  ASSERT_TRUE(recorded.ok()) << recorded.error().message();
  StationLoop replayed(StationLoop::Options{});
  ASSERT_TRUE(restore_session_start(path.string(), replayed).ok());
  ASSERT_TRUE(test::replay_fast(*recorded, path.filename().string(), replayed).ok());
  EXPECT_EQ(controller.loop().volume().content_hash(), replayed.volume().content_hash());
  EXPECT_EQ(controller.loop().counters().dabs, replayed.counters().dabs);
  EXPECT_GT(replayed.counters().dabs, 10);
}

// A controller that meshes nothing itself and autosaves nothing, its project
// in `dir`.
ControllerOptions quiet_controller(const test::ScratchDir& dir) {
  ControllerOptions co;
  co.loop.mesh = false;
  co.project = dir.path() / "p.sculpt";
  co.autosave_seconds = 0;
  return co;
}

TEST(InputHub, ALiveSessionSculptedOnItsThreadEndsOnTheReplaysVolume) {
  test::ScratchDir dir;
  StationController controller(quiet_controller(dir));
  SurfaceMesher mesher;
  LiveSession live = play_live("sheet", 8.0);
  InputHub hub(controller, std::move(live.registry), live.sim, live.normalizer, mesher);
  SurfaceSnapshot snapshot;
  std::vector<int> levels;
  hub.start();
  // The render thread's turns: the camera chooses levels, the meshes are
  // taken, the panel reads the pose and turns the camera.
  int turns = 0;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!hub.replay_done() && std::chrono::steady_clock::now() < give_up) {
    {
      std::lock_guard turn(hub.mutex());
      const core::Volume& v = controller.loop().volume();
      levels.assign(static_cast<size_t>(v.brick_count()), turns % 2);
      hub.set_levels(levels);
      if (auto delta = mesher.take()) {
        controller.surface_ready(*delta);
        snapshot.apply(std::move(*delta));
      }
      controller.camera().orbit(0.001f, 0.0f);
      EXPECT_TRUE(std::isfinite(controller.loop().pose().position.x));
      ++turns;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // drawing
  }
  ASSERT_TRUE(hub.replay_done()) << "the session did not end in 60 s";
  hub.stop();
  std::lock_guard last(hub.mutex());
  hub.poll_now();
  mesher.wait_until_meshed();
  if (auto delta = mesher.take()) {
    controller.surface_ready(*delta);
    snapshot.apply(std::move(*delta));
  }

  int64_t dabs = 0;
  EXPECT_EQ(controller.loop().volume().content_hash(), replayed_hash("sheet", &dabs));
  EXPECT_EQ(controller.loop().counters().dabs, dabs);
  EXPECT_GT(dabs, 10);
  // That the hub read the devices on its own thread is the replay_done()
  // asserted above (only its polls set it). How often it polled against the
  // frames is timing, not asserted: the sheet's polls are long (15 ms in a
  // Release build, hundreds under AddressSanitizer, where the two threads
  // then alternate one for one); `--stats` reports it (sculpting.polls).
  EXPECT_GT(snapshot.triangle_count(), 100);
  EXPECT_EQ(controller.session_latency().count, dabs);  // every dab's latency counted
  // Reports woke the hub between the clock's polls (the reader's doorbell):
  // a report that came during a poll, or between two, did not wait for the
  // next millisecond. (How many is timing; none means no ring reached it.)
  EXPECT_GT(hub.figures().polls_on_reports, 0);
}

// A device that floods the hub (20,000 reports queued at once on the fake
// transport, a SpaceNavigator's, read as fast as its reader can) wakes it
// at most once every kMinPollSpacingNs: the reports are taken many to a
// poll, not one poll each. An upper bound: no machine is too slow for it.
TEST(InputHub, AFloodingDeviceWakesThePollsAtMostEveryMinPollSpacing) {
  test::ScratchDir dir;
  StationController controller(quiet_controller(dir));
  SurfaceMesher mesher;
  auto backend = std::make_unique<hal::FeedBackend>("fake-hid");
  hal::DeviceInfo navigator;
  navigator.path = "hidraw0";
  navigator.vendor_id = 0x046d;
  navigator.product_id = 0xc626;
  const std::shared_ptr<hal::DeviceFeed> feed = backend->attach(navigator);
  std::vector<std::unique_ptr<hal::Backend>> backends;
  backends.push_back(std::move(backend));
  auto registry = std::make_unique<hal::DeviceRegistry>(std::move(backends));
  ASSERT_EQ(registry->scan().opened.size(), 1u);  // its reader starts now
  InputHub hub(controller, std::move(registry), nullptr, "", mesher);
  const int64_t started_ns = hal::monotonic_ns();
  hub.start();
  constexpr int kReports = 20'000;
  for (int i = 0; i < kReports; ++i) {
    // Translation report (id 1): three little-endian int16 axes.
    const uint8_t bytes[] = {1, static_cast<uint8_t>(i % 200), 0, 0, 0, 0, 0};
    feed->push(hal::RawEvent::report(hal::monotonic_ns(), bytes));
  }
  ASSERT_TRUE(feed->wait_drained(60'000)) << "the reader did not take the reports in 60 s";
  std::this_thread::sleep_for(std::chrono::milliseconds(5));  // the last poll takes them
  hub.stop();
  const int64_t elapsed_ns = hal::monotonic_ns() - started_ns;
  std::lock_guard last(hub.mutex());
  const InputHubFigures& f = hub.figures();
  EXPECT_GT(f.polls_on_reports, 0);
  EXPECT_LE(f.polls_on_reports, elapsed_ns / InputHub::kMinPollSpacingNs + 1)
      << f.polls << " polls in " << static_cast<double>(elapsed_ns) * 1e-6 << " ms";
}

// Device ids are never reused: after many re-plugs the device open has a
// high one. The hub still tells the panel (and a recording's header, which
// a replay parses with) which device it is. (It looked among ids 0-63.)
TEST(InputHub, NotesTheDeviceOpenAfterManyReplugs) {
  test::ScratchDir dir;
  StationController controller(quiet_controller(dir));
  SurfaceMesher mesher;
  auto backend = std::make_unique<hal::FeedBackend>("fake-hid");
  hal::FeedBackend* transport = backend.get();
  hal::DeviceInfo navigator;
  navigator.path = "hidraw0";
  navigator.name = "SpaceNavigator";
  navigator.vendor_id = 0x046d;
  navigator.product_id = 0xc626;
  std::vector<std::unique_ptr<hal::Backend>> backends;
  backends.push_back(std::move(backend));
  auto registry = std::make_unique<hal::DeviceRegistry>(std::move(backends));
  ASSERT_NO_FATAL_FAILURE(test::plug_in_and_out(*transport, *registry, navigator, 70));
  auto feed = transport->attach(navigator);
  ASSERT_EQ(registry->scan().opened.size(), 1u);
  InputHub hub(controller, std::move(registry), nullptr, "", mesher);
  EXPECT_EQ(controller.device_status().name, "SpaceNavigator");
}

// The window's session device waits for the station: the hub starts it once
// the opening surface is meshed (the render thread has given levels and the
// mesher is done), not while the window is still starting.
TEST(InputHub, AWaitingSessionStartsOnceTheOpeningSurfaceIsMeshed) {
  test::ScratchDir dir;
  StationController controller(quiet_controller(dir));
  SurfaceMesher mesher;
  LiveSession live = play_live("sheet", 8.0, nullptr, /*wait_for_start=*/true);
  InputHub hub(controller, std::move(live.registry), live.sim, live.normalizer, mesher);
  const uint64_t opening = controller.loop().volume().content_hash();
  hub.start();
  // No levels yet (no frame has drawn): polled, but nothing played.
  while (true) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::lock_guard turn(hub.mutex());
    if (hub.figures().polls >= 20) break;
  }
  {
    std::lock_guard turn(hub.mutex());
    EXPECT_EQ(controller.loop().volume().content_hash(), opening);
    EXPECT_EQ(controller.loop().counters().dabs, 0);
    EXPECT_FALSE(hub.replay_done());
    const core::Volume& v = controller.loop().volume();
    hub.set_levels(std::vector<int>(static_cast<size_t>(v.brick_count()), 0));
  }
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!hub.replay_done() && std::chrono::steady_clock::now() < give_up) {
    {
      std::lock_guard turn(hub.mutex());
      (void)mesher.take();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(hub.replay_done()) << "the session did not end in 60 s";
  hub.stop();
  int64_t dabs = 0;
  EXPECT_EQ(controller.loop().volume().content_hash(), replayed_hash("sheet", &dabs));
}

// The short session unplugs its device mid-stroke and plugs it back in: the
// live hub opens it again at its next scan and plays on to the end, as the
// replay does, instead of ending the session at the unplug.
TEST(InputHub, AnUnpluggedSimDeviceComesBackAndPlaysOn) {
  test::ScratchDir dir;
  StationController controller(quiet_controller(dir));
  SurfaceMesher mesher;
  LiveSession live = play_live("short", 8.0);
  InputHub hub(controller, std::move(live.registry), live.sim, live.normalizer, mesher);
  hub.start();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!hub.replay_done() && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(hub.replay_done()) << "the session did not end in 60 s";
  hub.stop();
  std::lock_guard last(hub.mutex());
  hub.poll_now();
  int64_t dabs = 0;
  EXPECT_EQ(controller.loop().volume().content_hash(), replayed_hash("short", &dabs));
  EXPECT_EQ(controller.loop().counters().dabs, dabs);
  EXPECT_EQ(controller.loop().counters().disconnects, 1);
  EXPECT_EQ(controller.loop().counters().strokes, 5);  // the last after the plug
}

// An offset asked for from the panel, computed in the background as the
// window does: the session's reports wait for it, and a panel command while
// it computes comes after the reports held meanwhile, as they came. The live
// volume is the recording's replay, and starts with the offset.
TEST(InputHub, ReportsDuringABackgroundOffsetWaitForItAndKeepTheirOrder) {
  test::ScratchDir dir;
  ControllerOptions co = quiet_controller(dir);
  co.loop.clay_margin = 100;  // a block of clay in the middle, to offset
  co.loop.background_morphology = true;
  StationController controller(co);
  SurfaceMesher mesher;
  LiveSession live = play_live("short", 8.0, &controller);
  InputHub hub(controller, std::move(live.registry), live.sim, live.normalizer, mesher);
  {
    std::lock_guard turn(hub.mutex());
    ASSERT_TRUE(controller.start_recording(dir.path() / "r.scs", hal::monotonic_ns()).ok());
  }
  hub.start();
  // Offsets asked for mid-session, as from the panel, until one computes
  // while reports come (none come while the session's device is unplugged).
  int offsets = 0;
  int64_t asked_at_sample = 0, held_when_asked = 0;
  bool commanded_while_pending = false;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!hub.replay_done() && std::chrono::steady_clock::now() < give_up) {
    {
      std::lock_guard turn(hub.mutex());
      const int64_t samples_now = controller.loop().counters().motion_samples;
      if (!commanded_while_pending && !controller.loop().morphology_pending() && offsets < 10 &&
          samples_now > asked_at_sample + 200) {
        ++offsets;
        asked_at_sample = samples_now;
        held_when_asked = hub.figures().held_events;
        ASSERT_TRUE(controller.offset_sculpture(1.0f, hal::monotonic_ns())) << controller.status();
        EXPECT_TRUE(controller.loop().morphology_pending());
      } else if (!commanded_while_pending && controller.loop().morphology_pending() &&
                 hub.figures().held_events > held_when_asked) {
        // The panel's strength: the reports held before it go first, at
        // the old strength, as they came.
        commanded_while_pending = true;
        const int64_t samples = controller.loop().counters().motion_samples;
        controller.set_strength(0.5f, hal::monotonic_ns());
        EXPECT_FALSE(controller.loop().morphology_pending());
        EXPECT_GT(controller.loop().counters().motion_samples, samples);
      }
      controller.camera().orbit(0.001f, 0.0f);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(hub.replay_done()) << "the session did not end in 60 s";
  hub.stop();
  std::lock_guard last(hub.mutex());
  hub.poll_now(/*land=*/true);
  EXPECT_GT(offsets, 0);
  EXPECT_TRUE(commanded_while_pending);
  EXPECT_GT(hub.figures().held_events, 0);
  EXPECT_EQ(controller.status().rfind("offset by +1 voxels: ", 0), 0u) << controller.status();
  controller.tick(hal::monotonic_ns());
  ASSERT_TRUE(controller.stop_recording().ok());

  expect_replays_to_the_live_volume(dir.path() / "r.scs", controller);
}

// The reader reads a device from the moment it opens, the hub only once it
// starts: a recording started in between has the reports waiting in the
// reader's ring, which the station applies after its opening.
TEST(InputHub, ARecordingStartedWithReportsInFlightHasThem) {
  test::ScratchDir dir;
  StationController controller(quiet_controller(dir));
  SurfaceMesher mesher;
  LiveSession live = play_live("short", 32.0, &controller);
  ASSERT_TRUE(live.registry->first_device().has_value());
  const hal::DeviceReader* reader = live.registry->reader(*live.registry->first_device());
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (reader->counters().motion_samples < 20 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_GE(reader->counters().motion_samples, 20) << "the session did not start in 60 s";
  InputHub hub(controller, std::move(live.registry), live.sim, live.normalizer, mesher);
  {
    std::lock_guard turn(hub.mutex());
    ASSERT_TRUE(controller.start_recording(dir.path() / "r.scs", hal::monotonic_ns()).ok());
    EXPECT_EQ(controller.loop().counters().motion_samples, 0);  // none applied yet
  }
  hub.start();
  while (!hub.replay_done() && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_TRUE(hub.replay_done()) << "the session did not end in 60 s";
  hub.stop();
  std::lock_guard last(hub.mutex());
  hub.poll_now(/*land=*/true);
  controller.tick(hal::monotonic_ns());
  ASSERT_TRUE(controller.stop_recording().ok());
  expect_replays_to_the_live_volume(dir.path() / "r.scs", controller);
}

// A hub with no device, over a controller that meshes nothing.
struct IdleHub {
  static ControllerOptions options() {
    ControllerOptions co;
    co.loop.mesh = false;
    co.autosave_seconds = 0;
    return co;
  }
  StationController controller{options()};
  SurfaceMesher mesher;
  InputHub hub{controller,
               std::make_unique<hal::DeviceRegistry>(std::vector<std::unique_ptr<hal::Backend>>{},
                                                     hal::NormalizerConfig{}, hal::ReaderOptions{}),
               nullptr, "", mesher};
};

TEST(InputHub, StopsCleanlyWithoutADevice) {
  IdleHub idle;
  InputHub& hub = idle.hub;
  StationController& controller = idle.controller;
  hub.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  hub.stop();
  hub.stop();  // twice is harmless
  EXPECT_FALSE(hub.replay_done());
  std::lock_guard last(hub.mutex());
  EXPECT_GT(hub.figures().polls, 2);
  EXPECT_EQ(controller.loop().counters().dabs, 0);
}

TEST(InputHub, AFrameDoesNotWaitForALongPollUnlessItMust) {
  IdleHub idle;
  InputHub& hub = idle.hub;
  EXPECT_TRUE(hub.frame_turn(false).owns_lock());  // nobody holds it
  // A poll that sculpts a big dab holds the turn until it is done.
  std::mutex done_mutex;
  std::condition_variable done_changed;
  bool holding = false, done = false;
  std::thread long_poll([&] {
    std::lock_guard poll(hub.mutex());
    std::unique_lock l(done_mutex);
    holding = true;
    done_changed.notify_all();
    done_changed.wait(l, [&] { return done; });
  });
  {
    std::unique_lock l(done_mutex);
    done_changed.wait(l, [&] { return holding; });
  }
  EXPECT_FALSE(hub.frame_turn(false).owns_lock());  // the frame draws without it
  std::thread last_frame([&] { EXPECT_TRUE(hub.frame_turn(true).owns_lock()); });
  {
    std::lock_guard l(done_mutex);
    done = true;
  }
  done_changed.notify_all();
  long_poll.join();
  last_frame.join();  // the last frame waited for the poll, then had its turn
  EXPECT_TRUE(hub.frame_turn(false).owns_lock());
}

}  // namespace
}  // namespace sculpt::station
