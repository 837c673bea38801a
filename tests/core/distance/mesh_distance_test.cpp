#include "sculpt/core/distance/mesh_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <tuple>

#include <glm/geometric.hpp>

#include "reference_distance.h"
#include "sculpt/core/distance/narrow_band.h"
#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// A closed octahedron-subdivided sphere: every feature kind occurs.
Mesh icosphere_like(float radius, glm::vec3 centre, int subdiv) {
  Mesh m;
  m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int s = 0; s < subdiv; ++s) {
    std::vector<glm::uvec3> next;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto k = std::minmax(a, b);
      auto it = mid.find(k);
      if (it != mid.end()) return it->second;
      m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      return mid[k] = uint32_t(m.positions.size() - 1);
    };
    for (auto t : m.triangles) {
      const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
      next.insert(next.end(), {{t.x, ab, ca}, {ab, t.y, bc}, {ca, bc, t.z}, {ab, bc, ca}});
    }
    m.triangles = next;
  }
  for (auto& p : m.positions)
    p = centre + radius * glm::normalize(p);
  return m;
}

TEST(PointTriangle, MatchesDenseSamplingOfTheTriangle) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int k = 0; k < 300; ++k) {
    const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const float d = std::sqrt(point_triangle_distance_squared(p, a, b, c));
    float best = 1e9f;
    for (int i = 0; i <= 60; ++i)
      for (int j = 0; i + j <= 60; ++j) {
        const float s = float(i) / 60.0f, t = float(j) / 60.0f;
        best = std::min(best, glm::length(p - (a + s * (b - a) + t * (c - a))));
      }
    ASSERT_LE(d, best + 1e-4f);
    ASSERT_GE(d, best - 0.15f);
  }
  // Degenerate triangle: a segment.
  EXPECT_NEAR(
      std::sqrt(point_triangle_distance_squared({0, 1, 0}, {-1, 0, 0}, {1, 0, 0}, {0, 0, 0})), 1.0f,
      1e-6f);
  // Two corners in one place: the segment from them to the third, whichever
  // two coincide.
  const glm::vec3 p(1.0f, 1.0f, 0.0f), q(0.0f, 0.0f, 0.0f), r(2.0f, 0.0f, 0.0f);
  for (const auto& [a, b, c] : {std::tuple{q, q, r}, std::tuple{q, r, r}, std::tuple{r, q, r}}) {
    EXPECT_NEAR(std::sqrt(point_triangle_distance_squared(p, a, b, c)), 1.0f, 1e-6f);
    EXPECT_NEAR(std::sqrt(triangle_distance2(p, a, b - a, c - a)), 1.0f, 1e-6f);
  }
}

TEST(MeshDistance, NarrowBandEqualsBruteAndSignIsRight) {
  const Mesh m = icosphere_like(8.3f, glm::vec3(12.2f, 11.7f, 12.4f), 3);
  const MeshDistance md(m);
  const glm::ivec3 dims(25);
  for (int threads : {1, 2}) {
    const NarrowBand nb = mesh_narrow_band(md, dims, NarrowBandOptions{3.0f, threads});
    int in_band = 0;
    for (int z = 0; z < 25; ++z)
      for (int y = 0; y < 25; ++y)
        for (int x = 0; x < 25; ++x) {
          const glm::vec3 p(x, y, z);
          const float ref = md.signed_distance_brute(p);
          const float d = nb.distance_at(x, y, z);
          if (std::abs(ref) < 2.999f) {
            ASSERT_NEAR(d, ref, 1e-4f) << x << " " << y << " " << z;
            ++in_band;
          } else if (std::abs(ref) > 3.001f) {
            ASSERT_TRUE(std::isinf(d));
          }
          // The pseudonormal sign agrees with the (almost) sphere.
          const float sphere = glm::length(p - glm::vec3(12.2f, 11.7f, 12.4f)) - 8.3f;
          if (std::abs(sphere) > 0.5f) {
            ASSERT_EQ(ref < 0, sphere < 0);
          }
        }
    EXPECT_GT(in_band, 1000);
  }
}

