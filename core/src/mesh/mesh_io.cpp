#include "sculpt/core/mesh/mesh_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/geometric.hpp>

#include <nlohmann/json.hpp>

#include "sculpt/base/atomic_file.h"

namespace sculpt::core {
namespace {

static_assert(std::endian::native == std::endian::little,
              "binary PLY and STL are written little-endian");

// Output goes through a buffer flushed in large pieces: a mesh of millions of
// triangles would otherwise cost a call per number.
class Buffered {
 public:
  explicit Buffered(AtomicFileWriter& file) : file_(file) { buffer_.reserve(kFlush + 256); }
  ~Buffered() { flush(); }
  void bytes(const void* data, size_t size) {
    buffer_.append(static_cast<const char*>(data), size);
    if (buffer_.size() >= kFlush) flush();
  }
  template <class T>
  void value(T v) {
    bytes(&v, sizeof(v));
  }
  void text(std::string_view s) { bytes(s.data(), s.size()); }
  void number(float v) {
    char tmp[32];
    const auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    bytes(tmp, static_cast<size_t>(r.ptr - tmp));
  }
  void number(uint64_t v) {
    char tmp[24];
    const auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    bytes(tmp, static_cast<size_t>(r.ptr - tmp));
  }
  void flush() {
    if (!buffer_.empty()) file_.write(buffer_.data(), buffer_.size());
    buffer_.clear();
  }

 private:
  static constexpr size_t kFlush = size_t{1} << 20;
  AtomicFileWriter& file_;
  std::string buffer_;
};

glm::vec3 normal_of(const Mesh& mesh, size_t v) {
  return v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
}

void write_ply(Buffered& out, const Mesh& mesh, bool ascii) {
  const bool normals = mesh.normals.size() == mesh.positions.size();
  out.text(std::string("ply\nformat ") + (ascii ? "ascii" : "binary_little_endian") +
           " 1.0\ncomment sculpt: iso-surface, voxel units\nelement vertex " +
           std::to_string(mesh.positions.size()) +
           "\nproperty float x\nproperty float y\nproperty float z\n");
  if (normals) out.text("property float nx\nproperty float ny\nproperty float nz\n");
  out.text("element face " + std::to_string(mesh.triangles.size()) +
           "\nproperty list uchar uint vertex_indices\nend_header\n");
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    const glm::vec3 n = normal_of(mesh, v);
    if (ascii) {
      for (int k = 0; k < 3; ++k) {
        if (k) out.text(" ");
        out.number(p[k]);
      }
      if (normals)
        for (int k = 0; k < 3; ++k) {
          out.text(" ");
          out.number(n[k]);
        }
      out.text("\n");
    } else {
      out.bytes(&p, sizeof(p));
      if (normals) out.bytes(&n, sizeof(n));
    }
  }
  for (const glm::uvec3& t : mesh.triangles) {
    if (ascii) {
      out.text("3");
      for (int k = 0; k < 3; ++k) {
        out.text(" ");
        out.number(uint64_t{t[k]});
      }
      out.text("\n");
    } else {
      out.value(uint8_t{3});
      out.bytes(&t, sizeof(t));
    }
  }
}

void write_obj(Buffered& out, const Mesh& mesh) {
  const bool normals = mesh.normals.size() == mesh.positions.size();
  out.text("# sculpt: iso-surface, voxel units\n");
  for (const glm::vec3& p : mesh.positions) {
    out.text("v");
    for (int k = 0; k < 3; ++k) {
      out.text(" ");
      out.number(p[k]);
    }
    out.text("\n");
  }
  if (normals)
    for (const glm::vec3& n : mesh.normals) {
      out.text("vn");
      for (int k = 0; k < 3; ++k) {
        out.text(" ");
        out.number(n[k]);
      }
      out.text("\n");
    }
  for (const glm::uvec3& t : mesh.triangles) {
    out.text("f");
    for (int k = 0; k < 3; ++k) {
      out.text(" ");
      out.number(uint64_t{t[k]} + 1);  // OBJ counts from 1
      if (normals) {
        out.text("//");
        out.number(uint64_t{t[k]} + 1);
      }
    }
    out.text("\n");
  }
}

void write_stl(Buffered& out, const Mesh& mesh) {
  // The header must not start with "solid", or readers take the file for ASCII STL.
  char header[80] = {};
  const char* text = "sculpt binary STL: iso-surface, voxel units";
  std::memcpy(header, text, std::strlen(text));
  out.bytes(header, sizeof(header));
  out.value(static_cast<uint32_t>(mesh.triangles.size()));
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    const glm::vec3 cr = glm::cross(b - a, c - a);
    const float len = glm::length(cr);
    const glm::vec3 n = len > 0.0f ? cr / len : glm::vec3(0.0f);
    out.bytes(&n, sizeof(n));
    out.bytes(&a, sizeof(a));
    out.bytes(&b, sizeof(b));
    out.bytes(&c, sizeof(c));
    out.value(uint16_t{0});
  }
}

