#include "sculpt/core/mesh/brick_mesh.h"

#include <unordered_map>

namespace sculpt::core {

Mesh weld_brick_meshes(const std::vector<const BrickMesh*>& bricks) {
  Mesh out;
  size_t vertices = 0, triangles = 0;
  for (const BrickMesh* b : bricks) {
    vertices += b->mesh.positions.size();
    triangles += b->mesh.triangles.size();
  }
  out.positions.reserve(vertices);
  out.normals.reserve(vertices);
  out.triangles.reserve(triangles);
  std::unordered_map<uint64_t, uint32_t> seam;
  std::vector<uint32_t> remap;
  for (const BrickMesh* b : bricks) {
    const Mesh& m = b->mesh;
    remap.resize(m.positions.size());
    auto next_seam = b->seams.begin();
    for (size_t v = 0; v < m.positions.size(); ++v) {
      const auto next = static_cast<uint32_t>(out.positions.size());
      if (next_seam != b->seams.end() && next_seam->vertex == v) {
        auto [it, inserted] = seam.try_emplace(next_seam->key, next);
        ++next_seam;
        remap[v] = it->second;
        if (!inserted) continue;
      } else {
        remap[v] = next;
      }
      out.positions.push_back(m.positions[v]);
      out.normals.push_back(m.normals[v]);
    }
    for (const glm::uvec3& t : m.triangles)
      out.triangles.emplace_back(remap[t.x], remap[t.y], remap[t.z]);
  }
  return out;
}

}  // namespace sculpt::core
