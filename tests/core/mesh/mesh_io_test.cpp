// Every exported format is read back by VTK (Debian python3-vtk9, through
// tests/data/mesh/read_mesh_vtk.py), a parser that shares no code with ours.

#include "sculpt/core/mesh/mesh_io.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>

#include <cstring>
#include <iterator>

#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

namespace fs = std::filesystem;

struct VtkView {
  int64_t points = -1, polys = -1, boundary_edges = -1, nonmanifold_edges = -1;
  double area = 0.0, volume = 0.0;
};

VtkView read_with_vtk(const fs::path& file) {
  const std::string script = std::string(SCULPT_TEST_DATA_DIR) + "/mesh/read_mesh_vtk.py";
  const std::string command = "/usr/bin/python3 '" + script + "' '" + file.string() + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  VtkView v;
  if (!pipe) return v;
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), pipe.get()))
    text += buf;
  std::istringstream in(text);
  std::string key;
  while (in >> key) {
    if (key == "points")
      in >> v.points;
    else if (key == "polys")
      in >> v.polys;
    else if (key == "area")
      in >> v.area;
    else if (key == "volume")
      in >> v.volume;
    else if (key == "boundary_edges")
      in >> v.boundary_edges;
    else if (key == "nonmanifold_edges")
      in >> v.nonmanifold_edges;
  }
  return v;
}

class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sculpt_mesh_io_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // Two bricks' worth of sphere, so the welding across bricks is exercised.
    mesh_ = marching_cubes(sphere_volume(48));
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  Mesh mesh_;
};

TEST_F(MeshIo, EveryFormatReadsBackWhole) {
  ASSERT_EQ(check_topology(mesh_).boundary_edges, 0);
  const double area = surface_area(mesh_), volume = enclosed_volume(mesh_);
  struct Case {
    const char* name;
    bool ascii;
  };
  for (const Case c : {Case{"binary.ply", false}, Case{"ascii.ply", true}, Case{"mesh.obj", false},
                       Case{"mesh.stl", false}, Case{"mesh.glb", false}}) {
    const fs::path file = dir_ / c.name;
    auto format = mesh_format_for(file, c.ascii);
    ASSERT_TRUE(format.ok());
    ASSERT_TRUE(write_mesh(file, mesh_, *format).ok()) << c.name;
    const VtkView v = read_with_vtk(file);
    // STL repeats vertices per triangle; VTK merges equal positions again,
    // which gives back our vertex count only if the welding was complete.
    EXPECT_EQ(v.points, static_cast<int64_t>(mesh_.positions.size())) << c.name;
    EXPECT_EQ(v.polys, static_cast<int64_t>(mesh_.triangles.size())) << c.name;
    EXPECT_EQ(v.boundary_edges, 0) << c.name;
    EXPECT_EQ(v.nonmanifold_edges, 0) << c.name;
    EXPECT_NEAR(v.area, area, 1e-4 * area) << c.name;
    EXPECT_NEAR(v.volume, volume, 1e-4 * volume) << c.name;
  }
}

TEST_F(MeshIo, UnknownExtensionIsRefusedByName) {
  auto format = mesh_format_for(dir_ / "mesh.xyz");
  ASSERT_FALSE(format.ok());
  EXPECT_NE(format.error().message().find("mesh.xyz"), std::string::npos);
  EXPECT_NE(format.error().message().find(".xyz"), std::string::npos);
  EXPECT_EQ(*mesh_format_for(dir_ / "UPPER.PLY"), MeshFormat::kPlyBinary);
  EXPECT_EQ(*mesh_format_for(dir_ / "a.ply", true), MeshFormat::kPlyAscii);
  EXPECT_EQ(*mesh_format_for(dir_ / "a.Obj"), MeshFormat::kObj);
  EXPECT_EQ(*mesh_format_for(dir_ / "a.stl"), MeshFormat::kStl);
  EXPECT_EQ(*mesh_format_for(dir_ / "a.GLB"), MeshFormat::kGlb);
}

