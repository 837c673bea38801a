#include "sculpt/core/sculpt/grab_brush.h"

#include <gtest/gtest.h>

#include "brush_test_shapes.h"

namespace sculpt::core {
namespace {

constexpr float kTop = 24.0f;
constexpr float kBumpRadius = 3.0f;

// A flat slab with a ball of kBumpRadius sitting on it at (24, 32).
Volume slab_with_bump(DenseGrid<uint8_t>& slab_only) {
  const Volume slab = test::slab([](float, float) { return kTop; });
  slab_only = slab.to_dense();
  DenseGrid<uint8_t> g = slab_only;
  const glm::vec3 c(24.0f, 32.0f, kTop + 1.0f);
  for (int z = 0; z < test::kSlabN; ++z)
    for (int y = 0; y < test::kSlabN; ++y)
      for (int x = 0; x < test::kSlabN; ++x) {
        const float d = glm::length(glm::vec3(x, y, z) - c) - kBumpRadius;
        g.at(x, y, z) = std::max(g.at(x, y, z), density_from_distance(d));
      }
  return Volume::from_dense(g);
}

// The bump's material (the volume less the slab) and its centroid.
struct Bump {
  double mass = 0.0;
  glm::dvec3 centroid{0.0};
};
Bump bump(const Volume& v, const DenseGrid<uint8_t>& slab_only) {
  const DenseGrid<uint8_t> g = v.to_dense();
  Bump b;
  for (int z = 0; z < test::kSlabN; ++z)
    for (int y = 0; y < test::kSlabN; ++y)
      for (int x = 0; x < test::kSlabN; ++x) {
        const double m = double(g.at(x, y, z)) - double(slab_only.at(x, y, z));
        b.mass += m;
        b.centroid += m * glm::dvec3(x, y, z);
      }
  b.centroid /= b.mass;
  b.mass /= 255.0;
  return b;
}

TEST(GrabBrush, TheBumpMovesByTheDisplacementKeepingItsVolume) {
  DenseGrid<uint8_t> slab_only;
  Volume v = slab_with_bump(slab_only);
  const Bump b0 = bump(v, slab_only);
  const double total0 = test::mass(v);
  const uint64_t before = v.content_hash();
  Sculptor s(v);
  GrabBrushOptions o;
  o.radius_vox = 16.0f;
  // Off the grid: 7.5 along x, 2.5 along y.
  const auto path = test::line_path({24.0f, 32.0f, kTop + 1.0f}, {31.5f, 34.5f, kTop + 1.0f});
  EXPECT_GT(grab_stroke(v, s, path, o), 100);
  const Bump b1 = bump(v, slab_only);
  const glm::dvec3 moved = b1.centroid - b0.centroid;
  std::printf(
      "grab: centroid moved (%.3f, %.3f, %.3f), bump volume %.2f -> %.2f, total %.1f -> %.1f\n",
      moved.x, moved.y, moved.z, b0.mass, b1.mass, total0, test::mass(v));
  EXPECT_NEAR(moved.x, 7.5, 0.2);
  EXPECT_NEAR(moved.y, 2.5, 0.2);
  EXPECT_NEAR(moved.z, 0.0, 0.1);
  EXPECT_NEAR(b1.mass, b0.mass, 0.02 * b0.mass);
  EXPECT_NEAR(test::mass(v), total0, 0.02 * b0.mass);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), before);
}

// A hard ball (its falloff drops over 2 voxels) dragged 14 voxels: 21 steps,
// and the bump under its core arrives whole.
TEST(GrabBrush, ALongDragWithAHardBallKeepsTheBump) {
  DenseGrid<uint8_t> slab_only;
  Volume v = slab_with_bump(slab_only);
  const Bump b0 = bump(v, slab_only);
  Sculptor s(v);
  GrabBrushOptions o;
  o.radius_vox = 16.0f;
  o.hardness = 1.0f;
  const auto path = test::line_path({24.0f, 32.0f, kTop + 1.0f}, {38.0f, 32.0f, kTop + 1.0f});
  EXPECT_GT(grab_stroke(v, s, path, o), 100);
  const Bump b1 = bump(v, slab_only);
  std::printf("grab, hard: centroid moved %.3f, bump volume %.2f -> %.2f\n",
              b1.centroid.x - b0.centroid.x, b0.mass, b1.mass);
  EXPECT_NEAR(b1.centroid.x - b0.centroid.x, 14.0, 0.2);
  EXPECT_NEAR(b1.mass, b0.mass, 0.02 * b0.mass);
}

TEST(GrabBrush, AStillPathChangesNothing) {
  DenseGrid<uint8_t> slab_only;
  Volume v = slab_with_bump(slab_only);
  Sculptor s(v);
  const StrokeSample at{{24.0f, 32.0f, kTop + 1.0f}, {}};
  EXPECT_EQ(grab_stroke(v, s, std::span(&at, 1), {}), 0);
  EXPECT_FALSE(s.undo());
}

TEST(GrabBrush, AbsurdOptionsAreRefusedByName) {
  GrabBrushOptions o;
  EXPECT_TRUE(check_grab_brush(o));
  o.radius_vox = 0.0f;
  ASSERT_FALSE(check_grab_brush(o));
  EXPECT_NE(check_grab_brush(o).error().message().find("'radius'"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::core
