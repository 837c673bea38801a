// .glb (binary glTF 2.0) meshes read: our own files back bit for bit, the
// node tree and primitive modes of other programs' files, and damaged or
// unsupported files refused with one message naming the file and the fault.

#include "sculpt/core/files/glb_file.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "scratch_dir.h"
#include "sculpt/core/files/mesh_file.h"
#include "sculpt/core/mesh/mesh_io.h"

namespace sculpt::core {
namespace {

using json = nlohmann::json;

// A GLB container around `gltf` and `bin` (both padded to 4 bytes).
std::string glb_bytes(const json& gltf, std::string bin) {
  std::string text = gltf.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  bin.append((4 - bin.size() % 4) % 4, '\0');
  std::string out = "glTF";
  auto u32 = [&out](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  u32(2);
  u32(static_cast<uint32_t>(12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size())));
  u32(static_cast<uint32_t>(text.size()));
  out += "JSON" + text;
  if (!bin.empty()) {
    u32(static_cast<uint32_t>(bin.size()));
    out.append("BIN\0", 4);
    out += bin;
  }
  return out;
}

// A closed tetrahedron, counter-clockwise seen from outside: 4 float
// positions (48 bytes) and 12 uint16 indices (24 bytes) in one buffer.
struct Tetra {
  std::string bin;
  json gltf;
  Tetra() {
    const float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint16_t i[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    bin.append(reinterpret_cast<const char*>(p), sizeof p);
    bin.append(reinterpret_cast<const char*>(i), sizeof i);
    gltf = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
            {"accessors",
             {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
              {{"bufferView", 1}, {"componentType", 5123}, {"count", 12}, {"type", "SCALAR"}}}},
            {"bufferViews",
             {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
              {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 24}}}},
            {"buffers", {{{"byteLength", 72}}}}};
  }
  std::string bytes() const { return glb_bytes(gltf, bin); }
};

TEST(GlbFile, OurOwnFileReadsBackBitForBit) {
  sculpt::test::ScratchDir dir;
  Mesh m;
  m.positions = {{0.5f, 0, 0}, {1.25f, 0, 0}, {0, 3.0f, 0}, {0, 0, 7.125f}};
  m.normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0.6f, 0.8f, 0}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::string path = dir.file("m.glb");
  ASSERT_TRUE(write_mesh(path, m, MeshFormat::kGlb).ok());
  const auto back = read_mesh_file(path);
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(*back, m);
}

TEST(GlbFile, NodeTransformsAndTriangleModesAreApplied) {
  Tetra t;
  // Under a parent that moves it by (10, 0, 0), a child that doubles it.
  t.gltf["scenes"] = {{{"nodes", {1}}}};
  t.gltf["nodes"] = {{{"mesh", 0}, {"scale", {2, 2, 2}}},
                     {{"translation", {10, 0, 0}}, {"children", {0}}}};
  auto m = read_glb(t.bytes(), "t.glb");
  ASSERT_TRUE(m.ok()) << m.error().message();
  ASSERT_EQ(m->positions.size(), 4u);
  EXPECT_EQ(m->positions[1], glm::vec3(12, 0, 0));
  EXPECT_EQ(m->positions[3], glm::vec3(10, 0, 2));
  EXPECT_EQ(check_topology(*m).misoriented_edges, 0);
  EXPECT_TRUE(check_topology(*m).closed());

  // A mirror reverses the winding so that the surface still faces out.
  t.gltf["nodes"] = {{{"mesh", 0}, {"scale", {-1, 1, 1}}}};
  t.gltf["scenes"] = {{{"nodes", {0}}}};
  m = read_glb(t.bytes(), "t.glb");
  ASSERT_TRUE(m.ok()) << m.error().message();
  EXPECT_GT(enclosed_volume(*m), 0.0);

  // A fan of the four corners 0 1 2 3 without indices: two triangles.
  Tetra fan;
  fan.gltf["meshes"][0]["primitives"][0].erase("indices");
  fan.gltf["meshes"][0]["primitives"][0]["mode"] = 6;
  m = read_glb(fan.bytes(), "fan.glb");
  ASSERT_TRUE(m.ok()) << m.error().message();
  EXPECT_EQ(m->triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}));
}

