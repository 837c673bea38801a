// Exactness of the linear-time EDT and the octree against the naive §3.1
// reference on random volumes.

#include "sculpt/core/distance/exact_edt.h"

#include <gtest/gtest.h>

#include <random>

#include "sculpt/core/distance/brute_distance.h"
#include "sculpt/core/distance/octree_distance.h"

namespace sculpt::core {
namespace {

DenseGrid<uint8_t> random_mask(glm::ivec3 dims, double p, uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution on(p);
  DenseGrid<uint8_t> m(dims);
  for (size_t i = 0; i < m.size(); ++i)
    m[i] = on(rng);
  return m;
}

TEST(ExactEdt, EqualsBruteOnRandomVolumes) {
  for (uint32_t seed = 1; seed <= 6; ++seed) {
    const glm::ivec3 dims(9 + seed, 13 - seed, 7 + 2 * seed);
    const DenseGrid<uint8_t> m = random_mask(dims, 0.02 * seed, seed);
    const DenseGrid<float> ref = brute_distance_to_points(dims, voxel_positions(m, 1));
    for (int threads : {1, 3}) {
      const DenseGrid<float> edt = exact_edt(m, 1, threads);
      for (size_t i = 0; i < m.size(); ++i)
        ASSERT_FLOAT_EQ(edt[i], ref[i]) << "seed " << seed << " voxel " << i;
    }
  }
}

TEST(ExactEdt, FeatureIsANearestSeed) {
  const glm::ivec3 dims(17, 11, 13);
  const DenseGrid<uint8_t> m = random_mask(dims, 0.03, 42);
  const FeatureTransform ft = feature_transform(m, 1, 2);
  const DenseGrid<float> sq = squared_edt(m, 1, 1);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const size_t i = m.index(x, y, z);
        ASSERT_EQ(ft.distance_squared[i], sq[i]);
        const int32_t s = ft.nearest[i];
        ASSERT_GE(s, 0);
        ASSERT_EQ(m[size_t(s)], 1);
        const int sx = s % dims.x, sy = (s / dims.x) % dims.y, sz = s / (dims.x * dims.y);
        const float d2 = float((x - sx) * (x - sx) + (y - sy) * (y - sy) + (z - sz) * (z - sz));
        ASSERT_EQ(d2, sq[i]);
      }
}

TEST(ExactEdt, NoSeedIsInfinityAndScipyConvention) {
  const DenseGrid<uint8_t> ones(glm::ivec3(4, 5, 6), 1);
  const DenseGrid<float> none = exact_edt(ones, 0);
  EXPECT_TRUE(std::isinf(none[0]));
  // scipy.ndimage.distance_transform_edt: distance to the nearest zero.
  DenseGrid<uint8_t> m(glm::ivec3(5, 1, 1), 1);
  m[0] = 0;
  const DenseGrid<float> d = exact_edt(m, 0);
  for (int x = 0; x < 5; ++x)
    EXPECT_FLOAT_EQ(d[size_t(x)], float(x));
}

TEST(OctreeDistance, EqualsBruteForPointsAndTriangles) {
  const glm::ivec3 dims(14, 12, 10);
  const DenseGrid<uint8_t> m = random_mask(dims, 0.01, 7);
  const auto pts = voxel_positions(m, 1);
  const DenseGrid<float> a = brute_distance_to_points(dims, pts);
  const DenseGrid<float> b = octree_distance_to_points(dims, pts, 2);
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(a[i], b[i]);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-2.0f, 15.0f);
  std::vector<Triangle3> tris;
  for (int k = 0; k < 60; ++k)
    tris.push_back({{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}});
  const DenseGrid<float> c = brute_distance_to_triangles(dims, tris);
  const DenseGrid<float> e = octree_distance_to_triangles(dims, tris, 2);
  for (size_t i = 0; i < c.size(); ++i)
    ASSERT_EQ(c[i], e[i]);
}

}  // namespace
}  // namespace sculpt::core
