#include "sculpt/core/mesh/mesh_reader.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace sculpt::core {
namespace {

Result<std::string> slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open file");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Status check_mesh(const Mesh& m) {
  if (m.triangles.empty()) return Error("no triangles");
  for (const glm::vec3& p : m.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return Error("vertex coordinate is not a finite number");
  return {};
}

Result<Mesh> read_obj(const std::string& text) {
  Mesh m;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      glm::vec3 p;
      if (!(ls >> p.x >> p.y >> p.z))
        return Error("line " + std::to_string(line_no) + ": v needs three numbers");
      m.positions.push_back(p);
    } else if (tag == "f") {
      std::vector<uint32_t> idx;
      std::string word;
      while (ls >> word) {
        long v = 0;
        try {
          v = std::stol(word.substr(0, word.find('/')));
        } catch (...) {
          return Error("line " + std::to_string(line_no) + ": bad face index '" + word + "'");
        }
        const long n = long(m.positions.size());
        const long i = v < 0 ? n + v : v - 1;
        if (v == 0 || i < 0 || i >= n)
          return Error("line " + std::to_string(line_no) + ": face index " + word +
                       " out of range (1.." + std::to_string(n) + ")");
        idx.push_back(uint32_t(i));
      }
      if (idx.size() < 3)
        return Error("line " + std::to_string(line_no) + ": face needs at least 3 vertices");
      for (size_t k = 1; k + 1 < idx.size(); ++k)
        m.triangles.push_back({idx[0], idx[k], idx[k + 1]});
    }
  }
  return m;
}

// PLY scalar types by name, with their sizes.
int ply_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

double ply_value(const char* p, const std::string& t, bool swap) {
  unsigned char b[8];
  const int n = ply_size(t);
  std::memcpy(b, p, n);
  if (swap) std::reverse(b, b + n);
  if (t == "char" || t == "int8") return double(int8_t(b[0]));
  if (t == "uchar" || t == "uint8") return double(b[0]);
  if (t == "short" || t == "int16") {
    int16_t v;
    std::memcpy(&v, b, 2);
    return v;
  }
  if (t == "ushort" || t == "uint16") {
    uint16_t v;
    std::memcpy(&v, b, 2);
    return v;
  }
  if (t == "int" || t == "int32") {
    int32_t v;
    std::memcpy(&v, b, 4);
    return v;
  }
  if (t == "uint" || t == "uint32") {
    uint32_t v;
    std::memcpy(&v, b, 4);
    return v;
  }
  if (t == "float" || t == "float32") {
    float v;
    std::memcpy(&v, b, 4);
    return v;
  }
  double v;
  std::memcpy(&v, b, 8);
  return v;
}

struct PlyProperty {
  std::string name, type, count_type;  // count_type non-empty: a list
};
struct PlyElement {
  std::string name;
  long count = 0;
  std::vector<PlyProperty> props;
};

