#include "sculpt/station/view/tool_outline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {
namespace {

TEST(ToolOutline, ASmallToolIsMeshedWhole) {
  const core::Tool tool = core::make_sphere_tool(12.0f);
  const core::Mesh outline = tool_outline(tool);
  const core::Mesh whole = core::marching_cubes(core::Volume::from_dense(tool.density), 0);
  // The same surface (marched with empty cells round it, shifted back).
  ASSERT_EQ(outline.positions.size(), whole.positions.size());
  for (size_t i = 0; i < whole.positions.size(); ++i)
    EXPECT_LT(glm::length(outline.positions[i] - whole.positions[i]), 1e-4f) << i;
  EXPECT_EQ(outline.triangles, whole.triangles);
}

double signed_volume(const core::Mesh& m) {
  double v = 0;
  for (const glm::uvec3& t : m.triangles)
    v += glm::dot(m.positions[t.x], glm::cross(m.positions[t.y], m.positions[t.z])) / 6.0;
  return v;
}

// A cube's grid ends where its density does: marched as it is, its faces
// on the grid stayed open, and a carving stand-in needs it closed.
TEST(ToolOutline, IsClosedWhereTheToolFillsItsGrid) {
  const core::Mesh outline = tool_outline(core::make_cube_tool(20.0f));
  const core::MeshTopology topology = core::check_topology(outline);
  EXPECT_EQ(topology.boundary_edges, 0);
  EXPECT_EQ(topology.misoriented_edges, 0);
  EXPECT_NEAR(signed_volume(outline), 20.0 * 20.0 * 20.0, 400.0);  // outward, the cube's
}

// What the window draws for a tool that is not a ball: its outline
// simplified, closed still, enclosing the same volume, with a fraction of
// the march's triangles (a cube's faces are flat).
TEST(ToolOutline, TheDrawnOutlineIsTheMarchSimplified) {
  for (const core::Tool& tool : {core::make_cube_tool(20.0f), core::make_cube_tool(100.0f)}) {
    const core::Mesh marched = tool_outline(tool);
    const core::Mesh drawn = drawn_outline(tool);
    const core::MeshTopology topology = core::check_topology(drawn);
    EXPECT_EQ(topology.boundary_edges, 0);
    EXPECT_EQ(topology.misoriented_edges, 0);
    EXPECT_EQ(topology.euler_characteristic(), 2);
    EXPECT_LT(20 * drawn.triangles.size(), marched.triangles.size());
    EXPECT_NEAR(signed_volume(drawn), signed_volume(marched), 0.01 * signed_volume(marched));
    EXPECT_EQ(window_tool_outline(tool).triangles, drawn.triangles);
  }
}

TEST(ToolOutline, ABallIsASphereAtItsSurfaceLevel) {
  for (const float hardness : {1.0f, 0.3f}) {
    const core::Tool ball = core::make_sphere_tool(24.0f, hardness);
    const core::Mesh sphere = ball_outline(ball);
    const core::Mesh marched = tool_outline(ball, kStandInCells);
    EXPECT_EQ(core::check_topology(sphere).misoriented_edges, 0);
    // Where the marched surface is, on average, and facing out.
    double marched_radius = 0;
    for (const glm::vec3& p : marched.positions)
      marched_radius += glm::length(p - ball.pivot);
    marched_radius /= static_cast<double>(marched.positions.size());
    for (const glm::vec3& p : sphere.positions)
      EXPECT_NEAR(glm::length(p - ball.pivot), marched_radius, 0.2) << hardness;
    EXPECT_GT(signed_volume(sphere), 0.0);
    EXPECT_NEAR(signed_volume(sphere) / signed_volume(marched), 1.0, 0.03) << hardness;
  }
}

TEST(ToolOutline, ABigToolIsMeshedCoarseInItsPlace) {
  // A 100-voxel ball: 205 voxels a side, averaged 4 to 1 (52 cells a side).
  const float radius = 100.0f;
  const core::Tool tool = core::make_sphere_tool(radius);
  const core::Mesh outline = tool_outline(tool);
  ASSERT_FALSE(outline.triangles.empty());
  // Whole, the ball has ~16 times the triangles; averaged, far fewer.
  EXPECT_LT(outline.triangles.size(), 40'000u);
  double worst = 0;
  for (const glm::vec3& p : outline.positions)
    worst = std::max(worst, std::abs(static_cast<double>(glm::length(p - tool.pivot)) - radius));
  // Within a coarse voxel (4) of the ball's surface, in the tool's coordinates.
  EXPECT_LT(worst, 4.0);
  EXPECT_GT(outline.positions.size(), 1000u);
}

// The window draws a ball as a sphere: few triangles, every edge's midpoint
// near the ball's surface (the silhouette is made of edges).
// A dab's stand-in is the same sphere, and its coarse one (drawn when many
// wait) about within kCoarseBallErrorVox.
TEST(ToolOutline, TheWindowDrawsABallAsASphereOfFewTriangles) {
  for (const float radius : {6.0f, 20.0f, 47.0f, 48.0f, 66.0f, 110.0f}) {
    const core::Tool ball = core::make_sphere_tool(radius);
    const float surface = glm::length(ball_outline(ball).positions.front() - ball.pivot);
    // How far inside the sphere an edge's midpoint lies, at worst.
    auto worst_dip = [&](const core::Mesh& drawn) {
      float worst = 0.0f;
      for (const glm::uvec3& t : drawn.triangles)
        for (int k = 0; k < 3; ++k) {
          const glm::vec3 mid = 0.5f * (drawn.positions[t[k]] + drawn.positions[t[(k + 1) % 3]]);
          worst = std::max(worst, surface - glm::length(mid - ball.pivot));
        }
      return worst;
    };
    const core::Mesh drawn = window_tool_outline(ball);
    const core::Mesh stand_in = stand_in_outline(ball), coarse = stand_in_outline(ball, true);
    std::printf("radius %.0f: %zu triangles, edge midpoints within %.3f voxel; coarse %zu\n",
                radius, drawn.triangles.size(), worst_dip(drawn), coarse.triangles.size());
    EXPECT_EQ(core::check_topology(drawn).misoriented_edges, 0) << radius;
    EXPECT_LT(worst_dip(drawn), kWindowBallErrorVox + 1e-3f) << radius;
    // Marched at 2:1, the 66-voxel ball was 29k triangles.
    EXPECT_LT(drawn.triangles.size(), 8'000u) << radius;
    EXPECT_EQ(stand_in.triangles, drawn.triangles) << radius;
    // Its longer edges bend more than the estimate the edge comes from
    // allows for (0.61 voxel at 66 voxels).
    EXPECT_LT(worst_dip(coarse), 1.05f * kCoarseBallErrorVox) << radius;
    EXPECT_LT(coarse.triangles.size(), drawn.triangles.size() / 2) << radius;
  }
}

}  // namespace
}  // namespace sculpt::station
