#include "sculpt/core/sculpt/clay_brush.h"

#include <gtest/gtest.h>

#include "brush_test_shapes.h"

namespace sculpt::core {
namespace {

using test::kSlabTop;

// The columns near the stroke's line, where the ball weighs fully.
test::HeightStats under_stroke(const Volume& v) {
  return test::top_stats(v, 24, 41, 30, 35);
}

TEST(ClayBrush, BuildsAFlatLayerOneLayerHighAndUndoes) {
  Volume v = test::bumpy_slab(1.5f);
  const uint64_t before = v.content_hash();
  const test::HeightStats h0 = under_stroke(v);
  Sculptor s(v);
  ClayBrushOptions o;  // radius 8, layer 0.25: 2 voxels above the surface
  const auto path = test::line_path({20.0f, 32.0f, kSlabTop}, {44.0f, 32.0f, kSlabTop});
  EXPECT_GT(clay_stroke(v, s, path, o), 1000);
  const test::HeightStats h1 = under_stroke(v);
  std::printf("clay: variance %.4f -> %.4f, mean %.2f -> %.2f\n", h0.variance, h1.variance, h0.mean,
              h1.mean);
  EXPECT_GT(h0.variance, 0.3);
  EXPECT_LT(h1.variance, 0.1 * h0.variance);
  // The top lies on the plane, a layer (0.25 x 8 voxels) above the surface.
  EXPECT_NEAR(h1.mean, kSlabTop + 2.0, 0.3);
  // A second stroke starting on the first layer (clear of its rounded end,
  // which would tilt the plane) builds the next layer.
  const auto path2 =
      test::line_path({26.0f, 32.0f, kSlabTop + 2.0f}, {44.0f, 32.0f, kSlabTop + 2.0f});
  EXPECT_GT(clay_stroke(v, s, path2, o), 1000);
  const test::HeightStats h2 = test::top_stats(v, 30, 41, 30, 35);
  std::printf("clay: second layer variance %.4f, mean %.2f\n", h2.variance, h2.mean);
  EXPECT_NEAR(h2.mean, kSlabTop + 4.0, 0.4);
  EXPECT_LT(h2.variance, 0.1 * h0.variance);
  // Each stroke one undo step, bit exact.
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), before);
  EXPECT_FALSE(s.undo());
}

TEST(ClayBrush, NothingUnderTheStartBuildsNothing) {
  Volume v = test::bumpy_slab(1.5f);
  const uint64_t before = v.content_hash();
  Sculptor s(v);
  const auto path = test::line_path({20.0f, 32.0f, 55.0f}, {44.0f, 32.0f, 55.0f});
  EXPECT_EQ(clay_stroke(v, s, path, {}), 0);
  EXPECT_EQ(v.content_hash(), before);
  EXPECT_FALSE(s.undo());
}

TEST(ClayBrush, AbsurdOptionsAreRefusedByName) {
  ClayBrushOptions o;
  EXPECT_TRUE(check_clay_brush(o));
  o.layer = 2.0f;
  ASSERT_FALSE(check_clay_brush(o));
  EXPECT_NE(check_clay_brush(o).error().message().find("'layer'"), std::string::npos);
  o = {};
  o.radius_vox = -1.0f;
  ASSERT_FALSE(check_clay_brush(o));
  EXPECT_NE(check_clay_brush(o).error().message().find("'radius'"), std::string::npos);
  o = {};
  o.strength = NAN;
  EXPECT_FALSE(check_clay_brush(o));
}

}  // namespace
}  // namespace sculpt::core
