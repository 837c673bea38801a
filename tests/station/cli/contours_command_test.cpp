// The `sculpt contours` command-line contract: the branching stack becomes a
// closed surface, as a volume or a mesh.

#include <gtest/gtest.h>

#include <filesystem>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;
const std::string kData = SCULPT_TEST_DATA_DIR "/distance/";

TEST(ContoursCommand, BranchingStackToVolumeAndClosedMesh) {
  sculpt::test::ScratchDir scratch;
  const CommandResult mesh =
      run_sculpt("contours " + kData + "branching.contours -o " + scratch.file("c.ply"));
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  EXPECT_NE(mesh.out.find("closed, 1 components, Euler characteristic 2"), std::string::npos)
      << mesh.out;
  EXPECT_GT(fs::file_size(scratch.file("c.ply")), 1000u);
  const CommandResult vol =
      run_sculpt("contours " + kData + "branching.contours -o " + scratch.file("c.nrrd"));
  ASSERT_EQ(vol.exit_code, 0) << vol.err;
  auto v = core::read_nrrd_u8(scratch.file("c.nrrd"));
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->dims(), glm::ivec3(48, 48, 40));
  EXPECT_GT(v->at(14, 24, 30), 127);
  EXPECT_LT(v->at(24, 24, 30), 128);
}

TEST(ContoursCommand, BadInputIsOneLineAndNoOutput) {
  sculpt::test::ScratchDir scratch;
  const CommandResult r =
      run_sculpt("contours " + kData + "unclosed.contours -o " + scratch.file("c.nrrd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("unclosed.contours"), std::string::npos);
  EXPECT_FALSE(fs::exists(scratch.file("c.nrrd")));
  const CommandResult ext =
      run_sculpt("contours " + kData + "branching.contours -o " + scratch.file("c.xyz"));
  EXPECT_EQ(ext.exit_code, 1);
  EXPECT_NE(ext.err.find("c.xyz"), std::string::npos);
  EXPECT_FALSE(fs::exists(scratch.file("c.xyz")));
}

}  // namespace
}  // namespace sculpt::station::test
