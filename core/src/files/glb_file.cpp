#include "sculpt/core/files/glb_file.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

// The Khronos glTF 2.0 specification, §4.4 (GLB), §3.6 (buffers, views,
// accessors), §3.5 (nodes). Every number the JSON gives is checked before it
// is used as a size or an offset, and every offset against the bytes it
// points into, so a damaged file is an error line and never a read outside
// the file. nlohmann::json is used without exceptions: types are tested
// (is_number_unsigned(), ...) before values are taken.

namespace sculpt::core {
namespace {

static_assert(std::endian::native == std::endian::little, "GLB is little-endian");

using json = nlohmann::json;

constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125, kFloat = 5126;

uint32_t le32(const char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

std::string item(const char* array, uint64_t index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

// obj[key] when present.
const json* field(const json& obj, const char* key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

// An unsigned integer field: `fallback` when missing and one is given.
Result<uint64_t> uint_field(const json& obj, const char* key, const std::string& where,
                            std::optional<uint64_t> fallback = std::nullopt) {
  const json* v = field(obj, key);
  if (v == nullptr) {
    if (fallback) return *fallback;
    return Error(where + ": no " + key);
  }
  if (!v->is_number_unsigned()) return Error(where + "." + key + ": not an unsigned integer");
  return v->get<uint64_t>();
}

// root[array][index], an object.
Result<const json*> element(const json& root, const char* array, uint64_t index) {
  const json* a = field(root, array);
  if (a == nullptr || !a->is_array())
    return Error(item(array, index) + ": the file has no " + array);
  if (index >= a->size())
    return Error(item(array, index) + ": past the end (" + std::to_string(a->size()) + " " + array +
                 ")");
  const json& e = (*a)[static_cast<size_t>(index)];
  if (!e.is_object()) return Error(item(array, index) + ": not an object");
  return &e;
}

// `count` finite numbers from an array field, or `fallback` when missing.
template <size_t N>
Result<std::array<double, N>> numbers(const json& obj, const char* key, const std::string& where,
                                      std::array<double, N> fallback) {
  const json* v = field(obj, key);
  if (v == nullptr) return fallback;
  if (!v->is_array() || v->size() != N)
    return Error(where + "." + key + ": expected " + std::to_string(N) + " numbers");
  std::array<double, N> out{};
  for (size_t i = 0; i < N; ++i) {
    const json& x = (*v)[i];
    if (!x.is_number() || !std::isfinite(x.get<double>()))
      return Error(where + "." + key + ": not a finite number");
    out[i] = x.get<double>();
  }
  return out;
}

// Where an accessor's elements are in the BIN chunk.
struct Elements {
  const char* base = nullptr;
  uint64_t count = 0;
  uint64_t stride = 0;
  int component_type = 0;
};

size_t component_bytes(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

class GlbDocument {
 public:
  GlbDocument(const json& root, std::string_view bin, const GlbLimits& limits)
      : root_(root), bin_(bin), limits_(limits) {}

  Result<Mesh> read();

 private:
  Result<Elements> accessor(uint64_t index, const char* type, bool indices);
  Status add_node(uint64_t node, const glm::dmat4& parent, int depth);
  Status add_mesh(uint64_t mesh, const glm::dmat4& world);
  Status add_primitive(const json& primitive, const std::string& where, const glm::dmat4& world);

  const json& root_;
  std::string_view bin_;
  const GlbLimits& limits_;
  Mesh mesh_;
  bool all_have_normals_ = true;
  std::vector<bool> reached_;
};

Result<Elements> GlbDocument::accessor(uint64_t index, const char* type, bool indices) {
  const std::string where = item("accessors", index);
  auto a = element(root_, "accessors", index);
  if (!a) return a.error();
  const json& acc = **a;
  if (field(acc, "sparse") != nullptr) return Error(where + ": sparse accessors are not read");
  auto view_index = uint_field(acc, "bufferView", where);
  if (!view_index) return view_index.error();
  auto component = uint_field(acc, "componentType", where);
  if (!component) return component.error();
  auto count = uint_field(acc, "count", where);
  if (!count) return count.error();
  auto offset = uint_field(acc, "byteOffset", where, 0);
  if (!offset) return offset.error();
  const json* t = field(acc, "type");
  if (t == nullptr || !t->is_string() || t->get<std::string>() != type)
    return Error(where + ": type must be " + type);
  const json* normalized = field(acc, "normalized");
  if (normalized != nullptr && !(normalized->is_boolean() && !normalized->get<bool>()))
    return Error(where + ": normalized integers are not read");
  const int ct = static_cast<int>(std::min<uint64_t>(*component, 1u << 30));
  if (indices ? (ct != kUnsignedByte && ct != kUnsignedShort && ct != kUnsignedInt)
              : ct != kFloat) {
    return Error(where + ": componentType " + std::to_string(*component) + " (" +
                 (indices ? "indices are unsigned byte, short or int: 5121, 5123, 5125"
                          : "POSITION and NORMAL are read as float, 5126; quantized meshes "
                            "are not read") +
                 ")");
  }
  if (*count == 0) return Error(where + ": count is 0");
  const uint64_t element_bytes = component_bytes(ct) * (indices ? 1 : 3);

  const std::string view_where = item("bufferViews", *view_index);
  auto v = element(root_, "bufferViews", *view_index);
  if (!v) return v.error();
  auto buffer_index = uint_field(**v, "buffer", view_where);
  if (!buffer_index) return buffer_index.error();
  auto view_offset = uint_field(**v, "byteOffset", view_where, 0);
  if (!view_offset) return view_offset.error();
  auto view_length = uint_field(**v, "byteLength", view_where);
  if (!view_length) return view_length.error();
  auto stride = uint_field(**v, "byteStride", view_where, element_bytes);
  if (!stride) return stride.error();
  if (*stride < element_bytes || *stride > 252)
    return Error(view_where + ": byteStride " + std::to_string(*stride) + " (expected " +
                 std::to_string(element_bytes) + " to 252 for " + where + ")");

  const std::string buffer_where = item("buffers", *buffer_index);
  auto b = element(root_, "buffers", *buffer_index);
  if (!b) return b.error();
  if (field(**b, "uri") != nullptr)
    return Error(buffer_where +
                 ": data in another file or a data: URI is not read (a .glb holds its data "
                 "in its BIN chunk)");
  if (*buffer_index != 0) return Error(buffer_where + ": only buffer 0 can be the BIN chunk");
  auto buffer_length = uint_field(**b, "byteLength", buffer_where);
  if (!buffer_length) return buffer_length.error();
  if (*buffer_length > bin_.size())
    return Error(buffer_where + ": byteLength " + std::to_string(*buffer_length) +
                 " exceeds the BIN chunk's " + std::to_string(bin_.size()) + " bytes");
  // Each term is at most the buffer's length (<= 2^32) before it is added.
  if (*view_offset > *buffer_length || *view_length > *buffer_length - *view_offset)
    return Error(view_where + ": bytes " + std::to_string(*view_offset) + " + " +
                 std::to_string(*view_length) + " reach past " + buffer_where + " (" +
                 std::to_string(*buffer_length) + " bytes)");
  if (*offset > *view_length || *count - 1 > (*view_length - *offset) / *stride ||
      (*count - 1) * *stride + element_bytes > *view_length - *offset)
    return Error(where + ": " + std::to_string(*count) + " elements from byte " +
                 std::to_string(*offset) + " reach past " + view_where + " (" +
                 std::to_string(*view_length) + " bytes)");
  return Elements{bin_.data() + *view_offset + *offset, *count, *stride, ct};
}

glm::dvec3 vec3_at(const Elements& e, uint64_t i) {
  float v[3];
  std::memcpy(v, e.base + i * e.stride, sizeof v);
  return {v[0], v[1], v[2]};
}

uint64_t index_at(const Elements& e, uint64_t i) {
  const char* p = e.base + i * e.stride;
  switch (e.component_type) {
    case kUnsignedByte:
      return static_cast<uint8_t>(*p);
    case kUnsignedShort: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    default:
      return le32(p);
  }
}

Status GlbDocument::add_primitive(const json& primitive, const std::string& where,
                                  const glm::dmat4& world) {
  const json& p = primitive;
  auto mode = uint_field(p, "mode", where, 4);
  if (!mode) return mode.error();
  if (*mode < 4) return {};  // points and lines: no surface
  if (*mode > 6) return Error(where + ": mode " + std::to_string(*mode) + " is not a glTF mode");
  const json* attributes = field(p, "attributes");
  if (attributes == nullptr || !attributes->is_object()) return Error(where + ": no attributes");
  auto position_index = uint_field(*attributes, "POSITION", where + ".attributes");
  if (!position_index) return position_index.error();
  auto positions = accessor(*position_index, "VEC3", false);
  if (!positions) return positions.error();
  std::optional<Elements> normals;
  if (field(*attributes, "NORMAL") != nullptr) {
    auto normal_index = uint_field(*attributes, "NORMAL", where + ".attributes");
    if (!normal_index) return normal_index.error();
    auto n = accessor(*normal_index, "VEC3", false);
    if (!n) return n.error();
    if (n->count != positions->count)
      return Error(where + ": " + std::to_string(n->count) + " normals for " +
                   std::to_string(positions->count) + " positions");
    normals = *n;
  }
  std::optional<Elements> indices;
  if (field(p, "indices") != nullptr) {
    auto index = uint_field(p, "indices", where);
    if (!index) return index.error();
    auto e = accessor(*index, "SCALAR", true);
    if (!e) return e.error();
    indices = *e;
  }
  const uint64_t vertices = positions->count;
  const uint64_t corners = indices ? indices->count : vertices;
  uint64_t triangles = 0;
  if (*mode == 4) {
    if (corners % 3 != 0)
      return Error(where + ": " + std::to_string(corners) + " corners, not a multiple of 3");
    triangles = corners / 3;
  } else {
    triangles = corners >= 3 ? corners - 2 : 0;
  }
  const uint64_t base = mesh_.positions.size();
  if (vertices > static_cast<uint64_t>(limits_.max_vertices) - base ||
      triangles > static_cast<uint64_t>(limits_.max_triangles) - mesh_.triangles.size())
    return Error(where + ": the mesh grows past " + std::to_string(limits_.max_vertices) +
                 " vertices or " + std::to_string(limits_.max_triangles) + " triangles");

  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
  const bool identity = world == glm::dmat4(1.0);
  const bool flip = glm::determinant(glm::dmat3(world)) < 0.0;  // mirrored: winding reverses
  mesh_.positions.reserve(base + vertices);
  for (uint64_t i = 0; i < vertices; ++i) {
    const glm::dvec3 v = vec3_at(*positions, i);
    mesh_.positions.emplace_back(identity ? glm::vec3(v) : glm::vec3(world * glm::dvec4(v, 1.0)));
  }
  if (normals && all_have_normals_) {
    for (uint64_t i = 0; i < vertices; ++i) {
      if (identity) {  // as stored: a file we wrote reads back bit for bit
        mesh_.normals.emplace_back(glm::vec3(vec3_at(*normals, i)));
        continue;
      }
      const glm::dvec3 n = normal_matrix * vec3_at(*normals, i);
      const double len = glm::length(n);
      mesh_.normals.emplace_back(len > 0.0 && std::isfinite(len) ? glm::vec3(n / len)
                                                                 : glm::vec3(0.0f));
    }
  } else {
    all_have_normals_ = false;
    mesh_.normals.clear();
  }
  auto corner = [&](uint64_t i) -> uint64_t { return indices ? index_at(*indices, i) : i; };
  for (uint64_t i = 0; i < corners; ++i) {
    if (corner(i) >= vertices)
      return Error(where + ": index " + std::to_string(corner(i)) + " at corner " +
                   std::to_string(i) + " is past its " + std::to_string(vertices) + " vertices");
  }
  mesh_.triangles.reserve(mesh_.triangles.size() + triangles);
  for (uint64_t t = 0; t < triangles; ++t) {
    uint64_t a, b, c;
    if (*mode == 4) {
      a = corner(3 * t), b = corner(3 * t + 1), c = corner(3 * t + 2);
    } else if (*mode == 5) {  // strip: every other triangle turns the other way
      a = corner(t), b = corner(t + 1 + t % 2), c = corner(t + 2 - t % 2);
    } else {  // fan
      a = corner(0), b = corner(t + 1), c = corner(t + 2);
    }
    if (flip) std::swap(b, c);
    mesh_.triangles.emplace_back(static_cast<uint32_t>(base + a), static_cast<uint32_t>(base + b),
                                 static_cast<uint32_t>(base + c));
  }
  return {};
}

Status GlbDocument::add_mesh(uint64_t index, const glm::dmat4& world) {
  auto m = element(root_, "meshes", index);
  if (!m) return m.error();
  const json* primitives = field(**m, "primitives");
  const std::string where = item("meshes", index);
  if (primitives == nullptr || !primitives->is_array()) return Error(where + ": no primitives");
  for (size_t i = 0; i < primitives->size(); ++i) {
    if (Status st = add_primitive((*primitives)[i], where + "." + item("primitives", i), world);
        !st)
      return st;
  }
  return {};
}

Status GlbDocument::add_node(uint64_t index, const glm::dmat4& parent, int depth) {
  const std::string where = item("nodes", index);
  auto n = element(root_, "nodes", index);
  if (!n) return n.error();
  if (reached_[index]) return Error(where + ": reached twice (a node has one parent; a cycle?)");
  reached_[index] = true;
  if (depth > limits_.max_node_depth)
    return Error(where + ": nodes nested deeper than " + std::to_string(limits_.max_node_depth));
  const json& node = **n;
  glm::dmat4 local(1.0);
  if (field(node, "matrix") != nullptr) {
    auto m = numbers<16>(node, "matrix", where, {});
    if (!m) return m.error();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        local[c][r] = (*m)[static_cast<size_t>(4 * c + r)];  // column-major, as glm
  } else {
    auto t = numbers<3>(node, "translation", where, {0, 0, 0});
    if (!t) return t.error();
    auto r = numbers<4>(node, "rotation", where, {0, 0, 0, 1});
    if (!r) return r.error();
    auto s = numbers<3>(node, "scale", where, {1, 1, 1});
    if (!s) return s.error();
    const glm::dquat q((*r)[3], (*r)[0], (*r)[1], (*r)[2]);  // glTF stores x, y, z, w
    const double qn = glm::length(q);
    if (!(qn > 0.0)) return Error(where + ".rotation: not a rotation (zero quaternion)");
    local = glm::translate(glm::dmat4(1.0), glm::dvec3((*t)[0], (*t)[1], (*t)[2])) *
            glm::mat4_cast(q / qn) *
            glm::scale(glm::dmat4(1.0), glm::dvec3((*s)[0], (*s)[1], (*s)[2]));
  }
  const glm::dmat4 world = parent * local;
  if (field(node, "mesh") != nullptr) {
    auto mesh = uint_field(node, "mesh", where);
    if (!mesh) return mesh.error();
    if (Status st = add_mesh(*mesh, world); !st) return st;
  }
  if (const json* children = field(node, "children"); children != nullptr) {
    if (!children->is_array()) return Error(where + ".children: not an array");
    for (const json& c : *children) {
      if (!c.is_number_unsigned()) return Error(where + ".children: not a node index");
      if (Status st = add_node(c.get<uint64_t>(), world, depth + 1); !st) return st;
    }
  }
  return {};
}

Result<Mesh> GlbDocument::read() {
  const json* asset = field(root_, "asset");
  const json* version = asset ? field(*asset, "version") : nullptr;
  if (version == nullptr || !version->is_string())
    return Error("no asset.version (not a glTF 2.0 file)");
  const std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) return Error("glTF version '" + v + "' (2.x is read)");
  if (const json* required = field(root_, "extensionsRequired"); required != nullptr) {
    if (!required->is_array()) return Error("extensionsRequired: not an array");
    if (!required->empty()) {
      const json& first = (*required)[0];
      return Error("needs the extension " + (first.is_string() ? first.get<std::string>() : "?") +
                   ", which is not read (export without compression or quantization)");
    }
  }
  const json* nodes = field(root_, "nodes");
  reached_.assign(nodes != nullptr && nodes->is_array() ? nodes->size() : 0, false);
  const json* scenes = field(root_, "scenes");
  if (scenes != nullptr && scenes->is_array() && !scenes->empty()) {
    auto scene_index = uint_field(root_, "scene", "scene", 0);
    if (!scene_index) return scene_index.error();
    auto scene = element(root_, "scenes", *scene_index);
    if (!scene) return scene.error();
    if (const json* roots = field(**scene, "nodes"); roots != nullptr) {
      if (!roots->is_array()) return Error(item("scenes", *scene_index) + ".nodes: not an array");
      for (const json& r : *roots) {
        if (!r.is_number_unsigned())
          return Error(item("scenes", *scene_index) + ".nodes: not a node index");
        if (Status st = add_node(r.get<uint64_t>(), glm::dmat4(1.0), 0); !st) return st.error();
      }
    }
  } else if (const json* meshes = field(root_, "meshes"); meshes != nullptr) {
    if (!meshes->is_array()) return Error("meshes: not an array");
    for (size_t i = 0; i < meshes->size(); ++i)
      if (Status st = add_mesh(i, glm::dmat4(1.0)); !st) return st.error();
  }
  if (mesh_.triangles.empty()) return Error("no triangles in the scene");
  for (const glm::vec3& p : mesh_.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Error("a vertex coordinate is not a finite number");
  return std::move(mesh_);
}

}  // namespace

Result<Mesh> read_glb(std::string_view bytes, const std::string& name, const GlbLimits& limits) {
  const auto fail = [&](const std::string& what) { return Error(name + ": " + what); };
  if (bytes.size() < 12) return fail("too short for a GLB header (12 bytes)");
  if (bytes.substr(0, 4) != "glTF") {
    const size_t first = bytes.find_first_not_of(" \t\r\n");
    if (first != std::string_view::npos && bytes[first] == '{')
      return fail("a glTF JSON file, not binary glTF: save it as .glb (binary)");
    return fail("not a binary glTF file (no 'glTF' magic)");
  }
  if (const uint32_t version = le32(bytes.data() + 4); version != 2)
    return fail("GLB version " + std::to_string(version) + " (2 is read)");
  if (const uint32_t length = le32(bytes.data() + 8); length != bytes.size())
    return fail("the header says " + std::to_string(length) + " bytes, the file has " +
                std::to_string(bytes.size()) + " (cut off?)");
  std::string_view json_text, bin;
  size_t at = 12;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8)
      return fail("chunk " + std::to_string(chunk) + ": header cut off at byte " +
                  std::to_string(at));
    const uint32_t length = le32(bytes.data() + at), type = le32(bytes.data() + at + 4);
    at += 8;
    if (length > bytes.size() - at)
      return fail("chunk " + std::to_string(chunk) + ": " + std::to_string(length) +
                  " bytes from byte " + std::to_string(at) + " reach past the end");
    const std::string_view data = bytes.substr(at, length);
    at += length;
    if (chunk == 0) {
      if (type != kChunkJson) return fail("the first chunk is not JSON");
      json_text = data;
    } else if (chunk == 1 && type == kChunkBin) {
      bin = data;
    } else if (type == kChunkJson || type == kChunkBin) {
      return fail("chunk " + std::to_string(chunk) + ": a second JSON or BIN chunk");
    }  // other chunk types: skipped, as the specification asks
  }
  if (json_text.empty()) return fail("no JSON chunk");
  const json root = json::parse(json_text.begin(), json_text.end(), nullptr, false);
  if (root.is_discarded() || !root.is_object()) return fail("the JSON chunk is not a JSON object");
  auto mesh = GlbDocument(root, bin, limits).read();
  if (!mesh) return mesh.error().in(name);
  return mesh;
}

Result<Mesh> read_glb(const std::filesystem::path& path, const GlbLimits& limits) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return Error(name + ": cannot open file");
  const std::streamoff size = in.tellg();
  if (size < 0) return Error(name + ": cannot read file");
  if (size > limits.max_file_bytes)
    return Error(name + ": " + std::to_string(size) + " bytes, more than the " +
                 std::to_string(limits.max_file_bytes) + " a .glb can hold");
  std::string bytes(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), size)) return Error(name + ": cannot read file");
  return read_glb(bytes, name, limits);
}

}  // namespace sculpt::core
