// The `sculpt voxelize` command-line contract and the mesh -> volume ->
// mesh round trip.

#include <gtest/gtest.h>

#include <filesystem>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;
const std::string kData = SCULPT_TEST_DATA_DIR "/distance/";

class VoxelizeCommandTest : public ::testing::Test {
 protected:
  sculpt::test::ScratchDir scratch_;
  std::string path(const std::string& name) const { return scratch_.file(name); }
};

TEST_F(VoxelizeCommandTest, RoundTripKeepsTheShape) {
  for (const char* mesh : {"octahedron.obj", "octahedron.ply", "octahedron.stl"}) {
    const CommandResult r =
        run_sculpt("voxelize " + kData + mesh + " --size 48 --margin 4 -o " + path("v.nrrd"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("grid = mesh * 19.5 + (23.5, 23.5, 23.5)"), std::string::npos) << r.out;
    auto v = core::read_nrrd_u8(path("v.nrrd"));
    ASSERT_TRUE(v.ok());
    // The octahedron |x|+|y|+|z| <= 19.5 around 23.5: its volume is
    // 4/3 19.5^3 = 9886.5 voxels; meshing the density gives it back.
    const core::Mesh m = core::marching_cubes(core::Volume::from_dense(*v));
    EXPECT_TRUE(core::check_topology(m).manifold());
    EXPECT_NEAR(core::enclosed_volume(m), 9886.5, 9886.5 * 0.03) << mesh;
  }
  const CommandResult sdf =
      run_sculpt("voxelize " + kData + "octahedron.obj --size 48 --sdf -o " + path("s.nrrd"));
  ASSERT_EQ(sdf.exit_code, 0) << sdf.err;
  auto s = core::read_nrrd_f32(path("s.nrrd"));
  ASSERT_TRUE(s.ok());
  // Centre: 19.5 / sqrt 3 inside the faces.
  EXPECT_NEAR(s->at(23, 23, 23), -(19.5f - 1.5f) / std::sqrt(3.0f), 0.01f);
}

TEST_F(VoxelizeCommandTest, BadMeshesAreOneLineErrorsAndNoOutput) {
  for (const auto& [file, words] : std::vector<std::pair<std::string, std::string>>{
           {"open_octahedron.obj", "not closed"},
           {"bad_index.obj", "line 4"},
           {"none.obj", "cannot open"},
           {"branching.contours", "unknown mesh extension"}}) {
    const CommandResult r =
        run_sculpt("voxelize " + kData + file + " --size 32 -o " + path("v.nrrd"));
    EXPECT_EQ(r.exit_code, 1) << file;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("v.nrrd")));
  }
  // A size out of range is bad input: one line, exit 1.
  const CommandResult small =
      run_sculpt("voxelize " + kData + "octahedron.obj --size 2 -o " + path("v.nrrd"));
  EXPECT_EQ(small.exit_code, 1);
  EXPECT_EQ(line_count(small.err), 1) << small.err;
}

}  // namespace
}  // namespace sculpt::station::test
