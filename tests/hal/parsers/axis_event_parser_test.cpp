#include "sculpt/hal/parsers/axis_event_parser.h"

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

TEST(AxisEventParser, SpacenavdAxesCloseOnSyncInTheStationFrame) {
  AxisEventParser p;  // spacenavd: +Z away from the user
  std::vector<InputEvent> out;
  p.parse(RawEvent::axis(5, 0, 175), out);
  p.parse(RawEvent::axis(5, 2, 350), out);
  p.parse(RawEvent::axis(5, 5, -350), out);
  EXPECT_TRUE(out.empty()) << "nothing before the sync";
  p.parse(RawEvent::sync(5), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 0.5f);
  EXPECT_FLOAT_EQ(out[0].axes[kTz], -1.0f);
  EXPECT_FLOAT_EQ(out[0].axes[kRz], 1.0f);
  p.parse(RawEvent::sync(6), out);
  EXPECT_EQ(out.size(), 1u) << "a sync without new axes is not a new sample";
  p.parse(RawEvent::button(7, 1, true), out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].kind, InputKind::kButton);
  EXPECT_EQ(out[1].button, 1);
  p.parse(RawEvent::axis(8, 9, 1), out);
  EXPECT_EQ(p.counters().unknown_reports, 1);
}

}  // namespace
}  // namespace sculpt::hal