// Binary glTF 2.0 (the Khronos specification, "GLB File Format"): a 12-byte
// header, a JSON chunk padded with spaces to 4 bytes, a BIN chunk padded
// with zeros. Units stay voxels; glTF's +Y up is the sculpture's (DESIGN.md
// §3), and triangles are counter-clockwise seen from outside in both.
void write_glb(Buffered& out, const Mesh& mesh) {
  if (mesh.triangles.empty()) {
    // glTF forbids empty buffers: no surface is a scene with nothing in it.
    std::string text = R"({"asset":{"version":"2.0","generator":"sculpt station"},)"
                       R"("scene":0,"scenes":[{}]})";
    text.append((4 - text.size() % 4) % 4, ' ');
    out.text("glTF");
    out.value<uint32_t>(2);
    out.value<uint32_t>(static_cast<uint32_t>(12 + 8 + text.size()));
    out.value<uint32_t>(static_cast<uint32_t>(text.size()));
    out.text("JSON");
    out.text(text);
    return;
  }
  const bool normals = mesh.normals.size() == mesh.positions.size();
  const size_t vertices = mesh.positions.size();
  const size_t vec3_bytes = vertices * sizeof(glm::vec3);
  const size_t index_bytes = mesh.triangles.size() * sizeof(glm::uvec3);
  const size_t normal_offset = vec3_bytes;
  const size_t index_offset = vec3_bytes * (normals ? 2 : 1);
  const size_t bin_bytes = index_offset + index_bytes;  // every part a multiple of 4
  glm::vec3 lo(0.0f), hi(0.0f);
  if (vertices > 0) {
    lo = hi = mesh.positions[0];
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  using json = nlohmann::json;
  constexpr int kFloat = 5126, kUnsignedInt = 5125;            // componentType
  constexpr int kArrayBuffer = 34962, kElementBuffer = 34963;  // bufferView target
  json attributes = {{"POSITION", 0}};
  json views = json::array(
      {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vec3_bytes}, {"target", kArrayBuffer}}});
  json accessors = json::array({{{"bufferView", 0},
                                 {"componentType", kFloat},
                                 {"count", vertices},
                                 {"type", "VEC3"},
                                 {"min", {lo.x, lo.y, lo.z}},
                                 {"max", {hi.x, hi.y, hi.z}}}});
  if (normals) {
    attributes["NORMAL"] = 1;
    views.push_back({{"buffer", 0},
                     {"byteOffset", normal_offset},
                     {"byteLength", vec3_bytes},
                     {"target", kArrayBuffer}});
    accessors.push_back(
        {{"bufferView", 1}, {"componentType", kFloat}, {"count", vertices}, {"type", "VEC3"}});
  }
  const int index_view = normals ? 2 : 1;
  views.push_back({{"buffer", 0},
                   {"byteOffset", index_offset},
                   {"byteLength", index_bytes},
                   {"target", kElementBuffer}});
  accessors.push_back({{"bufferView", index_view},
                       {"componentType", kUnsignedInt},
                       {"count", mesh.triangles.size() * 3},
                       {"type", "SCALAR"}});
  const json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "sculpt station"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"name", "sculpture"}}}},
      {"meshes",
       {{{"name", "sculpture"},
         {"primitives", {{{"attributes", attributes}, {"indices", index_view}, {"mode", 4}}}}}}},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"byteLength", bin_bytes}}}},
  };
  std::string text = gltf.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  const auto total = static_cast<uint32_t>(12 + 8 + text.size() + 8 + bin_bytes);
  out.text("glTF");
  out.value<uint32_t>(2);
  out.value<uint32_t>(total);
  out.value<uint32_t>(static_cast<uint32_t>(text.size()));
  out.text("JSON");
  out.text(text);
  out.value<uint32_t>(static_cast<uint32_t>(bin_bytes));
  out.text(std::string_view("BIN\0", 4));
  out.bytes(mesh.positions.data(), vec3_bytes);
  if (normals) out.bytes(mesh.normals.data(), vec3_bytes);
  out.bytes(mesh.triangles.data(), index_bytes);
}

}  // namespace