// A sphere cut by the grid's faces, in a box whose sides are no multiple of
// the brick size and differ per axis: bricks at the grid's end and triangles
// whose band leaves the grid.
TEST(MeshDistance, NarrowBandClippedByTheGridEqualsBrute) {
  const glm::vec3 centre(3.4f, 15.6f, 9.1f);
  const Mesh m = icosphere_like(7.7f, centre, 3);
  const MeshDistance md(m);
  const glm::ivec3 dims(13, 19, 22);
  const NarrowBand nb = mesh_narrow_band(md, dims, NarrowBandOptions{2.5f, 2});
  EXPECT_EQ(nb.bricks, glm::ivec3(2, 3, 3));
  int in_band = 0;
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const float ref = md.signed_distance_brute(glm::vec3(x, y, z));
        const float d = nb.distance_at(x, y, z);
        if (std::abs(ref) < 2.499f) {
          ASSERT_NEAR(d, ref, 1e-4f) << x << " " << y << " " << z;
          ASSERT_GE(nb.triangle_at(x, y, z), 0);
          ++in_band;
        } else if (std::abs(ref) > 2.501f) {
          ASSERT_TRUE(std::isinf(d)) << x << " " << y << " " << z;
          ASSERT_EQ(nb.triangle_at(x, y, z), -1);
        }
      }
  EXPECT_GT(in_band, 300);
  // Voxels past the grid's end in edge bricks stay outside the band.
  for (size_t s = 0; s < nb.slot_brick.size(); ++s)
    for (int k = 0; k < NarrowBand::kBrickVoxels; ++k) {
      const glm::ivec3 v = nb.voxel(int32_t(s), k);
      if (v.x >= dims.x || v.y >= dims.y || v.z >= dims.z) {
        ASSERT_EQ(nb.triangle[s * NarrowBand::kBrickVoxels + size_t(k)], -1);
      }
    }
}

TEST(MeshDistance, NarrowBandDoesNotDependOnThreadCount) {
  const Mesh m = icosphere_like(9.1f, glm::vec3(15.3f, 14.8f, 16.2f), 4);
  const MeshDistance md(m);
  const NarrowBand one = mesh_narrow_band(md, glm::ivec3(32), NarrowBandOptions{3.0f, 1});
  for (int threads : {2, 3, 7}) {
    const NarrowBand many = mesh_narrow_band(md, glm::ivec3(32), NarrowBandOptions{3.0f, threads});
    EXPECT_EQ(many.slot, one.slot) << threads;
    EXPECT_EQ(many.triangle, one.triangle) << threads;
    // Bitwise: the same triangles tried in the same order.
    ASSERT_EQ(many.distance.size(), one.distance.size());
    EXPECT_EQ(0, std::memcmp(many.distance.data(), one.distance.data(),
                             one.distance.size() * sizeof(float)))
        << threads;
  }
}

// The AVX2 kernel (8 voxels at once) and the baseline one (4) do the same
// arithmetic per voxel: the same band, bit for bit.
TEST(MeshDistance, NarrowBandKernelsAgree) {
  const Mesh m = icosphere_like(10.3f, glm::vec3(16.6f, 15.2f, 16.9f), 4);
  const MeshDistance md(m);
  const NarrowBand wide = mesh_narrow_band(md, glm::ivec3(35, 33, 34), NarrowBandOptions{3.0f, 2});
  const bool was = use_avx2_band_kernel(false);
  const NarrowBand narrow =
      mesh_narrow_band(md, glm::ivec3(35, 33, 34), NarrowBandOptions{3.0f, 2});
  use_avx2_band_kernel(was);
  EXPECT_EQ(wide.slot, narrow.slot);
  EXPECT_EQ(wide.triangle, narrow.triangle);
  ASSERT_EQ(wide.distance.size(), narrow.distance.size());
  EXPECT_EQ(0, std::memcmp(wide.distance.data(), narrow.distance.data(),
                           wide.distance.size() * sizeof(float)));
}

