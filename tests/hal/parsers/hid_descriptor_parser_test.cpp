#include "sculpt/hal/parsers/hid_descriptor_parser.h"

#include <gtest/gtest.h>

#include "multi_axis_descriptor.h"
#include "report_bytes.h"
#include "sculpt/hal/parsers/make_parser.h"

namespace sculpt::hal {
namespace {

DeviceInfo unknown_controller(bool relative) {
  DeviceInfo info;
  info.backend = "sim";
  info.path = "pad";
  info.vendor_id = 0x1234;
  info.product_id = 0x5678;
  info.report_descriptor = test::multi_axis_descriptor(relative);
  return info;
}

TEST(HidDescriptorParser, UnknownControllerWorksThroughItsDescriptor) {
  auto parser = make_parser(unknown_controller(true));
  ASSERT_TRUE(parser.ok()) << parser.error().message();
  std::vector<InputEvent> out;
  (*parser)->parse(test::report_at(7, test::axes_report(1, {250, 0, -500, 0, 0, 500})), out);
  (*parser)->parse(test::report_at(8, {3, 0x05}), out);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].kind, InputKind::kMotion);
  EXPECT_FALSE(out[0].absolute);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 0.5f);
  EXPECT_FLOAT_EQ(out[0].axes[kTy], 1.0f) << "HID -Z (lifted) is station +Y";
  EXPECT_FLOAT_EQ(out[0].axes[kRy], -1.0f);
  EXPECT_EQ(out[1].kind, InputKind::kButton);
  EXPECT_EQ(out[1].button, 0);
  EXPECT_EQ(out[2].button, 2);
}

TEST(HidDescriptorParser, AbsoluteAxesMapTheirRangeAndAreFlagged) {
  auto parser = make_parser(unknown_controller(false));
  ASSERT_TRUE(parser.ok());
  std::vector<InputEvent> out;
  (*parser)->parse(test::report_at(7, test::axes_report(1, {500, 0, 0, -500, 0, 0})), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].absolute);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 1.0f);
  EXPECT_FLOAT_EQ(out[0].axes[kRx], -1.0f);
}

TEST(HidDescriptorParser, ShortAndUnknownReportsAreCounted) {
  auto parser = make_parser(unknown_controller(true));
  ASSERT_TRUE(parser.ok());
  std::vector<InputEvent> out;
  (*parser)->parse(test::report_at(1, {9, 1, 2}), out);
  (*parser)->parse(test::report_at(2, {1, 1, 2, 3}), out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ((*parser)->counters().unknown_reports, 1);
  EXPECT_EQ((*parser)->counters().short_reports, 1);
}

TEST(HidDescriptorParser, NonControllerIsRefusedWithItsName) {
  DeviceInfo info = unknown_controller(true);
  info.report_descriptor = {0x05, 0x01, 0x09, 0x06, 0xA1, 0x01, 0xC0};  // a keyboard
  const auto parser = make_parser(info);
  ASSERT_FALSE(parser.ok());
  EXPECT_NE(parser.error().message().find("sim:pad (1234:5678)"), std::string::npos)
      << parser.error().message();
}

}  // namespace
}  // namespace sculpt::hal
