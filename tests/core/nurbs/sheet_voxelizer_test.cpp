#include "sculpt/core/nurbs/sheet_voxelizer.h"

#include <gtest/gtest.h>

#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/nurbs/surface_tessellator.h"

namespace sculpt::core::nurbs {
namespace {

TEST(SheetVoxelizer, FlatSheetBecomesASlabOfTheGivenThickness) {
  // A flat 20 x 20 sheet at z = 16: a 6-voxel shell is the slab |z - 16| <= 3.
  NurbsSurface s = flat_sheet(5, 5, 3, 3, 20.0, 20.0);
  for (glm::dvec3& p : s.points)
    p += glm::dvec3(6.0, 6.0, 16.0);
  const Mesh mesh = tessellate(s, 4);
  Volume volume(glm::ivec3(32), 0, VolumeOptions{16, 4, 1});
  const Box region = voxelize_shell(mesh, 6.0, ShellMode::kAdd, volume);
  EXPECT_EQ(region.lo, glm::ivec3(2, 2, 12));
  EXPECT_EQ(region.hi, glm::ivec3(31, 31, 21));
  EXPECT_EQ(volume.voxel({16, 16, 16}), 255);
  EXPECT_EQ(volume.voxel({16, 16, 19}), 127);  // d = 3: on the iso-surface (127.5 rounded down)
  EXPECT_EQ(volume.voxel({16, 16, 20}), 0);    // a voxel out: the ramp's foot
  EXPECT_EQ(volume.voxel({16, 16, 12}), 0);
  EXPECT_EQ(volume.voxel({2, 16, 16}), 0);
  int64_t full = 0;
  const DenseGrid<uint8_t> dense = volume.to_dense();
  for (int z = 0; z < 32; ++z) {
    for (int y = 0; y < 32; ++y) {
      for (int x = 0; x < 32; ++x)
        full += dense.at(x, y, z) == 255;
    }
  }
  // 21 x 21 columns over the sheet (x, y in 6..26) x 5 full layers (14..18:
  // d <= 2, a voxel inside the iso-surface),
  // plus the rounded rim around the sheet's border.
  EXPECT_GE(full, 21 * 21 * 5);
  EXPECT_LT(full, 27 * 27 * 5);
  // Subtracting the same shell empties it again.
  voxelize_shell(mesh, 6.0, ShellMode::kSubtract, volume);
  EXPECT_EQ(volume.voxel({16, 16, 16}), 0);
  Volume solid(glm::ivec3(32), 255, VolumeOptions{16, 4, 1});
  voxelize_shell(mesh, 6.0, ShellMode::kSubtract, solid);
  EXPECT_EQ(solid.voxel({16, 16, 16}), 0);
  EXPECT_EQ(solid.voxel({16, 16, 25}), 255);
}

}  // namespace
}  // namespace sculpt::core::nurbs
