// Bricks at different levels of detail side by side: the welded, stitched
// surface must be closed and manifold, and still the shape.

#include "sculpt/core/mesh/mixed_level_mesh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

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

// Empties every voxel of `box`: a dent where it meets the material.
void carve_box(Volume& v, const Box& box) {
  v.edit(box, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
    const int e = v.brick_edge();
    const Box local = intersect(box, Box{origin, origin + e});
    for (int z = local.lo.z; z < local.hi.z; ++z)
      for (int y = local.lo.y; y < local.hi.y; ++y)
        for (int x = local.lo.x; x < local.hi.x; ++x)
          voxels[(static_cast<size_t>(z - origin.z) * e + (y - origin.y)) * e + (x - origin.x)] = 0;
  });
}

// The voxels a sculptor would hand over for every brick of `bricks` (brick
// coordinates): each brick's current version, decoded; `changed_from`, when
// given, says for each (in z, y, x order) the version they changed from
// inside `changed`.
StoredVoxelsByBrick stored_as_decoded(const Volume& v, const Box& bricks,
                                      const std::vector<uint64_t>* changed_from = nullptr,
                                      const Box& changed = {}) {
  const int e = v.brick_edge();
  StoredVoxelsByBrick stored;
  size_t k = 0;
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        const glm::ivec3 b(x, y, z);
        StoredVoxels& s = stored[static_cast<int64_t>(grid_index(b, v.brick_grid()))];
        s.version = v.brick_version(b);
        s.voxels.resize(static_cast<size_t>(e) * e * e);
        v.decode_brick(b, s.voxels);
        if (changed_from != nullptr) {
          s.changed_from = (*changed_from)[k++];
          s.changed = changed;
        }
      }
  return stored;
}

void expect_watertight(const Mesh& mesh, int64_t euler, const char* what) {
  const MeshTopology t = check_topology(mesh);
  EXPECT_EQ(t.boundary_edges, 0) << what;
  EXPECT_EQ(t.nonmanifold_edges, 0) << what;
  EXPECT_EQ(t.misoriented_edges, 0) << what;
  EXPECT_EQ(t.nonmanifold_vertices, 0) << what;
  EXPECT_EQ(t.euler_characteristic(), euler) << what;
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
    expect_watertight(mesh, 2, p.name);
    EXPECT_GT(st.stitch_loops, 0) << p.name;  // there were cracks to close
    // Coarse bricks sit up to (2^3 - 1) / 2 voxels off (level convention):
    // the volume stays within 10%.
    EXPECT_NEAR(enclosed_volume(mesh), exact, 0.1 * exact) << p.name;
  }
}

