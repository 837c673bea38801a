#include "sculpt/sim/replay/sim_backend.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "sculpt/sim/synth/bundled_sessions.h"

namespace sculpt::sim {
namespace {

TEST(SimBackend, PlaysTheSessionDeviceThroughTheHalInterfaces) {
  Session s = short_session();
  const size_t commands = static_cast<size_t>(std::count_if(
      s.records.begin(), s.records.end(),
      [](const SessionRecord& r) { return r.kind == SessionRecord::Kind::kCommand; }));
  const size_t events = s.records.size() - commands;
  SimBackend backend(s, "short.scs", /*speed=*/1000.0);
  EXPECT_EQ(backend.name(), "sim");
  auto devices = backend.enumerate();
  ASSERT_TRUE(devices.ok());
  ASSERT_EQ(devices->size(), 1u);
  EXPECT_EQ((*devices)[0].id(), "sim:short.scs");
  EXPECT_EQ((*devices)[0].vendor_product(), "046d:c626");
  auto device = backend.open((*devices)[0]);
  ASSERT_TRUE(device.ok());
  EXPECT_FALSE(backend.open((*devices)[0]).ok());  // never opened twice

  size_t got = 0;
  int removals = 0;
  hal::RawEvent e;
  for (int timeouts = 0; timeouts < 3;) {
    switch ((*device)->read(e, 50)) {
      case hal::ReadResult::kEvent:
        ++got;
        break;
      case hal::ReadResult::kRemoved:
        ++removals;
        ++got;
        timeouts = 3;
        break;
      case hal::ReadResult::kTimeout:
        ++timeouts;
        break;
    }
  }
  // The short session unplugs the device once: everything up to it arrives.
  EXPECT_EQ(removals, 1);
  EXPECT_LT(got, events);
  EXPECT_GT(got, events / 2);
  EXPECT_GT(backend.take_commands().size(), 3u);
  EXPECT_EQ((*device)->read(e, 0), hal::ReadResult::kRemoved);  // and keeps saying so
  EXPECT_FALSE(backend.played());

  // Plugged back in, as `sculpt replay` has it: the backend says its list
  // changed, and the device opened again plays on from the record after the
  // unplug to the session's end.
  EXPECT_TRUE(backend.changed());
  EXPECT_FALSE(backend.changed());
  auto again = backend.open((*devices)[0]);
  ASSERT_TRUE(again.ok()) << again.error().message();
  int64_t last_t = 0;
  for (int timeouts = 0; timeouts < 3 && !backend.played();) {
    switch ((*again)->read(e, 50)) {
      case hal::ReadResult::kEvent:
        EXPECT_GT(e.t_ns, last_t);
        last_t = e.t_ns;
        ++got;
        break;
      case hal::ReadResult::kRemoved:
        ADD_FAILURE() << "unplugged twice";
        timeouts = 3;
        break;
      case hal::ReadResult::kTimeout:
        ++timeouts;
        break;
    }
  }
  EXPECT_TRUE(backend.played());
  EXPECT_EQ(got, events);  // every event, the unplug included, once
  EXPECT_EQ((*device)->read(e, 0), hal::ReadResult::kRemoved);  // the old handle stays gone
}

// The window opens a session's device while it is still starting; made to
// wait, the device hands out nothing, commands included, however long ago
// its records fell due, until the station starts to poll.
TEST(SimBackend, AWaitingDeviceHandsOutNothingUntilStarted) {
  const Session s = short_session();
  SimBackend backend(s, "short.scs", /*speed=*/1000.0, /*loop=*/false, /*wait_for_start=*/true);
  auto devices = backend.enumerate();
  ASSERT_TRUE(devices.ok());
  auto device = backend.open((*devices)[0]);
  ASSERT_TRUE(device.ok());
  hal::RawEvent e;
  // At a thousand times real time the whole session is due within these reads.
  for (int i = 0; i < 20; ++i)
    ASSERT_EQ((*device)->read(e, 5), hal::ReadResult::kTimeout) << i;
  EXPECT_TRUE(backend.take_commands().empty());
  EXPECT_FALSE(backend.played());

  backend.start_playing();
  int events = 0;
  for (int timeouts = 0; timeouts < 3 && events == 0;)
    (*device)->read(e, 50) == hal::ReadResult::kEvent ? ++events : ++timeouts;
  EXPECT_EQ(events, 1);
  EXPECT_FALSE(backend.take_commands().empty());  // the commands before the first report
}

TEST(SimBackend, ReadHonoursItsTimeoutDuringAPauseInTheRecording) {
  Session s;
  s.header.device.vendor_id = 0x256f;
  s.header.device.product_id = 0xc635;
  s.records.push_back(SessionRecord::of(hal::RawEvent::sync(0)));
  s.records.push_back(SessionRecord::of(hal::RawEvent::sync(3'600'000'000'000)));  // an hour later
  SimBackend backend(s, "pause.scs");
  auto device = backend.open(backend.enumerate()->front());
  ASSERT_TRUE(device.ok());
  hal::RawEvent e;
  EXPECT_EQ((*device)->read(e, 10), hal::ReadResult::kEvent);
  EXPECT_EQ((*device)->read(e, 10), hal::ReadResult::kTimeout);  // returns, does not sleep an hour
}

TEST(SimBackend, ALoopingDevicePlaysTheSessionAgainWithTimeGoingOn) {
  Session s;
  s.header.device.vendor_id = 0x256f;
  s.header.device.product_id = 0xc635;
  for (int i = 0; i < 3; ++i)
    s.records.push_back(SessionRecord::of(hal::RawEvent::sync(int64_t{i} * 1000)));
  SimBackend backend(s, "loop.scs", /*speed=*/1e6, /*loop=*/true);
  auto device = backend.open(backend.enumerate()->front());
  ASSERT_TRUE(device.ok());
  std::vector<int64_t> times;
  hal::RawEvent e;
  for (int reads = 0; reads < 200 && times.size() < 9; ++reads) {
    if ((*device)->read(e, 5) == hal::ReadResult::kEvent) times.push_back(e.t_ns);
  }
  ASSERT_EQ(times.size(), 9u) << "three rounds of three";
  // Each round follows the last a second after its end (2000 ns long).
  const int64_t round = 2000 + 1'000'000'000;
  EXPECT_EQ(times[3], round);
  EXPECT_EQ(times[8], 2 * round + 2000);
  EXPECT_TRUE(std::is_sorted(times.begin(), times.end()));
  EXPECT_FALSE(backend.played()) << "a looping device is never played out";
}

}  // namespace
}  // namespace sculpt::sim
