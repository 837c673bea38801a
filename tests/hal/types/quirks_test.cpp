#include "sculpt/hal/types/quirks.h"

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

TEST(Quirks, KnownDevicesAndTheirLayouts) {
  const DeviceQuirks* nav = find_quirks(0x046d, 0xc626);
  ASSERT_NE(nav, nullptr);
  EXPECT_EQ(nav->name, "SpaceNavigator");
  EXPECT_EQ(nav->layout, MotionLayout::kSplit);
  const DeviceQuirks* ent = find_quirks(0x256f, 0xc633);
  ASSERT_NE(ent, nullptr);
  EXPECT_EQ(ent->layout, MotionLayout::kCombined);
  EXPECT_EQ(ent->buttons, ButtonForm::kNumbered);
  for (int pid : {0xc627, 0xc628, 0xc625, 0xc629, 0xc62b})
    EXPECT_NE(find_quirks(0x046d, static_cast<uint16_t>(pid)), nullptr) << pid;
  for (int pid : {0xc62e, 0xc62f, 0xc631, 0xc632, 0xc635, 0xc652})
    EXPECT_NE(find_quirks(0x256f, static_cast<uint16_t>(pid)), nullptr) << pid;
  EXPECT_EQ(find_quirks(0x1234, 0x5678), nullptr);
}

TEST(Quirks, IgnoreListAndReceiverInterfaces) {
  EXPECT_TRUE(is_ignored(0x256f, 0xc650, 0, 0));  // CadMouse
  EXPECT_TRUE(is_ignored(0x256f, 0xc664, 0, 0));  // keyboard
  EXPECT_FALSE(is_ignored(0x046d, 0xc626, 1, 8));
  // Universal Receiver: the mouse interface is ignored, the 6-DOF one is not,
  // and an interface of unknown usage is tried.
  EXPECT_TRUE(is_ignored(0x256f, 0xc652, 1, 2));
  EXPECT_FALSE(is_ignored(0x256f, 0xc652, 1, 8));
  EXPECT_FALSE(is_ignored(0x256f, 0xc652, 0, 0));
  EXPECT_FALSE(is_ignored(0x1234, 0x5678, 1, 2)) << "unknown devices are not in the table";
}

TEST(Quirks, EveryAxisMapIsAPermutation) {
  for (const DeviceQuirks& q : all_quirks()) {
    std::array<bool, 6> seen{};
    for (uint8_t s : q.axis_source) {
      ASSERT_LT(s, 6);
      seen[s] = true;
    }
    for (bool b : seen)
      EXPECT_TRUE(b) << q.name;
  }
}

}  // namespace
}  // namespace sculpt::hal
