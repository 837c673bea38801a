// Simplified export: fewer triangles, the surface still closed, and the
// error measured (and within the bound when one is asked for).

#include "sculpt/core/mesh/mesh_simplify.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <glm/geometric.hpp>

#include "distance_volume.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/print_check.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"

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

// A ball in a hollow shell, a voxel from the cavity's wall: two sheets
// closer than the error asked. The wall is concave seen from the ball, so
// its simplified triangles (chords) cut into the gap, and at a bound of
// three voxels they pass through the ball. The result is made again with
// the input held around the crossings until none is left: it prints,
// within the bound, and more than half of the triangles still go.
TEST(MeshSimplify, TwoSheetsCloserThanTheErrorDoNotPassThroughEachOther) {
  const int n = 64;
  const glm::vec3 centre(static_cast<float>(n - 1) / 2.0f);
  const float ball = 14.0f, cavity = 15.0f, shell = 24.0f;
  const Mesh input = marching_cubes(test::volume_of(n, [&](glm::vec3 p) {
    const float r = glm::length(p - centre);
    return std::min(r - ball, std::max(r - shell, cavity - r));
  }));
  ASSERT_EQ(component_count(input), 3);  // the ball, the cavity's wall, the shell's outside
  ASSERT_EQ(count_self_intersections(input), 0);
  const float bound = 3.0f;
  const SimplifiedMesh s = simplify_mesh(input, {.max_error = bound});
  EXPECT_EQ(count_self_intersections(s.mesh), 0);
  EXPECT_GT(s.held_places, 0) << "simplified freely, the cavity's wall passes through the ball";
  EXPECT_LE(s.hausdorff, bound);
  EXPECT_TRUE(check_topology(s.mesh).manifold());
  EXPECT_EQ(component_count(s.mesh), 3);
  EXPECT_LT(s.mesh.triangles.size(), input.triangles.size() / 2);
  // The chunks, distances and crossings are found on every core: the same
  // mesh on one.
  set_default_threads(1);
  const SimplifiedMesh alone = simplify_mesh(input, {.max_error = bound});
  set_default_threads(0);
  EXPECT_EQ(alone.mesh, s.mesh);
}

}  // namespace
}  // namespace sculpt::core
