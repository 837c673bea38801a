#include "sculpt/core/nurbs/surface_tessellator.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "nurbs_fixtures.h"
#include "sculpt/core/nurbs/influence.h"
#include "sculpt/core/nurbs/path_deformation.h"

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

double max_gap(const Mesh& a, const Mesh& b) {
  double worst = 0.0;
  for (size_t k = 0; k < a.positions.size(); ++k) {
    worst = std::max(worst, static_cast<double>(glm::length(a.positions[k] - b.positions[k])));
    worst = std::max(worst, 1e3 * static_cast<double>(glm::length(a.normals[k] - b.normals[k])));
  }
  return worst;
}

TEST(SurfaceTessellator, RigidMotionsMoveWholeSupportsAndMatchARebuild) {
  NurbsSurface s = example_sheet();
  SurfaceTessellator t(s, 4);
  const int64_t evaluated = t.vertices_evaluated();
  RigidMotion m{rotation_between({1, 0, 0}, {1, 0.3, 0.2}), {60, 40, 0}, {2, -1, 7}};
  std::vector<int> moved;
  for (int j = 2; j <= 7; ++j) {
    for (int i = 3; i <= 10; ++i) {
      moved.push_back(s.index(i, j));
      s.point(i, j) = m.apply(s.point(i, j));
    }
  }
  t.update(s, moved, &m);
  // Spans whose 4 x 4 support lies inside the 8 x 6 block: u spans 6..10,
  // v spans 5..7, 4 x 4 vertex samples each.
  EXPECT_EQ(t.vertices_moved_rigidly(), (5 * 4) * (3 * 4));
  EXPECT_GT(t.vertices_evaluated(), evaluated);
  EXPECT_LT(max_gap(t.mesh(), SurfaceTessellator(s, 4).mesh()), 1e-4);
}

TEST(SurfaceTessellator, FollowsAWholePathStepByStep) {
  const NurbsSurface sheet = example_sheet();
  ParameterZone zone;
  zone.radius = 0.3;
  const NurbsSurface s = refine_in_zone(sheet, 0.5, 0.5, zone, 60).value();
  const glm::dvec3 a = evaluate(s, 0.5, 0.5);
  NurbsCurve path;
  path.degree = 2;
  path.knots = {0, 0, 0, 1, 1, 1};
  path.points = {a, a + glm::dvec3(0, 0, 40), a + glm::dvec3(30, 0, 40)};
  PathOptions o;
  o.steps = 30;
  PathDeformation d =
      PathDeformation::from_curve(s, 0.5, 0.5, zone_influence(s, 0.5, 0.5, zone).value(), path, o)
          .value();
  SurfaceTessellator t(s, 4);
  while (!d.done()) {
    const PathStep step = d.step();
    t.update(d.surface(), step.moved, step.motion ? &*step.motion : nullptr);
  }
  EXPECT_GT(t.vertices_moved_rigidly(), 0);
  EXPECT_LT(max_gap(t.mesh(), SurfaceTessellator(d.surface(), 4).mesh()), 1e-4);
}

// Without the rigid shortcut every touched vertex is re-evaluated, so after
// each step of a whole path the incremental mesh must be the from-scratch
// one bit for bit, whatever the number of cells per patch (runs of 1 to 6
// vertices per patch row with these cell counts).
TEST(SurfaceTessellator, IncrementalUpdatesEqualAFromScratchTessellationAtEveryStep) {
  const NurbsSurface sheet = example_sheet();
  ParameterZone zone;
  zone.radius = 0.3;
  const NurbsSurface s = refine_in_zone(sheet, 0.5, 0.5, zone, 60).value();
  const glm::dvec3 a = evaluate(s, 0.5, 0.5);
  NurbsCurve path;
  path.degree = 2;
  path.knots = {0, 0, 0, 1, 1, 1};
  path.points = {a, a + glm::dvec3(0, 0, 40), a + glm::dvec3(30, 0, 40)};
  PathOptions o;
  o.steps = 12;
  PathDeformation d =
      PathDeformation::from_curve(s, 0.5, 0.5, zone_influence(s, 0.5, 0.5, zone).value(), path, o)
          .value();
  SurfaceTessellator per_span(s, 3);
  SurfaceTessellator cells = SurfaceTessellator::with_cells(s, 70, 41);
  int touched = 0;
  while (!d.done()) {
    const PathStep step = d.step();
    touched += per_span.update(d.surface(), step.moved);
    cells.update(d.surface(), step.moved);
    ASSERT_EQ(per_span.mesh(), SurfaceTessellator(d.surface(), 3).mesh()) << "step " << step.step;
    ASSERT_EQ(cells.mesh(), SurfaceTessellator::with_cells(d.surface(), 70, 41).mesh())
        << "step " << step.step;
  }
  EXPECT_GT(touched, 0);
  EXPECT_EQ(per_span.vertices_moved_rigidly(), 0);
  // Only touched patches were evaluated: fewer than a rebuild per step.
  EXPECT_LT(per_span.vertices_evaluated(),
            int64_t(o.steps + 1) * per_span.vertices_u() * per_span.vertices_v());
}

TEST(SurfaceTessellator, CellsOverTheDomainKeepTheMeshSizeThroughRefinement) {
  const NurbsSurface s = example_sheet();  // 12 x 7 equal spans
  const SurfaceTessellator before = SurfaceTessellator::with_cells(s, 48, 28);
  EXPECT_EQ(before.vertices_u(), 49);
  EXPECT_EQ(before.vertices_v(), 29);
  EXPECT_EQ(before.mesh(), SurfaceTessellator(s, 4).mesh());
  // Halving two spans twice: they get 2 and 1 cells, the mesh stays 49 wide.
  const std::vector<double> x{0.5 + 1.0 / 48, 0.5 + 2.0 / 48, 0.5 + 3.0 / 48,
                              0.5 + 5.0 / 48, 0.5 + 6.0 / 48, 0.5 + 7.0 / 48};
  const NurbsSurface r = refine_u(s, x);
  const SurfaceTessellator after = SurfaceTessellator::with_cells(r, 48, 28);
  EXPECT_EQ(after.patches_u(), 18);
  EXPECT_EQ(after.vertices_u(), 49);
  double worst = 0.0;
  for (size_t k = 0; k < after.mesh().positions.size(); ++k) {
    worst = std::max(worst, static_cast<double>(glm::length(after.mesh().positions[k] -
                                                            before.mesh().positions[k])));
  }
  EXPECT_LT(worst, 1e-4);  // the same samples of the same surface
}

}  // namespace
}  // namespace sculpt::core::nurbs
