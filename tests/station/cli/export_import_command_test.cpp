// `sculpt export` and `sculpt import`: volumes both ways exactly, a sculpture
// out as a printable glTF mesh and back in as a volume, sessions exported,
// and bad input (damaged .glb, a mesh that would not print, options that do
// not apply) refused with one line, exit 1 and nothing written (DESIGN.md §7).

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "run_sculpt.h"
#include "sculpt/core/files/glb_file.h"
#include "sculpt/core/files/vdb_file.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/mesh/mesh_reader.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/sim/synth/bundled_sessions.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

// Lines of stderr other than the progress lines of work done before the
// fault was found ("mesh: 40%": stderr is no terminal here).
int error_lines(const std::string& err) {
  static const std::regex progress(R"(^[a-z]+: [0-9]+%$)");
  std::istringstream in(err);
  int n = 0;
  for (std::string line; std::getline(in, line);)
    n += !std::regex_match(line, progress);
  return n;
}

class ExportImportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    input_ = sculpt::core::sphere_density(40);
    input_.at(3, 4, 5) = 77;  // a lone voxel: the density is kept, not re-derived
    ASSERT_TRUE(sculpt::core::write_nrrd(path("in.nrrd"), input_).ok());
  }
  std::string path(const std::string& name) const { return scratch_.file(name); }

  void expect_refused(const CommandResult& r, const std::string& input, const std::string& what,
                      const std::string& output) const {
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(error_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(input), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output)) << output;
  }

  sculpt::test::ScratchDir scratch_;
  sculpt::core::DenseGrid<uint8_t> input_;
};

