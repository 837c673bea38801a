// The `sculpt distance` command-line contract.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

class DistanceCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(core::write_nrrd(path("in.nrrd"), core::sphere_density(40)).ok());
  }
  sculpt::test::ScratchDir scratch_;
  std::string path(const std::string& name) const { return scratch_.file(name); }
};

TEST_F(DistanceCommandTest, WritesASignedFloatFieldForEveryMethod) {
  for (const char* m :
       {"exact", "octree", "chamfer-345", "vcvdt", "evdt", "chamfer-city", "chamfer-5x5x5"})
    for (const char* init : {"binary", "shell"}) {
      const CommandResult r = run_sculpt("distance " + path("in.nrrd") + " --method " + m +
                                         " --init " + init + " -o " + path("d.nrrd"));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      auto d = core::read_nrrd_f32(path("d.nrrd"));
      ASSERT_TRUE(d.ok()) << d.error().message();
      // Sphere radius 14 around 19.5: voxel (20, 20, 20) is 13.13 inside.
      // Binary init measures to the centres of B, the inside voxels with an
      // outside 26-neighbour, which lie up to sqrt 3 inside the surface.
      // Chamfer transforms are off by several percent either way.
      const bool binary = std::string(init) == "binary";
      const bool chamfer = std::string(m).rfind("chamfer", 0) == 0;
      EXPECT_LE(d->at(20, 20, 20), binary || chamfer ? -11.3f : -12.9f) << m << " " << init;
      EXPECT_GE(d->at(20, 20, 20), chamfer ? -14.0f : -13.4f) << m << " " << init;
      EXPECT_GT(d->at(0, 0, 0), 18.0f) << m << " " << init;
    }
  // A float32 field is accepted as input (negative inside).
  const CommandResult again = run_sculpt("distance " + path("d.nrrd") + " -o " + path("e.nrrd"));
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST_F(DistanceCommandTest, BadInputIsOneLineNamingItAndNoOutput) {
  const CommandResult method =
      run_sculpt("distance " + path("in.nrrd") + " --method fast -o " + path("d.nrrd"));
  EXPECT_EQ(method.exit_code, 1);
  EXPECT_EQ(line_count(method.err), 1) << method.err;
  EXPECT_NE(method.err.find("fast"), std::string::npos);
  EXPECT_FALSE(fs::exists(path("d.nrrd")));

  const CommandResult missing =
      run_sculpt("distance " + path("none.nrrd") + " -o " + path("d.nrrd"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(line_count(missing.err), 1) << missing.err;
  EXPECT_NE(missing.err.find("none.nrrd"), std::string::npos);
  EXPECT_FALSE(fs::exists(path("d.nrrd")));

  ASSERT_TRUE(core::write_nrrd(path("big.nrrd"), core::DenseGrid<uint8_t>(glm::ivec3(100))).ok());
  const CommandResult brute =
      run_sculpt("distance " + path("big.nrrd") + " --method brute -o " + path("d.nrrd"));
  EXPECT_EQ(brute.exit_code, 1);
  EXPECT_NE(brute.err.find("too large for --method brute"), std::string::npos) << brute.err;

  const CommandResult no_out = run_sculpt("distance " + path("in.nrrd"));
  EXPECT_EQ(no_out.exit_code, 1);
  EXPECT_EQ(line_count(no_out.err), 1) << no_out.err;
}

TEST_F(DistanceCommandTest, AVolumeWithoutASurfaceIsRefusedNotWrittenAsInfinity) {
  // Before: an empty or solid block wrote a field of +-infinity, exit 0.
  const std::pair<const char*, uint8_t> blocks[] = {{"holds no material", 0},
                                                    {"solid throughout", 255}};
  for (const auto& [what, density] : blocks) {
    ASSERT_TRUE(
        core::write_nrrd(path("block.nrrd"), core::DenseGrid<uint8_t>(glm::ivec3(12), density))
            .ok());
    for (const std::string command :
         {"distance", "offset --by 2 --sdf", "close --radius 2 --sdf"}) {
      const CommandResult r =
          run_sculpt(command + " " + path("block.nrrd") + " -o " + path("d.nrrd"));
      EXPECT_EQ(r.exit_code, 1) << command;
      EXPECT_EQ(line_count(r.err), 1) << r.err;
      EXPECT_NE(r.err.find("block.nrrd: " + std::string(what)), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(path("d.nrrd"))) << command;
    }
    // As density, offsetting an empty or solid block is that block.
    const CommandResult density_out =
        run_sculpt("offset --by 2 " + path("block.nrrd") + " -o " + path("d.nrrd"));
    EXPECT_EQ(density_out.exit_code, 0) << density_out.err;
    fs::remove(path("d.nrrd"));
  }
}

TEST_F(DistanceCommandTest, TablePrintsEveryRow) {
  const CommandResult r = run_sculpt("distance --table --sizes 24 --methods exact,vcvdt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* row : {"| sphere | 24^3 | exact | binary |", "| sphere | 24^3 | vcvdt | shell |",
                          "| torus | 24^3 | exact | shell |"})
    EXPECT_NE(r.out.find(row), std::string::npos) << r.out;
  EXPECT_EQ(run_sculpt("distance --table --sizes 3").exit_code, 1);
}

}  // namespace
}  // namespace sculpt::station::test
