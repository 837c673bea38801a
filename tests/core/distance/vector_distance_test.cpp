// The vector distance transforms of Jones & Satherley §3.6: exact from one
// and from two surface points, and Mullikin's EVDT on the distance shell
// within the error range of the paper's Table 1 on the analytic shapes.

#include "sculpt/core/distance/vector_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "sculpt/core/distance/distance_comparison.h"
#include "sculpt/core/grid/grid_index.h"

namespace sculpt::core {
namespace {

const char* scheme_name(VectorScheme s) {
  return s == VectorScheme::kEvdt ? "evdt" : "vcvdt";
}

// One surface point off the grid: every voxel gets its exact distance.
TEST(VectorDistance, OneSeedReachesEveryVoxelExactly) {
  const glm::ivec3 dims(23, 19, 21);
  const glm::ivec3 seed(11, 9, 10);
  const glm::vec3 point = glm::vec3(seed) + glm::vec3(0.3f, -0.2f, 0.4f);
  const std::vector<VectorSeed> seeds = {
      {int32_t(grid_index(seed, dims)), point - glm::vec3(seed)}};
  for (VectorScheme s : {VectorScheme::kEvdt, VectorScheme::kVcvdt}) {
    const DenseGrid<float> d = vector_distance(dims, seeds, s);
    float worst = 0.0f;
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x)
          worst =
              std::max(worst, std::abs(d.at(x, y, z) - glm::length(glm::vec3(x, y, z) - point)));
    EXPECT_LT(worst, 1e-4f) << scheme_name(s);
  }
}

// Two surface points: the Voronoi regions are half-spaces, which the grid
// does not cut apart, so a scheme passing vectors on in every direction
// fills them exactly (both schemes were, on 3000 random layouts). The EVDT that scanned each
// slice's rows in one y direction per z sweep left 6 of these 300 layouts wrong by up to 0.50 voxel
// (issue 23).
TEST(VectorDistance, TwoSeedsGiveEveryVoxelTheNearerExactly) {
  const glm::ivec3 dims(16);
  std::mt19937 rng(7);
  // One draw per statement, so the layouts do not depend on the order a
  // compiler evaluates arguments in.
  auto next = [&](int n) { return int(rng() % uint32_t(n)); };
  for (int layout = 0; layout < 300; ++layout) {
    std::vector<VectorSeed> seeds;
    std::vector<glm::vec3> points;
    for (int k = 0; k < 2; ++k) {
      glm::ivec3 v;
      glm::vec3 o;
      for (int a = 0; a < 3; ++a)
        v[a] = next(16);
      for (int a = 0; a < 3; ++a)
        o[a] = float(next(100)) / 100.0f - 0.5f;
      seeds.push_back({int32_t(grid_index(v, dims)), o});
      points.push_back(glm::vec3(v) + o);
    }
    for (VectorScheme s : {VectorScheme::kEvdt, VectorScheme::kVcvdt}) {
      const DenseGrid<float> d = vector_distance(dims, seeds, s);
      float worst = 0.0f;
      for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
          for (int x = 0; x < dims.x; ++x) {
            const glm::vec3 p(x, y, z);
            const float truth = std::min(glm::length(p - points[0]), glm::length(p - points[1]));
            worst = std::max(worst, std::abs(d.at(x, y, z) - truth));
          }
      ASSERT_LT(worst, 1e-4f) << scheme_name(s) << " layout " << layout;
    }
  }
}

// Table 1 of the paper (CThead): EVDT on the distance shell errs from
// -1.873284 to +1.392951 voxels. On the analytic sphere and torus at 128^3,
// against their true distance, ours must stay inside that range; it is in
// fact within the triangulated shell's own error (the exact hybrid's range,
// about +-0.10 voxel), so 0.15 is asserted too. The EVDT that scanned each
// slice's rows one way per z sweep gave -0.62 -> +1.66 on this sphere
// (+3.52 at 256^3).
TEST(VectorDistance, EvdtOnTheShellErrsWithinThePapersRange) {
  constexpr float kPaperMin = -1.873284f, kPaperMax = 1.392951f;
  for (ComparisonShape shape : {ComparisonShape::kSphere, ComparisonShape::kTorus}) {
    const ComparisonInput in = comparison_input(shape, 128);
    const auto rows =
        compare_distance_methods(in, {{DistanceMethod::kEvdt, DistanceInit::kShell}}, 2);
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_GE(rows[0].min_error, kPaperMin) << in.name;
    EXPECT_LE(rows[0].max_error, kPaperMax) << in.name;
    EXPECT_GE(rows[0].min_error, -0.15f) << in.name;
    EXPECT_LE(rows[0].max_error, 0.15f) << in.name;
    // Sub-voxel on average, as the paper's 0.0157.
    EXPECT_LT(rows[0].mean_error, 0.03) << in.name;
  }
}

}  // namespace
}  // namespace sculpt::core
