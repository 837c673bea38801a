#include "sculpt/hal/parsers/hid_descriptor.h"

#include <gtest/gtest.h>

#include "multi_axis_descriptor.h"

namespace sculpt::hal {
namespace {

TEST(HidDescriptor, FindsSixRelativeAxesAndButtons) {
  const auto layout = parse_hid_descriptor(test::multi_axis_descriptor(/*relative=*/true));
  ASSERT_TRUE(layout.ok()) << layout.error().message();
  EXPECT_TRUE(layout->is_multi_axis_controller());
  EXPECT_TRUE(layout->numbered_reports);
  for (int a = 0; a < 6; ++a) {
    ASSERT_TRUE(layout->axes[a].has_value()) << "axis " << a;
    EXPECT_EQ(layout->axes[a]->bit_size, 16u);
    EXPECT_EQ(layout->axes[a]->logical_min, -500);
    EXPECT_EQ(layout->axes[a]->logical_max, 500);
    EXPECT_TRUE(layout->axes[a]->relative);
  }
  EXPECT_EQ(layout->axes[0]->report_id, 1);
  EXPECT_EQ(layout->axes[0]->bit_offset, 0u);
  EXPECT_EQ(layout->axes[5]->bit_offset, 80u);
  ASSERT_EQ(layout->buttons.size(), 4u);
  EXPECT_EQ(layout->buttons[3].report_id, 3);
  EXPECT_EQ(layout->buttons[3].bit_offset, 3u);
}

TEST(HidDescriptor, AbsoluteAxesAreFlagged) {
  const auto layout = parse_hid_descriptor(test::multi_axis_descriptor(/*relative=*/false));
  ASSERT_TRUE(layout.ok());
  EXPECT_FALSE(layout->axes[2]->relative);
}

TEST(HidDescriptor, MouseIsNotAMultiAxisController) {
  const std::vector<uint8_t> mouse = {0x05, 0x01, 0x09, 0x02, 0xA1, 0x01, 0x09,
                                      0x30, 0x09, 0x31, 0x15, 0x81, 0x25, 0x7F,
                                      0x75, 0x08, 0x95, 0x02, 0x81, 0x06, 0xC0};
  const auto layout = parse_hid_descriptor(mouse);
  ASSERT_TRUE(layout.ok());
  EXPECT_FALSE(layout->is_multi_axis_controller());
  EXPECT_EQ(layout->usage, 2);
}

TEST(HidDescriptor, MalformedDescriptorsNameTheByte) {
  // Logical Maximum announcing 2 data bytes, none present.
  const std::vector<uint8_t> cut = {0x05, 0x01, 0x09, 0x08, 0xA1, 0x01, 0x26};
  const auto a = parse_hid_descriptor(cut);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().message().find("runs past the end"), std::string::npos)
      << a.error().message();
  const std::vector<uint8_t> open = {0x05, 0x01, 0x09, 0x08, 0xA1, 0x01};
  const auto b = parse_hid_descriptor(open);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().message().find("not closed"), std::string::npos);
}

TEST(HidDescriptor, ExtractsSignedAndUnsignedBitFields) {
  HidField f;
  f.bit_offset = 4;
  f.bit_size = 8;
  f.logical_min = -128;
  f.logical_max = 127;
  const std::vector<uint8_t> data = {0xF0, 0x0F};  // bits 4..11 = 0xFF
  EXPECT_EQ(extract_hid_field(data, f), -1);
  f.logical_min = 0;
  f.logical_max = 255;
  EXPECT_EQ(extract_hid_field(data, f), 255);
  f.bit_offset = 9;
  EXPECT_FALSE(extract_hid_field(data, f).has_value()) << "past the end of the data";
}

}  // namespace
}  // namespace sculpt::hal

namespace sculpt::hal {
namespace {

TEST(HidDescriptor, HugeReportCountIsRefusedNotLoopedOver) {
  // Report Count 0xFFFFFFFF of 8-bit fields: billions of fields if believed.
  const std::vector<uint8_t> d = {0x05, 0x01, 0x09, 0x08, 0xA1, 0x01, 0x75, 0x08,
                                  0x97, 0xFF, 0xFF, 0xFF, 0xFF, 0x81, 0x02, 0xC0};
  const auto layout = parse_hid_descriptor(d);
  ASSERT_FALSE(layout.ok());
  EXPECT_NE(layout.error().message().find("bits, more than"), std::string::npos)
      << layout.error().message();
}

TEST(HidDescriptor, ButtonFieldsAreBoundedWhateverTheDescriptorDeclares) {
  // 255 reports of 4000 one-bit button fields each (usages 1..65535): the
  // parser keeps only the buttons a report can carry and it reports (usages
  // up to 128 within the first 64 bytes), so each report walks a bounded
  // list. One report of them is within the limits; all of them are refused.
  const auto descriptor = [](int reports) {
    std::vector<uint8_t> d = {0x05, 0x01, 0x09, 0x08, 0xA1, 0x01, 0x05,
                              0x09, 0x15, 0x00, 0x25, 0x01, 0x75, 0x01};
    for (int id = 1; id <= reports; ++id) {
      // Report ID, Usage Minimum 1, Usage Maximum 65535, Report Count 4000, Input.
      d.insert(d.end(),
               {0x85, uint8_t(id), 0x19, 0x01, 0x2A, 0xFF, 0xFF, 0x96, 0xA0, 0x0F, 0x81, 0x02});
    }
    d.push_back(0xC0);
    return d;
  };
  const auto one = parse_hid_descriptor(descriptor(1));
  ASSERT_TRUE(one.ok()) << one.error().message();
  EXPECT_EQ(one->buttons.size(), 128u);
  const auto many = parse_hid_descriptor(descriptor(255));
  ASSERT_FALSE(many.ok());
  EXPECT_NE(many.error().message().find("more than 1024 button fields"), std::string::npos)
      << many.error().message();
}

}  // namespace
}  // namespace sculpt::hal
