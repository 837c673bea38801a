// A big change's interim meshes (MixedLevelMeshCache::interim_meshes()):
// drawn with the meshes of the bricks around them, which they do not touch,
// the surface must be closed, near the full-detail one, and cheaper.

#include <algorithm>
#include <cmath>
#include <string>
#include <array>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

// A ball of density added to `v` as a dab adds it (max with the material),
// its edge ramped over two voxels.
void add_ball(Volume& v, glm::vec3 centre, float radius) {
  const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(centre - radius - 2.0f)), glm::ivec3(0));
  const glm::ivec3 hi = glm::min(glm::ivec3(glm::ceil(centre + radius + 2.0f)), v.dims());
  DenseGrid<uint8_t> region = v.read(Box{lo, hi});
  for (int z = lo.z; z < hi.z; ++z)
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        const float d = glm::length(glm::vec3(x, y, z) - centre) - radius;
        const float f = std::clamp(0.5f - d / 4.0f, 0.0f, 1.0f);
        uint8_t& m = region.at(x - lo.x, y - lo.y, z - lo.z);
        m = std::max(m, static_cast<uint8_t>(std::lround(255.0f * f)));
      }
  v.write(lo, region);
}

// The surface a renderer draws: each brick's interim mesh where there is
// one, else the cache's mesh, joined by position (interim meshes carry no
// seam keys): vertices at the same point are one. Returns the brick meshes'
// triangle count in `interim_triangles`.
Mesh drawn_surface(const MixedLevelMeshCache& cache,
                   const std::vector<MixedLevelMeshCache::InterimMesh>& interim,
                   int64_t* interim_triangles = nullptr) {
  const glm::ivec3 grid = cache.brick_grid();
  std::vector<const Mesh*> meshes(static_cast<size_t>(grid.x) * grid.y * grid.z, nullptr);
  for (int z = 0; z < grid.z; ++z)
    for (int y = 0; y < grid.y; ++y)
      for (int x = 0; x < grid.x; ++x)
        meshes[grid_index({x, y, z}, grid)] = &cache.brick_mesh({x, y, z}).mesh;
  int64_t n = 0;
  for (const auto& m : interim) {
    meshes[grid_index(m.brick, grid)] = &m.mesh.mesh;
    n += static_cast<int64_t>(m.mesh.mesh.triangles.size());
  }
  if (interim_triangles) *interim_triangles = n;
  Mesh out;
  auto key_of = [](glm::vec3 p) {
    return std::array<float, 3>{p.x, p.y, p.z};
  };
  std::map<std::array<float, 3>, uint32_t> at;
  for (const Mesh* m : meshes) {
    std::vector<uint32_t> joined(m->positions.size());
    for (size_t v = 0; v < m->positions.size(); ++v) {
      const auto [it, added] =
          at.try_emplace(key_of(m->positions[v]), static_cast<uint32_t>(out.positions.size()));
      if (added) {
        out.positions.push_back(m->positions[v]);
        out.normals.push_back(m->normals[v]);
      }
      joined[v] = it->second;
    }
    for (const glm::uvec3& t : m->triangles) {
      // A stitch's fan over a straight polyline has triangles of no
      // area, whose centre is where a vertex of the polyline is: dropped,
      // as position joins them (their fan closes the gap all the same).
      if (joined[t.x] == joined[t.y] || joined[t.y] == joined[t.z] || joined[t.x] == joined[t.z])
        continue;
      out.triangles.emplace_back(joined[t.x], joined[t.y], joined[t.z]);
    }
  }
  return out;
}

// Closed up to float rounding: where a fine part meets a coarse one, both
// compute the crossings on the coarse grid's edges from the same values
// (the fine side from values interpolated along the edge), up to 2.3e-4
// voxel apart where the values change little along it; between bricks of
// different levels their seam keys join them. Here the ends of edges in
// one triangle are joined within 1e-3 voxel; then every edge must be in two triangles, once each way, and the
// surface of the given Euler characteristic.
void expect_closed(Mesh mesh, int64_t euler, const std::string& what) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      ++directed[{t[c], t[(c + 1) % 3]}];
  std::vector<uint32_t> ends;
  for (const auto& [e, n] : directed)
    if (!directed.contains({e.second, e.first})) {
      ends.push_back(e.first);
      ends.push_back(e.second);
    }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::vector<uint32_t> same(mesh.positions.size());
  for (uint32_t v = 0; v < same.size(); ++v)
    same[v] = v;
  int64_t joined = 0;
  for (size_t i = 0; i < ends.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (same[ends[j]] == ends[j] &&
          glm::length(mesh.positions[ends[i]] - mesh.positions[ends[j]]) < 1e-3f) {
        same[ends[i]] = ends[j];
        ++joined;
        break;
      }
  for (glm::uvec3& t : mesh.triangles)
    t = glm::uvec3(same[t.x], same[t.y], same[t.z]);
  const MeshTopology t = check_topology(mesh);
  EXPECT_EQ(t.boundary_edges, 0) << what << " (" << joined << " ends joined)";
  EXPECT_EQ(t.nonmanifold_edges, 0) << what;
  EXPECT_EQ(t.misoriented_edges, 0) << what;
  EXPECT_EQ(t.degenerate_triangles, 0) << what;
  EXPECT_EQ(t.euler_characteristic(), euler) << what;
  // Joining merged only ends a rounding apart, not whole gaps.
  EXPECT_LT(joined, static_cast<int64_t>(mesh.triangles.size()) / 10) << what;
}

