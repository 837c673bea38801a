#include "sculpt/hal/normalizer/normalizer.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

NormalizerConfig plain() {
  NormalizerConfig c;
  c.deadzone.fill(0.0f);
  c.curve = CurveKind::kLinear;
  c.filter = false;
  return c;
}

InputEvent motion(std::array<float, 6> axes, int64_t t_ns = 0) {
  InputEvent e;
  e.kind = InputKind::kMotion;
  e.axes = axes;
  e.t_ns = t_ns;
  return e;
}

TEST(Normalizer, DeadzoneSilencesRestAndRescalesBeyondIt) {
  NormalizerConfig c = plain();
  c.deadzone.fill(0.1f);
  Normalizer n(c);
  InputEvent e = motion({0.05f, -0.1f, 0.55f, 1.0f, -1.0f, 0.0f});
  n.apply(e);
  EXPECT_EQ(e.axes[0], 0.0f);
  EXPECT_EQ(e.axes[1], 0.0f);
  EXPECT_NEAR(e.axes[2], 0.5f, 1e-6);
  EXPECT_NEAR(e.axes[3], 1.0f, 1e-6) << "full deflection stays full";
  EXPECT_NEAR(e.axes[4], -1.0f, 1e-6);
}

TEST(Normalizer, MapInvertsAndSwaps) {
  NormalizerConfig c = plain();
  c.map_source = {0, 2, 1, 3, 4, 5};
  c.map_sign = {-1, 1, 1, 1, 1, 1};
  Normalizer n(c);
  InputEvent e = motion({0.5f, 0.2f, 0.7f, 0, 0, 0});
  n.apply(e);
  EXPECT_FLOAT_EQ(e.axes[kTx], -0.5f);
  EXPECT_FLOAT_EQ(e.axes[kTy], 0.7f);
  EXPECT_FLOAT_EQ(e.axes[kTz], 0.2f);
}

TEST(Normalizer, LocksAndDominantAxis) {
  NormalizerConfig c = plain();
  c.lock = AxisLock::kTranslation;
  Normalizer t(c);
  InputEvent e = motion({0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f});
  t.apply(e);
  EXPECT_EQ(e.axes[kRx], 0.0f);
  EXPECT_EQ(e.axes[kRz], 0.0f);
  EXPECT_FLOAT_EQ(e.axes[kTz], 0.3f);

  c.lock = AxisLock::kNone;
  c.dominant = true;
  Normalizer d(c);
  InputEvent f = motion({0.1f, -0.8f, 0.3f, 0.4f, 0.5f, 0.6f});
  d.apply(f);
  EXPECT_EQ(f.axes, (std::array<float, 6>{0, -0.8f, 0, 0, 0, 0}));
}

TEST(Normalizer, CubicCurveGivesFineControlNearRest) {
  NormalizerConfig c = plain();
  c.curve = CurveKind::kCubic;
  c.curve_param = 0.5f;
  Normalizer n(c);
  InputEvent e = motion({0.2f, 1.0f, -1.0f, 0, 0, 0});
  n.apply(e);
  EXPECT_NEAR(e.axes[0], 0.5f * 0.2f + 0.5f * 0.008f, 1e-6);
  EXPECT_LT(e.axes[0], 0.2f);
  EXPECT_FLOAT_EQ(e.axes[1], 1.0f);
  EXPECT_FLOAT_EQ(e.axes[2], -1.0f);
}

TEST(Normalizer, SensitivityScalesAndClamps) {
  NormalizerConfig c = plain();
  c.sensitivity.fill(2.0f);
  Normalizer n(c);
  InputEvent e = motion({0.25f, 0.75f, 0, 0, 0, 0});
  n.apply(e);
  EXPECT_FLOAT_EQ(e.axes[0], 0.5f);
  EXPECT_FLOAT_EQ(e.axes[1], 1.0f);
}

TEST(Normalizer, OneEuroFilterReducesJitterAtRestButFollowsAStep) {
  NormalizerConfig c = plain();
  c.filter = true;
  Normalizer n(c);
  double raw_var = 0, out_var = 0;
  uint32_t s = 7;
  for (int i = 0; i < 1000; ++i) {
    s = s * 1664525u + 1013904223u;
    const float noise = (static_cast<float>(s >> 8) / 16777216.0f - 0.5f) * 0.04f;
    InputEvent e = motion({0.3f + noise, 0, 0, 0, 0, 0}, int64_t{i} * 1'000'000);
    n.apply(e);
    if (i >= 200) {
      raw_var += double(noise) * noise;
      out_var += (e.axes[0] - 0.3) * (e.axes[0] - 0.3);
    }
  }
  EXPECT_LT(out_var, raw_var / 10) << "jitter at rest must be cut by 10x or more";
  // A full push then settles on the new value within 200 ms of 1 kHz samples.
  InputEvent e;
  for (int i = 1000; i < 1200; ++i) {
    e = motion({1.0f, 0, 0, 0, 0, 0}, int64_t{i} * 1'000'000);
    n.apply(e);
  }
  EXPECT_GT(e.axes[0], 0.95f);
}

TEST(Normalizer, AbsoluteSamplesKeepTheirPosition) {
  NormalizerConfig c = plain();
  c.deadzone.fill(0.2f);
  c.dominant = true;
  Normalizer n(c);
  InputEvent e = motion({0.1f, 0.5f, 0, 0, 0, 0});
  e.absolute = true;
  n.apply(e);
  EXPECT_FLOAT_EQ(e.axes[0], 0.1f);
  EXPECT_FLOAT_EQ(e.axes[1], 0.5f);
}

}  // namespace
}  // namespace sculpt::hal
