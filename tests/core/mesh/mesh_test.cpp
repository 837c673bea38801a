// The mesh checks every surface test relies on must themselves catch holes,
// flips, pinches and wrong sizes.

#include "sculpt/core/mesh/mesh.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace sculpt::core {
namespace {

// A unit cube, 12 outward triangles.
Mesh cube() {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.positions.emplace_back(k & 1, (k >> 1) & 1, k >> 2);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TEST(MeshTopology, ClosedCubeIsAManifoldSphere) {
  const Mesh m = cube();
  const MeshTopology t = check_topology(m);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.vertices, 8);
  EXPECT_EQ(t.edges, 18);
  EXPECT_EQ(t.faces, 12);
  EXPECT_EQ(t.euler_characteristic(), 2);
  EXPECT_DOUBLE_EQ(surface_area(m), 6.0);
  EXPECT_DOUBLE_EQ(enclosed_volume(m), 1.0);
  EXPECT_EQ(component_count(m), 1);
}

TEST(MeshTopology, HoleFlipAndPinchAreFound) {
  Mesh hole = cube();
  hole.triangles.pop_back();
  EXPECT_EQ(check_topology(hole).boundary_edges, 3);
  EXPECT_FALSE(check_topology(hole).closed());
  const glm::uvec3 gone = cube().triangles.back();
  std::vector<bool> border;
  check_topology(hole, &border);
  for (uint32_t v = 0; v < 8; ++v)
    EXPECT_EQ(border[v], v == gone.x || v == gone.y || v == gone.z) << v;

  Mesh flipped = cube();
  std::swap(flipped.triangles[0].y, flipped.triangles[0].z);
  EXPECT_EQ(check_topology(flipped).misoriented_edges, 3);

  Mesh doubled = cube();
  doubled.triangles.push_back(doubled.triangles[0]);
  EXPECT_EQ(check_topology(doubled).nonmanifold_edges, 3);

  // Two cubes touching at one corner: closed edges, a pinched vertex.
  Mesh two = cube();
  const Mesh other = cube();
  for (glm::vec3 p : other.positions)
    two.positions.push_back(p + glm::vec3(1.0f));
  for (glm::uvec3 t : other.triangles) {
    glm::uvec3 u = t + 8u;
    for (int k = 0; k < 3; ++k)
      if (u[k] == 8) u[k] = 7;  // the second cube's corner 0 is the first's corner 7
    two.triangles.push_back(u);
  }
  const MeshTopology t = check_topology(two);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.nonmanifold_vertices, 1);
  EXPECT_FALSE(t.manifold());
  EXPECT_DOUBLE_EQ(enclosed_volume(two), 2.0);
}

TEST(MeshTopology, InwardWindingGivesNegativeVolume) {
  Mesh m = cube();
  for (glm::uvec3& t : m.triangles)
    std::swap(t.y, t.z);
  EXPECT_TRUE(check_topology(m).closed());
  EXPECT_DOUBLE_EQ(enclosed_volume(m), -1.0);
}

// The ends of the edges of one triangle, degenerate triangles skipped (as
// check_topology skips them).
std::vector<bool> border_by_definition(const Mesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const glm::uvec3& tri : m.triangles) {
    if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) continue;  // degenerate
    for (int k = 0; k < 3; ++k)
      ++uses[std::minmax(tri[k], tri[(k + 1) % 3])];
  }
  std::vector<bool> border(m.positions.size(), false);
  for (const auto& [edge, n] : uses)
    if (n == 1) border[edge.first] = border[edge.second] = true;
  return border;
}

