// The `sculpt mesh` command-line contract (DESIGN.md §7).

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "run_sculpt.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

class MeshCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sculpt::core::write_nrrd(dir_ / "in.nrrd", sculpt::core::sphere_density(70)).ok());
  }
  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
  std::string path(const std::string& name) const { return scratch_.file(name); }
};

TEST_F(MeshCommandTest, WritesEachFormatClosed) {
  for (const char* out : {"m.ply", "m.obj", "m.stl"}) {
    const CommandResult r = run_sculpt("mesh " + path("in.nrrd") + " -o " + path(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("closed manifold, Euler characteristic 2"), std::string::npos) << r.out;
    EXPECT_GT(fs::file_size(path(out)), 1000u) << out;
  }
  const CommandResult ascii =
      run_sculpt("mesh " + path("in.nrrd") + " --ascii --lod 1 -o " + path("a.ply"));
  ASSERT_EQ(ascii.exit_code, 0) << ascii.err;
  EXPECT_EQ(read_text(path("a.ply")).rfind("ply\nformat ascii 1.0\n", 0), 0u);
}

// A 16-bit CT-like volume (a ball of 1000 in -1000 around it): refused
// without a mapping, meshed closed with --window or --data-iso.
TEST_F(MeshCommandTest, SixteenBitVolumesAreMeshedThroughAWindow) {
  std::string data;
  const int n = 40;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double r =
            std::sqrt(double((x - 20) * (x - 20) + (y - 20) * (y - 20) + (z - 20) * (z - 20)));
        const auto v =
            static_cast<int16_t>(std::clamp(1000.0 - 400.0 * (r - 12.0), -1000.0, 1000.0));
        data.append(reinterpret_cast<const char*>(&v), 2);
      }
  std::ofstream(dir_ / "ct.nrrd", std::ios::binary)
      << "NRRD0004\ntype: short\ndimension: 3\nsizes: 40 40 40\nendian: little\nencoding: raw\n\n"
      << data;
  const CommandResult refused = run_sculpt("mesh " + path("ct.nrrd") + " -o " + path("r.ply"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("holds int16 voxels: map them to density with --window"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "r.ply"));
  for (const char* mapping : {" --window -1000,1000", " --data-iso 0"}) {
    const CommandResult r =
        run_sculpt("mesh " + path("ct.nrrd") + mapping + " -o " + path("ct.ply"));
    ASSERT_EQ(r.exit_code, 0) << mapping << r.err;
    EXPECT_NE(r.out.find("closed"), std::string::npos) << r.out;
  }
  const CommandResult both =
      run_sculpt("mesh " + path("ct.nrrd") + " --window 0,1 --data-iso 0 -o " + path("b.ply"));
  EXPECT_NE(both.exit_code, 0);
}

TEST_F(MeshCommandTest, BadInputIsOneLineNamingItAndNoOutput) {
  const CommandResult ext = run_sculpt("mesh " + path("in.nrrd") + " -o " + path("m.xyz"));
  EXPECT_EQ(ext.exit_code, 1);
  EXPECT_EQ(line_count(ext.err), 1) << ext.err;
  EXPECT_NE(ext.err.find("m.xyz"), std::string::npos);
  EXPECT_FALSE(fs::exists(path("m.xyz")));

  const CommandResult missing = run_sculpt("mesh " + path("none.nrrd") + " -o " + path("m.ply"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(line_count(missing.err), 1) << missing.err;
  EXPECT_NE(missing.err.find("none.nrrd"), std::string::npos);
  EXPECT_FALSE(fs::exists(path("m.ply")));

  const CommandResult lod = run_sculpt("mesh " + path("in.nrrd") + " --lod 9 -o " + path("m.ply"));
  EXPECT_EQ(lod.exit_code, 1);  // a value out of range is bad input
  EXPECT_EQ(line_count(lod.err), 1) << lod.err;
  EXPECT_FALSE(fs::exists(path("m.ply")));
}

TEST_F(MeshCommandTest, AMessageQuotingAHostileHeaderIsOnePrintableShortLine) {
  // A header line with an escape sequence and 3000 more bytes: the message
  // quotes it, but shows control bytes as \xNN and stops at ~300 bytes.
  std::ofstream(path("ctrl.nrrd")) << "NRRD0004\ntype: uint8\x1b[2J" << std::string(3000, 'A')
                                   << "\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n";
  const CommandResult r = run_sculpt("mesh " + path("ctrl.nrrd") + " -o " + path("m.ply"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos);
  EXPECT_NE(r.err.find("\\x1b[2J"), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 320u);
  EXPECT_NE(r.err.find("ctrl.nrrd"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::station::test
