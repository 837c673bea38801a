// The evdev records and layout a session holds, decoded into motion and
// buttons: frames, absolute and relative axes, the HID-to-station axis
// mapping, SYN_DROPPED, and bad bytes counted and dropped.

#include "sculpt/hal/parsers/evdev_event_parser.h"

#include <linux/input.h>

#include <gtest/gtest.h>

#include "sculpt/hal/parsers/make_parser.h"

namespace sculpt::hal {
namespace {

EvdevLayout absolute_layout() {
  EvdevLayout l;
  for (EvdevAxisRange& a : l.axes)
    a = {EvdevAxisKind::kAbsolute, -350, 350};
  l.button_codes = {BTN_0, BTN_1};
  return l;
}

EvdevLayout relative_layout() {
  EvdevLayout l;
  for (EvdevAxisRange& a : l.axes)
    a = {EvdevAxisKind::kRelative, 0, 350};
  l.button_codes = {BTN_0};
  return l;
}

RawEvent report(std::initializer_list<EvdevRecord> records, int64_t t_ns = 7) {
  std::vector<uint8_t> bytes(records.size() * kEvdevRecordBytes);
  size_t i = 0;
  for (const EvdevRecord& r : records)
    encode_evdev_record(r, bytes.data() + kEvdevRecordBytes * i++);
  return RawEvent::report(t_ns, bytes);
}

constexpr EvdevRecord kSyn{EV_SYN, SYN_REPORT, 0};

std::vector<InputEvent> parse_all(ReportParser& p, std::initializer_list<RawEvent> events) {
  std::vector<InputEvent> out;
  for (const RawEvent& e : events)
    p.parse(e, out);
  return out;
}

TEST(EvdevLayoutBytes, RoundTripAndBadLayoutsRefused) {
  EvdevLayout l = absolute_layout();
  l.axes[3] = {EvdevAxisKind::kRelative, 0, 500};
  const std::vector<uint8_t> bytes = encode_evdev_layout(l);
  EvdevLayout back;
  ASSERT_EQ(decode_evdev_layout(bytes, back), EvdevLayoutError::kNone);
  EXPECT_EQ(back.button_codes, l.button_codes);
  EXPECT_EQ(back.axes[3].kind, EvdevAxisKind::kRelative);
  EXPECT_EQ(back.axes[3].maximum, 500);
  EXPECT_EQ(back.axes[0].minimum, -350);

  std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 1);
  EXPECT_EQ(decode_evdev_layout(cut, back), EvdevLayoutError::kShort);
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_EQ(decode_evdev_layout(longer, back), EvdevLayoutError::kLong);
  std::vector<uint8_t> magic = bytes;
  magic[0] = 'X';
  EXPECT_EQ(decode_evdev_layout(magic, back), EvdevLayoutError::kBadMagic);
  EvdevLayout empty_range = absolute_layout();
  empty_range.axes[2] = {EvdevAxisKind::kAbsolute, 5, 5};
  EXPECT_EQ(decode_evdev_layout(encode_evdev_layout(empty_range), back),
            EvdevLayoutError::kBadAxis);
  std::vector<uint8_t> kind = bytes;
  kind[4] = 9;  // the first axis's kind
  EXPECT_EQ(decode_evdev_layout(kind, back), EvdevLayoutError::kBadAxis);
  EXPECT_FALSE(describe(EvdevLayoutError::kBadAxis).empty());
}

TEST(EvdevEventParser, AFrameOfAbsoluteAxesIsOneMotionInTheStationFrame) {
  EvdevEventParser p(absolute_layout());
  // HID frame: +X right, +Y toward the user, +Z down; full push right,
  // half toward the user, a quarter down, and a twist about Z (down).
  const auto out = parse_all(p, {report({{EV_ABS, ABS_X, 350},
                                         {EV_ABS, ABS_Y, 175},
                                         {EV_ABS, ABS_Z, 87},
                                         {EV_ABS, ABS_RZ, -350}}),
                                 report({kSyn}, 9)});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, InputKind::kMotion);
  EXPECT_EQ(out[0].t_ns, 9);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 1.0f);
  EXPECT_NEAR(out[0].axes[kTy], -87.0f / 350, 1e-6);  // station +Y is up: HID -Z
  EXPECT_FLOAT_EQ(out[0].axes[kTz], 0.5f);            // station +Z toward the user: HID +Y
  EXPECT_FLOAT_EQ(out[0].axes[kRy], 1.0f);            // station rotation about up: -HID RZ
  EXPECT_FLOAT_EQ(out[0].axes[kRx], 0.0f);
  EXPECT_FALSE(out[0].absolute) << "a 3D mouse's axes are deflections";
}

TEST(EvdevEventParser, AbsoluteRangesNormaliseAroundTheirMiddleAndClamp) {
  EvdevLayout l = absolute_layout();
  l.axes[0] = {EvdevAxisKind::kAbsolute, 0, 1000};
  EvdevEventParser p(l);
  const auto out =
      parse_all(p, {report({{EV_ABS, ABS_X, 750}, kSyn}), report({{EV_ABS, ABS_X, 5000}, kSyn})});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 0.5f);
  EXPECT_FLOAT_EQ(out[1].axes[kTx], 1.0f);
}

