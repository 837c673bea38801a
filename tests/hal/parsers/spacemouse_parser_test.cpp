#include "sculpt/hal/parsers/spacemouse_parser.h"

#include <gtest/gtest.h>

#include "report_bytes.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

using test::axes_report;
using test::report_at;

const DeviceQuirks& navigator() {
  return *find_quirks(0x046d, 0xc626);
}
const DeviceQuirks& compact() {
  return *find_quirks(0x256f, 0xc635);
}

std::vector<InputEvent> feed(ReportParser& p, const std::vector<RawEvent>& events) {
  std::vector<InputEvent> out;
  for (const RawEvent& e : events)
    p.parse(e, out);
  return out;
}

TEST(SpaceMouseParser, SplitLayoutEmitsOneSampleWhenBothHalvesArrive) {
  SpaceMouseParser p(navigator());
  std::vector<InputEvent> out;
  p.parse(report_at(1000, axes_report(1, {350, 0, 0})), out);
  EXPECT_TRUE(out.empty()) << "translation alone is half a sample";
  p.parse(report_at(2000, axes_report(2, {0, 0, 175})), out);
  ASSERT_EQ(out.size(), 1u);
  const InputEvent& m = out[0];
  EXPECT_EQ(m.kind, InputKind::kMotion);
  EXPECT_EQ(m.t_ns, 2000);
  EXPECT_FALSE(m.translation_stale);
  EXPECT_FALSE(m.rotation_stale);
  EXPECT_FLOAT_EQ(m.axes[kTx], 1.0f);
  // HID rz (twist about the down axis) becomes -ry in the station frame (+Y up).
  EXPECT_FLOAT_EQ(m.axes[kRy], -0.5f);
  EXPECT_FLOAT_EQ(m.axes[kRz], 0.0f);
}

TEST(SpaceMouseParser, HidFrameBecomesStationFrame) {
  SpaceMouseParser p(navigator());
  // Pulling the cap toward the user is HID +Y; pushing it down is HID +Z.
  const auto out = feed(
      p, {report_at(1, axes_report(1, {0, 350, 350})), report_at(2, axes_report(2, {0, 0, 0}))});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FLOAT_EQ(out[0].axes[kTz], 1.0f) << "toward the user is +Z";
  EXPECT_FLOAT_EQ(out[0].axes[kTy], -1.0f) << "pushing down is -Y";
}

TEST(SpaceMouseParser, RepeatedHalfFlagsTheOtherAsStale) {
  SpaceMouseParser p(navigator());
  const auto out = feed(
      p, {report_at(10, axes_report(1, {100, 0, 0})), report_at(20, axes_report(1, {200, 0, 0})),
          report_at(30, axes_report(2, {0, 0, 0}))});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].t_ns, 10);
  EXPECT_TRUE(out[0].rotation_stale);
  EXPECT_FALSE(out[0].translation_stale);
  EXPECT_NEAR(out[0].axes[kTx], 100.0f / 350.0f, 1e-6);
  EXPECT_EQ(out[1].t_ns, 30);
  EXPECT_FALSE(out[1].rotation_stale);
  EXPECT_NEAR(out[1].axes[kTx], 200.0f / 350.0f, 1e-6);
}

TEST(SpaceMouseParser, CombinedLayoutIsOneSamplePerReport) {
  SpaceMouseParser p(compact());
  const auto out = feed(p, {report_at(5, axes_report(1, {-350, 0, 0, 350, 0, 0})),
                            report_at(6, axes_report(1, {0, 0, 0, 0, 0, 0}))});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], -1.0f);
  EXPECT_FLOAT_EQ(out[0].axes[kRx], 1.0f);
  EXPECT_FLOAT_EQ(out[1].axes[kTx], 0.0f);
  EXPECT_EQ(p.counters().overlong_reports, 0);
}

TEST(SpaceMouseParser, CombinedReportOnSplitDeviceIsReadByLength) {
  SpaceMouseParser p(navigator());
  const auto out = feed(p, {report_at(5, axes_report(1, {0, 0, 0, 0, 0, 70}))});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].axes[kRy], -0.2f, 1e-6);
}

TEST(SpaceMouseParser, BitmaskButtonsGivePressAndRelease) {
  SpaceMouseParser p(navigator());
  const auto out = feed(p, {report_at(1, {3, 0x01, 0x00}), report_at(2, {3, 0x03, 0x00}),
                            report_at(3, {3, 0x00, 0x00})});
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].button, 0);
  EXPECT_TRUE(out[0].pressed);
  EXPECT_EQ(out[1].button, 1);
  EXPECT_TRUE(out[1].pressed);
  EXPECT_FALSE(out[2].pressed);
  EXPECT_FALSE(out[3].pressed);
  EXPECT_EQ(out[2].button + out[3].button, 1);
}

TEST(SpaceMouseParser, ProButtonMapCompactsSparseBits) {
  SpaceMouseParser p(*find_quirks(0x046d, 0xc62b));
  // Bit 12 is the Pro's seventh key (logical 5); bit 2 is not a key.
  const auto out = feed(p, {report_at(1, {3, 0x04, 0x10, 0x00, 0x00})});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].button, 5);
  EXPECT_TRUE(out[0].pressed);
}

TEST(SpaceMouseParser, NumberedButtonsReportHeldButtons) {
  SpaceMouseParser p(*find_quirks(0x256f, 0xc633));
  const auto out = feed(p, {report_at(1, {0x1c, 3, 0, 0, 0}), report_at(2, {0x1c, 3, 12, 0, 0}),
                            report_at(3, {0x1c, 0, 0, 0, 0})});
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].button, 2);
  EXPECT_TRUE(out[0].pressed);
  EXPECT_EQ(out[1].button, 11);
  EXPECT_TRUE(out[1].pressed);
  EXPECT_FALSE(out[2].pressed);
  EXPECT_FALSE(out[3].pressed);
}

TEST(SpaceMouseParser, BatteryReport) {
  SpaceMouseParser p(*find_quirks(0x256f, 0xc62f));
  const auto out = feed(p, {report_at(9, {0x17, 87, 1})});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, InputKind::kBattery);
  EXPECT_EQ(out[0].battery_percent, 87);
  EXPECT_TRUE(out[0].charging);
}

TEST(SpaceMouseParser, UnknownShortAndOverlongReportsAreCountedNotFatal) {
  SpaceMouseParser p(navigator());
  std::vector<uint8_t> overlong = axes_report(2, {0, 0, 0});
  overlong.push_back(0xAA);
  std::vector<uint8_t> huge(100, 0);
  huge[0] = 1;
  const auto out = feed(p, {report_at(1, {4, 1}),           // LED echo: unknown id
                            report_at(2, {1, 0x10, 0x00}),  // short translation
                            report_at(3, {}),               // empty
                            report_at(4, axes_report(1, {35, 0, 0})),
                            report_at(5, overlong),  // rotation with a trailing byte
                            report_at(6, huge)});    // cut to 64 bytes, read as combined
  EXPECT_EQ(p.counters().unknown_reports, 1);
  EXPECT_EQ(p.counters().short_reports, 2);
  EXPECT_EQ(p.counters().overlong_reports,
            3);  // the trailing byte; the cut report (truncated + > 13)
  ASSERT_EQ(out.size(), 2u) << "the short report must not have produced motion";
  EXPECT_NEAR(out[0].axes[kTx], 0.1f, 1e-6);
  EXPECT_FLOAT_EQ(out[1].axes[kTx], 0.0f);
}

}  // namespace
}  // namespace sculpt::hal
