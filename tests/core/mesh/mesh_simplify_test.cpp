// Simplified export: fewer triangles, the surface still closed, and the
// error measured (and within the bound when one is asked for).

#include "sculpt/core/mesh/mesh_simplify.h"

#include <gtest/gtest.h>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

Mesh unit_cube(glm::vec3 offset = glm::vec3(0.0f)) {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.positions.push_back(glm::vec3(k & 1, (k >> 1) & 1, k >> 2) + offset);
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TEST(HausdorffDistance, IsTheFarthestVertexEitherWay) {
  EXPECT_DOUBLE_EQ(hausdorff_distance(unit_cube(), unit_cube()), 0.0);
  EXPECT_NEAR(hausdorff_distance(unit_cube(), unit_cube({0.25f, 0, 0})), 0.25, 1e-6);
  // A far vertex on one side only still counts.
  Mesh spike = unit_cube();
  spike.positions[7] = {3, 1, 1};
  EXPECT_NEAR(hausdorff_distance(unit_cube(), spike), 2.0, 1e-6);
  EXPECT_NEAR(hausdorff_distance(spike, unit_cube()), 2.0, 1e-6);
}

TEST(MeshSimplify, ARatioKeepsThatShareAndTheSurfaceClosed) {
  const Mesh sphere = marching_cubes(sphere_volume(64));
  const SimplifiedMesh s = simplify_mesh(sphere, {.ratio = 0.1});
  EXPECT_LE(s.mesh.triangles.size(), sphere.triangles.size() / 10 + 1);
  EXPECT_GT(s.mesh.triangles.size(), sphere.triangles.size() / 20);
  EXPECT_TRUE(check_topology(s.mesh).manifold());
  EXPECT_EQ(s.mesh.normals.size(), s.mesh.positions.size());
  EXPECT_GT(s.hausdorff, 0.0);
  EXPECT_LT(s.hausdorff, 1.0) << "a tenth of a sphere of radius 22 stays within a voxel";
  EXPECT_NEAR(enclosed_volume(s.mesh), enclosed_volume(sphere), 0.01 * enclosed_volume(sphere));
}

TEST(MeshSimplify, AnErrorBoundIsKeptAsMeasured) {
  const Mesh sphere = marching_cubes(sphere_volume(64));
  for (const float bound : {0.05f, 0.2f, 0.5f}) {
    const SimplifiedMesh s = simplify_mesh(sphere, {.max_error = bound});
    EXPECT_LT(s.mesh.triangles.size(), sphere.triangles.size()) << bound;
    EXPECT_LE(s.hausdorff, bound) << bound;
    EXPECT_TRUE(check_topology(s.mesh).manifold()) << bound;
  }
  // Nothing asked: the mesh as it was.
  const SimplifiedMesh none = simplify_mesh(sphere, {});
  EXPECT_EQ(none.mesh, sphere);
  EXPECT_EQ(none.hausdorff, 0.0);
}

}  // namespace
}  // namespace sculpt::core