// A mesh's triangles as their corners' positions and normals, each
// triangle turned to start at its least corner, sorted: equal for two
// meshes of the same surface to the bit, however their vertices are
// numbered and welded.
std::vector<std::array<float, 18>> triangle_corners(const Mesh& mesh) {
  std::vector<std::array<float, 18>> out;
  for (const glm::uvec3& t : mesh.triangles) {
    std::array<std::array<float, 6>, 3> c;
    for (int i = 0; i < 3; ++i) {
      const glm::vec3 p = mesh.positions[t[i]], n = mesh.normals[t[i]];
      c[static_cast<size_t>(i)] = {p.x, p.y, p.z, n.x, n.y, n.z};
    }
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    std::array<float, 18>& flat = out.emplace_back();
    for (size_t i = 0; i < 3; ++i)
      std::copy(c[i].begin(), c[i].end(), flat.begin() + static_cast<std::ptrdiff_t>(6 * i));
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(MixedLevelMesh, UniformLevelsNeedNoStitching) {
  const Volume v = sphere_volume(96);
  for (int level = 0; level <= 2; ++level) {
    MixedLevelStats st;
    const Mesh mesh =
        mixed_level_mesh(v, std::vector<int>(static_cast<size_t>(v.brick_count()), level), {}, &st);
    expect_watertight(mesh, 2, "uniform");
    EXPECT_EQ(st.stitch_loops, 0) << "level " << level;
    // The same surface as the whole-level extraction, to the bit: the same
    // triangles, corners and normals (bricks with every neighbour at their
    // level march their voxels as bytes, the others as floats).
    ASSERT_TRUE(triangle_corners(mesh) == triangle_corners(marching_cubes(v, level)))
        << "level " << level;
  }
}

TEST(MixedLevelMesh, UniformBricksBesideTheSurfaceAreReadAsTheirValue) {
  // A small ball in a big block: most bricks the surface's bricks read are
  // uniform (air around, solid inside), read from one shared buffer per
  // value. The same surface as the whole-level extraction, to the bit, also
  // after edits that make bricks uniform and others not.
  Volume v =
      Volume::from_dense(sphere_density(128, 0.2f), VolumeOptions{.brick_edge = 16, .levels = 4});
  int uniform = 0;
  for (int64_t i = 0; i < v.brick_count(); ++i)
    uniform += v.brick(grid_position(i, v.brick_grid())).is_uniform() ? 1 : 0;
  ASSERT_GT(uniform, v.brick_count() / 2);
  // And a block whose top lies a third of a voxel above a brick face (and
  // whose sides stay off the volume's): the solid bricks below the top are
  // uniform, and the normals at the face's crossings read their voxels.
  DenseGrid<uint8_t> slab(glm::ivec3(64));
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const float top = 32.3f + 0.05f * static_cast<float>(x + y % 7);
        slab.at(x, y, z) = density_from_distance(
            std::max({static_cast<float>(z) - top, 8.0f - static_cast<float>(z),
                      std::abs(static_cast<float>(x) - 32.0f) - 20.0f,
                      std::abs(static_cast<float>(y) - 32.0f) - 20.0f}));
      }
  const Volume slab_volume = Volume::from_dense(slab, VolumeOptions{.brick_edge = 16, .levels = 4});
  ASSERT_TRUE(slab_volume.brick({1, 1, 1}).is_uniform());
  for (const Volume* shape : {static_cast<const Volume*>(&v), &slab_volume})
    for (int level = 0; level <= 1; ++level) {
      const std::vector<int> levels(static_cast<size_t>(shape->brick_count()), level);
      MixedLevelMeshCache cache;
      cache.update(*shape, levels);
      EXPECT_TRUE(triangle_corners(cache.welded_mesh()) ==
                  triangle_corners(marching_cubes(*shape, level)))
          << "level " << level;
    }
  const std::vector<int> full(static_cast<size_t>(v.brick_count()), 0);
  MixedLevelMeshCache cache;
  cache.update(v, full);
  for (int i = 0; i < 3; ++i) {
    v.write(glm::ivec3(36 + 4 * i, 40, 44), DenseGrid<uint8_t>(glm::ivec3(8), i % 2 ? 0 : 255));
    cache.update(v, full);
    EXPECT_TRUE(triangle_corners(cache.welded_mesh()) == triangle_corners(marching_cubes(v, 0)))
        << "edit " << i;
  }
  EXPECT_EQ(cache.unforeseen_decodes(), 0);
}

TEST(MixedLevelMesh, TorusAcrossLevelsKeepsItsGenus) {
  const Volume v =
      Volume::from_dense(torus_density(glm::ivec3(128), glm::vec3(63.5f), 36.0f, 14.0f));
  MixedLevelStats st;
  const Mesh mesh = mixed_level_mesh(
      v, levels_by(v, [](glm::ivec3 b) { return (b.x + 2 * b.y + b.z) % 3; }), {}, &st);
  expect_watertight(mesh, 0, "torus");
}

TEST(MixedLevelMesh, RandomLevelsKeepTheTopology) {
  // Any assignment of levels 0..3, neighbours differing by up to three
  // levels across faces, edges and corners: closed, manifold, and still one
  // sphere (Euler characteristic 2, one component).
  const Volume v = sphere_volume(160, 0.3f);
  int64_t loops = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    uint32_t r = seed * 2654435761u;
    std::vector<int> levels;
    for (int64_t i = 0; i < v.brick_count(); ++i) {
      r = r * 1664525u + 1013904223u;
      levels.push_back(static_cast<int>((r >> 24) % 4));
    }
    MixedLevelStats st;
    const Mesh mesh = mixed_level_mesh(v, levels, {}, &st);
    const std::string what = "seed " + std::to_string(seed);
    expect_watertight(mesh, 2, what.c_str());
    EXPECT_EQ(component_count(mesh), 1) << what;
    EXPECT_GT(enclosed_volume(mesh), 0.0) << what;
    loops += st.stitch_loops;
  }
  EXPECT_GT(loops, 0);
}