TEST_F(ExportImportTest, NrrdToVdbAndBackIsExact) {
  CommandResult r = run_sculpt("export " + path("in.nrrd") + " -o " + path("v.vdb"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto grids = sculpt::core::read_vdb(path("v.vdb"));
  ASSERT_TRUE(grids.ok()) << grids.error().message();
  EXPECT_EQ(grids->grid_name, "density");
  r = run_sculpt("import " + path("v.vdb") + " -o " + path("back.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto back = sculpt::core::read_nrrd_u8(path("back.nrrd"));
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(*back, input_);
  // A coarser level on the way out, as `wavelet --lod` writes it.
  r = run_sculpt("export " + path("in.nrrd") + " --lod 1 -o " + path("half.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto half = sculpt::core::read_nrrd_u8(path("half.nrrd"));
  ASSERT_TRUE(half.ok());
  EXPECT_EQ(half->dims(), glm::ivec3(20));
}

TEST_F(ExportImportTest, GlbOutIsPrintableAndComesBackAsTheSameMeshAndAVolume) {
  CommandResult r = run_sculpt("export " + path("in.nrrd") + " --check -o " + path("s.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("print check printable"), std::string::npos) << r.out;
  // The same surface as `sculpt mesh` writes: exported once, read back equal.
  r = run_sculpt("mesh " + path("in.nrrd") + " -o " + path("s.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto glb = sculpt::core::read_glb(path("s.glb"));
  ASSERT_TRUE(glb.ok()) << glb.error().message();
  const auto ply = sculpt::core::read_mesh(path("s.ply"));
  ASSERT_TRUE(ply.ok());
  EXPECT_EQ(glb->positions, ply->positions);
  EXPECT_EQ(glb->triangles, ply->triangles);
  // Checked again as a file from elsewhere: watertight.
  r = run_sculpt("mesh " + path("s.glb") + " --check");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("watertight  yes"), std::string::npos) << r.out;
  // Simplified on the way out, still printable.
  r = run_sculpt("export " + path("in.nrrd") + " --simplify 0.3 --check -o " + path("small.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("simplified"), std::string::npos) << r.out;
  const auto small = sculpt::core::read_glb(path("small.glb"));
  ASSERT_TRUE(small.ok());
  EXPECT_LE(small->triangles.size(), glb->triangles.size() * 3 / 10 + 1);

  // In again: voxelized by the code of `sculpt voxelize`.
  r = run_sculpt("import " + path("s.glb") + " --size 32 -o " + path("vox.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto vox = sculpt::core::read_nrrd_u8(path("vox.nrrd"));
  ASSERT_TRUE(vox.ok());
  EXPECT_EQ(vox->dims(), glm::ivec3(32));
  EXPECT_EQ(vox->at(16, 16, 16), 255);
  EXPECT_EQ(vox->at(0, 0, 0), 0);
  r = run_sculpt("voxelize " + path("s.glb") + " --size 32 -o " + path("vox2.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(path("vox2.nrrd")), read_text(path("vox.nrrd")));
}

TEST_F(ExportImportTest, VoxelMmKeepsTheMeshSize) {
  // Our meshes are in voxels; as an STL one voxel is one millimetre.
  ASSERT_EQ(run_sculpt("export " + path("in.nrrd") + " -o " + path("s.stl")).exit_code, 0);
  const auto mesh = sculpt::core::read_mesh(path("s.stl"));
  ASSERT_TRUE(mesh.ok());
  const sculpt::core::MeshBounds b = sculpt::core::mesh_bounds(*mesh);
  CommandResult r =
      run_sculpt("import " + path("s.stl") + " --voxel-mm 0.5 --margin 2 -o " + path("fine.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fine = sculpt::core::read_nrrd_u8(path("fine.nrrd"));
  ASSERT_TRUE(fine.ok());
  const int expected = static_cast<int>(std::ceil((b.hi.x - b.lo.x) * 2.0f)) + 1 + 4;
  EXPECT_EQ(fine->dims().x, expected);
  // Neither or both grid choices: one line.
  expect_refused(run_sculpt("import " + path("s.stl") + " -o " + path("none.nrrd")), "s.stl",
                 "give the grid as --size N or --voxel-mm S", path("none.nrrd"));
  // A glTF file is metres: at 0.5 mm a voxel, 30 "metres" is too large.
  ASSERT_EQ(run_sculpt("export " + path("in.nrrd") + " -o " + path("s.glb")).exit_code, 0);
  expect_refused(run_sculpt("import " + path("s.glb") + " --voxel-mm 0.5 -o " + path("big.nrrd")),
                 "s.glb", "a mesh unit 1000 mm", path("big.nrrd"));
}

TEST_F(ExportImportTest, ASessionExportsTheSculptureTheStationMade) {
  const std::string session = sculpt::sim::bundled_session_path("short");
  CommandResult r = run_sculpt("export " + session + " -o " + path("s.vdb"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_sculpt("replay " + session + " --fast --volume " + path("s.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_sculpt("import " + path("s.vdb") + " -o " + path("back.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(sculpt::core::read_nrrd_u8(path("back.nrrd")).value(),
            sculpt::core::read_nrrd_u8(path("s.nrrd")).value());
  // replay --mesh takes the export options too.
  r = run_sculpt("replay " + session + " --fast --simplify 0.5 --mesh " + path("half.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("simplified"), std::string::npos) << r.out;
  r = run_sculpt("export " + session + " --simplify 0.5 -o " + path("half2.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(path("half.ply")), read_text(path("half2.ply")));
  expect_refused(run_sculpt("export " + session + " --iso 100 -o " + path("iso.ply")), "short",
                 "--iso, --lod, --window and --data-iso apply to a volume input", path("iso.ply"));
}

TEST_F(ExportImportTest, AMeshThatWouldNotPrintIsRefusedWithCheck) {
  // The station's meshes are closed (the block's faces close them), so
  // what a volume can fail on is having no surface at all.
  const sculpt::core::DenseGrid<uint8_t> empty(glm::ivec3(16), 0);
  ASSERT_TRUE(sculpt::core::write_nrrd(path("empty.nrrd"), empty).ok());
  for (const char* out : {"p.stl", "p.glb"}) {
    expect_refused(run_sculpt("export " + path("empty.nrrd") + " --check -o " + path(out)), out,
                   "not written: the mesh would not print: no surface", path(out));
  }
  // A mesh with a hole, as another program might hand it over in glTF.
  sculpt::core::Mesh open;
  open.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  open.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}};  // the fourth face missing
  ASSERT_TRUE(
      sculpt::core::write_mesh(path("open.glb"), open, sculpt::core::MeshFormat::kGlb).ok());
  expect_refused(run_sculpt("mesh " + path("open.glb") + " --check -o " + path("o.stl")),
                 "open.glb", "3 boundary edges", path("o.stl"));
  expect_refused(run_sculpt("import " + path("open.glb") + " --size 16 -o " + path("o.nrrd")),
                 "open.glb", "mesh is not closed", path("o.nrrd"));
}

TEST_F(ExportImportTest, BadInputAndOptionsThatDoNotApplyAreOneLine) {
  ASSERT_EQ(run_sculpt("export " + path("in.nrrd") + " -o " + path("s.glb")).exit_code, 0);
  const std::string bytes = read_text(path("s.glb"));
  std::ofstream(path("cut.glb"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::string wrong = bytes;  // POSITION's componentType 5126 -> 5123
  const size_t at = wrong.find("\"componentType\":5126");
  ASSERT_NE(at, std::string::npos);
  wrong.replace(at + 16, 4, "5123");
  std::ofstream(path("wrong.glb"), std::ios::binary) << wrong;
  std::string past = bytes;  // "count" of the positions, same length, all nines: past the buffer
  const size_t count = past.find("\"count\":") + 8;
  ASSERT_NE(count, std::string::npos + 8);
  const size_t digits = past.find_first_not_of("0123456789", count) - count;
  ASSERT_NE(past.substr(count, digits), std::string(digits, '9'));
  past.replace(count, digits, std::string(digits, '9'));
  std::ofstream(path("past.glb"), std::ios::binary) << past;
  std::ofstream(path("text.glb")) << "{\"asset\": {\"version\": \"2.0\"}}\n";

  const struct {
    const char* file;
    const char* what;
  } cases[] = {{"cut.glb", "cut off?"},
               {"wrong.glb", "componentType 5123"},
               {"past.glb", "reach past bufferViews[0]"},
               {"text.glb", "a glTF JSON file, not binary glTF"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string in = path(c.file);
    expect_refused(run_sculpt("import " + in + " --size 24 -o " + path("o.nrrd")), in, c.what,
                   path("o.nrrd"));
    expect_refused(run_sculpt("voxelize " + in + " --size 24 -o " + path("o.vdb")), in, c.what,
                   path("o.vdb"));
    expect_refused(run_sculpt("mesh " + in + " --check -o " + path("o.stl")), in, c.what,
                   path("o.stl"));
  }
  expect_refused(run_sculpt("export " + path("in.nrrd") + " -o " + path("o.fbx")), "o.fbx",
                 "export writes a volume (.vdb, .nrrd) or a mesh", path("o.fbx"));
  expect_refused(run_sculpt("export " + path("in.nrrd") + " --simplify 0.5 -o " + path("o.vdb")),
                 "o.vdb", "apply to a mesh output", path("o.vdb"));
  expect_refused(run_sculpt("export " + path("s.glb") + " -o " + path("o.ply")), "s.glb",
                 "`sculpt import` brings a mesh in", path("o.ply"));
  expect_refused(run_sculpt("import " + path("in.nrrd") + " --size 64 -o " + path("o.vdb")),
                 "in.nrrd", "a volume is imported on its own grid", path("o.vdb"));
  expect_refused(run_sculpt("import " + path("in.nrrd") + " -o " + path("o.glb")), "o.glb",
                 "import writes a volume", path("o.glb"));
}

}  // namespace
}  // namespace sculpt::station::test