TEST(MeshDistance, NarrowBandDenseGridsMatchTheBricks) {
  const Mesh m = icosphere_like(6.2f, glm::vec3(9.5f, 10.1f, 8.7f), 2);
  const MeshDistance md(m);
  const glm::ivec3 dims(20, 17, 19);
  const NarrowBand nb = mesh_narrow_band(md, dims, NarrowBandOptions{3.0f, 2});
  const DenseGrid<float> d = nb.dense_distance(2);
  const DenseGrid<int32_t> t = nb.dense_triangle(2);
  ASSERT_EQ(d.dims(), dims);
  int in_band = 0;
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        ASSERT_EQ(d.at(x, y, z), nb.distance_at(x, y, z));
        ASSERT_EQ(t.at(x, y, z), nb.triangle_at(x, y, z));
        in_band += t.at(x, y, z) >= 0;
      }
  EXPECT_GT(in_band, 500);
}

using test::distance_in_double;

// Checks every voxel of `dims` against the double-precision reference: within
// 1e-4 voxel inside the band, infinite beyond it (ties at the band's edge
// are not checked). Returns how many voxels lie in the band.
int expect_band_matches_reference(const Mesh& m, const NarrowBand& nb, glm::ivec3 dims,
                                  float band) {
  int in_band = 0;
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        double ref = 1e9;
        for (const glm::uvec3 t : m.triangles)
          ref = std::min(ref, distance_in_double(glm::dvec3(x, y, z), m.positions[t.x],
                                                 m.positions[t.y], m.positions[t.z]));
        if (ref < band - 1e-3) {
          EXPECT_NEAR(std::abs(nb.distance_at(x, y, z)), ref, 1e-4) << x << " " << y << " " << z;
          ++in_band;
        } else if (ref > band + 1e-3) {
          EXPECT_TRUE(std::isinf(nb.distance_at(x, y, z))) << x << " " << y << " " << z;
        }
      }
  return in_band;
}

// Zero-area triangles have no face to project into: their distance is the
// nearest of their edges (a segment, or a point).
TEST(MeshDistance, NarrowBandOfDegenerateTrianglesMeasuresTheirEdges) {
  Mesh m;
  m.positions = {{3.2f, 4.1f, 5.3f}, {9.7f, 6.2f, 4.4f}, {6.45f, 5.15f, 4.85f},  // collinear
                 {5.5f, 9.3f, 8.2f},                                             // a point
                 {2.1f, 2.2f, 9.1f}, {2.1f, 2.2f, 9.1f}, {4.9f, 3.3f, 9.6f}};    // repeated corner
  m.triangles = {{0, 1, 2}, {3, 3, 3}, {4, 5, 6}};
  const MeshDistance md(m);
  const glm::ivec3 dims(14, 13, 15);
  const NarrowBand nb = mesh_narrow_band(md, dims, NarrowBandOptions{2.0f, 1});
  EXPECT_GT(expect_band_matches_reference(m, nb, dims, 2.0f), 100);
}

// Slivers: thin triangles whose cross product is mostly rounding must not
// lift the kernel's lower bound above the true distance.
TEST(MeshDistance, NarrowBandOfSliversIsExact) {
  Mesh m;
  int k = 0;
  for (float thin : {1e-6f, 3e-4f, 4e-3f, 2e-2f}) {
    const glm::vec3 a(2.3f, 2.1f + 3.0f * float(k), 2.7f), b(a + glm::vec3(9.1f, 0.3f, 1.7f));
    const glm::vec3 c = a + 0.5f * (b - a) + glm::vec3(0.0f, thin, -thin * 0.4f);
    m.positions.insert(m.positions.end(), {a, b, c});
    const uint32_t base = uint32_t(3 * k);
    m.triangles.push_back({base, base + 1, base + 2});
    ++k;
  }
  const MeshDistance md(m);
  const glm::ivec3 dims(16, 16, 9);
  for (bool avx2 : {true, false}) {
    const bool was = use_avx2_band_kernel(avx2);
    const NarrowBand nb = mesh_narrow_band(md, dims, NarrowBandOptions{2.5f, 1});
    use_avx2_band_kernel(was);
    expect_band_matches_reference(m, nb, dims, 2.5f);
  }
}

