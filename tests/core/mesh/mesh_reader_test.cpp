#include "sculpt/core/mesh/mesh_reader.h"

#include <gtest/gtest.h>

#include <fstream>

#include "scratch_dir.h"

namespace sculpt::core {
namespace {

const std::string kData = SCULPT_TEST_DATA_DIR "/distance/";

TEST(MeshReader, ReadsObjPlyAndStlAsTheSameClosedMesh) {
  for (const char* name : {"octahedron.obj", "octahedron.ply", "octahedron.stl"}) {
    auto m = read_mesh(kData + name);
    ASSERT_TRUE(m.ok()) << m.error().message();
    EXPECT_EQ(m->positions.size(), 6u) << name;
    EXPECT_EQ(m->triangles.size(), 8u) << name;
    EXPECT_TRUE(check_topology(*m).manifold()) << name;
    EXPECT_GT(enclosed_volume(*m), 1.3) << name;  // 4/3, facing outward
  }
}

TEST(MeshReader, ErrorsNameTheFileAndWhat) {
  auto bad = read_mesh(kData + "bad_index.obj");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message().find("bad_index.obj: line 4"), std::string::npos)
      << bad.error().message();
  auto ext = read_mesh(kData + "branching.contours");
  ASSERT_FALSE(ext.ok());
  EXPECT_NE(ext.error().message().find("unknown mesh extension"), std::string::npos);
  auto none = read_mesh(kData + "none.obj");
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message().find("cannot open"), std::string::npos);
}

TEST(MeshReader, AFaceIndexThatIsNotAWholeNumberIsRefused) {
  // A PLY whose face list holds floats (found by fuzzing: 1e20 was cast to
  // an index, undefined behaviour).
  sculpt::test::ScratchDir scratch;
  for (const std::string index : {"1e20", "0.5", "-1"}) {
    const std::string path = scratch.file("f.ply");
    std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                           "property float y\nproperty float z\nelement face 1\n"
                           "property list uchar float vertex_indices\nend_header\n"
                           "0 0 0\n1 0 0\n0 1 0\n3 0 1 "
                        << index << "\n";
    const auto mesh = read_mesh(path);
    ASSERT_FALSE(mesh.ok()) << index;
    EXPECT_NE(mesh.error().message().find("is not a whole number from 0"), std::string::npos)
        << mesh.error().message();
  }
}

// Found by fuzzing: a 240-byte PLY declaring 622,222,222 vertices of no
// properties stored them all (1.6 GB) before anything was checked.
TEST(MeshReader, AnElementCountTheDataCannotHoldIsRefusedBeforeStoring) {
  const auto found = read_mesh(SCULPT_TEST_DATA_DIR "/mesh/fuzz_oom_vertex_count.ply");
  ASSERT_FALSE(found.ok());
  EXPECT_NE(found.error().message().find("fuzz_oom_vertex_count.ply"), std::string::npos);
  sculpt::test::ScratchDir dir;
  const auto many = dir.path() / "many.ply";
  std::ofstream(many, std::ios::binary)
      << "ply\nformat ascii 1.0\nelement vertex 1000000\nproperty float x\nend_header\n0 1 2\n";
  const auto r = read_mesh(many);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message().find("1000000 instances, but the data holds only 6 bytes"),
            std::string::npos)
      << r.error().message();
}

}  // namespace
}  // namespace sculpt::core
