// The `sculpt wavelet` and `sculpt run` command-line contract (DESIGN.md §7).

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <filesystem>

#include "run_sculpt.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

class WaveletCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    input_ = sculpt::core::sphere_density(70);
    input_.at(5, 6, 7) = 99;
    ASSERT_TRUE(sculpt::core::write_nrrd(dir_ / "in.nrrd", input_).ok());
  }

  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
  std::string path(const std::string& name) const { return scratch_.file(name); }
  sculpt::core::DenseGrid<uint8_t> input_;
};

TEST_F(WaveletCommandTest, LevelZeroIsTheInputBitForBit) {
  const CommandResult r =
      run_sculpt("wavelet " + path("in.nrrd") + " --levels 5 --lod 0 -o " + path("l0.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto back = sculpt::core::read_nrrd_u8(path("l0.nrrd"));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, input_);
}

TEST_F(WaveletCommandTest, WritesTheRequestedLevel) {
  const CommandResult r =
      run_sculpt("wavelet " + path("in.nrrd") + " --levels 5 --lod 2 -o " + path("l2.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto back = sculpt::core::read_nrrd_u8(path("l2.nrrd"));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->dims(), glm::ivec3(18));  // ceil(70 / 4)
  EXPECT_EQ(*back, sculpt::core::Volume::from_dense(input_).to_dense(2));
}

TEST_F(WaveletCommandTest, VerifiesTheRoundTripAndReportsSparsity) {
  const CommandResult r = run_sculpt("wavelet " + path("in.nrrd") + " --levels 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("round trip  bit-exact"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("% zero"), std::string::npos);
  EXPECT_NE(r.out.find("level 5     3x3x3"), std::string::npos) << r.out;
}

TEST_F(WaveletCommandTest, BadInputIsOneLineExitOneAndNoOutput) {
  std::ofstream(dir_ / "bad.nrrd")
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\nshort";
  const CommandResult r =
      run_sculpt("wavelet " + path("bad.nrrd") + " --levels 2 --lod 1 -o " + path("out.nrrd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.nrrd"), std::string::npos);
  EXPECT_NE(r.err.find("truncated"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "out.nrrd"));

  const CommandResult missing = run_sculpt("wavelet " + path("nope.nrrd") + " --levels 2");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("nope.nrrd: cannot open"), std::string::npos) << missing.err;
}

TEST_F(WaveletCommandTest, UsageErrorsExitTwo) {
  EXPECT_EQ(run_sculpt("wavelet").exit_code, 2);
  // A value out of range is bad input, not a usage error.
  EXPECT_EQ(run_sculpt("wavelet " + path("in.nrrd") + " --levels 9").exit_code, 1);
  EXPECT_EQ(run_sculpt("wavelet " + path("in.nrrd") + " --bogus").exit_code, 2);
  EXPECT_EQ(run_sculpt("").exit_code, 2);
  EXPECT_EQ(run_sculpt("no-such-command").exit_code, 2);
  const CommandResult lod =
      run_sculpt("wavelet " + path("in.nrrd") + " --levels 2 --lod 3 -o " + path("x.nrrd"));
  EXPECT_EQ(lod.exit_code, 1);
  EXPECT_NE(lod.err.find("--lod 3 exceeds --levels 2"), std::string::npos) << lod.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.nrrd"));
}

TEST_F(WaveletCommandTest, HelpExitsZero) {
  const CommandResult r = run_sculpt("wavelet --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--levels"), std::string::npos);
  EXPECT_EQ(run_sculpt("--help").exit_code, 0);
}

}  // namespace
}  // namespace sculpt::station::test