TEST(MixedLevelMeshCache, KeepsWhatDidNotChange) {
  Volume v = sphere_volume(128);  // 4^3 bricks
  std::vector<int> levels = levels_by(v, [](glm::ivec3 b) { return (b.x + 2 * b.y + b.z) % 3; });
  MixedLevelMeshCache cache;
  MeshUpdate u = cache.update(v, levels);
  EXPECT_EQ(u.bricks_changed, v.brick_count());
  EXPECT_GT(u.bricks_meshed, 0);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));

  // Nothing changed: nothing re-meshed, nothing decoded.
  auto mesh_versions = [&] {
    std::vector<uint64_t> out;
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
          out.push_back(cache.brick_mesh_version({x, y, z}));
    return out;
  };
  const std::vector<uint64_t> first = mesh_versions();
  EXPECT_EQ(std::count(first.begin(), first.end(), 1u), v.brick_count());
  u = cache.update(v, levels);
  EXPECT_EQ(u.bricks_changed, 0);
  EXPECT_EQ(u.bricks_decoded, 0);
  EXPECT_EQ(mesh_versions(), first);

  // A dent in the surface inside brick (2, 2, 3): it and its 26 neighbours
  // at most are re-meshed, and the result is what meshing from scratch gives.
  const Box box{glm::ivec3(66, 66, 100), glm::ivec3(76, 76, 115)};
  carve_box(v, box);
  u = cache.update(v, levels);
  EXPECT_GT(u.bricks_changed, 0);
  EXPECT_LE(u.bricks_changed, 27);
  // Exactly the re-meshed bricks moved their mesh versions.
  const std::vector<uint64_t> after = mesh_versions();
  int64_t moved = 0;
  for (size_t i = 0; i < after.size(); ++i)
    moved += after[i] != first[i];
  EXPECT_EQ(moved, u.bricks_changed);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
  MixedLevelStats st = cache.stats();
  expect_watertight(cache.welded_mesh(), 2, "after edit");

  // One brick changes level: only the bricks that read its level follow.
  levels[(2 * 4 + 1) * 4 + 1] = 3;
  u = cache.update(v, levels);
  EXPECT_GT(u.bricks_changed, 0);
  EXPECT_LE(u.bricks_changed, 27);
  EXPECT_EQ(cache.brick_level({1, 1, 2}), 3);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
  st = cache.stats();
  expect_watertight(cache.welded_mesh(), 2, "after level change");
}

TEST(MixedLevelMeshCache, FollowsEditsAnywhereAsMeshingFromScratchWould) {
  // Balls added and carved across brick faces, edges and corners, bricks of
  // four levels: after each, the cached meshes equal a fresh meshing, and
  // only bricks near the edit were redone.
  Volume v = sphere_volume(128, 0.3f);
  const std::vector<int> levels =
      levels_by(v, [](glm::ivec3 b) { return (b.x * 7 + b.y * 3 + b.z * 5) % 4; });
  MixedLevelMeshCache cache;
  cache.update(v, levels);
  const glm::vec3 centres[] = {{64, 64, 100}, {32, 40, 64}, {96, 96, 63}, {64, 40, 40}};
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 c = centres[i];
    const Box box{glm::ivec3(c) - 8, glm::ivec3(c) + 8};
    const int e = v.brick_edge();
    v.edit(box, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
      const Box local = intersect(box, Box{origin, origin + e});
      for (int z = local.lo.z; z < local.hi.z; ++z)
        for (int y = local.lo.y; y < local.hi.y; ++y)
          for (int x = local.lo.x; x < local.hi.x; ++x) {
            const glm::vec3 d = glm::vec3(x, y, z) - c;
            if (glm::dot(d, d) > 36.0f) continue;
            voxels[(static_cast<size_t>(z - origin.z) * e + (y - origin.y)) * e + (x - origin.x)] =
                i % 2 ? 0 : 255;
          }
    });
    const MeshUpdate u = cache.update(v, levels);
    EXPECT_GT(u.bricks_changed, 0) << i;
    EXPECT_LE(u.bricks_changed, 27) << i;
    EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels)) << i;
  }
}

