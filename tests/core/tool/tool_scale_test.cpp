// A tool at another size keeps its shape: the density's volume scales by the
// cube of the factor (within 1%), the pivot stays at the same point of the
// shape, and factor 1 changes nothing.
#include "sculpt/core/tool/tool_scale.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

double volume_of(const Tool& t) {
  double sum = 0.0;
  for (uint8_t v : t.density.values())
    sum += v;
  return sum / 255.0;
}

glm::dvec3 centroid_of(const Tool& t) {
  glm::dvec3 c(0.0);
  double sum = 0.0;
  const glm::ivec3 d = t.density.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const double w = t.density.at(x, y, z);
        c += w * glm::dvec3(x, y, z);
        sum += w;
      }
  return c / sum;
}

TEST(ToolScale, KeepsTheShapesVolumeAndPivot) {
  const Tool shapes[] = {make_sphere_tool(12.0f), make_cube_tool(17.0f),
                         make_cylinder_tool(8.0f, 20.0f), make_ring_tool(11.0f, 4.0f)};
  for (const Tool& tool : shapes) {
    const double before = volume_of(tool);
    for (float factor : {0.5f, 1.5f, 2.0f, 3.0f}) {
      const Tool scaled = scale_tool(tool, factor);
      // The factor each axis really took (dims are whole voxels).
      const glm::dvec3 s = glm::dvec3(scaled.density.dims()) / glm::dvec3(tool.density.dims());
      const double want = before * s.x * s.y * s.z;
      EXPECT_NEAR(volume_of(scaled), want, 0.01 * want)
          << tool.density.dims().x << " by " << factor;
      // Symmetric shapes: the pivot is their centre, before and after.
      EXPECT_LT(glm::length(centroid_of(scaled) - glm::dvec3(scaled.pivot)), 0.05)
          << tool.density.dims().x << " by " << factor;
    }
  }
}

TEST(ToolScale, FactorOneIsTheSameTool) {
  const Tool tool = make_ring_tool(9.0f, 3.5f, 0.4f);
  const Tool same = scale_tool(tool, 1.0f);
  EXPECT_EQ(same.density.dims(), tool.density.dims());
  EXPECT_EQ(same.density.values(), tool.density.values());
  EXPECT_EQ(same.pivot, tool.pivot);
  EXPECT_EQ(same.hardness, tool.hardness);
}

TEST(ToolScale, TheSmallestScaleLeavesAtLeastOneVoxel) {
  const Tool tiny = scale_tool(make_sphere_tool(1.0f), kMinToolScale);
  EXPECT_GE(tiny.density.dims().x, 1);
  EXPECT_GE(tiny.density.dims().y, 1);
  EXPECT_GE(tiny.density.dims().z, 1);
}

}  // namespace
}  // namespace sculpt::core
