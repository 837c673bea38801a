#include "sculpt/core/distance/distance_normals.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

TEST(DistanceNormals, PointOutwardAlongTheRadiusOfASphere) {
  const DenseGrid<float> d = surface_distance(level_function(sphere_density(48, 0.3f)), 2);
  const glm::vec3 c(23.5f);
  float worst = 0.0f;
  for (int k = 0; k < 200; ++k) {
    // Points on the sphere at off-grid positions.
    const float th = 0.1f + 2.9f * float(k) / 200.0f, ph = 0.37f * float(k);
    const glm::vec3 dir(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    const glm::vec3 n = distance_normal(d, c + 14.4f * dir);
    worst = std::max(worst, glm::length(n - dir));
  }
  // Smooth normals: a few degrees at most, not the 26 directions of a
  // binary field.
  EXPECT_LT(worst, 0.05f);
  Mesh m;
  m.positions = {c + glm::vec3(14.4f, 0, 0), c - glm::vec3(0, 14.4f, 0)};
  set_normals_from_distance(d, m);
  ASSERT_EQ(m.normals.size(), 2u);
  EXPECT_GT(m.normals[0].x, 0.99f);
  EXPECT_LT(m.normals[1].y, -0.99f);
}

}  // namespace
}  // namespace sculpt::core
