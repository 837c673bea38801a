// Marching cubes on the reference shapes: the surface must be closed,
// manifold, of the right genus, the right size and facing outward.

#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"
#include "sphere_normal_error.h"

namespace sculpt::core {
namespace {

constexpr double kPi = std::numbers::pi;

// Share of vertices whose normal agrees with the winding of their triangles.
double outward_normal_share(const Mesh& mesh) {
  std::vector<glm::dvec3> face_sum(mesh.positions.size(), glm::dvec3(0.0));
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k)
      face_sum[t[k]] += n;
  }
  int64_t agree = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    agree += glm::dot(face_sum[v], glm::dvec3(mesh.normals[v])) > 0.0;
  }
  return static_cast<double>(agree) / static_cast<double>(mesh.positions.size());
}

void expect_closed_manifold(const Mesh& mesh, int64_t euler) {
  const MeshTopology t = check_topology(mesh);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.nonmanifold_edges, 0);
  EXPECT_EQ(t.misoriented_edges, 0);
  EXPECT_EQ(t.nonmanifold_vertices, 0);
  EXPECT_EQ(t.degenerate_triangles, 0);
  EXPECT_TRUE(t.manifold());
  EXPECT_EQ(t.euler_characteristic(), euler);
  EXPECT_EQ(t.vertices, static_cast<int64_t>(mesh.positions.size())) << "unused vertices";
}

TEST(MarchingCubes, SphereIsClosedRoundAndOutward) {
  const int n = 128;
  const Volume v = sphere_volume(n);
  const Mesh mesh = marching_cubes(v);
  expect_closed_manifold(mesh, 2);
  EXPECT_EQ(component_count(mesh), 1);
  const double r = 0.35 * n;
  EXPECT_NEAR(surface_area(mesh), 4.0 * kPi * r * r, 0.01 * 4.0 * kPi * r * r);
  EXPECT_NEAR(enclosed_volume(mesh), 4.0 / 3.0 * kPi * r * r * r,
              0.01 * 4.0 / 3.0 * kPi * r * r * r);
  // Every vertex lies on the sphere and its normal points away from the centre.
  const glm::vec3 c(static_cast<float>(n - 1) / 2.0f);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 radial = mesh.positions[i] - c;
    ASSERT_NEAR(glm::length(radial), r, 0.1) << "vertex " << i;
    ASSERT_GT(glm::dot(glm::normalize(radial), mesh.normals[i]), 0.99f) << "vertex " << i;
  }
  EXPECT_EQ(outward_normal_share(mesh), 1.0);
}

// The density ramps over two voxels across the surface and is clipped to 0
// and 255 beyond: a central difference reaching past the ramp reads that
// axis's slope short, and the normal tilts by how far the surface lies
// between grid points, which on a sphere is rings of shading. The
// differences on the ramp's side keep the normals on the sphere's, at every
// radius (22 to 101 voxels here; the demo's biggest ball is 66).
TEST(MarchingCubes, DensityNormalsFollowTheSurface) {
  for (const float r_frac : {0.1f, 0.35f, 0.45f}) {
    const int n = 224;
    const Volume v = sphere_volume(n, r_frac);
    const test::NormalError e =
        test::sphere_normal_error(marching_cubes(v), glm::vec3(static_cast<float>(n - 1) / 2.0f));
    std::printf("radius %.1f: normals off the sphere's by %.3f degrees on average, %.3f at most\n",
                static_cast<double>(r_frac) * n, e.mean_deg, e.max_deg);
    EXPECT_LT(e.mean_deg, 0.5);
    EXPECT_LT(e.max_deg, 2.0);
  }
}

TEST(MarchingCubes, TorusHasGenusOne) {
  const glm::vec3 c(63.5f);
  const float big = 36.0f, small = 14.0f;
  const Volume v = Volume::from_dense(torus_density(glm::ivec3(128), c, big, small));
  const Mesh mesh = marching_cubes(v);
  expect_closed_manifold(mesh, 0);
  EXPECT_EQ(component_count(mesh), 1);
  const double area = 4.0 * kPi * kPi * big * small;
  const double volume = 2.0 * kPi * kPi * big * small * small;
  EXPECT_NEAR(surface_area(mesh), area, 0.01 * area);
  EXPECT_NEAR(enclosed_volume(mesh), volume, 0.01 * volume);
  EXPECT_GT(outward_normal_share(mesh), 0.999);
}

