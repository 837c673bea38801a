#include "sculpt/hal/pose/deflection_integral.h"

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

InputEvent sample(float tx, int64_t t_ns, bool absolute = false) {
  InputEvent e;
  e.kind = InputKind::kMotion;
  e.axes[kTx] = tx;
  e.t_ns = t_ns;
  e.absolute = absolute;
  return e;
}

TEST(DeflectionIntegral, TrapezoidOverSampleTimes) {
  DeflectionIntegral d;
  InputEvent a = sample(0.0f, 0), b = sample(1.0f, 10'000'000), c = sample(1.0f, 20'000'000);
  d.accumulate(a);
  d.accumulate(b);
  d.accumulate(c);
  EXPECT_DOUBLE_EQ(a.integral[kTx], 0.0);
  EXPECT_NEAR(b.integral[kTx], 0.005, 1e-12);  // ramp 0 -> 1 over 10 ms
  EXPECT_NEAR(c.integral[kTx], 0.015, 1e-12);
}

TEST(DeflectionIntegral, SilenceHoldsTheLastDeflectionForTheCapOnly) {
  DeflectionIntegral d(50'000'000);
  InputEvent a = sample(0.0f, 0),
             b = sample(1.0f, 3'000'000'000);  // at rest, then pushed 3 s later
  d.accumulate(a);
  d.accumulate(b);
  EXPECT_DOUBLE_EQ(b.integral[kTx], 0.0) << "a device silent at rest did not move";
  InputEvent c = sample(1.0f, 6'000'000'000);  // pushed, then silent (unplugged?) for 3 s
  d.accumulate(c);
  EXPECT_NEAR(c.integral[kTx], 0.05, 1e-12);
}

TEST(DeflectionIntegral, OutOfOrderAndAbsoluteSamplesAddNothing) {
  DeflectionIntegral d;
  InputEvent a = sample(1.0f, 10'000'000), old = sample(1.0f, 5'000'000),
             pos = sample(0.5f, 20'000'000, true);
  d.accumulate(a);
  d.accumulate(old);
  d.accumulate(pos);
  EXPECT_DOUBLE_EQ(old.integral[kTx], 0.0);
  EXPECT_DOUBLE_EQ(pos.integral[kTx], 0.0);
}

}  // namespace
}  // namespace sculpt::hal
