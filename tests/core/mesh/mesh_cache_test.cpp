// The per-brick mesh cache: after edits, re-meshing only what changed must
// give exactly the mesh of a full re-mesh, and cost only the touched bricks.

#include "sculpt/core/mesh/mesh_cache.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

// Adds (or carves) a ball of `radius` voxels at `centre`, as a sculpting dab.
void dab(Volume& volume, glm::vec3 centre, float radius, bool carve = false) {
  const glm::ivec3 lo = glm::ivec3(glm::floor(centre - radius - 2.0f));
  const glm::ivec3 hi = glm::ivec3(glm::ceil(centre + radius + 2.0f)) + 1;
  const int e = volume.brick_edge();
  volume.edit(Box{lo, hi}, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
    for (int z = 0; z < e; ++z)
      for (int y = 0; y < e; ++y)
        for (int x = 0; x < e; ++x) {
          const glm::vec3 p = glm::vec3(origin + glm::ivec3(x, y, z)) - centre;
          const uint8_t ball = density_from_distance(std::sqrt(glm::dot(p, p)) - radius);
          uint8_t& v = voxels[(static_cast<size_t>(z) * e + y) * e + x];
          v = carve ? std::min<uint8_t>(v, static_cast<uint8_t>(255 - ball)) : std::max(v, ball);
        }
  });
}

void expect_same_as_full(const MeshCache& cache, const Volume& volume) {
  MeshCache full(cache.level(), MarchingCubesOptions{cache.iso(), 1});
  full.update(volume);
  const glm::ivec3 g = cache.brick_grid();
  for (int z = 0; z < g.z; ++z)
    for (int y = 0; y < g.y; ++y)
      for (int x = 0; x < g.x; ++x) {
        ASSERT_TRUE(cache.brick_mesh({x, y, z}) == full.brick_mesh({x, y, z}))
            << "brick " << x << "," << y << "," << z << " level " << cache.level();
      }
  const Mesh mesh = cache.welded_mesh();
  EXPECT_TRUE(mesh == full.welded_mesh());
  EXPECT_TRUE(check_topology(mesh).manifold());
}

TEST(MeshCache, IncrementalEqualsFullAfterEdits) {
  Volume volume = sphere_volume(128);
  // Two consumers of one volume at different levels; neither drains the
  // volume's dirty list, and something else may drain it at any time.
  MeshCache fine(0), coarse(2), coarsest(5);  // level 5: bricks of one voxel
  fine.update(volume);
  coarse.update(volume);
  coarsest.update(volume);
  const glm::vec3 c(63.5f);
  const float r = 0.35f * 128;
  struct Dab {
    glm::vec3 at;
    float radius;
    bool carve;
  };
  // On the surface, across brick corners (64 is a brick boundary), carving
  // through, and one far inside the material (no visible change).
  const Dab dabs[] = {{c + glm::vec3(r, 0, 0), 6.0f, false},
                      {glm::vec3(64.0f, 64.0f, c.z + r), 16.0f, false},
                      {c + glm::vec3(0, -r, 0), 10.0f, true},
                      {glm::vec3(64.0f, 31.5f, 96.0f), 12.0f, true},
                      {c, 5.0f, false}};
  for (const Dab& d : dabs) {
    dab(volume, d.at, d.radius, d.carve);
    if (&d == &dabs[2]) (void)volume.take_dirty_bricks();
    fine.update(volume);
    coarse.update(volume);
    coarsest.update(volume);
    expect_same_as_full(fine, volume);
    expect_same_as_full(coarse, volume);
    expect_same_as_full(coarsest, volume);
  }
}