// check_topology's counts by their definitions, with ordered maps: each
// undirected edge's uses and directions, and each vertex's link (the edge
// opposite it in each of its triangles) as one cycle: every link vertex
// left once and entered once, all of them reached from one.
MeshTopology topology_by_definition(const Mesh& m) {
  MeshTopology t;
  t.faces = static_cast<int64_t>(m.triangles.size());
  std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> uses;  // {uses, forward}
  std::map<uint32_t, std::vector<std::pair<uint32_t, uint32_t>>> link;
  for (const glm::uvec3& tri : m.triangles) {
    if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) {
      ++t.degenerate_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      ++u.first;
      u.second += a < b;
      link[a].push_back({b, c});
    }
  }
  for (const auto& [edge, u] : uses) {
    ++t.edges;
    t.boundary_edges += u.first == 1;
    t.nonmanifold_edges += u.first > 2;
    t.misoriented_edges += u.first == 2 && u.second != 1;
  }
  for (const auto& [v, edges] : link) {
    ++t.vertices;
    std::map<uint32_t, int> out, in;
    std::map<uint32_t, uint32_t> next;
    for (const auto& [a, b] : edges) {
      ++out[a];
      ++in[b];
      next[a] = b;
    }
    bool cycle = out.size() == edges.size() && in.size() == edges.size();
    for (const auto& [a, n] : out)
      cycle = cycle && in.contains(a);
    if (cycle) {
      std::set<uint32_t> seen;
      for (uint32_t at = edges[0].first; seen.insert(at).second;)
        at = next[at];
      cycle = seen.size() == edges.size();
    }
    t.nonmanifold_vertices += !cycle;
  }
  return t;
}

TEST(MeshTopology, CountsAndBordersMatchTheirDefinitionsOnDamagedCubes) {
  // Two cubes sharing a corner, then triangles dropped, doubled, flipped,
  // made degenerate or given another corner, a few at a time: closed,
  // open, pinched and non-manifold meshes alike.
  Mesh two = cube();
  for (glm::uvec3 t : cube().triangles)
    two.triangles.push_back(t + 7u);
  two.positions.resize(15);
  std::mt19937 random(7);
  int damaged = 0, pinched = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Mesh m = two;
    const int changes = static_cast<int>(random() % 4);
    for (int c = 0; c < changes && !m.triangles.empty(); ++c) {
      const size_t i = random() % m.triangles.size();
      switch (random() % 5) {
        case 0:
          m.triangles.erase(m.triangles.begin() + static_cast<ptrdiff_t>(i));
          break;
        case 1:
          m.triangles.push_back(m.triangles[i]);
          break;
        case 2:
          std::swap(m.triangles[i].y, m.triangles[i].z);
          break;
        case 3:
          m.triangles[i].y = m.triangles[i].x;
          break;
        default:
          m.triangles[i][static_cast<int>(random() % 3)] = static_cast<uint32_t>(random() % 15);
          break;
      }
    }
    std::vector<bool> border;
    const MeshTopology got = check_topology(m, &border), want = topology_by_definition(m);
    ASSERT_EQ(got.vertices, want.vertices) << "trial " << trial;
    ASSERT_EQ(got.edges, want.edges) << "trial " << trial;
    ASSERT_EQ(got.faces, want.faces) << "trial " << trial;
    ASSERT_EQ(got.boundary_edges, want.boundary_edges) << "trial " << trial;
    ASSERT_EQ(got.nonmanifold_edges, want.nonmanifold_edges) << "trial " << trial;
    ASSERT_EQ(got.misoriented_edges, want.misoriented_edges) << "trial " << trial;
    ASSERT_EQ(got.nonmanifold_vertices, want.nonmanifold_vertices) << "trial " << trial;
    ASSERT_EQ(got.degenerate_triangles, want.degenerate_triangles) << "trial " << trial;
    ASSERT_EQ(border, border_by_definition(m)) << "trial " << trial;
    damaged += !got.closed();
    pinched += got.closed() && got.nonmanifold_vertices > 0;
  }
  // Both kinds were met: damaged, and closed but pinched (the shared
  // corner, or a corner moved onto another).
  EXPECT_GT(damaged, 1000);
  EXPECT_GT(pinched, 300);
}

}  // namespace
}  // namespace sculpt::core