TEST(GlbFile, DamagedOrUnsupportedFilesAreOneLineNamingTheFault) {
  struct Case {
    const char* name;
    std::string bytes;
    const char* what;
  };
  std::vector<Case> cases;
  const std::string good = Tetra().bytes();
  cases.push_back({"cut", good.substr(0, good.size() / 2), "cut off?"});
  cases.push_back({"short", "glTF", "too short for a GLB header"});
  cases.push_back({"text", "{\"asset\": {}}     ", "a glTF JSON file, not binary glTF"});
  cases.push_back({"magic", "PK\x03\x04" + good.substr(4), "no 'glTF' magic"});
  {
    std::string v1 = good;
    v1[4] = 1;
    cases.push_back({"version", v1, "GLB version 1"});
  }
  {
    std::string junk = good;
    std::memset(junk.data() + 20, '!', 8);  // inside the JSON text
    cases.push_back({"json", junk, "not a JSON object"});
  }
  auto edited = [&](const char* name, auto edit, const char* what) {
    Tetra t;
    edit(t.gltf);
    cases.push_back({name, t.bytes(), what});
  };
  edited(
      "position type", [](json& g) { g["accessors"][0]["componentType"] = 5123; },
      "componentType 5123 (POSITION and NORMAL are read as float");
  edited(
      "index type", [](json& g) { g["accessors"][1]["componentType"] = 5126; },
      "componentType 5126 (indices are unsigned");
  edited(
      "shape", [](json& g) { g["accessors"][0]["type"] = "VEC2"; }, "type must be VEC3");
  edited(
      "count", [](json& g) { g["accessors"][0]["count"] = 4000000000u; },
      "4000000000 elements from byte 0 reach past bufferViews[0]");
  edited(
      "view", [](json& g) { g["bufferViews"][1]["byteLength"] = 1u << 31; },
      "reach past buffers[0]");
  edited(
      "buffer", [](json& g) { g["buffers"][0]["byteLength"] = 100000; },
      "exceeds the BIN chunk's 72 bytes");
  edited(
      "uri", [](json& g) { g["buffers"][0]["uri"] = "data.bin"; }, "is not read (a .glb holds");
  edited(
      "draco", [](json& g) { g["extensionsRequired"] = {"KHR_draco_mesh_compression"}; },
      "needs the extension KHR_draco_mesh_compression");
  edited(
      "cycle", [](json& g) { g["nodes"][0]["children"] = {0}; }, "nodes[0]: reached twice");
  edited(
      "sparse", [](json& g) { g["accessors"][0]["sparse"] = json::object(); },
      "sparse accessors are not read");
  edited(
      "missing", [](json& g) { g["accessors"][0].erase("count"); }, "accessors[0]: no count");
  edited(
      "negative", [](json& g) { g["accessors"][0]["byteOffset"] = -4; },
      "byteOffset: not an unsigned integer");
  edited(
      "lines only", [](json& g) { g["meshes"][0]["primitives"][0]["mode"] = 1; }, "no triangles");
  edited(
      "version 3", [](json& g) { g["asset"]["version"] = "3.0"; }, "glTF version '3.0'");
  {
    Tetra t;
    const uint16_t past = 4;
    std::memcpy(t.bin.data() + 48 + 2 * 5, &past, 2);
    cases.push_back({"index", t.bytes(), "index 4 at corner 5 is past its 4 vertices"});
  }
  {
    Tetra t;
    const float inf = 1e30f;
    t.gltf["nodes"][0]["scale"] = {1e30, 1, 1};
    std::memcpy(t.bin.data() + 12, &inf, 4);
    cases.push_back({"infinite", t.bytes(), "not a finite number"});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const auto m = read_glb(c.bytes, "bad.glb");
    ASSERT_FALSE(m.ok());
    const std::string& e = m.error().message();
    EXPECT_EQ(e.rfind("bad.glb: ", 0), 0u) << e;
    EXPECT_NE(e.find(c.what), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

TEST(GlbFile, TheFuzzSeedsAreWholeMeshes) {
  // tests/fuzz/corpus/glb_file: a node tree with a strip of byte indices,
  // interleaved normals under a fan, our own layout.
  const std::filesystem::path seeds =
      std::filesystem::path(SCULPT_TEST_DATA_DIR) / ".." / "fuzz" / "corpus" / "glb_file";
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
    SCOPED_TRACE(entry.path().string());
    const auto m = read_glb(entry.path());
    ASSERT_TRUE(m.ok()) << m.error().message();
    EXPECT_FALSE(m->triangles.empty());
    ++read;
  }
  EXPECT_EQ(read, 3);
}

TEST(GlbFile, RandomDamageIsAnErrorOrAMeshNeverACrash) {
  // A cheap, deterministic cousin of glb_file_fuzz for every test run (and
  // the sanitizer builds): bytes flipped, the file cut, lengths inflated.
  const std::string good = Tetra().bytes();
  uint32_t state = 12345;
  auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  int refused = 0;
  for (int round = 0; round < 5000; ++round) {
    std::string bytes = good;
    const int flips = 1 + static_cast<int>(next() % 4);
    for (int f = 0; f < flips; ++f)
      bytes[next() % bytes.size()] = static_cast<char>(next() >> 24);
    if (round % 7 == 0) bytes.resize(next() % bytes.size());
    const auto m = read_glb(bytes, "r.glb");
    if (!m.ok()) {
      ++refused;
      EXPECT_EQ(m.error().message().find('\n'), std::string::npos);
    } else {
      for (const glm::uvec3& t : m->triangles)
        ASSERT_LT(std::max({t.x, t.y, t.z}), m->positions.size());
    }
  }
  EXPECT_GT(refused, 2500);
}

TEST(GlbFile, AMeshInstancedPastTheLimitIsRefusedBeforeItIsBuilt) {
  Tetra t;
  json nodes = json::array();
  json roots = json::array();
  for (int i = 0; i < 100; ++i) {
    nodes.push_back({{"mesh", 0}});
    roots.push_back(i);
  }
  t.gltf["nodes"] = nodes;
  t.gltf["scenes"] = {{{"nodes", roots}}};
  GlbLimits limits;
  limits.max_triangles = 200;
  const auto m = read_glb(t.bytes(), "many.glb", limits);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message().find("grows past"), std::string::npos) << m.error().message();
  EXPECT_TRUE(read_glb(t.bytes(), "many.glb").ok());
}

}  // namespace
}  // namespace sculpt::core