TEST(EvdevEventParser, NothingMovesBeforeTheFrameEnds) {
  EvdevEventParser p(absolute_layout());
  const auto out = parse_all(p, {report({{EV_ABS, ABS_X, 100}, {EV_KEY, BTN_0, 1}})});
  EXPECT_TRUE(out.empty());
}

TEST(EvdevEventParser, ButtonsFollowTheFramesMotionAndOnlyChangesCount) {
  EvdevEventParser p(absolute_layout());
  const auto out = parse_all(p, {report({{EV_ABS, ABS_X, 10}, {EV_KEY, BTN_1, 1}, kSyn}),
                                 report({{EV_KEY, BTN_1, 2}, kSyn}),  // autorepeat: still held
                                 report({{EV_KEY, BTN_1, 0}, {EV_KEY, BTN_5, 1}, kSyn})});
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].kind, InputKind::kMotion);
  EXPECT_EQ(out[1].kind, InputKind::kButton);
  EXPECT_EQ(out[1].button, 1);
  EXPECT_TRUE(out[1].pressed);
  EXPECT_EQ(out[2].kind, InputKind::kButton);
  EXPECT_FALSE(out[2].pressed) << "BTN_5 is not one of the layout's buttons";
}

TEST(EvdevEventParser, RelativeAxesAreZeroWhenAFrameLeavesThemOut) {
  EvdevEventParser p(relative_layout());
  const auto out =
      parse_all(p, {report({{EV_REL, REL_X, 175}, {EV_REL, REL_RY, -350}, kSyn}),
                    report({{EV_REL, REL_X, 175}, kSyn}), report({kSyn}), report({kSyn})});
  ASSERT_EQ(out.size(), 3u) << "the last empty frame changes nothing";
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 0.5f);
  EXPECT_FLOAT_EQ(out[0].axes[kRz], -1.0f);  // HID RY is the station's RZ
  EXPECT_FLOAT_EQ(out[0].axes[kTz], 0.0f);
  EXPECT_FLOAT_EQ(out[1].axes[kTx], 0.5f);
  for (float a : out[2].axes)
    EXPECT_EQ(a, 0.0f);
}

TEST(EvdevEventParser, SynDroppedDiscardsTheCutFrameAndTheResyncFrameApplies) {
  EvdevEventParser p(absolute_layout());
  const auto out = parse_all(p, {report({{EV_ABS, ABS_X, 100}, kSyn}),
                                 report({{EV_ABS, ABS_X, 300},
                                         {EV_SYN, SYN_DROPPED, 0},
                                         {EV_ABS, ABS_Y, 300},
                                         {EV_KEY, BTN_0, 1},
                                         kSyn}),
                                 report({{EV_ABS, ABS_X, -350}, {EV_KEY, BTN_0, 0}, kSyn})});
  EXPECT_EQ(p.overruns(), 1);
  ASSERT_EQ(out.size(), 2u) << "no motion and no button from the cut frame";
  EXPECT_NEAR(out[0].axes[kTx], 100.0f / 350, 1e-6);
  EXPECT_FLOAT_EQ(out[1].axes[kTx], -1.0f);
  EXPECT_FLOAT_EQ(out[1].axes[kTz], 0.0f) << "ABS_Y 300 was in the dropped frame";
}

TEST(EvdevEventParser, BadReportsAreCountedAndDropped) {
  EvdevEventParser p(absolute_layout());
  std::vector<InputEvent> out;
  p.parse(RawEvent::report(1, std::vector<uint8_t>(12, 0)), out);  // not whole records
  p.parse(RawEvent::report(1, std::vector<uint8_t>(3, 0)), out);   // not one record
  p.parse(RawEvent::report(1, {}), out);
  std::vector<uint8_t> huge(80, 0);
  p.parse(RawEvent::report(1, huge), out);  // truncated at 64
  p.parse(report({{EV_REL, REL_X, 5}, {EV_ABS, 40, 9}, {EV_MSC, MSC_SCAN, 3}, kSyn}), out);
  EXPECT_TRUE(out.empty()) << "a relative event on an absolute axis moves nothing";
  EXPECT_EQ(p.counters().invalid_reports, 2);
  EXPECT_EQ(p.counters().short_reports, 2);
  EXPECT_EQ(p.counters().unknown_reports, 1);
}

TEST(EvdevEventParser, MakeParserReadsTheLayoutFromTheDescriptor) {
  DeviceInfo info;
  info.backend = "evdev";
  info.path = "/dev/input/event4";
  info.vendor_id = 0x256f;
  info.product_id = 0xc635;
  info.report_descriptor = encode_evdev_layout(relative_layout());
  auto parser = make_parser(info);
  ASSERT_TRUE(parser.ok()) << parser.error().message();
  std::vector<InputEvent> out;
  (*parser)->parse(report({{EV_REL, REL_Y, 350}, kSyn}), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FLOAT_EQ(out[0].axes[kTz], 1.0f);

  info.report_descriptor.pop_back();
  auto bad = make_parser(info);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message().find("evdev:/dev/input/event4"), std::string::npos)
      << bad.error().message();
  EXPECT_NE(bad.error().message().find("cut short"), std::string::npos) << bad.error().message();
}

}  // namespace
}  // namespace sculpt::hal