TEST(MarchingCubes, BoxFacesAreExact) {
  // Faces between voxel centres: the density is linear across each face, so
  // marching cubes places the flat faces exactly; only the edges and corners,
  // where the distance field bends, are cut by less than a voxel.
  const glm::vec3 lo(20.25f, 15.5f, 10.75f), hi(100.25f, 105.5f, 110.75f);
  const Volume v = Volume::from_dense(box_density(glm::ivec3(128), lo, hi));
  const Mesh mesh = marching_cubes(v);
  expect_closed_manifold(mesh, 2);
  const glm::dvec3 s = glm::dvec3(hi - lo);
  const double area = 2.0 * (s.x * s.y + s.y * s.z + s.z * s.x);
  const double volume = s.x * s.y * s.z;
  EXPECT_NEAR(surface_area(mesh), area, 0.01 * area);
  EXPECT_NEAR(enclosed_volume(mesh), volume, 0.01 * volume);
  EXPECT_GT(outward_normal_share(mesh), 0.999);
  // The flat part of each face lies at the box's coordinate.
  int64_t on_faces = 0;
  for (const glm::vec3& p : mesh.positions) {
    for (int a = 0; a < 3; ++a) {
      if (std::abs(p[a] - lo[a]) < 0.01f || std::abs(p[a] - hi[a]) < 0.01f) {
        ++on_faces;
        break;
      }
    }
  }
  EXPECT_GT(on_faces, static_cast<int64_t>(mesh.positions.size() * 9 / 10));
}

TEST(MarchingCubes, NoiseHasNoHolesWhereverFacesAreAmbiguous) {
  // Random densities make every ambiguous face configuration occur many
  // times, also across brick boundaries.
  DenseGrid<uint8_t> noise{glm::ivec3(40, 37, 35)};
  uint32_t s = 987654321u;
  for (uint8_t& v : noise.values()) {
    s = s * 1664525u + 1013904223u;
    v = static_cast<uint8_t>(s >> 24);
  }
  VolumeOptions o;
  o.brick_edge = 16;
  o.levels = 4;
  const Volume v = Volume::from_dense(noise, o);
  for (float iso : {127.5f, 60.0f, 200.5f}) {
    MarchingCubesOptions mo;
    mo.iso = iso;
    const Mesh mesh = marching_cubes(v, 0, mo);
    const MeshTopology t = check_topology(mesh);
    EXPECT_TRUE(t.closed()) << "iso " << iso << ": " << t.boundary_edges << " boundary, "
                            << t.nonmanifold_edges << " non-manifold, " << t.misoriented_edges
                            << " misoriented edges";
    EXPECT_EQ(t.nonmanifold_vertices, 0) << "iso " << iso;
    EXPECT_GT(enclosed_volume(mesh), 0.0) << "iso " << iso;
  }
}

TEST(MarchingCubes, SolidTouchingTheVolumeFacesIsClosed) {
  // The outside reads empty, so material up to the faces is closed off there.
  const Volume v(glm::ivec3(20, 33, 7), 255);
  const Mesh mesh = marching_cubes(v);
  expect_closed_manifold(mesh, 2);
  // Faces half a voxel outside the outer voxel centres (255 and 0 cross at
  // the middle), so the mesh spans exactly [-0.5, dims - 0.5].
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  EXPECT_EQ(lo, glm::vec3(-0.5f));
  EXPECT_EQ(hi, glm::vec3(19.5f, 32.5f, 6.5f));
  // Marching cubes cuts a prism of section 1/8 off every edge of the block.
  const double edges = 4.0 * (20 + 33 + 7);
  EXPECT_LT(enclosed_volume(mesh), 20.0 * 33.0 * 7.0);
  EXPECT_GT(enclosed_volume(mesh), 20.0 * 33.0 * 7.0 - edges / 8.0);
}

TEST(MarchingCubes, EmptyAndFullBricksGiveNothing) {
  EXPECT_TRUE(marching_cubes(Volume(glm::ivec3(64), 0)).triangles.empty());
  EXPECT_TRUE(marching_cubes(Volume(glm::ivec3(64), 127)).triangles.empty());
}

TEST(MarchingCubes, CoarseLevelMatchesTheShapeInVoxelUnits) {
  const int n = 128;
  const Volume v = sphere_volume(n);
  const double r = 0.35 * n;
  for (int level = 1; level <= 3; ++level) {
    const Mesh mesh = marching_cubes(v, level);
    expect_closed_manifold(mesh, 2);
    const double exact = 4.0 / 3.0 * kPi * r * r * r;
    // Averaging over 2^k voxels and chords across 2^k-voxel cells shrink a
    // convex shape by an amount that grows with the square of the cell size:
    // 0.3% at level 1 (measured 0.24%), four times more per level.
    const double tolerance = 0.003 * std::pow(4.0, level - 1);
    EXPECT_NEAR(enclosed_volume(mesh), exact, tolerance * exact) << "level " << level;
    // Level-k voxel i is placed at i 2^k: the mesh is the sphere shifted by
    // (2^k - 1) / 2 voxels toward the origin on each axis.
    glm::dvec3 mean(0.0);
    for (const glm::vec3& p : mesh.positions)
      mean += glm::dvec3(p);
    mean /= static_cast<double>(mesh.positions.size());
    const double shift = ((1 << level) - 1) / 2.0;
    EXPECT_NEAR(glm::length(mean - glm::dvec3((n - 1) / 2.0 - shift)), 0.0, 0.05)
        << "level " << level;
    EXPECT_LT(mesh.triangles.size(), marching_cubes(v, level - 1).triangles.size() / 3);
  }
}

}  // namespace
}  // namespace sculpt::core
