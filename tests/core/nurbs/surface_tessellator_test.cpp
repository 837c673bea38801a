#include "sculpt/core/nurbs/surface_tessellator.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"

namespace sculpt::core::nurbs {
namespace {

TEST(SurfaceTessellator, VerticesLieOnTheSurfaceWithItsNormals) {
  const NurbsSurface s = test::quarter_cylinder(3.0, 5.0);
  const SurfaceTessellator t(s, 6);
  // 1 x 3 non-empty spans, 6 cells each: 7 x 19 vertices.
  EXPECT_EQ(t.vertices_u(), 7);
  EXPECT_EQ(t.vertices_v(), 19);
  const Mesh& m = t.mesh();
  ASSERT_EQ(m.positions.size(), 7u * 19u);
  EXPECT_EQ(m.triangles.size(), 2u * 6u * 18u);
  for (int b = 0; b < t.vertices_v(); ++b) {
    for (int a = 0; a < t.vertices_u(); ++a) {
      const size_t k = static_cast<size_t>(a + t.vertices_u() * b);
      const glm::dvec3 p = evaluate(s, t.vertex_u(a), t.vertex_v(b));
      EXPECT_NEAR(glm::length(glm::dvec3(m.positions[k]) - p), 0.0, 1e-5);
      const glm::dvec3 n = normal(s, t.vertex_u(a), t.vertex_v(b));
      EXPECT_NEAR(glm::length(glm::dvec3(m.normals[k]) - n), 0.0, 1e-6);
    }
  }
  // An open sheet: one boundary loop, no fold.
  const MeshTopology topo = check_topology(m);
  EXPECT_EQ(topo.boundary_edges, 2 * (6 + 18));
  EXPECT_EQ(topo.misoriented_edges, 0);
  EXPECT_EQ(topo.nonmanifold_edges, 0);
  // Triangles wind counter-clockwise around the vertex normals.
  const glm::uvec3 tri = m.triangles[40];
  const glm::vec3 face =
      glm::cross(m.positions[tri.y] - m.positions[tri.x], m.positions[tri.z] - m.positions[tri.x]);
  EXPECT_GT(glm::dot(face, m.normals[tri.x]), 0.0f);
}

TEST(SurfaceTessellator, UpdatingMovedPointsEqualsARebuildAndTouchesOnlyTheirPatches) {
  NurbsSurface s = example_sheet();  // 12 x 7 patches
  SurfaceTessellator t(s, 4);
  EXPECT_EQ(t.patch_count(), 12 * 7);
  // An interior control point reaches (p+1) x (q+1) patches.
  const int k = s.index(7, 4);
  s.points[static_cast<size_t>(k)] += glm::dvec3(1.0, -2.0, 5.0);
  const int moved[] = {k};
  EXPECT_EQ(t.update(s, moved), 16);
  EXPECT_EQ(t.mesh(), SurfaceTessellator(s, 4).mesh());
  // A corner point reaches one patch.
  const int corner = s.index(0, 0);
  s.points[static_cast<size_t>(corner)].z += 3.0;
  const int moved2[] = {corner};
  EXPECT_EQ(t.update(s, moved2), 1);
  EXPECT_EQ(t.mesh(), SurfaceTessellator(s, 4).mesh());
  EXPECT_EQ(t.update(s, {}), 0);
  // New knots: everything is rebuilt.
  const std::vector<double> x{0.52};
  const NurbsSurface r = refine_u(s, x);
  EXPECT_EQ(t.update(r, moved), 13 * 7);
  EXPECT_EQ(t.mesh(), SurfaceTessellator(r, 4).mesh());
}

}  // namespace
}  // namespace sculpt::core::nurbs
