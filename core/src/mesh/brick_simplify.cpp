#include "sculpt/core/mesh/brick_simplify.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#include <meshoptimizer.h>

#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

namespace {

constexpr float kEstimateShare = 0.5f;
// The vertex cache the triangle order is made for: first in, first out,
// of meshoptimizer's usual size.
constexpr unsigned kVertexCacheSize = 16;

// The triangles with a vertex on the brick's faces: its seam vertices
// (keyed, on cell edges shared with a neighbour, whether still open or
// covered by the triangles that close the gaps against a coarser
// neighbour) and any other vertex of its open border. They are kept as
// marched (BorderHold::kBand). With the border's vertices alone locked, an
// inner vertex that collapses onto one face vertex can join it to another,
// and the neighbour may join the same two (an edge of four triangles once
// welded); keeping the band keeps every vertex next to a face, so nothing
// can reach across one. `on_border`: the mesh's border vertices
// (check_topology). With BorderHold::kVertices, the band of the covered
// seam vertices alone: the flat fans that close gaps against a
// coarser neighbour, which the simplifier would fold.
std::vector<bool> face_band(const BrickMesh& brick, std::vector<bool> on_border, BorderHold hold) {
  const Mesh& m = brick.mesh;
  if (hold == BorderHold::kVertices) {
    std::vector<bool> covered(on_border.size(), false);
    for (const BrickMesh::Seam& seam : brick.seams)
      covered[seam.vertex] = !on_border[seam.vertex];
    on_border = std::move(covered);
  } else {
    for (const BrickMesh::Seam& seam : brick.seams)
      on_border[seam.vertex] = true;
  }
  std::vector<bool> band(m.triangles.size(), false);
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const glm::uvec3& tri = m.triangles[t];
    band[t] = on_border[tri.x] || on_border[tri.y] || on_border[tri.z];
  }
  return band;
}

// The brick made of `indices` (into brick's vertices), its unused vertices
// dropped, in their old order (seams stay sorted by vertex).
BrickMesh compact(const BrickMesh& brick, const std::vector<unsigned>& indices) {
  const Mesh& in = brick.mesh;
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> remap(in.positions.size(), kUnused);
  for (unsigned i : indices)
    remap[i] = 0;
  BrickMesh out;
  Mesh& m = out.mesh;
  const bool normals = in.normals.size() == in.positions.size();
  for (size_t v = 0; v < in.positions.size(); ++v) {
    if (remap[v] == kUnused) continue;
    remap[v] = static_cast<uint32_t>(m.positions.size());
    m.positions.push_back(in.positions[v]);
    if (normals) m.normals.push_back(in.normals[v]);
  }
  m.triangles.resize(indices.size() / 3);
  for (size_t t = 0; t < m.triangles.size(); ++t)
    m.triangles[t] = {remap[indices[3 * t]], remap[indices[3 * t + 1]], remap[indices[3 * t + 2]]};
  for (const BrickMesh::Seam& seam : brick.seams)
    if (remap[seam.vertex] != kUnused) out.seams.push_back({remap[seam.vertex], seam.key});
  return out;
}

// Whether simplifying kept the brick's surface whole: the same open border,
// and no edge or vertex where sheets meet that the march did not have.
bool same_topology(const MeshTopology& marched, const Mesh& simplified) {
  const MeshTopology t = check_topology(simplified);
  return t.boundary_edges == marched.boundary_edges && t.nonmanifold_edges == 0 &&
         t.misoriented_edges == 0 && t.nonmanifold_vertices <= marched.nonmanifold_vertices;
}

}  // namespace

SimplifiedBrick simplify_brick_mesh(const BrickMesh& brick, float max_error, BorderHold hold) {
  const Mesh& in = brick.mesh;
  if (in.triangles.empty() || !(max_error > 0.0f)) return {brick, 0.0f};
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float) &&
                sizeof(glm::uvec3) == 3 * sizeof(unsigned));
  const float* positions = &in.positions[0].x;
  const size_t vertex_count = in.positions.size();
  // The march's topology, which simplifying must keep, and its border.
  std::vector<bool> border;
  const MeshTopology marched = check_topology(in, &border);
  // Held, as marched: the band, or (the border's vertices locked below)
  // the band of the gaps' fans alone.
  const std::vector<bool> band = face_band(brick, std::move(border), hold);
  std::vector<unsigned> kept, inner;
  for (size_t t = 0; t < in.triangles.size(); ++t) {
    std::vector<unsigned>& to = band[t] ? kept : inner;
    to.insert(to.end(), {in.triangles[t].x, in.triangles[t].y, in.triangles[t].z});
  }
  // The simplifier's error is relative to the mesh's extent.
  const float scale = meshopt_simplifyScale(positions, vertex_count, sizeof(glm::vec3));
  if (inner.empty() || !(scale > 0.0f)) return {brick, 0.0f};
  // meshoptimizer does not check every collapse against folding the
  // surface onto itself: now and then (one brick of the played demo's
  // thousand) a collapse makes an edge of four triangles. Such a result is
  // refused and the brick simplified again, less, and at worst kept as
  // marched.
  float target = max_error;
  for (int attempt = 0; attempt < 3; ++attempt, target *= 0.5f) {
    // Target 0 triangles: as few as the error bound allows. The inner
    // part's border (the band's inner edge) stays where it is. The
    // simplifier's error is an estimate: the marched vertices measured up
    // to 1.8 times as far from the simplified surface, so it is asked for
    // half the bound.
    std::vector<unsigned> simplified(inner.size());
    float relative_error = 0.0f;
    simplified.resize(meshopt_simplify(
        simplified.data(), inner.data(), inner.size(), positions, vertex_count, sizeof(glm::vec3),
        0, kEstimateShare * target / scale, meshopt_SimplifyLockBorder, &relative_error));
    std::vector<unsigned> indices = kept;
    indices.insert(indices.end(), simplified.begin(), simplified.end());
    BrickMesh out = compact(brick, indices);
    if (same_topology(marched, out.mesh)) {
      // The triangles in an order that uses recently used vertices again:
      // a software renderer (Mesa's llvmpipe) shades a vertex again once it
      // has left a small cache, and the drawn meshes are these (5-15% less
      // of llvmpipe's time per frame on the played demo). The FIFO
      // ordering: as good there as meshoptimizer's general one, in less time.
      if (!out.mesh.triangles.empty()) {
        unsigned* corners = &out.mesh.triangles[0].x;
        meshopt_optimizeVertexCacheFifo(corners, corners, 3 * out.mesh.triangles.size(),
                                        out.mesh.positions.size(), kVertexCacheSize);
      }
      return {std::move(out), relative_error * scale / kEstimateShare};
    }
  }
  return {brick, 0.0f};
}

}  // namespace sculpt::core
