// The ball brushes' path distances (brush_field.h) against their definition:
// every voxel of the box measured to every segment of the path, the nearest
// kept where it is within reach. PathDistance measures only the stretches of
// rows each segment's capsule reaches; a stretch that missed a voxel would
// leave it out of the brush (or give it a farther segment), so the
// comparison is exact, over paths in every direction, along the axes
// (where the capsule's quadratic is flat) and with repeated samples.

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/brush_field.h"

namespace sculpt::core {
namespace {

struct Nearest {
  float distance = std::numeric_limits<float>::infinity();
  size_t segment = 0;  // ending at that sample; 0: the first point
};

// The definition: the first point, then each segment a -> b, a voxel taking
// a segment only when strictly nearer, measured as |p - closest(p)|.
Nearest nearest_by_definition(glm::vec3 p, const std::vector<StrokeSample>& path, float reach) {
  Nearest best;
  for (size_t i = 0; i < path.size(); ++i) {
    const glm::vec3 a = path[i == 0 ? 0 : i - 1].position_vox, b = path[i].position_vox;
    const glm::vec3 ab = b - a;
    const float ab2 = glm::dot(ab, ab);
    const float t = ab2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
    const float d = glm::length(p - (a + t * ab));
    if (d < reach && d < best.distance) best = {d, i};
  }
  return best;
}

// Returns the voxels within reach.
int64_t expect_definition(const std::vector<StrokeSample>& path, const Box& box, float reach) {
  const brush::PathDistance distance(path, box, reach, /*nearest_points=*/true);
  // The brushes that never ask for the nearest point get the same distances.
  const brush::PathDistance distance_only(path, box, reach);
  int64_t within = 0, wrong = 0;
  std::string first_wrong;
  auto check = [&](bool right, glm::ivec3 v) {
    if (right) return;
    if (wrong++ == 0)
      first_wrong = std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z);
  };
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x) {
        const glm::ivec3 v(x, y, z);
        const Nearest expected = nearest_by_definition(glm::vec3(v), path, reach);
        const float got = distance.at(v);
        check(std::bit_cast<uint32_t>(distance_only.at(v)) == std::bit_cast<uint32_t>(got), v);
        if (std::isinf(expected.distance)) {
          check(std::isinf(got), v);
          continue;
        }
        ++within;
        check(got == expected.distance, v);
        const size_t i = expected.segment;
        const glm::vec3 a = path[i == 0 ? 0 : i - 1].position_vox, b = path[i].position_vox;
        const glm::vec3 ab = b - a;
        const float ab2 = glm::dot(ab, ab);
        const glm::vec3 p(v);
        const float t = ab2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
        check(distance.closest(v) == a + t * ab, v);
      }
  EXPECT_EQ(wrong, 0) << "of " << within << " voxels within reach; the first: " << first_wrong;
  return within;
}

TEST(BrushPathDistance, IsItsDefinitionBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(4.0f, 44.0f);
  std::uniform_real_distribution<float> step(-12.0f, 12.0f);
  std::uniform_real_distribution<float> radius(0.5f, 14.0f);
  for (int trial = 0; trial < 24; ++trial) {
    std::vector<StrokeSample> path;
    glm::vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
    const int samples = 1 + trial % 6;
    for (int k = 0; k < samples; ++k) {
      path.push_back({p, glm::quat(1.0f, 0.0f, 0.0f, 0.0f)});
      p += glm::vec3(step(rng), step(rng), step(rng));
    }
    const float reach = radius(rng);
    // A box holding all of the path's reach, and one cutting through it.
    EXPECT_GT(expect_definition(path, brush::path_box(path, reach), reach), 0);
    expect_definition(path, Box{glm::ivec3(10, 6, 12), glm::ivec3(40, 38, 34)}, reach);
  }
}

TEST(BrushPathDistance, SegmentsAlongTheAxesAndRepeatedSamplesToo) {
  const glm::quat still(1.0f, 0.0f, 0.0f, 0.0f);
  const glm::vec3 o(20.3f, 21.6f, 19.2f);
  for (const glm::vec3 along :
       {glm::vec3(9.0f, 0.0f, 0.0f), glm::vec3(0.0f, 9.0f, 0.0f), glm::vec3(0.0f, 0.0f, 9.0f),
        glm::vec3(9.0f, 1e-4f, 0.0f), glm::vec3(0.0f)}) {
    const std::vector<StrokeSample> path = {{o, still}, {o + along, still}, {o + along, still}};
    for (const float reach : {1.0f, 6.5f, 9.0f})
      EXPECT_GT(expect_definition(path, brush::path_box(path, reach), reach), 0);
  }
}

}  // namespace
}  // namespace sculpt::core
