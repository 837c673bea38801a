// The ball brushes' blur (brush_field.h) against its definition: passes of
// [1 2 1] / 4 along x, y and z, edges clamped, each voxel from the pass
// before. Recorded sessions replay to the same volume only if every float
// comes out the same, so the comparison is exact.

#include <random>

#include <gtest/gtest.h>

#include "sculpt/brush_field.h"

namespace sculpt::core {
namespace {

void blur_by_definition(DenseGrid<float>& g, int passes) {
  const glm::ivec3 d = g.dims();
  for (int k = 0; k < passes; ++k)
    for (int axis = 0; axis < 3; ++axis) {
      const DenseGrid<float> was = g;
      for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
          for (int x = 0; x < d.x; ++x) {
            glm::ivec3 lo(x, y, z), hi(x, y, z);
            lo[axis] = std::max(lo[axis] - 1, 0);
            hi[axis] = std::min(hi[axis] + 1, d[axis] - 1);
            g.at(x, y, z) = 0.25f * was.at(lo.x, lo.y, lo.z) + 0.5f * was.at(x, y, z) +
                            0.25f * was.at(hi.x, hi.y, hi.z);
          }
    }
}

TEST(BrushBlur, IsItsDefinitionBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> density(0.0f, 255.0f);
  for (const glm::ivec3 dims :
       {glm::ivec3(1, 1, 1), glm::ivec3(2, 3, 1), glm::ivec3(17, 9, 23), glm::ivec3(33, 1, 8)}) {
    DenseGrid<float> grid(dims);
    for (float& v : grid.values())
      v = density(rng);
    DenseGrid<float> expected = grid;
    blur_by_definition(expected, 4);
    brush::blur(grid, 4);
    ASSERT_EQ(grid.values(), expected.values()) << dims.x << "x" << dims.y << "x" << dims.z;
  }
}

}  // namespace
}  // namespace sculpt::core
