// The mesh checks every surface test relies on must themselves catch holes,
// flips, pinches and wrong sizes.

#include "sculpt/core/mesh/mesh.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sculpt::core