// A cancelled update meshes no brick after the cancel says so (the station's
// refiner stops a pass over a volume that a newer one replaced); a cache
// that is not cancelled meshes them all.
TEST(MixedLevelMeshCache, ACancelledUpdateMeshesNoMoreBricks) {
  const Volume v = sphere_volume(128);  // 4^3 bricks
  const std::vector<int> levels(static_cast<size_t>(v.brick_count()), 0);
  MixedLevelMeshCache whole(MarchingCubesOptions{.threads = 2});
  const int64_t all = whole.update(v, levels).bricks_meshed;
  ASSERT_GT(all, 16);
  for (const int after : {0, 5}) {
    MixedLevelMeshCache cut(MarchingCubesOptions{.threads = 2});
    std::atomic<int> asked{0};
    cut.set_cancel([&] { return asked.fetch_add(1) >= after; });
    const MeshUpdate u = cut.update(v, levels);
    EXPECT_EQ(asked.load(), v.brick_count());  // asked before every brick
    EXPECT_LE(u.bricks_meshed, after) << after;
  }
}

TEST(MixedLevelMeshCache, ParallelMeshingEqualsOneThreadAndDecodesEverythingFirst) {
  // Stale bricks are meshed in parallel from voxels decoded beforehand; the
  // result is the one-thread result bit for bit, and no read was missed,
  // with one-voxel bricks (a neighbourhood of radius 2) included.
  for (const int edge : {16, 4}) {
    Volume v = Volume::from_dense(sphere_density(64, 0.3f),
                                  VolumeOptions{.brick_edge = edge, .levels = edge == 16 ? 4 : 2});
    const int top = v.levels();
    std::vector<int> levels =
        levels_by(v, [](glm::ivec3 b) { return (b.x * 5 + b.y + b.z * 3) % 7; });
    for (int& l : levels)
      l = std::min(l, top);
    MixedLevelMeshCache parallel(MarchingCubesOptions{.threads = 2});
    MixedLevelMeshCache serial(MarchingCubesOptions{.threads = 1});
    parallel.update(v, levels);
    serial.update(v, levels);
    for (int i = 0; i < 6; ++i) {
      DenseGrid<uint8_t> blob(glm::ivec3(5 + i), i % 2 ? 0 : 255);
      v.write(glm::ivec3(12 + 7 * i, 30, 14 + 5 * i), blob);
      if (i == 3) std::rotate(levels.begin(), levels.begin() + 5, levels.end());
      parallel.update(v, levels);
      serial.update(v, levels);
      ASSERT_EQ(parallel.welded_mesh(), serial.welded_mesh()) << edge << " " << i;
    }
    EXPECT_EQ(parallel.unforeseen_decodes(), 0) << edge;
    EXPECT_EQ(serial.unforeseen_decodes(), 0) << edge;
  }
}

TEST(MixedLevelMeshCache, MaterialAppearingAmongUniformBricksIsMeshed) {
  // Uniform neighbourhoods are not meshed (nothing is decoded there), so the
  // first material put in an empty block must still be seen. Reproducer:
  // the window showed nothing after the demo's new empty block.
  Volume v(glm::ivec3(96), 0, VolumeOptions{.brick_edge = 16, .levels = 4});
  const std::vector<int> levels = levels_by(v, [](glm::ivec3 b) { return b.x % 2; });
  MixedLevelMeshCache cache;
  EXPECT_EQ(cache.update(v, levels).bricks_meshed, 0);
  EXPECT_EQ(cache.triangle_count(), 0);
  v.write({30, 40, 20}, DenseGrid<uint8_t>(glm::ivec3(20, 12, 30), 255));
  cache.update(v, levels);
  EXPECT_GT(cache.triangle_count(), 100);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
  // And gone again.
  v.write({30, 40, 20}, DenseGrid<uint8_t>(glm::ivec3(20, 12, 30), 0));
  cache.update(v, levels);
  EXPECT_EQ(cache.triangle_count(), 0);
}

