// The device's coming and going around its pipeline: the sequence the live
// reader and a replay both hand the station.

#include "sculpt/hal/input/device_stream.h"

#include <gtest/gtest.h>

#include "../parsers/report_bytes.h"
#include "sculpt/hal/parsers/spacemouse_parser.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

MotionPipeline spacemouse_pipeline() {
  NormalizerConfig direct;
  direct.filter = false;
  return MotionPipeline(std::make_unique<SpaceMouseParser>(*find_quirks(0x046d, 0xc626)), direct);
}

RawEvent removal(int64_t t_ns) {
  RawEvent e;
  e.kind = RawEventKind::kRemoved;
  e.t_ns = t_ns;
  return e;
}

std::vector<InputKind> kinds(const std::vector<InputEvent>& events) {
  std::vector<InputKind> k;
  for (const InputEvent& e : events)
    k.push_back(e.kind);
  return k;
}

TEST(DeviceStream, BracketsTheEventsWithConnectAndDisconnectAndReplugsWithAFreshPipeline) {
  int pipelines_made = 0;
  DeviceStream stream(5, spacemouse_pipeline(), [&] {
    ++pipelines_made;
    return spacemouse_pipeline();
  });
  std::vector<InputEvent> out;
  stream.feed(test::report_at(10, {3, 0x01}), out);  // button 0 down
  stream.feed(test::report_at(11, {3, 0x00}), out);  // and up
  stream.feed(removal(12), out);
  // Plugged back in: connected again at its first report, button state fresh.
  stream.feed(test::report_at(20, {3, 0x00}), out);
  stream.feed(test::report_at(21, {3, 0x01}), out);
  stream.feed(test::report_at(22, {99}), out);  // a report id the family lacks
  EXPECT_EQ(kinds(out), (std::vector<InputKind>{InputKind::kConnected, InputKind::kButton,
                                                InputKind::kButton, InputKind::kDisconnected,
                                                InputKind::kConnected, InputKind::kButton}));
  EXPECT_EQ(out[0].t_ns, 10);
  EXPECT_EQ(out[3].t_ns, 12) << "the removal's own time";
  EXPECT_EQ(out[4].t_ns, 20);
  for (const InputEvent& e : out)
    EXPECT_EQ(e.device_id, 5u);
  EXPECT_TRUE(out[5].pressed);
  EXPECT_EQ(pipelines_made, 1);
  EXPECT_TRUE(stream.connected());
  EXPECT_EQ(stream.parser_counters().unknown_reports, 1);
}

TEST(DeviceStream, ConnectsOnceAndDisconnectsWhenTheReaderStops) {
  DeviceStream stream(1, spacemouse_pipeline());
  std::vector<InputEvent> out;
  stream.connect(100, out);
  stream.connect(101, out);
  stream.feed(test::report_at(102, {3, 0x01}), out);
  stream.disconnect(103, out);
  EXPECT_EQ(kinds(out), (std::vector<InputKind>{InputKind::kConnected, InputKind::kButton,
                                                InputKind::kDisconnected}));
  EXPECT_FALSE(stream.connected());
}

}  // namespace
}  // namespace sculpt::hal
