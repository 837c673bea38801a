// A tracker's recorded bytes to pose events: what the station moves the tool
// by, live and in a replay, and what it does with bad bytes and lost tracking.

#include "sculpt/hal/parsers/tracker_report_parser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/hal/parsers/opentrack_datagram.h"
#include "sculpt/hal/parsers/vrpn_message.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal {
namespace {

std::vector<InputEvent> parse(ReportParser& parser, const RawEvent& raw) {
  std::vector<InputEvent> out;
  parser.parse(raw, out);
  return out;
}

TEST(TrackerReportParser, AnOpenTrackDatagramIsOneAbsolutePose) {
  TrackerReportParser parser(TrackerFormat::kOpenTrack);
  const auto bytes = encode_opentrack_datagram(1.0, 2.0, -3.0, 90.0, 0, 0);
  const auto out = parse(parser, RawEvent::report(42, bytes));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, InputKind::kMotion);
  EXPECT_TRUE(out[0].absolute);
  EXPECT_TRUE(out[0].has_pose);
  EXPECT_EQ(out[0].t_ns, 42);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[0], 10.0);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[2], -30.0);
  // Yaw 90 degrees: a half-angle of 45 degrees about +Y.
  EXPECT_NEAR(out[0].pose.quat_wxyz[0], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(out[0].pose.quat_wxyz[2], std::sqrt(0.5), 1e-12);
}

TEST(TrackerReportParser, AVrpnPosQuatKeepsItsSensor) {
  TrackerReportParser parser(TrackerFormat::kVrpn);
  const auto bytes = encode_vrpn_pos_quat(3, {0.1, 0.0, -0.2}, {0, 0, 0, 1});
  const auto out = parse(parser, RawEvent::report(7, bytes));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].has_pose);
  EXPECT_EQ(out[0].pose.sensor, 3);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[0], 100.0);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[2], -200.0);
}

TEST(TrackerReportParser, AReportWithNoBytesIsTrackingLost) {
  TrackerReportParser parser(TrackerFormat::kOpenTrack);
  const auto out = parse(parser, RawEvent::report(9, {}));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, InputKind::kTrackingLost);
  EXPECT_EQ(out[0].t_ns, 9);
}

TEST(TrackerReportParser, BadBytesAreCountedAndDropped) {
  TrackerReportParser parser(TrackerFormat::kOpenTrack);
  auto good = encode_opentrack_datagram(1, 2, 3, 4, 5, 6);
  EXPECT_TRUE(parse(parser, RawEvent::report(1, std::span(good).first(47))).empty());
  std::vector<uint8_t> long_bytes(good.begin(), good.end());
  long_bytes.push_back(0);
  EXPECT_TRUE(parse(parser, RawEvent::report(2, long_bytes)).empty());
  const auto nan =
      encode_opentrack_datagram(std::numeric_limits<double>::quiet_NaN(), 0, 0, 0, 0, 0);
  EXPECT_TRUE(parse(parser, RawEvent::report(3, nan)).empty());
  const std::vector<uint8_t> oversized(100, 0);
  EXPECT_TRUE(parse(parser, RawEvent::report(4, oversized)).empty());
  EXPECT_TRUE(parse(parser, RawEvent::axis(5, 0, 1)).empty());
  EXPECT_EQ(parser.counters().reports, 5);
  EXPECT_EQ(parser.counters().short_reports, 1);
  EXPECT_EQ(parser.counters().invalid_reports, 3);
  EXPECT_EQ(parser.counters().unknown_reports, 1);
  // Still decodes after all that.
  EXPECT_EQ(parse(parser, RawEvent::report(6, good)).size(), 1u);

  TrackerReportParser vrpn(TrackerFormat::kVrpn);
  auto zero_quat = encode_vrpn_pos_quat(0, {0, 0, 0}, {0, 0, 0, 0});
  EXPECT_TRUE(parse(vrpn, RawEvent::report(1, zero_quat)).empty());
  EXPECT_TRUE(parse(vrpn, RawEvent::report(2, std::span(zero_quat).first(10))).empty());
  EXPECT_EQ(vrpn.counters().invalid_reports, 1);
  EXPECT_EQ(vrpn.counters().short_reports, 1);
}

// A recorded session can hold any bytes (a damaged or hand-edited file):
// random reports of 0..80 bytes never crash the parser, and every pose it
// lets through is finite with a unit quaternion. Deterministic (fixed seed).
TEST(TrackerReportParser, RandomBytesNeverGiveABadPose) {
  uint32_t seed = 22;
  auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return seed >> 8;
  };
  for (TrackerFormat format : {TrackerFormat::kOpenTrack, TrackerFormat::kVrpn}) {
    TrackerReportParser parser(format);
    int64_t poses = 0;
    for (int i = 0; i < 20000; ++i) {
      // Mostly the format's own length, so the decoding paths run.
      const size_t right = format == TrackerFormat::kOpenTrack ? 48 : 64;
      std::vector<uint8_t> bytes(next() % 4 == 0 ? next() % 81 : right);
      for (uint8_t& b : bytes)
        b = static_cast<uint8_t>(next());
      // VRPN: a small sensor number and exponents in range half the time.
      if (format == TrackerFormat::kVrpn && bytes.size() == right && next() % 2 == 0)
        bytes[0] = bytes[1] = bytes[2] = 0;
      for (const InputEvent& e : parse(parser, RawEvent::report(i, bytes))) {
        if (!e.has_pose) continue;
        ++poses;
        EXPECT_TRUE(is_finite_unit_pose(e.pose, 1e-9)) << "report " << i;
      }
    }
    EXPECT_EQ(parser.counters().reports, 20000);
    EXPECT_GT(poses, 0) << "random bytes of the right length include valid poses";
  }
}

TEST(TrackerReportParser, MakeParserPicksItByBackendAndThePipelineKeepsThePose) {
  for (const char* backend : {"opentrack", "vrpn"}) {
    DeviceInfo info;
    info.backend = backend;
    info.path = "x";
    auto parser = make_parser(info);
    ASSERT_TRUE(parser.ok()) << backend << ": " << parser.error().message();
  }
  DeviceInfo info;
  info.backend = "opentrack";
  info.path = "127.0.0.1:4242";
  NormalizerConfig config;
  config.filter = true;  // axis filters and maps must leave a pose alone
  MotionPipeline pipeline(make_parser(info).value(), config);
  std::vector<InputEvent> out;
  pipeline.feed(RawEvent::report(100, encode_opentrack_datagram(5, 6, 7, 0, 0, 0)), 2, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].device_id, 2u);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[0], 50.0);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[1], 60.0);
  EXPECT_DOUBLE_EQ(out[0].pose.position_mm[2], 70.0);
}

}  // namespace
}  // namespace sculpt::hal
