#include "sculpt/station/view/tool_outline.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {
namespace {

TEST(ToolOutline, ASmallToolIsMeshedWhole) {
  const core::Tool tool = core::make_sphere_tool(12.0f);
  const core::Mesh outline = tool_outline(tool);
  const core::Mesh whole = core::marching_cubes(core::Volume::from_dense(tool.density), 0);
  EXPECT_EQ(outline.positions, whole.positions);
  EXPECT_EQ(outline.triangles.size(), whole.triangles.size());
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

}  // namespace
}  // namespace sculpt::station
