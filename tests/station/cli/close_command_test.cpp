// The `sculpt close` command-line contract: a gap narrower than 2R closes.

#include <gtest/gtest.h>

#include <filesystem>

#include <glm/geometric.hpp>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

TEST(CloseCommand, BridgesAGapAndReportsErrors) {
  sculpt::test::ScratchDir scratch;
  core::DenseGrid<uint8_t> g(glm::ivec3(44, 40, 40));
  for (int z = 0; z < 40; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 44; ++x) {
        const glm::vec3 p(x, y, z);
        g.at(x, y, z) =
            core::density_from_distance(std::min(glm::length(p - glm::vec3(13, 20, 20)),
                                                 glm::length(p - glm::vec3(29, 20, 20))) -
                                        7.0f);
      }
  ASSERT_TRUE(core::write_nrrd(scratch.file("in.nrrd"), g).ok());
  const CommandResult r =
      run_sculpt("close " + scratch.file("in.nrrd") + " --radius 3 -o " + scratch.file("c.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto c = core::read_nrrd_u8(scratch.file("c.nrrd"));
  ASSERT_TRUE(c.ok());
  EXPECT_LT(g.at(21, 20, 20), 128);
  EXPECT_GT(c->at(21, 20, 20), 127);

  const CommandResult sdf = run_sculpt("close " + scratch.file("in.nrrd") +
                                       " --radius 3 --sdf -o " + scratch.file("s.nrrd"));
  ASSERT_EQ(sdf.exit_code, 0) << sdf.err;
  EXPECT_TRUE(core::read_nrrd_f32(scratch.file("s.nrrd")).ok());

  const CommandResult missing =
      run_sculpt("close " + scratch.file("none.nrrd") + " --radius 3 -o " + scratch.file("x.nrrd"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(line_count(missing.err), 1);
  EXPECT_NE(missing.err.find("none.nrrd"), std::string::npos);
  EXPECT_FALSE(fs::exists(scratch.file("x.nrrd")));
  const CommandResult negative =
      run_sculpt("close " + scratch.file("in.nrrd") + " --radius -1 -o " + scratch.file("x.nrrd"));
  EXPECT_EQ(negative.exit_code, 1);  // a value out of range is bad input
  EXPECT_EQ(line_count(negative.err), 1) << negative.err;
}

}  // namespace
}  // namespace sculpt::station::test
