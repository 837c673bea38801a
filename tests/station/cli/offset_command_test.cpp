// The `sculpt offset` command-line contract.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

TEST(OffsetCommand, InflatesAndDeflatesBySubVoxelAmounts) {
  sculpt::test::ScratchDir scratch;
  ASSERT_TRUE(
      core::write_nrrd(scratch.file("in.nrrd"), core::sphere_density(40, 0.25f)).ok());  // r 10
  const CommandResult grow = run_sculpt("offset " + scratch.file("in.nrrd") +
                                        " --by 2.5 --sdf -o " + scratch.file("g.nrrd"));
  ASSERT_EQ(grow.exit_code, 0) << grow.err;
  auto g = core::read_nrrd_f32(scratch.file("g.nrrd"));
  ASSERT_TRUE(g.ok());
  // Along +x from centre 19.5 the surface moves from 29.5 to 32.
  EXPECT_NEAR(g->at(32, 19, 19), 0.0f + (std::sqrt(12.5f * 12.5f + 0.5f) - 12.5f), 0.15f);
  const CommandResult shrink =
      run_sculpt("offset " + scratch.file("in.nrrd") + " --by -2.5 -o " + scratch.file("s.nrrd"));
  ASSERT_EQ(shrink.exit_code, 0) << shrink.err;
  auto s = core::read_nrrd_u8(scratch.file("s.nrrd"));
  ASSERT_TRUE(s.ok());
  EXPECT_GT(s->at(26, 19, 19), 127);
  EXPECT_LT(s->at(28, 19, 19), 128);

  std::ofstream(scratch.file("bad.nrrd")) << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4\n";
  const CommandResult bad =
      run_sculpt("offset " + scratch.file("bad.nrrd") + " --by 1 -o " + scratch.file("x.nrrd"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(line_count(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find("bad.nrrd"), std::string::npos);
  EXPECT_FALSE(fs::exists(scratch.file("x.nrrd")));
}

}  // namespace
}  // namespace sculpt::station::test
