// The exact point-to-triangle distance against an independent double-precision
// reference, on ordinary triangles, slivers and degenerate ones.

#include "sculpt/core/mesh/point_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "reference_distance.h"

namespace sculpt::core {
namespace {

struct Triangle {
  glm::vec3 a, b, c;
};

// Points on a grid around the triangle, as the distance transforms visit them.
template <class Check>
void for_grid_points_near(const Triangle& t, Check check) {
  const glm::vec3 lo = glm::floor(glm::min(glm::min(t.a, t.b), t.c)) - 3.0f;
  const glm::vec3 hi = glm::ceil(glm::max(glm::max(t.a, t.b), t.c)) + 3.0f;
  for (float z = lo.z; z <= hi.z; z += 1.0f)
    for (float y = lo.y; y <= hi.y; y += 1.0f)
      for (float x = lo.x; x <= hi.x; x += 1.0f)
        check(glm::vec3(x, y, z));
}

void expect_exact(const Triangle& t, const char* what) {
  for_grid_points_near(t, [&](glm::vec3 p) {
    const double ref = test::distance_in_double(p, t.a, t.b, t.c);
    const ClosestPoint cp = closest_point_on_triangle(p, t.a, t.b, t.c);
    ASSERT_NEAR(std::sqrt(cp.distance_squared), ref, 1e-4)
        << what << " at " << p.x << "," << p.y << "," << p.z;
    // The closest point is that far away, and lies on the triangle.
    ASSERT_NEAR(glm::length(p - cp.point), ref, 1e-4) << what;
    ASSERT_NEAR(test::distance_in_double(cp.point, t.a, t.b, t.c), 0.0, 1e-4) << what;
    const float d2 = triangle_distance2(p, t.a, t.b - t.a, t.c - t.a);
    ASSERT_NEAR(std::sqrt(d2), ref, 1e-4) << what << " (triangle_distance2)";
  });
}

TEST(PointTriangle, RandomTrianglesMatchTheDoubleReference) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  for (int i = 0; i < 200; ++i) {
    const Triangle t{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    expect_exact(t, "random");
  }
}

// A marching-cubes mesh is full of needle triangles; in float the region
// tests' differences of products lose most of their bits on them.
TEST(PointTriangle, SliversMatchTheDoubleReference) {
  const glm::vec3 a(2.3f, 2.1f, 2.7f), b = a + glm::vec3(9.1f, 0.3f, 1.7f);
  for (float thin : {1e-6f, 3e-4f, 4e-3f, 2e-2f, 0.1f}) {
    for (float along : {0.02f, 0.5f, 0.97f}) {
      const Triangle t{a, b, a + along * (b - a) + glm::vec3(0.0f, thin, -thin * 0.4f)};
      expect_exact(t, "sliver");
    }
  }
  // A needle: one very short edge.
  expect_exact({a, b, a + glm::vec3(1e-3f, 2e-3f, 0.0f)}, "needle");
}

TEST(PointTriangle, DegenerateTrianglesMeasureTheirEdges) {
  const glm::vec3 a(3.2f, 4.1f, 5.3f), b(9.7f, 6.2f, 4.4f);
  expect_exact({a, b, 0.5f * (a + b)}, "collinear");
  expect_exact({a, a, b}, "repeated corner");
  expect_exact({a, a, a}, "a point");
}

TEST(PointTriangle, SliverTestIsAboutTheAngle) {
  EXPECT_FALSE(is_sliver({1, 0, 0}, {0, 1, 0}));
  EXPECT_FALSE(is_sliver({1, 0, 0}, {1, 0.2f, 0}));  // about 11 degrees
  EXPECT_TRUE(is_sliver({1, 0, 0}, {1, 0.05f, 0}));  // about 3 degrees
  EXPECT_FALSE(is_sliver({0, 0, 0}, {1, 0, 0}));     // no area at all: the edge path
}

}  // namespace
}  // namespace sculpt::core