TEST(MixedLevelMeshCache, ABallInAUniformBrickReMeshesOnlyTheBricksThatReadIt) {
  // A brick that was uniform had nothing decoded to compare with, and its
  // whole box counted as changed: every brick around re-meshed (a big ball
  // added in the air made 304 bricks stale where 107 read voxels it
  // changed). Its old voxels are its uniform value: a ball well inside it,
  // in the air or carved out of solid clay, re-meshes it alone, at any mix
  // of levels, and the meshes are those of a fresh meshing.
  for (const uint8_t fill : {uint8_t{0}, uint8_t{255}}) {
    Volume v(glm::ivec3(96), fill, VolumeOptions{.brick_edge = 16, .levels = 4});
    const std::vector<int> levels = levels_by(v, [](glm::ivec3 b) { return b.x % 2; });
    MixedLevelMeshCache cache;
    // Some surface elsewhere (bricks 4 and 5; 3 to 5 meshed, 2 to 5 decoded),
    // so that uniform bricks sit beside meshed ones.
    v.write({70, 70, 70}, DenseGrid<uint8_t>(glm::ivec3(20), static_cast<uint8_t>(255 - fill)));
    cache.update(v, levels);
    const uint8_t other = static_cast<uint8_t>(255 - fill);
    // A 6-voxel cube in the middle of brick (1, 1, 1): voxels 21..26, more
    // than the two-voxel margin a level-0 neighbour reads from its faces.
    v.write({21, 21, 21}, DenseGrid<uint8_t>(glm::ivec3(6), other));
    const MeshUpdate u = cache.update(v, levels);
    EXPECT_EQ(u.bricks_changed, 1) << int{fill};
    EXPECT_GT(cache.triangle_count(), 0);
    EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels)) << int{fill};
    // Across a face: the brick beside it reads the change too.
    v.write({30, 22, 22}, DenseGrid<uint8_t>(glm::ivec3(4), other));
    const MeshUpdate across = cache.update(v, levels);
    EXPECT_GE(across.bricks_changed, 2) << int{fill};
    EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels)) << int{fill};
  }
}

TEST(MixedLevelMeshCache, ABrickBesideAChangeIsMeshedAgainOnlyWhenItsBorderMoved) {
  // A brick reads two voxels into each brick around it. A change with one
  // part at brick (1, 1, 1)'s low x border and another at its high y border
  // re-meshes the bricks beyond those borders, but not the brick beyond
  // their shared edge, (0, 2, 1): the box around both parts reaches it, the
  // moved voxels do not.
  Volume v(glm::ivec3(64), 0, VolumeOptions{.brick_edge = 16, .levels = 4});
  v.write({0, 0, 0}, DenseGrid<uint8_t>(glm::ivec3(64, 64, 24), 255));  // a floor
  const std::vector<int> levels(static_cast<size_t>(v.brick_count()), 0);
  MixedLevelMeshCache cache;
  cache.update(v, levels);
  const uint64_t beyond_the_edge = cache.brick_mesh_version({0, 2, 1});
  v.write({16, 22, 26}, DenseGrid<uint8_t>(glm::ivec3(2, 3, 3), 255));  // x 16..17: low x border
  v.write({22, 30, 26}, DenseGrid<uint8_t>(glm::ivec3(3, 2, 3), 255));  // y 30..31: high y border
  const MeshUpdate u = cache.update(v, levels);
  EXPECT_EQ(u.bricks_changed, 3);  // (1, 1, 1), (0, 1, 1) and (1, 2, 1)
  EXPECT_EQ(cache.brick_mesh_version({0, 2, 1}), beyond_the_edge);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
}

TEST(MixedLevelMeshCache, AHandedOutMeshIsNeverChangedByALaterUpdate) {
  // The station hands the window each re-made mesh without a copy
  // (shared_brick_mesh): a later update makes the brick's next mesh anew,
  // so the one handed out stays as it was, and zooming out and back gives
  // the very mesh kept, not a copy.
  Volume v = sphere_volume(128);  // 4^3 bricks
  const std::vector<int> near = levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 0 : 1; });
  const std::vector<int> far = levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 2 : 3; });
  MixedLevelMeshCache cache;
  cache.update(v, near);
  const glm::ivec3 b(2, 2, 3);  // on the sphere's surface
  const std::shared_ptr<const BrickMesh> handed = cache.shared_brick_mesh(b);
  ASSERT_FALSE(handed->empty());
  EXPECT_EQ(handed.get(), &cache.brick_mesh(b));
  const BrickMesh as_handed = *handed;
  // A dent in it: re-meshed, into a new mesh.
  const Box box{glm::ivec3(66, 66, 100), glm::ivec3(76, 76, 115)};
  carve_box(v, box);
  cache.update(v, near);
  EXPECT_EQ(*handed, as_handed);
  EXPECT_NE(cache.brick_mesh(b), as_handed);
  EXPECT_NE(cache.shared_brick_mesh(b).get(), handed.get());
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, near));
  // Out and back: the kept mesh itself comes back.
  const std::shared_ptr<const BrickMesh> dented = cache.shared_brick_mesh(b);
  cache.update(v, far);
  EXPECT_NE(cache.shared_brick_mesh(b).get(), dented.get());
  cache.update(v, near);
  EXPECT_EQ(cache.shared_brick_mesh(b).get(), dented.get());
  // A brick with no surface hands out an empty mesh, not a null one.
  const std::shared_ptr<const BrickMesh> air = cache.shared_brick_mesh({0, 0, 0});
  ASSERT_NE(air, nullptr);
  EXPECT_TRUE(air->empty());
}

