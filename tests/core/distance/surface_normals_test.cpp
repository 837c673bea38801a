#include "sculpt/core/distance/surface_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sphere_normal_error.h"

namespace sculpt::core {
namespace {

using test::sphere_normal_error;

TEST(SurfaceNormals, DistanceGradientNormalsOfASphereAreTrueToAFractionOfADegree) {
  const int n = 64;
  const Volume volume = sphere_volume(n, 0.3f);
  Mesh mesh = marching_cubes(volume);
  ASSERT_GT(mesh.positions.size(), 1000u);
  const glm::vec3 centre(0.5f * (n - 1));
  set_normals_from_surface_distance(volume, mesh);
  const auto distance = sphere_normal_error(mesh, centre);
  EXPECT_LT(distance.mean_deg, 0.5) << "mean";
  EXPECT_LT(distance.max_deg, 3.0) << "worst";
}

// At a coarse level the density is a mean over 2^3 voxels, whose ramp
// across the surface bends where the density gradient reads it: its normals
// are degrees off (4.0 on average, 11.8 at worst, at level 1 on a sphere
// of radius 38), the distance field's four times truer (1.1 and 2.0). At
// level 0 the density gradient's are the truer (0.11 and 0.35 degrees:
// marching_cubes_test.cpp).
TEST(SurfaceNormals, AtACoarseLevelDistanceGradientNormalsAreTruerThanTheDensitys) {
  const int n = 128, level = 1;
  const Volume volume = sphere_volume(n, 0.3f);
  Mesh mesh = marching_cubes(volume, level);
  // A level-k surface sits (2^k - 1) / 2 voxels toward -x, -y, -z.
  const glm::vec3 centre(0.5f * (n - 1) - 0.5f * ((1 << level) - 1));
  const auto density = sphere_normal_error(mesh, centre);
  set_normals_from_surface_distance(volume, mesh);
  const auto distance = sphere_normal_error(mesh, centre);
  EXPECT_LT(distance.mean_deg, 0.5 * density.mean_deg)
      << distance.mean_deg << " " << density.mean_deg;
  EXPECT_LT(distance.max_deg, 0.5 * density.max_deg) << distance.max_deg << " " << density.max_deg;
}

TEST(SurfaceNormals, APieceOfTheMeshGetsTheSameNormalsAsTheWhole) {
  // Normals depend on the surface around each vertex, not on which mesh
  // (a brick's or the whole's) the vertex is in.
  const Volume volume = sphere_volume(48, 0.3f);
  Mesh whole = marching_cubes(volume);
  set_normals_from_surface_distance(volume, whole);
  Mesh piece;
  for (size_t i = 0; i < whole.positions.size(); i += 7)
    piece.positions.push_back(whole.positions[i]);
  piece.normals.assign(piece.positions.size(), glm::vec3(0, 0, 1));
  set_normals_from_surface_distance(volume, piece);
  for (size_t k = 0; k < piece.positions.size(); ++k) {
    const glm::vec3 a = whole.normals[k * 7], b = piece.normals[k];
    EXPECT_NEAR(glm::dot(a, b), 1.0f, 1e-5f) << k;
  }
}

TEST(SurfaceNormals, ABricksMeshGetsTheWholeMeshsNormalsAtEveryLevel) {
  // What the window re-shades is one brick's mesh at a time, at that
  // brick's level: its normals must be those of the whole surface at the
  // same points, up to the brick's faces, or bricks show as shading squares.
  const Volume volume = sphere_volume(64, 0.3f);
  for (int level : {0, 1, 2}) {
    Mesh whole = marching_cubes(volume, level);
    set_normals_from_surface_distance(volume, whole);
    for (const glm::vec3 lo :
         {glm::vec3(16, 16, 32), glm::vec3(32, 16, 16), glm::vec3(8, 24, 24)}) {
      Mesh brick;
      std::vector<size_t> from;
      for (size_t i = 0; i < whole.positions.size(); ++i) {
        const glm::vec3 p = whole.positions[i] - lo;
        if (glm::all(glm::greaterThanEqual(p, glm::vec3(0))) &&
            glm::all(glm::lessThanEqual(p, glm::vec3(16)))) {
          brick.positions.push_back(whole.positions[i]);
          from.push_back(i);
        }
      }
      ASSERT_GT(brick.positions.size(), 4u) << level;
      brick.normals.assign(brick.positions.size(), glm::vec3(0, 0, 1));
      set_normals_from_surface_distance(volume, brick);
      for (size_t k = 0; k < brick.positions.size(); ++k)
        ASSERT_NEAR(glm::dot(whole.normals[from[k]], brick.normals[k]), 1.0f, 1e-5f)
            << "level " << level << ", vertex at " << brick.positions[k].x << " "
            << brick.positions[k].y << " " << brick.positions[k].z;
    }
  }
}

}  // namespace
}  // namespace sculpt::core