Result<Mesh> read_ply(const std::string& data) {
  const size_t end = data.find("end_header");
  if (data.rfind("ply", 0) != 0 || end == std::string::npos)
    return Error("not a PLY file (no 'ply' magic or no end_header)");
  size_t body = data.find('\n', end);
  if (body == std::string::npos) return Error("header has no end");
  ++body;
  std::istringstream hs(data.substr(0, end));
  std::string line, format;
  std::vector<PlyElement> elements;
  while (std::getline(hs, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "format") {
      ls >> format;
    } else if (tag == "element") {
      PlyElement e;
      ls >> e.name >> e.count;
      if (e.count < 0 || e.count > (1L << 31)) return Error("element " + e.name + ": bad count");
      elements.push_back(e);
    } else if (tag == "property") {
      if (elements.empty()) return Error("property before any element");
      PlyProperty p;
      ls >> p.type;
      if (p.type == "list") ls >> p.count_type >> p.type;
      ls >> p.name;
      if (ply_size(p.type) == 0 || (!p.count_type.empty() && ply_size(p.count_type) == 0))
        return Error("property " + p.name + ": unknown type");
      elements.back().props.push_back(p);
    }
  }
  const bool ascii = format == "ascii";
  const bool little = format == "binary_little_endian";
  if (!ascii && !little && format != "binary_big_endian")
    return Error("format '" + format + "' is not ascii or binary");
  const bool swap = !ascii && (little != (std::endian::native == std::endian::little));
  // Every instance of an element holds at least one byte of data, so a
  // count the body cannot hold is refused before anything is stored (a
  // 240-byte file declaring 622,222,222 vertices of no properties grew to
  // 1.6 GB: found by fuzzing).
  const size_t body_bytes = data.size() - body;
  for (const PlyElement& e : elements) {
    if (e.count > 0 && e.props.empty())
      return Error("element " + e.name + ": " + std::to_string(e.count) +
                   " instances of no properties");
    if (static_cast<size_t>(e.count) > body_bytes)
      return Error("element " + e.name + ": " + std::to_string(e.count) +
                   " instances, but the data holds only " + std::to_string(body_bytes) + " bytes");
  }
  Mesh m;
  size_t pos = body;
  std::istringstream as(ascii ? data.substr(body) : std::string());
  auto read = [&](const std::string& type, double& v) -> bool {
    if (ascii) return bool(as >> v);
    const int n = ply_size(type);
    if (pos + n > data.size()) return false;
    v = ply_value(data.data() + pos, type, swap);
    pos += n;
    return true;
  };
  for (const PlyElement& e : elements) {
    for (long i = 0; i < e.count; ++i) {
      glm::vec3 p(0.0f);
      for (const PlyProperty& prop : e.props) {
        double v = 0;
        if (prop.count_type.empty()) {
          if (!read(prop.type, v))
            return Error(e.name + " " + std::to_string(i) + ": data ends early");
          if (e.name == "vertex") {
            if (prop.name == "x") p.x = float(v);
            if (prop.name == "y") p.y = float(v);
            if (prop.name == "z") p.z = float(v);
          }
          continue;
        }
        double count = 0;
        if (!read(prop.count_type, count) || count < 0 || count > 1e6)
          return Error(e.name + " " + std::to_string(i) + ": bad list length");
        std::vector<uint32_t> idx;
        for (int k = 0; k < int(count); ++k) {
          if (!read(prop.type, v))
            return Error(e.name + " " + std::to_string(i) + ": data ends early");
          // A float or huge index (found by fuzzing) is refused before the cast.
          if (!(v >= 0.0 && v < 4294967296.0) || v != std::floor(v))
            return Error(e.name + " " + std::to_string(i) + ": vertex index " + std::to_string(v) +
                         " is not a whole number from 0");
          idx.push_back(uint32_t(v));
        }
        if (e.name == "face" && (prop.name == "vertex_indices" || prop.name == "vertex_index")) {
          if (idx.size() < 3) return Error("face " + std::to_string(i) + ": fewer than 3 vertices");
          for (size_t k = 1; k + 1 < idx.size(); ++k)
            m.triangles.push_back({idx[0], idx[k], idx[k + 1]});
        }
      }
      if (e.name == "vertex") m.positions.push_back(p);
    }
  }
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (m.triangles[t][k] >= m.positions.size())
        return Error("face " + std::to_string(t) + ": vertex index " +
                     std::to_string(m.triangles[t][k]) + " out of range");
  return m;
}

Result<Mesh> read_stl(const std::string& data) {
  std::vector<glm::vec3> corners;
  const bool maybe_ascii = data.rfind("solid", 0) == 0 && data.find("facet") != std::string::npos;
  if (!maybe_ascii) {
    if (data.size() < 84) return Error("binary STL shorter than its 84-byte header");
    uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    if (data.size() < 84 + size_t(n) * 50)
      return Error("binary STL says " + std::to_string(n) + " triangles but holds " +
                   std::to_string((data.size() - 84) / 50));
    for (uint32_t t = 0; t < n; ++t)
      for (int k = 0; k < 3; ++k) {
        float v[3];
        std::memcpy(v, data.data() + 84 + size_t(t) * 50 + 12 + 12 * k, 12);
        corners.emplace_back(v[0], v[1], v[2]);
      }
  } else {
    std::istringstream in(data);
    std::string word;
    while (in >> word)
      if (word == "vertex") {
        glm::vec3 p;
        if (!(in >> p.x >> p.y >> p.z)) return Error("vertex needs three numbers");
        corners.push_back(p);
      }
    if (corners.size() % 3 != 0) return Error("vertex count is not a multiple of 3");
  }
  // Weld equal positions: STL repeats every corner per triangle.
  Mesh m;
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  auto id = [&](glm::vec3 p) {
    auto [it, added] = ids.try_emplace({p.x, p.y, p.z}, uint32_t(m.positions.size()));
    if (added) m.positions.push_back(p);
    return it->second;
  };
  for (size_t t = 0; t + 2 < corners.size(); t += 3)
    m.triangles.push_back({id(corners[t]), id(corners[t + 1]), id(corners[t + 2])});
  return m;
}

}  // namespace

Result<Mesh> read_mesh(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj" && ext != ".ply" && ext != ".stl")
    return Error(path.string() + ": unknown mesh extension '" + ext + "' (.obj, .ply, .stl)");
  auto data = slurp(path);
  if (!data) return data.error();
  Result<Mesh> mesh = ext == ".obj"   ? read_obj(*data)
                      : ext == ".ply" ? read_ply(*data)
                                      : read_stl(*data);
  if (!mesh) return mesh.error().in(path.string());
  if (Status st = check_mesh(*mesh); !st) return st.error().in(path.string());
  return mesh;
}

}  // namespace sculpt::core