TEST(MeshDistance, NarrowBandOfNoTrianglesIsEmpty) {
  const Mesh empty;
  const MeshDistance md(empty);
  const NarrowBand nb = mesh_narrow_band(md, glm::ivec3(9, 8, 7));
  EXPECT_TRUE(nb.distance.empty());
  EXPECT_TRUE(std::isinf(nb.distance_at(8, 7, 6)));
  EXPECT_EQ(nb.triangle_at(0, 0, 0), -1);
}

// The pseudonormals are sums over the triangles around a vertex or edge,
// computed in parallel: their order must not depend on the threads.
TEST(MeshDistance, PseudonormalsDoNotDependOnThreadCount) {
  Mesh m = icosphere_like(7.3f, glm::vec3(10.2f, 9.9f, 10.4f), 3);
  m.triangles.push_back({m.triangles[5].x, m.triangles[5].y, 0});  // a fin: a non-manifold edge
  m.triangles.push_back({3, 3, 9});                                // a repeated corner
  set_default_threads(1);
  const MeshDistance one(m);
  set_default_threads(3);
  const MeshDistance three(m);
  set_default_threads(0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 20.0f);
  for (int k = 0; k < 2000; ++k) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const uint32_t t = uint32_t(rng() % m.triangles.size());
    const float a = one.signed_distance_to(p, t), b = three.signed_distance_to(p, t);
    ASSERT_EQ(0, std::memcmp(&a, &b, sizeof a)) << k;
  }
}

TEST(MeshDistance, FullFieldIsSignedEverywhere) {
  const Mesh m = icosphere_like(6.0f, glm::vec3(10.5f, 10.2f, 9.8f), 3);
  const MeshDistance md(m);
  const DenseGrid<float> d = mesh_signed_distance(md, glm::ivec3(21), 2);
  for (int z = 0; z < 21; ++z)
    for (int y = 0; y < 21; ++y)
      for (int x = 0; x < 21; ++x) {
        const float ref = md.signed_distance_brute(glm::vec3(x, y, z));
        ASSERT_NEAR(d.at(x, y, z), ref, 0.05f) << x << " " << y << " " << z;
      }
}

TEST(MeshDistance, FitMappingCentresTheMesh) {
  const Mesh m = icosphere_like(1.0f, glm::vec3(5, 5, 5), 1);
  const VoxelizeMapping map = fit_mesh_to_grid(m, 64, 4.0f).value();
  const Mesh t = transform_mesh(m, map);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (auto p : t.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  EXPECT_NEAR(lo.x, 4.0f, 1e-4f);
  EXPECT_NEAR(hi.x, 59.0f, 1e-4f);
}

// Reproducer from the hardening review: a mesh 1e-38 across mapped by a
// scale of infinity (and one near FLT_MAX by an overflowing centre).
TEST(MeshDistance, FitRefusesMeshesFloatCannotPlace) {
  const Result<VoxelizeMapping> tiny =
      fit_mesh_to_grid(icosphere_like(1e-38f, glm::vec3(0.0f), 1), 64, 4.0f);
  ASSERT_FALSE(tiny.ok());
  EXPECT_NE(tiny.error().message().find("extent"), std::string::npos);
  const Result<VoxelizeMapping> far =
      fit_mesh_to_grid(icosphere_like(1.0f, glm::vec3(3e38f, 0.0f, 0.0f), 1), 64, 4.0f);
  EXPECT_FALSE(far.ok());
}

}  // namespace
}  // namespace sculpt::core