TEST_F(MeshIo, UnwritableTargetLeavesNothingAndNamesThePath) {
  const fs::path file = dir_ / "missing_folder" / "mesh.ply";
  const Status st = write_mesh(file, mesh_, MeshFormat::kPlyBinary);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message().find("mesh.ply"), std::string::npos);
  EXPECT_FALSE(fs::exists(file));
}

TEST_F(MeshIo, BinaryPlyLayoutIsExact) {
  const fs::path file = dir_ / "layout.ply";
  ASSERT_TRUE(write_mesh(file, mesh_, MeshFormat::kPlyBinary).ok());
  std::ifstream in(file, std::ios::binary);
  std::string line, header;
  while (std::getline(in, line) && line != "end_header")
    header += line + "\n";
  const size_t header_bytes = header.size() + std::string("end_header\n").size();
  const size_t expected = header_bytes + mesh_.positions.size() * 24 + mesh_.triangles.size() * 13;
  EXPECT_EQ(fs::file_size(file), expected);
}

// GLB (glTF 2.0 binary): the header's length is the file's, both chunks are
// 4-byte aligned, the BIN chunk holds positions, normals and indices whole;
// no surface is a valid empty scene (glTF forbids an empty buffer).
TEST_F(MeshIo, GlbLayoutIsExactAndAnEmptyMeshIsAnEmptyScene) {
  auto read_u32 = [](const std::string& b, size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);
    return v;
  };
  for (const bool empty : {false, true}) {
    const fs::path file = dir_ / "layout.glb";
    ASSERT_TRUE(write_mesh(file, empty ? Mesh{} : mesh_, MeshFormat::kGlb).ok());
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GE(bytes.size(), 20u);
    EXPECT_EQ(bytes.substr(0, 4), "glTF");
    EXPECT_EQ(read_u32(bytes, 4), 2u);
    EXPECT_EQ(read_u32(bytes, 8), bytes.size());
    const uint32_t json_bytes = read_u32(bytes, 12);
    EXPECT_EQ(bytes.substr(16, 4), "JSON");
    EXPECT_EQ(json_bytes % 4, 0u);
    if (empty) {
      EXPECT_EQ(bytes.size(), 20u + json_bytes);
      continue;
    }
    const size_t bin_at = 20 + json_bytes;
    const size_t bin_bytes = mesh_.positions.size() * 24 + mesh_.triangles.size() * 12;
    EXPECT_EQ(read_u32(bytes, bin_at), bin_bytes);
    EXPECT_EQ(bytes.substr(bin_at + 4, 4), std::string("BIN\0", 4));
    EXPECT_EQ(bytes.size(), bin_at + 8 + bin_bytes);
    EXPECT_EQ(
        std::memcmp(bytes.data() + bin_at + 8, mesh_.positions.data(), mesh_.positions.size() * 12),
        0);
  }
}

TEST_F(MeshIo, RefusesNonFiniteCoordinatesAndStrayIndicesInEveryFormat) {
  Mesh nan_vertex = mesh_;
  nan_vertex.positions[1].y = std::nanf("");
  Mesh inf_normal = mesh_;
  inf_normal.normals[2].z = std::numeric_limits<float>::infinity();
  Mesh stray_index = mesh_;
  stray_index.triangles.back().z = static_cast<unsigned>(mesh_.positions.size());
  const std::pair<const Mesh*, std::string> cases[] = {
      {&nan_vertex, "vertex 1 is not a finite position"},
      {&inf_normal, "the normal of vertex 2 is not finite"},
      {&stray_index, "names a vertex beyond"}};
  for (MeshFormat format : {MeshFormat::kPlyBinary, MeshFormat::kPlyAscii, MeshFormat::kObj,
                            MeshFormat::kStl, MeshFormat::kGlb}) {
    for (const auto& [mesh, what] : cases) {
      const fs::path file = dir_ / "bad.mesh";
      const Status st = write_mesh(file, *mesh, format);
      ASSERT_FALSE(st.ok()) << what;
      EXPECT_NE(st.error().message().find("bad.mesh"), std::string::npos);
      EXPECT_NE(st.error().message().find(what), std::string::npos) << st.error().message();
      EXPECT_FALSE(fs::exists(file));
    }
  }
}

}  // namespace
}  // namespace sculpt::core