TEST(MixedLevelMeshCache, VoxelsGivenWithAChangeAreTakenInsteadOfDecoding) {
  // The voxels a sculptor stored, given to update(): taken for the bricks
  // whose version they are of (the meshes those of decoding), ignored for
  // a brick stored again since (here deliberately wrong voxels).
  Volume v = sphere_volume(128);  // 4^3 bricks
  const std::vector<int> levels = levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 0 : 1; });
  MixedLevelMeshCache cache;
  cache.update(v, levels);
  const Box box{glm::ivec3(50, 50, 98), glm::ivec3(80, 80, 115)};  // across bricks, on the surface
  carve_box(v, box);
  const Box moved = v.bricks_overlapping(box);
  StoredVoxelsByBrick stored = stored_as_decoded(v, moved);
  ASSERT_GE(stored.size(), 4u);
  // One of them given for an older version, its voxels all wrong.
  StoredVoxels& stale = stored.begin()->second;
  stale.version -= 1;
  std::fill(stale.voxels.begin(), stale.voxels.end(), uint8_t{255});
  const MeshUpdate u = cache.update(v, levels, &stored);
  EXPECT_EQ(u.bricks_given, static_cast<int64_t>(moved.voxel_count()) - 1);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
  expect_watertight(cache.welded_mesh(), 2, "given voxels");
}

TEST(MixedLevelMeshCache, GivenVoxelsAreComparedOnlyWhereTheSculptorChangedThem) {
  // A sculptor that says where a brick's voxels changed since the version
  // kept: only those rows are compared to find what moved (the rest are
  // the same); the meshes are decoding's. A brick whose change is told
  // against another version is compared whole.
  Volume v = sphere_volume(128);  // 4^3 bricks
  const std::vector<int> levels(static_cast<size_t>(v.brick_count()), 0);
  MixedLevelMeshCache cache;
  cache.update(v, levels);
  const Box box{glm::ivec3(50, 50, 98), glm::ivec3(80, 80, 115)};  // across bricks, on the surface
  const Box moved = v.bricks_overlapping(box);
  std::vector<uint64_t> before;
  for (int z = moved.lo.z; z < moved.hi.z; ++z)
    for (int y = moved.lo.y; y < moved.hi.y; ++y)
      for (int x = moved.lo.x; x < moved.hi.x; ++x)
        before.push_back(v.brick_version({x, y, z}));
  carve_box(v, box);
  StoredVoxelsByBrick stored = stored_as_decoded(v, moved, &before, box);
  ASSERT_GE(stored.size(), 4u);
  *stored.begin()->second.changed_from += 1;  // told against another version
  const auto given = static_cast<int64_t>(stored.size());
  const MeshUpdate u = cache.update(v, levels, &stored);
  EXPECT_EQ(u.bricks_given, given);
  EXPECT_EQ(u.bricks_compared_where_changed, given - 1);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
  expect_watertight(cache.welded_mesh(), 2, "voxels given with where they changed");
}

TEST(MixedLevelMeshCache, ZoomingBackReMeshesNothing) {
  // Levels by camera distance: near (fine), then far (coarse), then near
  // again. The way back gives every brick the mesh it had, marching none.
  const Volume v = sphere_volume(128);
  const std::vector<int> near = levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 0 : 1; });
  const std::vector<int> far = levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 2 : 3; });
  MixedLevelMeshCache cache;
  const MeshUpdate first = cache.update(v, near);
  const Mesh near_mesh = cache.welded_mesh();
  const MeshUpdate zoomed_out = cache.update(v, far);
  EXPECT_GT(zoomed_out.bricks_meshed, 0);
  EXPECT_EQ(zoomed_out.bricks_reused, 0);
  EXPECT_GT(cache.kept_mesh_bytes(), 0u);
  const MeshUpdate zoomed_in = cache.update(v, near);
  EXPECT_EQ(zoomed_in.bricks_meshed, 0);
  EXPECT_GE(zoomed_in.bricks_reused, first.bricks_meshed);  // the empty ones too
  EXPECT_EQ(zoomed_in.bricks_reused, zoomed_in.bricks_changed);
  EXPECT_EQ(cache.welded_mesh(), near_mesh);
  // And out again: the far meshes were kept in their turn.
  EXPECT_EQ(cache.update(v, far).bricks_meshed, 0);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, far));
}

