// The 2D signed distance of a slice's polygons: exact near the contour,
// within sqrt(2) pixels (never below the truth) farther out, the even-odd
// sign everywhere, at a cost linear in the pixels and the contour's length.

#include "sculpt/core/distance/polygon_distance.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

float brute_distance(glm::vec2 p, const std::vector<std::vector<glm::vec2>>& polygons,
                     bool& inside) {
  float best = std::numeric_limits<float>::infinity();
  inside = false;
  for (const auto& v : polygons) {
    for (size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
      const glm::vec2 a = v[j], b = v[i], ab = b - a;
      const float len2 = glm::dot(ab, ab);
      const float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
      const glm::vec2 d = p - (a + t * ab);
      best = std::min(best, glm::dot(d, d));
      if ((v[i].y > p.y) != (v[j].y > p.y) &&
          p.x < (v[j].x - v[i].x) * (p.y - v[i].y) / (v[j].y - v[i].y) + v[i].x)
        inside = !inside;
    }
  }
  return std::sqrt(best);
}

TEST(PolygonDistance, ExactNearTheContourBoundedFartherAndSignedByEvenOdd) {
  std::mt19937 rng(7);
  const glm::ivec2 dims(53, 41);
  std::uniform_real_distribution<float> x(0.0f, 52.0f), y(0.0f, 40.0f);
  for (int trial = 0; trial < 20; ++trial) {
    // A star-ish polygon and a random (self-crossing) one: holes and overlaps.
    std::vector<std::vector<glm::vec2>> polygons(2);
    for (int k = 0; k < 9; ++k) {
      const float a = 6.2831853f * static_cast<float>(k) / 9.0f;
      const float r = (k % 2 ? 6.0f : 14.0f) + static_cast<float>(trial % 3);
      polygons[0].emplace_back(26.0f + r * std::cos(a), 20.0f + r * std::sin(a));
    }
    for (int k = 0; k < 5 + trial; ++k)
      polygons[1].emplace_back(x(rng), y(rng));
    std::vector<const std::vector<glm::vec2>*> refs = {&polygons[0], &polygons[1]};
    const std::vector<float> field = polygon_signed_distance(dims, refs);
    for (int py = 0; py < dims.y; ++py)
      for (int px = 0; px < dims.x; ++px) {
        bool inside = false;
        const float truth = brute_distance(glm::vec2(px, py), polygons, inside);
        const float got = field[size_t(py) * size_t(dims.x) + size_t(px)];
        ASSERT_EQ(got < 0.0f, inside && truth > 0.0f) << px << " " << py;
        if (truth <= kExactBand) {
          ASSERT_EQ(std::fabs(got), truth) << px << " " << py;
        } else {
          ASSERT_GE(std::fabs(got), truth - 1e-4f) << px << " " << py;
          ASSERT_LE(std::fabs(got), truth + 1.4143f) << px << " " << py;
        }
      }
  }
}

// Reproducer from the hardening review: a contour file whose cost grew far
// faster than its size (every pixel against every edge). Here the work is
// bounded by the pixels and the contour's length, whatever its point count.
TEST(PolygonDistance, CostIsLinearInPixelsAndContourLength) {
  const glm::ivec2 dims(512, 512);
  for (int points : {1000, 20000}) {
    // A circle of radius 200 drawn with more and more points: the same length.
    std::vector<glm::vec2> circle;
    for (int k = 0; k < points; ++k) {
      const float a = 6.2831853f * static_cast<float>(k) / static_cast<float>(points);
      circle.emplace_back(255.5f + 200.0f * std::cos(a), 255.5f + 200.0f * std::sin(a));
    }
    PolygonDistanceCost cost;
    (void)polygon_signed_distance(dims, {&circle}, &cost);
    const double length = 2.0 * 3.14159265 * 200.0;
    // Per edge: its samples (two per pixel of length, plus at most three) over a 7x7
    // patch; then one evaluation per pixel outside the band.
    const double bound = 49.0 * (2.0 * length + 3.0 * points) + double(dims.x) * dims.y;
    EXPECT_LE(double(cost.edge_distances), bound) << points;
    EXPECT_LE(cost.crossings, int64_t{2} * dims.y) << points;
  }
}

}  // namespace
}  // namespace sculpt::core