std::vector<int> all_level(const Volume& v, int level) {
  return std::vector<int>(static_cast<size_t>(v.brick_count()), level);
}

TEST(InterimMesh, ABallOnTheMaterialIsClosedAgainstTheMeshesAroundIt) {
  // Balls of several sizes and places on a sphere: across faces, edges and
  // corners of bricks, the change's bricks meet the unchanged bricks' meshes
  // exactly (rims) and their own coarse cores (stitched).
  struct Case {
    glm::vec3 centre;
    float radius;
  };
  const Case cases[] = {
      {{64, 64, 108}, 20},  // on the sphere's side, within a few bricks
      {{96, 96, 96}, 30},   // over a corner of eight bricks
      {{64, 20, 64}, 12},   // a small one astride a face
      {{70, 60, 64}, 50},   // swallowing most of the sphere
  };
  for (const Case& c : cases) {
    const std::string what =
        "ball r=" + std::to_string(c.radius) + " at " + std::to_string(c.centre.x);
    Volume v = sphere_volume(128);  // 4^3 bricks of 32
    const std::vector<int> levels = all_level(v, 0);
    MixedLevelMeshCache cache;
    cache.update(v, levels);
    add_ball(v, c.centre, c.radius);
    const auto interim = cache.interim_meshes(v, levels);
    ASSERT_FALSE(interim.empty()) << what;
    int64_t interim_triangles = 0;
    const Mesh drawn = drawn_surface(cache, interim, &interim_triangles);
    expect_closed(drawn, 2, what);
    // The change at full detail: the interim is coarser, and encloses
    // about the same volume.
    cache.update(v, levels);
    int64_t full_triangles = 0;
    for (const auto& m : interim)
      full_triangles += static_cast<int64_t>(cache.brick_mesh(m.brick).mesh.triangles.size());
    EXPECT_LT(interim_triangles, full_triangles * 3 / 4) << what;
    const Mesh full = cache.welded_mesh();
    EXPECT_NEAR(enclosed_volume(drawn), enclosed_volume(full), 0.05 * enclosed_volume(full))
        << what;
  }
}

TEST(InterimMesh, LeavesTheCacheAsItWas) {
  // update() after interim_meshes() finds and meshes the change as it would
  // have without: the same meshes as meshing from scratch.
  Volume v = sphere_volume(128);
  const std::vector<int> levels = all_level(v, 0);
  MixedLevelMeshCache cache;
  cache.update(v, levels);
  add_ball(v, {64, 64, 108}, 20);
  EXPECT_FALSE(cache.interim_meshes(v, levels).empty());
  const MeshUpdate u = cache.update(v, levels);
  EXPECT_GT(u.bricks_meshed, 0);
  EXPECT_EQ(cache.welded_mesh(), mixed_level_mesh(v, levels));
  // Nothing moved since: nothing to show.
  EXPECT_TRUE(cache.interim_meshes(v, levels).empty());
}

TEST(InterimMesh, OnlyWhereItApplies) {
  Volume v = sphere_volume(128);
  const std::vector<int> levels = all_level(v, 0);
  MixedLevelMeshCache cache;
  // Before the first update: no meshes to keep.
  add_ball(v, {64, 64, 108}, 20);
  EXPECT_TRUE(cache.interim_meshes(v, levels).empty());
  cache.update(v, levels);
  add_ball(v, {64, 64, 20}, 20);
  // Other levels than the last update's, or a small change.
  EXPECT_TRUE(cache.interim_meshes(v, all_level(v, 1)).empty());
  EXPECT_TRUE(cache.interim_meshes(v, levels, 1000).empty());
  // A coarse brick next to the change (zoomed out): not shown this way.
  std::vector<int> mixed = levels;
  cache.update(v, levels);
  mixed[grid_index({2, 2, 0}, v.brick_grid())] = 1;
  cache.update(v, mixed);
  add_ball(v, {64, 64, 20}, 24);
  EXPECT_TRUE(cache.interim_meshes(v, mixed).empty());
}

}  // namespace
}  // namespace sculpt::core