Result<MeshFormat> mesh_format_for(const std::filesystem::path& path, bool ascii_ply) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".ply") return ascii_ply ? MeshFormat::kPlyAscii : MeshFormat::kPlyBinary;
  if (ext == ".obj") return MeshFormat::kObj;
  if (ext == ".stl") return MeshFormat::kStl;
  if (ext == ".glb") return MeshFormat::kGlb;
  return Error(path.string() + ": unknown mesh format '" + ext +
               "' (expected .ply, .obj, .stl or .glb)");
}

namespace {

bool finite(glm::vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// What every format assumes and no reader downstream forgives: finite
// coordinates (a NaN vertex is a bug upstream, named here rather than
// written) and triangles that index existing vertices.
Status check_writable(const std::filesystem::path& path, const Mesh& mesh) {
  auto fail = [&](const std::string& what) {
    return Error(path.string() + ": " + what + "; nothing written");
  };
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    if (!finite(mesh.positions[v]))
      return fail("vertex " + std::to_string(v) + " is not a finite position");
  for (size_t v = 0; v < mesh.normals.size(); ++v)
    if (!finite(mesh.normals[v]))
      return fail("the normal of vertex " + std::to_string(v) + " is not finite");
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 tri = mesh.triangles[t];
    if (std::max({tri.x, tri.y, tri.z}) >= mesh.positions.size())
      return fail("triangle " + std::to_string(t) + " names a vertex beyond the " +
                  std::to_string(mesh.positions.size()) + " there are");
  }
  return {};
}

}  // namespace

Status write_mesh(const std::filesystem::path& path, const Mesh& mesh, MeshFormat format) {
  if (Status writable = check_writable(path, mesh); !writable) return writable;
  if (format == MeshFormat::kStl && mesh.triangles.size() > UINT32_MAX) {
    return Error(path.string() + ": " + std::to_string(mesh.triangles.size()) +
                 " triangles do not fit a binary STL file");
  }
  // A GLB's lengths are 32-bit: at most 4 GiB in all.
  if (format == MeshFormat::kGlb &&
      mesh.positions.size() * 24 + mesh.triangles.size() * 12 > (uint64_t{1} << 32) - (1 << 16)) {
    return Error(path.string() + ": the mesh does not fit a GLB file's 4 GiB");
  }
  AtomicFileWriter file(path);
  if (!file.ok()) return file.error();
  {
    Buffered out(file);
    switch (format) {
      case MeshFormat::kPlyBinary:
        write_ply(out, mesh, false);
        break;
      case MeshFormat::kPlyAscii:
        write_ply(out, mesh, true);
        break;
      case MeshFormat::kObj:
        write_obj(out, mesh);
        break;
      case MeshFormat::kStl:
        write_stl(out, mesh);
        break;
      case MeshFormat::kGlb:
        write_glb(out, mesh);
        break;
    }
  }
  return file.commit();
}

}  // namespace sculpt::core