TEST(MixedLevelMeshCache, AnEditUnderAReusedMeshIsSeen) {
  // Fine bricks beside coarse ones, zoomed out and back (their meshes
  // reused), then a cut a coarse level does not show: the fine bricks'
  // meshes follow it, as meshing from scratch would.
  Volume v = sphere_volume(128);
  const std::vector<int> near = levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 0 : 2; });
  const std::vector<int> far = levels_by(v, [](glm::ivec3) { return 3; });
  MixedLevelMeshCache cache;
  cache.update(v, near);
  cache.update(v, far);
  EXPECT_GT(cache.update(v, near).bricks_reused, 0);
  v.write({30, 64, 93}, DenseGrid<uint8_t>(glm::ivec3(1, 1, 1), 0));  // just inside
  cache.update(v, near);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, near));
}

TEST(MixedLevelMeshCache, AnEditDropsTheKeptMeshesThatReadIt) {
  // Zoom out, carve near (fine-level detail the coarse levels may not even
  // show), zoom back in: the bricks around the cut are marched again and
  // the surface is what meshing from scratch gives; far from it, reused.
  Volume v = sphere_volume(128);
  const std::vector<int> near = levels_by(v, [](glm::ivec3) { return 0; });
  const std::vector<int> far = levels_by(v, [](glm::ivec3) { return 2; });
  MixedLevelMeshCache cache;
  cache.update(v, near);
  cache.update(v, far);
  v.write({62, 62, 104}, DenseGrid<uint8_t>(glm::ivec3(2, 2, 2), 0));  // on the surface
  cache.update(v, far);
  const MeshUpdate back = cache.update(v, near);
  EXPECT_GT(back.bricks_meshed, 0);
  EXPECT_GT(back.bricks_reused, 0);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, near));
}

TEST(MixedLevelMeshCache, KeptMeshesStayWithinTheirBudget) {
  // A budget of a few bricks' meshes: the least recently kept are dropped,
  // what is left is within it, and the surface is still right.
  const Volume v = sphere_volume(128);
  const std::vector<int> a = levels_by(v, [](glm::ivec3) { return 0; });
  const std::vector<int> b = levels_by(v, [](glm::ivec3) { return 1; });
  MixedLevelMeshCache unbounded;
  unbounded.update(v, a);
  unbounded.update(v, b);
  const size_t all = unbounded.kept_mesh_bytes();
  ASSERT_GT(all, 0u);
  MixedLevelMeshCache cache;
  cache.set_kept_mesh_budget(all / 4);
  cache.update(v, a);
  cache.update(v, b);
  EXPECT_LE(cache.kept_mesh_bytes(), all / 4);
  EXPECT_GT(cache.kept_mesh_bytes(), 0u);
  const MeshUpdate back = cache.update(v, a);
  EXPECT_GT(back.bricks_meshed, 0);
  EXPECT_GT(back.bricks_reused, 0);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, a));
  cache.set_kept_mesh_budget(0);
  cache.update(v, b);
  EXPECT_EQ(cache.kept_mesh_bytes(), 0u);
}

TEST(MixedLevelMeshCache, BrickMeshesDrawTheWholeSurface) {
  // What a renderer draws: every brick's own mesh; together (welded by
  // their seam keys) a closed surface, whichever bricks are coarse.
  const Volume v = sphere_volume(128);
  MixedLevelMeshCache cache;
  cache.update(v, levels_by(v, [](glm::ivec3 b) { return b.x < 2 ? 0 : 2; }));
  int64_t triangles = 0;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        triangles += static_cast<int64_t>(cache.brick_mesh({x, y, z}).mesh.triangles.size());
  EXPECT_EQ(triangles, cache.triangle_count());
  const Mesh welded = cache.welded_mesh();
  EXPECT_EQ(static_cast<int64_t>(welded.triangles.size()), triangles);
  expect_watertight(welded, 2, "halves 0/2");
}

}  // namespace
}  // namespace sculpt::core
