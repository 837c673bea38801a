#include "sculpt/core/sculpt/flatten_brush.h"

#include <gtest/gtest.h>

#include "brush_test_shapes.h"

namespace sculpt::core {
namespace {

using test::kSlabTop;

TEST(FlattenBrush, ABumpySurfaceFlattensAndUndoes) {
  Volume v = test::bumpy_slab(1.5f);
  const uint64_t before = v.content_hash();
  const double mass_before = test::mass(v);
  const test::HeightStats h0 = test::top_stats(v, 24, 41, 30, 35);
  Sculptor s(v);
  const auto path = test::line_path({20.0f, 32.0f, kSlabTop}, {44.0f, 32.0f, kSlabTop});
  EXPECT_GT(flatten_stroke(v, s, path, {}), 1000);
  const test::HeightStats h1 = test::top_stats(v, 24, 41, 30, 35);
  std::printf("flatten: variance %.4f -> %.4f, mean %.2f -> %.2f\n", h0.variance, h1.variance,
              h0.mean, h1.mean);
  EXPECT_GT(h0.variance, 0.3);
  EXPECT_LT(h1.variance, 0.2 * h0.variance);
  // The plane runs through the bumps' middle: it adds about what it takes.
  EXPECT_NEAR(h1.mean, kSlabTop, 0.3);
  EXPECT_NEAR(test::mass(v), mass_before, 0.01 * mass_before);
  const uint64_t after = v.content_hash();
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), before);
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(v.content_hash(), after);
}

TEST(FlattenBrush, HalfStrengthFlattensLess) {
  Volume full = test::bumpy_slab(1.5f), half = test::bumpy_slab(1.5f);
  Sculptor sf(full), sh(half);
  const auto path = test::line_path({20.0f, 32.0f, kSlabTop}, {44.0f, 32.0f, kSlabTop});
  FlattenBrushOptions o;
  (void)flatten_stroke(full, sf, path, o);
  o.strength = 0.5f;
  (void)flatten_stroke(half, sh, path, o);
  const double v0 = test::top_stats(test::bumpy_slab(1.5f), 24, 41, 30, 35).variance;
  const double vh = test::top_stats(half, 24, 41, 30, 35).variance;
  const double vf = test::top_stats(full, 24, 41, 30, 35).variance;
  EXPECT_LT(vf, vh);
  EXPECT_LT(vh, v0);
}

TEST(FlattenBrush, AbsurdOptionsAreRefusedByName) {
  FlattenBrushOptions o;
  EXPECT_TRUE(check_flatten_brush(o));
  o.hardness = -0.5f;
  ASSERT_FALSE(check_flatten_brush(o));
  EXPECT_NE(check_flatten_brush(o).error().message().find("'hardness'"), std::string::npos);
  o = {};
  o.radius_vox = 1e6f;
  EXPECT_FALSE(check_flatten_brush(o));
}

}  // namespace
}  // namespace sculpt::core