TEST(MeshCache, OnlyBricksWhoseVoxelsChangedAreRemeshed) {
  Volume volume = sphere_volume(256);  // 8^3 bricks of 32^3
  MeshCache cache(0);
  const MeshUpdate first = cache.update(volume);
  EXPECT_EQ(first.bricks_changed, volume.brick_count());
  // Uniform bricks with uniform neighbours on one side cost nothing: only
  // bricks near the sphere are marched.
  EXPECT_LT(first.bricks_meshed, volume.brick_count() / 2);
  EXPECT_GT(first.bricks_meshed, 0);

  const MeshUpdate idle = cache.update(volume);
  EXPECT_EQ(idle.bricks_changed, 0);
  EXPECT_EQ(idle.bricks_meshed, 0);

  // A small dab on the surface, well inside brick (6, 4, 4): one brick.
  const glm::vec3 c(127.5f);
  const glm::vec3 on_surface = c + 0.35f * 256 * glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f));
  dab(volume, on_surface, 4.0f);
  const MeshUpdate one = cache.update(volume);
  EXPECT_EQ(one.bricks_changed, 1);
  EXPECT_EQ(one.bricks_meshed, 1);

  // A 32^3 dab centred on a brick corner touches 8 bricks, none of their
  // faces toward other bricks: exactly those 8 are re-meshed.
  dab(volume, glm::vec3(192.0f), 13.0f);
  const MeshUpdate eight = cache.update(volume);
  EXPECT_EQ(eight.bricks_changed, 8);
  EXPECT_EQ(eight.bricks_meshed, 8);

  // Changing the first voxel layer of a brick changes the far cells and the
  // normals of the brick below it: that neighbour is re-meshed too.
  const glm::ivec3 p(192, 150, 150);
  DenseGrid<uint8_t> one_voxel(glm::ivec3(1), static_cast<uint8_t>(volume.voxel(p) ^ 0x80));
  volume.write(p, one_voxel);
  const MeshUpdate face = cache.update(volume);
  EXPECT_EQ(face.bricks_changed, 1);
  EXPECT_EQ(face.bricks_meshed, 2);

  // Storing the same voxels bumps the version but changes no voxel.
  volume.edit(Box{glm::ivec3(70), glm::ivec3(71)}, [](glm::ivec3, std::span<uint8_t>) {});
  const MeshUpdate same = cache.update(volume);
  EXPECT_EQ(same.bricks_changed, 1);
  EXPECT_EQ(same.bricks_meshed, 0);
  expect_same_as_full(cache, volume);
}

TEST(MeshCache, UniformVolumesDecodeAndMeshNothing) {
  for (uint8_t fill : {uint8_t{0}, uint8_t{100}}) {
    const Volume volume(glm::ivec3(256), fill);
    MeshCache cache(0);
    const MeshUpdate u = cache.update(volume);
    EXPECT_EQ(u.bricks_decoded, 0);
    EXPECT_EQ(u.bricks_meshed, 0);
    EXPECT_EQ(cache.triangle_count(), 0);
  }
}

TEST(MeshCache, AnotherVolumeIsMeshedFromScratch) {
  const Volume a = sphere_volume(64);
  const Volume b = sphere_volume(64, 0.2f);
  MeshCache cache(1);
  cache.update(a);
  cache.update(b);
  expect_same_as_full(cache, b);
}

TEST(MeshCache, BrickBlocksEqualTheVolumesOwnRead) {
  // Each brick's march reads a block assembled from its own and its
  // neighbours' cached voxels (rows of the brick edge, of one or two voxels,
  // of partial far bricks; uniform bricks as repeated rows). Marching the
  // same block read straight from the volume must give the same mesh, for
  // every brick, at every level.
  const glm::ivec3 dims(45, 38, 27);
  DenseGrid<uint8_t> grid{dims};
  uint32_t s = 24681357u;
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        s = s * 1664525u + 1013904223u;
        // Full, then noise, then empty along x: uniform bricks beside detailed ones.
        grid.at(x, y, z) = x < 12 ? 255 : (x < 30 ? static_cast<uint8_t>(s >> 24) : 0);
      }
  VolumeOptions o;
  o.brick_edge = 8;
  o.levels = 3;
  const Volume volume = Volume::from_dense(grid, o);
  for (int level = 0; level <= 2; ++level) {
    MeshCache cache(level, MarchingCubesOptions{127.5f, 1});
    cache.update(volume);
    const int m = o.brick_edge >> level;
    const glm::ivec3 ld = volume.level_dims(level);
    const glm::ivec3 g = cache.brick_grid();
    for (int z = 0; z < g.z; ++z)
      for (int y = 0; y < g.y; ++y)
        for (int x = 0; x < g.x; ++x) {
          const glm::ivec3 b(x, y, z);
          glm::ivec3 c0, c1;
          for (int a = 0; a < 3; ++a) {
            c0[a] = b[a] * m - (b[a] == 0 ? 1 : 0);
            c1[a] = std::min((b[a] + 1) * m, ld[a]);
          }
          const DenseGrid<uint8_t> voxels = volume.read(Box{c0 - 1, c1 + 2}, level);
          MarchBlock block;
          block.voxels = voxels.data();
          block.cells = c1 - c0;
          block.origin = c0;
          block.level_dims = ld;
          block.level = level;
          BrickMesh expected;
          march_block(block, expected);
          ASSERT_TRUE(cache.brick_mesh(b) == expected)
              << "brick " << x << "," << y << "," << z << " level " << level;
        }
  }
}

}  // namespace
}  // namespace sculpt::core
