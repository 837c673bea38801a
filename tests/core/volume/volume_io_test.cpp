#include "sculpt/core/volume/volume_io.h"

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <filesystem>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

namespace fs = std::filesystem;

class VolumeIoTest : public ::testing::Test {
 protected:
  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
};

TEST_F(VolumeIoTest, StreamedReadEqualsTheDenseGrid) {
  DenseGrid<uint8_t> g = sphere_density(70);
  g.at(69, 69, 69) = 3;  // a detail in the padded corner brick
  ASSERT_TRUE(write_nrrd(dir_ / "in.nrrd", g).ok());
  const auto v = read_volume_nrrd(dir_ / "in.nrrd");
  ASSERT_TRUE(v.ok()) << v.error().message();
  EXPECT_EQ(v->dims(), glm::ivec3(70));
  EXPECT_EQ(v->to_dense(), g);
}

TEST_F(VolumeIoTest, WritesEveryLevel) {
  const Volume v = sphere_volume(80);
  for (int level = 0; level <= v.levels(); ++level) {
    const fs::path p = dir_ / ("level" + std::to_string(level) + ".nrrd");
    ASSERT_TRUE(write_volume_nrrd(p, v, level).ok());
    const auto back = read_nrrd_u8(p);
    ASSERT_TRUE(back.ok()) << back.error().message();
    EXPECT_EQ(*back, v.to_dense(level)) << "level " << level;
  }
}

TEST_F(VolumeIoTest, RefusesDistanceFieldsAndOversizedBrickSettings) {
  ASSERT_TRUE(write_nrrd(dir_ / "f.nrrd", DenseGrid<float>({2, 2, 2}, 1.0f)).ok());
  const auto r = read_volume_nrrd(dir_ / "f.nrrd");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message().find("holds float voxels: map them to density with --window"),
            std::string::npos)
      << r.error().message();
}

}  // namespace
}  // namespace sculpt::core
