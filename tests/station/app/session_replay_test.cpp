#include "sculpt/station/app/session_replay.h"

#include <gtest/gtest.h>

#include "sculpt/core/util/parallel_for.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/sim/synth/session_script.h"

#include "../replay_fast.h"

namespace sculpt::station {
namespace {

struct Outcome {
  uint64_t hash = 0;
  int64_t dabs = 0;
  int64_t triangles = 0;
};

Outcome replay(const sim::Session& s, double speed, bool fast, int threads) {
  core::set_default_threads(threads);
  StationLoop loop(StationLoop::Options{});
  ReplayOptions o;
  o.speed = speed;
  o.fast = fast;
  const auto r = replay_session(s, "test", loop, o);
  core::set_default_threads(0);
  EXPECT_TRUE(r.ok()) << r.error().message();
  return {loop.volume().content_hash(), loop.counters().dabs, loop.mesh().triangle_count()};
}

// A scripted session steers from the pose the station reaches, across an
// unplug too: the device back reports through a new pipeline, and the tool
// goes on from where it was (it was thrown back by the old stream's
// integral, 20 voxels here, where the script did not put it).
TEST(SessionReplay, AReplugGoesOnWhereTheScriptSteered) {
  sim::SessionScript s(sim::scripted_device(0x046d, 0xc626), sim::scripted_normalizer(), 125);
  s.volume(glm::ivec3(64), 0);
  s.place(glm::vec3(16, 32, 32));
  s.rest(0.1f);
  s.move_to(glm::vec3(36, 32, 32), 0.5f);
  s.unplug_and_replug(0.5f);
  s.rest(0.1f);
  s.move_to(glm::vec3(36, 44, 32), 0.5f);
  const glm::vec3 steered = s.pose().position;
  EXPECT_NEAR(steered.y, 44.0f, 0.5f);
  StationLoop loop(StationLoop::Options{});
  ASSERT_TRUE(test::replay_fast(s.finish(), "replug", loop).ok());
  EXPECT_EQ(loop.counters().disconnects, 1);
  EXPECT_NEAR(glm::length(loop.pose().position - steered), 0.0f, 1e-3f)
      << loop.pose().position.x << " " << loop.pose().position.y;
}

// The bundled sessions replayed at different speeds and thread counts give
// the same volume, bit for bit.
TEST(SessionReplay, IsDeterministicOnEveryBundledSession) {
  for (std::string_view name : sim::bundled_session_names()) {
    const auto s = sim::read_session_file(sim::bundled_session_path(name));
    ASSERT_TRUE(s.ok());
    const Outcome a = replay(*s, 1, /*fast=*/true, 1);
    const Outcome b = replay(*s, 1, /*fast=*/true, 4);
    EXPECT_EQ(a.hash, b.hash) << name;
    EXPECT_EQ(a.triangles, b.triangles) << name;
    EXPECT_GT(a.dabs, 50) << name;
    EXPECT_GT(a.triangles, 1000) << name;
    if (name == "short") {  // short enough to also replay paced (~3.8 s at 8x: 0.5 s)
      const Outcome c = replay(*s, 8, /*fast=*/false, 2);
      EXPECT_EQ(a.hash, c.hash);
    }
  }
}

TEST(SessionReplay, ShortSessionStrokesUndoAndUnplugBehave) {
  const sim::Session s = sim::short_session();
  StationLoop loop(StationLoop::Options{});
  ReplayOptions o;
  o.fast = true;
  int64_t connects = 0, disconnects = 0;
  o.on_sample = [&](const hal::InputEvent& e) {
    connects += e.kind == hal::InputKind::kConnected;
    disconnects += e.kind == hal::InputKind::kDisconnected;
  };
  const auto r = replay_session(s, "short", loop, o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(loop.volume().dims(), glm::ivec3(64));
  EXPECT_EQ(loop.counters().strokes, 5);  // the stroke cut by the unplug, and one after the re-plug
  EXPECT_EQ(loop.counters().undos, 1);
  EXPECT_EQ(loop.counters().redos, 1);
  EXPECT_EQ(disconnects, 1);
  EXPECT_EQ(connects, 2);
  EXPECT_FALSE(loop.pressed());
  EXPECT_EQ(r->unknown_reports, 0);
  EXPECT_EQ(r->dab_latency.count,
            loop.counters().dabs);  // every dab comes from a report (buttons too)
}

TEST(SessionReplay, UndoRestoresTheVolumeBitForBit) {
  // Replaying up to the stray cut and after its undo must agree.
  sim::Session s = sim::demo_session();
  const auto undo =
      std::find_if(s.records.begin(), s.records.end(), [](const sim::SessionRecord& r) {
        return r.kind == sim::SessionRecord::Kind::kCommand &&
               r.command.kind == sim::CommandKind::kUndo;
      });
  ASSERT_NE(undo, s.records.end());
  // The stroke the undo takes back starts at the last press before it.
  sim::Session before_cut = s;
  before_cut.records.assign(s.records.begin(), undo);
  sim::Session with_undo = s;
  with_undo.records.assign(s.records.begin(), undo + 1);
  auto last_press = std::find_if(before_cut.records.rbegin(), before_cut.records.rend(),
                                 [](const sim::SessionRecord& r) {
                                   return r.kind == sim::SessionRecord::Kind::kEvent &&
                                          r.event.kind == hal::RawEventKind::kReport &&
                                          r.event.data[0] == 3 && r.event.data[1] == 1;
                                 });
  ASSERT_NE(last_press, before_cut.records.rend());
  before_cut.records.erase(std::prev(last_press.base()), before_cut.records.end());
  const Outcome a = replay(before_cut, 1, true, 0);
  const Outcome b = replay(with_undo, 1, true, 0);
  EXPECT_EQ(a.hash, b.hash);
}

TEST(SessionReplay, RefusesADeviceWithoutAParser) {
  sim::Session s;
  s.header.device.name = "gamepad";
  s.header.device.vendor_id = 0x1234;
  s.header.device.product_id = 0x5678;
  s.header.device.usage_page = 1;
  s.header.device.usage = 5;
  StationLoop loop(StationLoop::Options{});
  const auto r = replay_session(s, "pad.scs", loop);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message().find("pad.scs: "), std::string::npos) << r.error().message();
}

}  // namespace
}  // namespace sculpt::station
