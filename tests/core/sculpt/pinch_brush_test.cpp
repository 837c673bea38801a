#include "sculpt/core/sculpt/pinch_brush.h"

#include <gtest/gtest.h>

#include "brush_test_shapes.h"

namespace sculpt::core {
namespace {

using test::kSlabTop;

// The groove's floor depth below the top and its width at half that depth,
// across y at x = 32 (linear between voxels).
struct Groove {
  float depth = 0.0f, width = 0.0f;
};
Groove groove(const Volume& v) {
  const DenseGrid<uint8_t> g = v.to_dense();
  Groove r;
  r.depth = kSlabTop - test::top_height(g, 32, 32);
  const float z = kSlabTop - 0.5f * r.depth;
  const int z0 = static_cast<int>(std::floor(z));
  const float t = z - static_cast<float>(z0);
  auto density = [&](int y) { return (1.0f - t) * g.at(32, y, z0) + t * g.at(32, y, z0 + 1); };
  // From the groove's middle outward on each side to the wall's 127.5.
  auto wall = [&](int step) {
    for (int y = 32; y + step >= 0 && y + step < test::kSlabN; y += step) {
      const float a = density(y), b = density(y + step);
      if (a < 127.5f && b >= 127.5f)
        return static_cast<float>(y) + static_cast<float>(step) * (127.5f - a) / (b - a);
    }
    return 32.0f;
  };
  r.width = wall(1) - wall(-1);
  return r;
}

TEST(PinchBrush, AGrooveNarrowsAtHalfDepthAndUndoes) {
  Volume v = test::slab([](float, float) { return kSlabTop; });
  Sculptor s(v);
  s.set_tool(make_sphere_tool(5.0f));
  const auto path = test::line_path({8.0f, 32.0f, kSlabTop}, {56.0f, 32.0f, kSlabTop});
  (void)sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
  const Groove g0 = groove(v);
  const uint64_t before = v.content_hash();
  PinchBrushOptions o;
  o.radius_vox = 10.0f;
  EXPECT_GT(pinch_stroke(v, s, path, o), 1000);
  const Groove g1 = groove(v);
  std::printf("pinch: groove depth %.2f -> %.2f, width at half depth %.2f -> %.2f\n", g0.depth,
              g1.depth, g0.width, g1.width);
  EXPECT_GT(g0.width, 7.0f);
  EXPECT_LT(g1.width, 0.8f * g0.width);
  EXPECT_GT(g1.depth, 0.5f * g0.depth);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), before);
}

TEST(PinchBrush, AbsurdOptionsAreRefusedByName) {
  PinchBrushOptions o;
  EXPECT_TRUE(check_pinch_brush(o));
  o.strength = 3.0f;
  ASSERT_FALSE(check_pinch_brush(o));
  EXPECT_NE(check_pinch_brush(o).error().message().find("'strength'"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core
