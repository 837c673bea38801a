// Bricks at different levels of detail side by side: the welded, stitched
// surface must be closed and manifold, and still the shape.

#include "sculpt/core/mesh/mixed_level_mesh.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<int> levels_by(const Volume& v, int (*pick)(glm::ivec3)) {
  const glm::ivec3 g = v.brick_grid();
  std::vector<int> levels;
  for (int z = 0; z < g.z; ++z)
    for (int y = 0; y < g.y; ++y)
      for (int x = 0; x < g.x; ++x)
        levels.push_back(pick({x, y, z}));
  return levels;
}

void expect_watertight(const Mesh& mesh, const MixedLevelStats& st, int64_t euler,
                       const char* what) {
  const MeshTopology t = check_topology(mesh);
  EXPECT_EQ(t.boundary_edges, 0) << what;
  EXPECT_EQ(t.nonmanifold_edges, 0) << what;
  EXPECT_EQ(t.misoriented_edges, 0) << what;
  EXPECT_EQ(t.nonmanifold_vertices, 0) << what;
  EXPECT_EQ(t.euler_characteristic(), euler) << what;
  // Every gap that was stitched lay in a brick face: nothing else was patched.
  EXPECT_EQ(st.stitch_off_face, 0) << what;
}

TEST(MixedLevelMesh, SphereWithEveryLevelPairingIsWatertight) {
  const Volume v = sphere_volume(128);  // 4^3 bricks
  const double r = 0.35 * 128;
  const double exact = 4.0 / 3.0 * kPi * r * r * r;
  struct Pattern {
    const char* name;
    int (*pick)(glm::ivec3);
  };
  const Pattern patterns[] = {
      {"checkerboard 0/1", [](glm::ivec3 b) { return (b.x + b.y + b.z) % 2; }},
      {"checkerboard 0/2", [](glm::ivec3 b) { return 2 * ((b.x + b.y + b.z) % 2); }},
      {"halves 0/3", [](glm::ivec3 b) { return b.x < 2 ? 0 : 3; }},
      {"mixed 0..3", [](glm::ivec3 b) { return (b.x * 7 + b.y * 3 + b.z * 5) % 4; }},
  };
  for (const Pattern& p : patterns) {
    MixedLevelStats st;
    const Mesh mesh = mixed_level_mesh(v, levels_by(v, p.pick), {}, &st);
    expect_watertight(mesh, st, 2, p.name);
    EXPECT_GT(st.stitch_loops, 0) << p.name;  // there were cracks to close
    // Coarse bricks sit up to (2^3 - 1) / 2 voxels off (level convention):
    // the volume stays within 10%.
    EXPECT_NEAR(enclosed_volume(mesh), exact, 0.1 * exact) << p.name;
  }
}

TEST(MixedLevelMesh, UniformLevelsNeedNoStitching) {
  const Volume v = sphere_volume(96);
  for (int level = 0; level <= 2; ++level) {
    MixedLevelStats st;
    const Mesh mesh =
        mixed_level_mesh(v, std::vector<int>(static_cast<size_t>(v.brick_count()), level), {}, &st);
    expect_watertight(mesh, st, 2, "uniform");
    EXPECT_EQ(st.stitch_loops, 0) << "level " << level;
    // The same surface as the whole-level extraction.
    EXPECT_EQ(mesh.triangles.size(), marching_cubes(v, level).triangles.size())
        << "level " << level;
  }
}

TEST(MixedLevelMesh, TorusAcrossLevelsKeepsItsGenus) {
  const Volume v =
      Volume::from_dense(torus_density(glm::ivec3(128), glm::vec3(63.5f), 36.0f, 14.0f));
  MixedLevelStats st;
  const Mesh mesh = mixed_level_mesh(
      v, levels_by(v, [](glm::ivec3 b) { return (b.x + 2 * b.y + b.z) % 3; }), {}, &st);
  expect_watertight(mesh, st, 0, "torus");
}

TEST(MixedLevelMesh, RandomLevelsLeaveNoCrack) {
  // Any assignment of levels 0..3: every edge in exactly two triangles, walked
  // once each way. (Random assignments can change the topology, see the
  // header; the structured ones above keep it.)
  const Volume v = sphere_volume(160, 0.3f);
  for (uint32_t seed = 1; seed <= 12; ++seed) {
    uint32_t r = seed * 2654435761u;
    std::vector<int> levels;
    for (int64_t i = 0; i < v.brick_count(); ++i) {
      r = r * 1664525u + 1013904223u;
      levels.push_back(static_cast<int>((r >> 24) % 4));
    }
    MixedLevelStats st;
    const Mesh mesh = mixed_level_mesh(v, levels, {}, &st);
    const MeshTopology t = check_topology(mesh);
    EXPECT_EQ(t.boundary_edges, 0) << "seed " << seed;
    EXPECT_EQ(t.nonmanifold_edges, 0) << "seed " << seed;
    EXPECT_EQ(t.misoriented_edges, 0) << "seed " << seed;
    EXPECT_EQ(st.stitch_off_face, 0) << "seed " << seed;
    EXPECT_GT(enclosed_volume(mesh), 0.0) << "seed " << seed;
  }
}

}  // namespace
}  // namespace sculpt::core
