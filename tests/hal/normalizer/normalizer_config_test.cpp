#include "sculpt/hal/normalizer/normalizer_config.h"

#include <gtest/gtest.h>

#include "sculpt/hal/types/input_event.h"

namespace sculpt::hal {
namespace {

TEST(NormalizerConfig, EmptyFileGivesDefaults) {
  const auto c = parse_normalizer_config("# nothing set\n\n", "input.conf");
  ASSERT_TRUE(c.ok());
  EXPECT_FLOAT_EQ(c->deadzone[0], NormalizerConfig{}.deadzone[0]);
  EXPECT_TRUE(c->filter);
}

TEST(NormalizerConfig, ReadsEveryKey) {
  const auto c = parse_normalizer_config(
      "deadzone = 0.1\ndeadzone.rz = 0.2   # twist is twitchy\nsensitivity.rotation = 0.5\n"
      "sensitivity.tx = 2\ncurve = power 2\nmap = tx -tz ty rx -rz ry\nlock = rotation\n"
      "dominant = on\nfilter = off\nfilter.beta = 0.3\nfilter.min_cutoff_hz = "
      "2\nfilter.d_cutoff_hz = 3",
      "input.conf");
  ASSERT_TRUE(c.ok()) << c.error().message();
  EXPECT_FLOAT_EQ(c->deadzone[kTx], 0.1f);
  EXPECT_FLOAT_EQ(c->deadzone[kRz], 0.2f);
  EXPECT_FLOAT_EQ(c->sensitivity[kRx], 0.5f);
  EXPECT_FLOAT_EQ(c->sensitivity[kTx], 2.0f);
  EXPECT_FLOAT_EQ(c->sensitivity[kTy], 1.0f);
  EXPECT_EQ(c->curve, CurveKind::kPower);
  EXPECT_FLOAT_EQ(c->curve_param, 2.0f);
  EXPECT_EQ(c->map_source[kTy], kTz);
  EXPECT_EQ(c->map_sign[kTy], -1);
  EXPECT_EQ(c->lock, AxisLock::kRotation);
  EXPECT_TRUE(c->dominant);
  EXPECT_FALSE(c->filter);
  EXPECT_FLOAT_EQ(c->filter_params.beta, 0.3f);
  EXPECT_FLOAT_EQ(c->filter_params.d_cutoff_hz, 3.0f);
}

TEST(NormalizerConfig, ErrorsNameFileLineAndKey) {
  const auto bad_key = parse_normalizer_config("deadzone = 0.1\nspeed = 3\n", "my.conf");
  ASSERT_FALSE(bad_key.ok());
  EXPECT_EQ(bad_key.error().message(), "my.conf:2: unknown key 'speed'");
  const auto range = parse_normalizer_config("deadzone = 2", "my.conf");
  ASSERT_FALSE(range.ok());
  EXPECT_NE(range.error().message().find("my.conf:1: deadzone: expected a number"),
            std::string::npos);
  EXPECT_FALSE(parse_normalizer_config("map = tx tx ty rx ry rz", "c").ok());
  EXPECT_FALSE(parse_normalizer_config("map = tx ty", "c").ok());
  EXPECT_FALSE(parse_normalizer_config("curve = quadratic", "c").ok());
  EXPECT_FALSE(parse_normalizer_config("lock", "c").ok());
  EXPECT_FALSE(parse_normalizer_config("sensitivity = 0", "c").ok());
}

TEST(NormalizerConfig, TextFormRoundTrips) {
  NormalizerConfig c;
  c.deadzone[kRy] = 0.123f;
  c.sensitivity[kTz] = 3.3f;
  c.curve = CurveKind::kLinear;
  c.map_source = {1, 0, 2, 3, 5, 4};
  c.map_sign = {1, -1, 1, 1, 1, -1};
  c.lock = AxisLock::kTranslation;
  const auto back = parse_normalizer_config(to_text(c), "text");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(back->deadzone, c.deadzone);
  EXPECT_EQ(back->sensitivity, c.sensitivity);
  EXPECT_EQ(back->curve, c.curve);
  EXPECT_EQ(back->map_source, c.map_source);
  EXPECT_EQ(back->map_sign, c.map_sign);
  EXPECT_EQ(back->lock, c.lock);
}

TEST(NormalizerConfig, MissingFileIsNamed) {
  const auto c = load_normalizer_config("/nonexistent/input.conf");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error().message(), "/nonexistent/input.conf: cannot open");
}

}  // namespace
}  // namespace sculpt::hal

namespace sculpt::hal {
namespace {

TEST(NormalizerConfig, ShippedExampleFileParsesToTheDefaults) {
  const auto c =
      load_normalizer_config(std::string(SCULPT_TEST_DATA_DIR) + "/../../hal/config/input.conf");
  ASSERT_TRUE(c.ok()) << c.error().message();
  const NormalizerConfig d;
  EXPECT_EQ(c->deadzone, d.deadzone);
  EXPECT_EQ(c->sensitivity, d.sensitivity);
  EXPECT_EQ(c->curve, d.curve);
  EXPECT_FLOAT_EQ(c->curve_param, d.curve_param);
  EXPECT_EQ(c->map_source, d.map_source);
  EXPECT_EQ(c->filter, d.filter);
  EXPECT_FLOAT_EQ(c->filter_params.beta, d.filter_params.beta);
}

TEST(NormalizerConfig, MissingUserFileMeansDefaults) {
  const auto c = load_normalizer_config_or_defaults("/nonexistent/sculpt/input.conf");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->deadzone, NormalizerConfig{}.deadzone);
}

}  // namespace
}  // namespace sculpt::hal
