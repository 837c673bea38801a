#include "sculpt/core/shapes/analytic_shapes.h"

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(AnalyticShapes, DensityRampCrossesTheIsoLevelAtTheSurface) {
  EXPECT_EQ(density_from_distance(-5.0f), 255);
  EXPECT_EQ(density_from_distance(5.0f), 0);
  EXPECT_EQ(density_from_distance(0.0f), 127);  // 127.5 truncated, as numpy's astype
  EXPECT_GT(density_from_distance(-0.01f), 127);
  EXPECT_LT(density_from_distance(0.01f), 128);
}

TEST(AnalyticShapes, SphereMatchesPeersDefinitionAndItsBrickedForm) {
  const DenseGrid<uint8_t> s = sphere_density(64);
  // Centre (n-1)/2 = 31.5, radius 0.35 * 64 = 22.4.
  EXPECT_EQ(s.at(31, 31, 31), 255);
  EXPECT_EQ(s.at(0, 0, 0), 0);
  EXPECT_EQ(s.at(31, 31, 31 + 23),
            density_from_distance(std::sqrt(0.25f + 0.25f + 22.5f * 22.5f) - 22.4f));
  EXPECT_EQ(sphere_volume(64).to_dense(), s);
}

}  // namespace
}  // namespace sculpt::core
