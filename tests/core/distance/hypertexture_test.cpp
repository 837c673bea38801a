#include "sculpt/core/distance/hypertexture.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

TEST(Hypertexture, GrowsANoisySkinOnlyInTheBoxAndSoftRegion) {
  DenseGrid<uint8_t> g = sphere_density(48, 0.25f);  // radius 12
  const DenseGrid<uint8_t> before = g;
  HypertextureOptions o;
  o.width_vox = 4.0f;
  const Box box{glm::ivec3(24, 0, 0), glm::ivec3(48)};
  const int64_t changed = bake_hypertexture(g, box, o);
  EXPECT_GT(changed, 500);
  int64_t counted = 0, grown_solid = 0;
  for (int z = 0; z < 48; ++z)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) {
        const uint8_t a = before.at(x, y, z), b = g.at(x, y, z);
        ASSERT_GE(b, a);  // never carves
        if (a == b) continue;
        ++counted;
        ASSERT_GE(x, 24);  // only inside the box
        const float r = glm::length(glm::vec3(x, y, z) - glm::vec3(23.5f));
        ASSERT_GT(r, 11.5f);                       // outside the surface
        ASSERT_LT(r, 12.0f + o.width_vox + 0.6f);  // within the soft region
        grown_solid += a <= 127 && b > 127;
      }
  EXPECT_EQ(counted, changed);
  // The iso-surface moved out somewhere, by a varying amount (noise).
  EXPECT_GT(grown_solid, 100);
}

TEST(Hypertexture, VolumeBrushMatchesTheDenseBake) {
  const DenseGrid<uint8_t> g = sphere_density(64, 0.25f);
  Volume volume = Volume::from_dense(g);
  DenseGrid<uint8_t> dense = g;
  const Box box{glm::ivec3(30, 20, 20), glm::ivec3(60, 44, 44)};
  const int64_t a = bake_hypertexture(volume, box);
  const int64_t b = bake_hypertexture(dense, box);
  EXPECT_GT(a, 0);
  const DenseGrid<uint8_t> out = volume.to_dense();
  int64_t off_by_more_than_two = 0;
  for (size_t i = 0; i < out.size(); ++i)
    off_by_more_than_two += std::abs(int(out[i]) - int(dense[i])) > 2;
  EXPECT_LE(off_by_more_than_two, b / 100);
}

}  // namespace
}  // namespace sculpt::core
