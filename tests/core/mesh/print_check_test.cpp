// The print check must pass a marched sphere, and catch what a slicer
// would choke on: a hole, a surface through itself, a flipped shell.

#include "sculpt/core/mesh/print_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

Mesh sphere_mesh() {
  return marching_cubes(sphere_volume(48));  // radius 16.8 voxels
}

// `b` moved by `offset` and appended to `a`: two shells in one mesh.
Mesh with_copy(const Mesh& a, glm::vec3 offset) {
  Mesh m = a;
  const auto base = static_cast<uint32_t>(m.positions.size());
  for (const glm::vec3& p : a.positions)
    m.positions.push_back(p + offset);
  for (const glm::uvec3& t : a.triangles)
    m.triangles.push_back(t + glm::uvec3(base));
  return m;
}

TEST(PrintCheck, AMarchedSphereIsPrintableWithItsVolumeInMillimetres) {
  const Mesh m = sphere_mesh();
  const PrintCheck c = check_print(m, 0.5);
  EXPECT_TRUE(c.topology.manifold());
  EXPECT_EQ(c.self_intersections, 0);
  EXPECT_EQ(c.components, 1);
  EXPECT_TRUE(c.printable());
  const double r_mm = 0.35 * 48 * 0.5;
  EXPECT_NEAR(c.volume_mm3, 4.0 / 3.0 * std::numbers::pi * r_mm * r_mm * r_mm, 0.02 * c.volume_mm3);
  EXPECT_NEAR(c.bounds_mm.hi.x - c.bounds_mm.lo.x, 2 * r_mm, 0.5);
}

TEST(PrintCheck, TwoShellsThroughEachOtherAreSelfIntersecting) {
  const Mesh m = sphere_mesh();
  const Mesh overlapping = with_copy(m, {10.3f, 0.0f, 0.0f});
  const PrintCheck c = check_print(overlapping, 1.0);
  EXPECT_TRUE(c.topology.manifold()) << "each shell is closed: only the crossing is wrong";
  EXPECT_GT(c.self_intersections, 0);
  EXPECT_FALSE(c.printable());
  // Apart, they are two printable parts.
  const PrintCheck apart = check_print(with_copy(m, {40.0f, 0.0f, 0.0f}), 1.0);
  EXPECT_EQ(apart.self_intersections, 0);
  EXPECT_EQ(apart.components, 2);
  EXPECT_TRUE(apart.printable());
  // The count stops at the limit asked for.
  EXPECT_EQ(count_self_intersections(overlapping, 3), 3);
}

TEST(PrintCheck, AHoleOrAnInsideOutShellIsNotPrintable) {
  Mesh hole = sphere_mesh();
  hole.triangles.pop_back();
  const PrintCheck h = check_print(hole, 1.0);
  EXPECT_GT(h.topology.boundary_edges, 0);
  EXPECT_FALSE(h.printable());
  Mesh inside_out = sphere_mesh();
  for (glm::uvec3& t : inside_out.triangles)
    std::swap(t[1], t[2]);
  const PrintCheck i = check_print(inside_out, 1.0);
  EXPECT_TRUE(i.topology.manifold());
  EXPECT_LT(i.volume_mm3, 0.0);
  EXPECT_FALSE(i.printable());
  EXPECT_FALSE(check_print(Mesh{}, 1.0).printable());
}

}  // namespace
}  // namespace sculpt::core
