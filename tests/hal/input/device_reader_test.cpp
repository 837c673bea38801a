// The reader thread on its own, through the byte-level fake transport.

#include "sculpt/hal/input/device_reader.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include <sched.h>

#include "../parsers/report_bytes.h"
#include "sculpt/base/thread_priority.h"
#include "sculpt/hal/backends/feed_backend.h"
#include "sculpt/hal/parsers/spacemouse_parser.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

using test::axes_report;

// A SpaceNavigator on the fake transport: its feed and the opened device.
struct FakeSpaceMouse {
  FeedBackend backend;
  std::shared_ptr<DeviceFeed> feed;
  Result<std::unique_ptr<Device>> device;
  FakeSpaceMouse() : feed(backend.attach(info())), device(backend.open(feed->info())) {}
  static DeviceInfo info() {
    DeviceInfo i;
    i.path = "hidraw0";
    i.vendor_id = 0x046d;
    i.product_id = 0xc626;
    return i;
  }
};

TEST(DeviceReader, CountsDroppedMotionButNeverDropsButtonsOrDisconnect) {
  FakeSpaceMouse mouse;
  auto& feed = mouse.feed;
  auto& device = mouse.device;
  ASSERT_TRUE(device.ok());
  auto parser = std::make_unique<SpaceMouseParser>(*find_quirks(0x046d, 0xc626));
  ReaderOptions o;
  o.ring_capacity = 8;
  NormalizerConfig direct;
  direct.filter = false;
  DeviceReader reader(7, std::move(device).value(), MotionPipeline(std::move(parser), direct), o);
  // Queue everything before the thread starts so the ring overflows for sure.
  for (int64_t i = 0; i < 100; ++i) {
    feed->push(test::report_at(i, axes_report(1, {static_cast<int16_t>(i), 0, 0, 0, 0, 0})));
  }
  feed->push(test::report_at(100, {3, 0x01}));
  feed->remove(101);
  reader.start();
  InputFrame all;
  for (int i = 0; i < 5000 && !reader.finished(); ++i) {
    reader.poll(all, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(reader.finished());
  const ReaderCounters c = reader.counters();
  EXPECT_EQ(c.motion_samples, 100);
  EXPECT_EQ(c.raw_events, 101);
  EXPECT_GT(c.dropped, 0) << "an 8-slot ring cannot hold 100 samples";
  std::vector<InputEvent> others;
  int64_t motion_delivered = 0;
  for (const InputEvent& e : all.events) {
    if (e.kind == InputKind::kMotion) {
      ++motion_delivered;
    } else {
      others.push_back(e);
    }
  }
  EXPECT_EQ(motion_delivered + c.dropped, 100) << "every sample is delivered or counted";
  ASSERT_EQ(others.size(), 3u);
  EXPECT_EQ(others[0].kind, InputKind::kConnected);
  EXPECT_EQ(others[1].kind, InputKind::kButton);
  EXPECT_EQ(others[2].kind, InputKind::kDisconnected);
  EXPECT_EQ(others[2].device_id, 7u);
}

// Each report's events say when the reader read it, on this machine's clock
// (a played session's reports carry the recording's times), and the reader
// rings its doorbell once they are in the ring: the window's sculpting
// thread sleeps on it between polls (InputHub::run()).
TEST(DeviceReader, StampsWhenAReportWasReadAndRingsTheDoorbell) {
  FakeSpaceMouse mouse;
  ASSERT_TRUE(mouse.device.ok());
  auto parser = std::make_unique<SpaceMouseParser>(*find_quirks(0x046d, 0xc626));
  ReaderOptions o;
  o.doorbell = std::make_shared<Doorbell>();
  NormalizerConfig direct;
  direct.filter = false;
  DeviceReader reader(3, std::move(mouse.device).value(), MotionPipeline(std::move(parser), direct),
                      o);
  const Doorbell& bell = *o.doorbell;
  // Long enough for any machine; a lost ring fails the test after it.
  constexpr int64_t kPatienceNs = int64_t{10} * 1'000'000'000;
  uint32_t seen = bell.rings();
  reader.start();
  // The connect event rings too. (A lost ring would sleep to the deadline.)
  ASSERT_TRUE(bell.wait_until(seen, monotonic_ns() + kPatienceNs));
  ASSERT_NE(bell.rings(), seen);
  InputFrame frame;
  reader.poll(frame, monotonic_ns());
  ASSERT_EQ(frame.events.size(), 1u);
  EXPECT_EQ(frame.events[0].kind, InputKind::kConnected);
  EXPECT_GT(frame.events[0].arrived_ns, 0);

  frame.clear();
  seen = bell.rings();
  const int64_t before = monotonic_ns();
  constexpr int64_t kRecordedNs = 5'000;  // a recording's clock, long before now
  mouse.feed->push(test::report_at(kRecordedNs, axes_report(1, {100, 0, 0, 0, 0, 0})));
  ASSERT_TRUE(bell.wait_until(seen, monotonic_ns() + kPatienceNs));
  ASSERT_NE(bell.rings(), seen);
  const int64_t after = monotonic_ns();
  reader.poll(frame, after);
  ASSERT_EQ(frame.events.size(), 1u);
  const InputEvent& e = frame.events[0];
  EXPECT_EQ(e.kind, InputKind::kMotion);
  EXPECT_EQ(e.t_ns, kRecordedNs);
  EXPECT_GE(e.arrived_ns, before);
  EXPECT_LE(e.arrived_ns, after);
  // Late counts from when it was read, not from the recording's time.
  EXPECT_EQ(reader.counters().late, 0);
  reader.stop();
}

// A reader asked for real-time priority takes it as it starts (the window's
// readers, a device plugged in later included), and an unasked one does not.
TEST(DeviceReader, TakesTheRealtimePriorityAskedFor) {
  for (const int priority : {0, 1}) {
    FakeSpaceMouse mouse;
    ASSERT_TRUE(mouse.device.ok());
    ReaderOptions o;
    o.realtime_priority = priority;
    DeviceReader reader(
        1, std::move(mouse.device).value(),
        MotionPipeline(std::make_unique<SpaceMouseParser>(*find_quirks(0x046d, 0xc626)), {}), o);
    reader.start();
    // Its first event (connected) comes after it took its priority.
    InputFrame frame;
    for (int i = 0; i < 5000 && frame.events.empty(); ++i) {
      reader.poll(frame, 0);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_FALSE(frame.events.empty());
    const std::vector<int> readers = threads_named("reader");
    ASSERT_EQ(readers.size(), 1u);
    const ThreadScheduling reader_scheduling = thread_scheduling(readers[0]);
    if (priority == 0) {
      EXPECT_EQ(reader_scheduling, (ThreadScheduling{SCHED_OTHER, 0}));
      continue;
    }
    bool allowed = reader_scheduling.policy == SCHED_FIFO;
    if (!allowed)
      std::thread([&] { allowed = set_this_thread_scheduling({SCHED_FIFO, 1}); }).join();
    if (!allowed) GTEST_SKIP() << "no real-time priority here";
    EXPECT_EQ(reader_scheduling, (ThreadScheduling{SCHED_FIFO, 1}));
  }
}

}  // namespace
}  // namespace sculpt::hal
