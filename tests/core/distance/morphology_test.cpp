// True 3D closing (§4.2) against binary morphological closing with a
// Euclidean ball, and offsets.

#include "sculpt/core/distance/morphology.h"

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "sculpt/core/distance/exact_edt.h"
#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

// Two balls of radius 7 whose surfaces are 2 voxels apart along x.
DenseGrid<uint8_t> two_balls() {
  DenseGrid<uint8_t> g(glm::ivec3(44, 40, 40));
  for (int z = 0; z < 40; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 44; ++x) {
        const glm::vec3 p(x, y, z);
        const float d = std::min(glm::length(p - glm::vec3(13.1f, 19.6f, 20.2f)),
                                 glm::length(p - glm::vec3(29.1f, 19.6f, 20.2f))) -
                        7.0f;
        g.at(x, y, z) = density_from_distance(d);
      }
  return g;
}

TEST(Morphology, ClosingAgreesWithBinaryClosingByABall) {
  const DenseGrid<uint8_t> g = two_balls();
  const DenseGrid<float> phi = level_function(g);
  const float radius = 3.0f;
  const DenseGrid<float> closed = close_distance(phi, radius, 2);
  // Binary: dilate by the ball (distance to the object <= R), then erode
  // (distance to the outside of the dilation > R).
  const DenseGrid<uint8_t> mask = inside_mask(phi);
  const DenseGrid<float> to_object = exact_edt(mask, 1);
  DenseGrid<uint8_t> dilated(mask.dims());
  for (size_t i = 0; i < mask.size(); ++i)
    dilated[i] = to_object[i] <= radius;
  const DenseGrid<float> to_outside = exact_edt(dilated, 0);
  int64_t both = 0, differ = 0, union_count = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    const bool binary = to_outside[i] > radius;
    const bool ours = closed[i] < 0.0f;
    both += binary && ours;
    differ += binary != ours;
    union_count += binary || ours;
  }
  // The two differ only by the binary result's voxel staircase.
  EXPECT_GT(both, 2000);
  EXPECT_LT(double(differ) / double(union_count), 0.05) << differ << " of " << union_count;
  // The 2-voxel gap is bridged; it was open before.
  EXPECT_GT(phi.at(21, 20, 20), 0.0f);
  EXPECT_LT(closed.at(21, 20, 20), 0.0f);
  EXPECT_TRUE(to_outside.at(21, 20, 20) > radius);
  // Closing is extensive: nothing clearly inside is lost, and far away
  // nothing is added.
  for (size_t i = 0; i < mask.size(); ++i) {
    if (phi[i] < -127.0f) {
      ASSERT_LT(closed[i], 0.0f);
    }
  }
  EXPECT_GT(closed.at(2, 2, 2), 5.0f);
}

TEST(Morphology, OffsetMovesTheSurfaceByD) {
  const DenseGrid<uint8_t> g = sphere_density(40, 0.25f);  // radius 10, centre 19.5
  const DenseGrid<float> d = surface_distance(level_function(g), 2);
  const DenseGrid<float> grown = offset_distance(d, 2.5f);
  // Along +x from the centre the surface moves from 29.5 to 32.
  EXPECT_LT(grown.at(31, 19, 19), 0.0f);
  EXPECT_GT(grown.at(33, 19, 19), 0.0f);
  EXPECT_NEAR(grown.at(32, 20, 20), glm::length(glm::vec3(32, 20, 20) - glm::vec3(19.5f)) - 12.5f,
              0.15f);
  const DenseGrid<float> shrunk = offset_distance(d, -2.5f);
  EXPECT_LT(shrunk.at(26, 19, 19), 0.0f);
  EXPECT_GT(shrunk.at(28, 19, 19), 0.0f);
}

}  // namespace
}  // namespace sculpt::core
