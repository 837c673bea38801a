// The narrow band of the exact distance (what a .vdb level set holds) is the
// exact distance to the triangulated surface where it is nearer than the
// half width, and only there.
#include "sculpt/core/distance/surface_band.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/core/distance/distance_comparison.h"
#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/signed_distance.h"

namespace sculpt::core {
namespace {

void expect_band_of(const DenseGrid<float>& phi, float half_width, const char* what) {
  // Brute force over every triangle of the same triangulation (shell init).
  const DenseGrid<float> brute =
      signed_distance(phi, DistanceMethod::kBrute, DistanceInit::kShell, 2);
  const DenseGrid<float> band = surface_band_distance(phi, half_width, 2);
  ASSERT_EQ(band.dims(), phi.dims());
  int64_t in_band = 0;
  for (size_t i = 0; i < phi.size(); ++i) {
    ASSERT_EQ(std::signbit(band[i]), phi[i] < 0.0f) << what << " voxel " << i;
    const float exact = std::abs(brute[i]);
    if (std::abs(exact - half_width) < 1e-4f) continue;  // on the band's edge: either
    if (exact < half_width) {
      ++in_band;
      ASSERT_NEAR(band[i], brute[i], 1e-5f) << what << " voxel " << i;
    } else {
      ASSERT_TRUE(std::isinf(band[i])) << what << " voxel " << i << " at " << brute[i];
    }
  }
  EXPECT_GT(in_band, 1000) << what;
  // The same band whatever the thread count.
  const DenseGrid<float> one_thread = surface_band_distance(phi, half_width, 1);
  for (size_t i = 0; i < phi.size(); ++i)
    ASSERT_EQ(std::memcmp(&one_thread[i], &band[i], sizeof(float)), 0) << what << " voxel " << i;
}

TEST(SurfaceBand, IsTheExactDistanceWithinTheBandAndInfiniteBeyond) {
  for (ComparisonShape shape : {ComparisonShape::kSphere, ComparisonShape::kTorus}) {
    const ComparisonInput in = comparison_input(shape, 32);
    expect_band_of(level_function(in.density), 3.0f, in.name.c_str());
  }
}

TEST(SurfaceBand, AWiderBandReachesFurther) {
  const ComparisonInput in = comparison_input(ComparisonShape::kSphere, 32);
  expect_band_of(level_function(in.density), 5.5f, "sphere, half width 5.5");
}

TEST(SurfaceBand, NoSurfaceIsNoBand) {
  const DenseGrid<float> empty = surface_band_distance(DenseGrid<float>(glm::ivec3(8), 1.0f), 3.0f);
  for (float v : empty.values())
    EXPECT_EQ(v, INFINITY);
  const DenseGrid<float> full = surface_band_distance(DenseGrid<float>(glm::ivec3(8), -1.0f), 3.0f);
  for (float v : full.values())
    EXPECT_EQ(v, -INFINITY);
}

}  // namespace
}  // namespace sculpt::core
