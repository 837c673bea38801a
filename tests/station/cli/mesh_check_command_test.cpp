// `sculpt mesh --check`: the print check on a marched volume and on a mesh
// from elsewhere; a mesh that would not print is one error line, exit 1 and
// nothing written.

#include <gtest/gtest.h>

#include <filesystem>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;
const std::string kData = SCULPT_TEST_DATA_DIR "/distance/";

class MeshCheckCommandTest : public ::testing::Test {
 protected:
  sculpt::test::ScratchDir scratch_;
  std::string path(const std::string& name) const { return scratch_.file(name); }
};

TEST_F(MeshCheckCommandTest, AMarchedSphereIsPrintableAndWrittenWithItsSizeInMillimetres) {
  const std::string volume = path("sphere.nrrd");
  ASSERT_TRUE(core::write_nrrd(volume, core::sphere_density(40)).ok());
  const CommandResult r =
      run_sculpt("mesh " + volume + " --check --voxel-mm 0.5 -o " + path("sphere.stl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("print check printable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("watertight  yes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("intersects  0 pairs"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mm^3 (voxel 0.5 mm)"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(path("sphere.stl")));
}

TEST_F(MeshCheckCommandTest, AMeshFileIsCheckedAndConvertedOnlyWhenItWouldPrint) {
  const CommandResult ok =
      run_sculpt("mesh " + kData + "octahedron.obj --check -o " + path("octahedron.stl"));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("print check printable"), std::string::npos) << ok.out;
  EXPECT_TRUE(fs::exists(path("octahedron.stl")));
  const CommandResult open =
      run_sculpt("mesh " + kData + "open_octahedron.obj --check -o " + path("open.stl"));
  EXPECT_EQ(open.exit_code, 1);
  EXPECT_EQ(line_count(open.err), 1) << open.err;
  EXPECT_NE(open.err.find("open_octahedron.obj: the mesh would not print: 3 boundary edges"),
            std::string::npos)
      << open.err;
  EXPECT_NE(open.out.find("NOT printable"), std::string::npos) << open.out;
  EXPECT_FALSE(fs::exists(path("open.stl"))) << "nothing written";
  // Reading a mesh is only for checking it; a volume's mesh needs an output.
  const CommandResult no_check = run_sculpt("mesh " + kData + "octahedron.obj -o " + path("x.ply"));
  EXPECT_EQ(no_check.exit_code, 1);
  EXPECT_NE(no_check.err.find("a mesh read in is checked (--check) or simplified"),
            std::string::npos)
      << no_check.err;
  const CommandResult bad_size =
      run_sculpt("mesh " + kData + "octahedron.obj --check --voxel-mm nan");
  EXPECT_EQ(bad_size.exit_code, 1);
  EXPECT_NE(bad_size.err.find("--voxel-mm"), std::string::npos) << bad_size.err;
}

TEST_F(MeshCheckCommandTest, SimplifyingAnExportKeepsItPrintableAndSaysHowFarItMoved) {
  const std::string volume = path("sphere.nrrd");
  ASSERT_TRUE(core::write_nrrd(volume, core::sphere_density(48)).ok());
  const CommandResult r = run_sculpt(
      "mesh " + volume + " --simplify 0.2 --max-error 0.5 --check -o " + path("light.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("simplified  "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("print check printable"), std::string::npos) << r.out;
  // And a mesh from elsewhere: simplified and written without a check.
  const CommandResult again =
      run_sculpt("mesh " + path("light.ply") + " --simplify 0.5 -o " + path("lighter.stl"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(fs::exists(path("lighter.stl")));
  const CommandResult bad = run_sculpt("mesh " + volume + " --simplify 0 -o " + path("x.ply"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--simplify"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("x.ply")));
}

// The demo's head, where the coil and the spiral lie within a fraction of a
// voxel of the clay: simplified, those sheets passed through each other
// (11 places at --max-error 0.2) and the print check refused the export.
// Now the places are held as marched and the export prints.
TEST_F(MeshCheckCommandTest, TheDemosHeadSimplifiedStillPrints) {
  const CommandResult demo = run_sculpt("run --headless --out " + path("demo"));
  ASSERT_EQ(demo.exit_code, 0) << demo.err;
  const CommandResult r = run_sculpt("mesh " + path("demo/volume.nrrd") +
                                     " --max-error 0.2 --check -o " + path("head.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("print check printable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("where simplifying made the surface pass through itself"), std::string::npos)
      << r.out;
  EXPECT_TRUE(fs::exists(path("head.ply")));
}

}  // namespace
}  // namespace sculpt::station::test
