#include "sculpt/core/mesh/brick_simplify.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_set>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <meshoptimizer.h>

#include "mesh/by_vertex.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/point_triangle.h"

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

// The vertices renumbered in the order the triangles first use them
// (meshoptimizer's vertex fetch order; normals and seams follow). llvmpipe
// keeps the vertices it has shaded by their number's low byte (256 slots):
// numbered as they are drawn, a vertex used again soon is still in its
// slot, where numbered in the march's order, two used together may take
// one slot in turn. compact() leaves no vertex unused.
void number_vertices_in_use_order(BrickMesh& brick) {
  Mesh& m = brick.mesh;
  unsigned* corners = &m.triangles[0].x;
  const size_t corner_count = 3 * m.triangles.size();
  std::vector<unsigned> remap(m.positions.size());
  const size_t used =
      meshopt_optimizeVertexFetchRemap(remap.data(), corners, corner_count, m.positions.size());
  meshopt_remapIndexBuffer(corners, corners, corner_count, remap.data());
  auto reorder = [&](std::vector<glm::vec3>& values) {
    if (values.size() != remap.size()) return;
    std::vector<glm::vec3> out(used);
    meshopt_remapVertexBuffer(out.data(), values.data(), values.size(), sizeof(glm::vec3),
                              remap.data());
    values = std::move(out);
  };
  reorder(m.positions);
  reorder(m.normals);
  for (BrickMesh::Seam& seam : brick.seams)
    seam.vertex = remap[seam.vertex];
  std::sort(brick.seams.begin(), brick.seams.end(),
            [](const BrickMesh::Seam& a, const BrickMesh::Seam& b) { return a.vertex < b.vertex; });
}

// Whether simplifying kept the brick's surface whole: the same open border,
// and no edge or vertex where sheets meet that the march did not have.
bool same_topology(const MeshTopology& marched, const Mesh& simplified) {
  const MeshTopology t = check_topology(simplified);
  return t.boundary_edges == marched.boundary_edges && t.nonmanifold_edges == 0 &&
         t.misoriented_edges == 0 && t.nonmanifold_vertices <= marched.nonmanifold_vertices;
}

// Marched triangles held around each corner of a simplified triangle whose
// normals turn too far (NormalTurnLimit), in rings of triangles, and how
// many times a part is simplified again for them. On
// the played demo at 37 degrees: one ring a round left streaks after eight
// rounds; two rings none, nine parts in ten done within two rounds.
constexpr int kHeldRings = 2;
// Around a removed vertex (NormalTurnLimit::max_removed_deg), one ring is
// enough: the played demo and bust as clean as with two, with 6% more
// triangles drawn instead of 13% and 7%.
constexpr int kHeldRingsAroundRemoved = 1;
constexpr int kHoldRounds = 4;

// The marched triangles: which lie around each vertex, and whether a
// triangle is one of them. Made when first asked for: most parts simplify
// without a triangle that turns too far.
class MarchedTriangles {
 public:
  explicit MarchedTriangles(const Mesh& m) : m_(m) {}

  bool contains(unsigned a, unsigned b, unsigned c) {
    if (keys_.empty()) {
      keys_.reserve(m_.triangles.size());
      for (const glm::uvec3& t : m_.triangles)
        keys_.insert(key(t.x, t.y, t.z));
    }
    return keys_.contains(key(a, b, c));
  }

  // Holds the triangles within `rings` rings of triangles around
  // `vertices`; whether any was not held before.
  bool hold(std::vector<uint32_t> vertices, int rings, std::vector<bool>& held) {
    if (!around_) {
      around_.emplace(m_.positions.size(), [&](auto put) {
        for (size_t t = 0; t < m_.triangles.size(); ++t)
          for (int k = 0; k < 3; ++k)
            put(m_.triangles[t][k], static_cast<uint32_t>(t));
      });
    }
    bool more = false;
    for (int ring = 0; ring < rings; ++ring) {
      std::vector<uint32_t> next;
      for (uint32_t v : vertices)
        for (const uint32_t t : around_->of(v)) {
          if (held[t]) continue;
          held[t] = more = true;
          next.insert(next.end(), {m_.triangles[t].x, m_.triangles[t].y, m_.triangles[t].z});
        }
      vertices = std::move(next);
    }
    return more;
  }

 private:
  // The same triangle whichever corner comes first (the simplifier keeps
  // a triangle's winding, not its first corner): 21 bits a corner
  // (simplify_part checks no larger mesh).
  static uint64_t key(uint64_t a, uint64_t b, uint64_t c) {
    if (b < a && b < c) return key(b, c, a);
    if (c < a && c < b) return key(c, a, b);
    return a | (b << 21) | (c << 42);
  }

  const Mesh& m_;
  std::unordered_set<uint64_t> keys_;
  std::optional<detail::ByVertex<uint32_t>> around_;  // each vertex's triangles
};

// The triangles a simplifier made, binned in a grid of cells each made
// triangle's box, grown by `reach`, overlaps: a point within `reach` of its
// nearest made triangle finds it among its cell's.
class MadeTriangles {
 public:
  struct Made {
    glm::vec3 a, ab, ac;
    glm::uvec3 corners;
  };

  MadeTriangles(const Mesh& in, const std::vector<unsigned>& made, float reach) : reach_(reach) {
    triangles_.reserve(made.size() / 3);
    std::vector<std::pair<glm::vec3, glm::vec3>> boxes;
    boxes.reserve(made.size() / 3);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (size_t i = 0; i + 2 < made.size(); i += 3) {
      const glm::uvec3 t(made[i], made[i + 1], made[i + 2]);
      const glm::vec3 a = in.positions[t.x], b = in.positions[t.y], c = in.positions[t.z];
      triangles_.push_back({a, b - a, c - a, t});
      boxes.emplace_back(glm::min(a, glm::min(b, c)) - reach, glm::max(a, glm::max(b, c)) + reach);
      lo = glm::min(lo, boxes.back().first);
      hi = glm::max(hi, boxes.back().second);
    }
    if (triangles_.empty()) return;
    // Cells about twice the reach, at most kMaxCells along an axis.
    const glm::vec3 extent = hi - lo;
    cell_ = std::max(
        {2.0f * reach, extent.x / kMaxCells, extent.y / kMaxCells, extent.z / kMaxCells, 1e-6f});
    lo_ = lo;
    dims_ = glm::clamp(glm::ivec3(extent / cell_) + 1, 1, kMaxCells + 1);
    first_.assign(static_cast<size_t>(dims_.x) * dims_.y * dims_.z + 1, 0);
    auto each_cell = [&](const std::pair<glm::vec3, glm::vec3>& box, auto&& f) {
      const glm::ivec3 c0 = cell_of(box.first), c1 = cell_of(box.second);
      for (int z = c0.z; z <= c1.z; ++z)
        for (int y = c0.y; y <= c1.y; ++y)
          for (int x = c0.x; x <= c1.x; ++x)
            f(static_cast<size_t>((z * dims_.y + y) * dims_.x + x));
    };
    for (const auto& box : boxes)
      each_cell(box, [&](size_t c) { ++first_[c + 1]; });
    for (size_t c = 1; c < first_.size(); ++c)
      first_[c] += first_[c - 1];
    in_cell_.resize(first_.back());
    std::vector<uint32_t> next(first_.begin(), first_.end() - 1);
    for (size_t t = 0; t < boxes.size(); ++t)
      each_cell(boxes[t], [&](size_t c) { in_cell_[next[c]++] = static_cast<uint32_t>(t); });
  }

  bool empty() const { return triangles_.empty(); }

  // The made triangle nearest to p (not empty()).
  const Made& nearest(glm::vec3 p) const {
    const glm::ivec3 c = cell_of(p);
    const Made* best = nullptr;
    float best_d2 = reach_ * reach_;
    auto consider = [&](const Made& t) {
      const float d2 = triangle_distance2(p, t.a, t.ab, t.ac);
      if (d2 <= best_d2) {
        best_d2 = d2;
        best = &t;
      }
    };
    if (glm::all(glm::equal(c, glm::clamp(c, glm::ivec3(0), dims_ - 1)))) {
      const size_t cell = static_cast<size_t>((c.z * dims_.y + c.y) * dims_.x + c.x);
      for (uint32_t i = first_[cell]; i < first_[cell + 1]; ++i)
        consider(triangles_[in_cell_[i]]);
    }
    if (best != nullptr) return *best;
    // Further than the reach from every made triangle: all of them.
    best_d2 = std::numeric_limits<float>::max();
    for (const Made& t : triangles_)
      consider(t);
    return *best;
  }

 private:
  static constexpr int kMaxCells = 24;

  glm::ivec3 cell_of(glm::vec3 p) const { return glm::ivec3(glm::floor((p - lo_) / cell_)); }

  float reach_;
  std::vector<Made> triangles_;
  glm::vec3 lo_{0.0f};
  float cell_ = 1.0f;
  glm::ivec3 dims_{1};
  std::vector<uint32_t> first_, in_cell_;  // each cell's triangles
};

// The vertices of `part` the simplifier removed (no triangle of `made` uses
// them) whose own normal lies further than acos(min_cos) from the one the
// simplified surface interpolates at its nearest point. Where the clay
// turns one way and back (a concave fillet at an eyebrow's end), the
// corners of a triangle over it can agree within any angle, yet it drops
// the turn between them: a light blob on the drawn clay. `reach`: about
// how far the removed vertices lie from the made surface (the error
// bound; any distance is right, this one is quick).
std::vector<uint32_t> removed_turning(const Mesh& in, const std::vector<unsigned>& part,
                                      const std::vector<unsigned>& made, float min_cos,
                                      float reach) {
  std::vector<uint32_t> turning;
  const MadeTriangles triangles(in, made, reach);
  if (triangles.empty()) return turning;
  std::vector<uint8_t> seen(in.positions.size(), 0);
  for (const unsigned v : made)
    seen[v] = 1;
  for (const unsigned v : part) {
    if (seen[v] != 0) continue;
    seen[v] = 1;  // each removed vertex once
    const glm::vec3 p = in.positions[v];
    const MadeTriangles::Made& t = triangles.nearest(p);
    // Barycentric weights of the nearest point (on the triangle, so in
    // [0, 1]); a degenerate triangle interpolates evenly.
    const glm::vec3 q = closest_point_on_triangle(p, t.a, t.a + t.ab, t.a + t.ac).point - t.a;
    const float d00 = glm::dot(t.ab, t.ab), d01 = glm::dot(t.ab, t.ac), d11 = glm::dot(t.ac, t.ac);
    const float d20 = glm::dot(q, t.ab), d21 = glm::dot(q, t.ac);
    const float den = d00 * d11 - d01 * d01;
    float wb = 1.0f / 3.0f, wc = 1.0f / 3.0f;
    if (den > 0.0f) {
      wb = std::clamp((d11 * d20 - d01 * d21) / den, 0.0f, 1.0f);
      wc = std::clamp((d00 * d21 - d01 * d20) / den, 0.0f, 1.0f - wb);
    }
    const glm::vec3 n = (1.0f - wb - wc) * in.normals[t.corners.x] + wb * in.normals[t.corners.y] +
                        wc * in.normals[t.corners.z];
    const float len = glm::length(n);
    if (!(len > 0.0f) || glm::dot(in.normals[v], n) < min_cos * len) turning.push_back(v);
  }
  return turning;
}

// The marched triangles not `held`, simplified with their part's border
// locked, as indices into the marched vertices. Where the normals turn
// further than `turn` allows, the marched triangles around are held: around
// the corners of a simplified triangle (not one of the marched) whose
// corners' normals are further apart than turn.max_deg (or, along an edge
// longer than turn.full_turn_length, than that angle times
// full_turn_length over the edge's length), and around a vertex it removed
// further than turn.max_removed_deg from the surface made over it
// (removed_turning). The part is then simplified again, up to kHoldRounds
// times; `held` grows by them. With TurnLimit::kCount nothing is held:
// the made triangles are only counted (removed vertices not looked at).
// `max_error`: the bound `relative_target` stands for, in the positions'
// units (the reach of removed_turning's search). `relative_error` becomes
// at least the simplifier's estimate, `turning_left` grows by the places
// left.
std::vector<unsigned> simplify_part(const Mesh& in, MarchedTriangles& marched,
                                    std::vector<bool>& held, float relative_target, float max_error,
                                    const NormalTurnLimit& turn, float& relative_error,
                                    int64_t& turning_left) {
  auto cos_of = [](float deg) { return deg >= 180.0f ? -2.0f : std::cos(glm::radians(deg)); };
  const float min_turn_cos = cos_of(turn.max_deg), min_removed_cos = cos_of(turn.max_removed_deg);
  const float full_turn_length = turn.full_turn_length;
  const bool has_normals =
      in.normals.size() == in.positions.size() && in.positions.size() < (size_t{1} << 21);
  const bool turns_checked = min_turn_cos > -1.0f && has_normals;
  const bool removed_checked =
      min_removed_cos > -1.0f && has_normals && turn.action == TurnLimit::kHold;
  const float max_turn_rad = std::acos(std::max(min_turn_cos, -1.0f));
  auto edge_turns = [&](unsigned a, unsigned b) {
    const float cos = glm::dot(in.normals[a], in.normals[b]);
    if (cos < min_turn_cos) return true;
    const float length = glm::distance(in.positions[a], in.positions[b]);
    return full_turn_length > 0.0f && length > full_turn_length &&
           std::acos(std::min(cos, 1.0f)) * length > max_turn_rad * full_turn_length;
  };
  auto turns_too_far = [&](unsigned a, unsigned b, unsigned c) {
    return edge_turns(a, b) || edge_turns(b, c) || edge_turns(a, c);
  };
  for (int round = 0;; ++round) {
    std::vector<unsigned> part;
    for (size_t t = 0; t < in.triangles.size(); ++t)
      if (!held[t])
        part.insert(part.end(), {in.triangles[t].x, in.triangles[t].y, in.triangles[t].z});
    if (part.empty()) return part;
    // Target 0 triangles: as few as the error bound allows.
    std::vector<unsigned> out(part.size());
    float error = 0.0f;
    out.resize(meshopt_simplify(out.data(), part.data(), part.size(), &in.positions[0].x,
                                in.positions.size(), sizeof(glm::vec3), 0, relative_target,
                                meshopt_SimplifyLockBorder, &error));
    std::vector<uint32_t> turning;
    if (turns_checked)
      for (size_t i = 0; i + 2 < out.size(); i += 3)
        if (turns_too_far(out[i], out[i + 1], out[i + 2]) &&
            !marched.contains(out[i], out[i + 1], out[i + 2]))
          turning.insert(turning.end(), {out[i], out[i + 1], out[i + 2]});
    std::vector<uint32_t> removed;
    if (removed_checked) removed = removed_turning(in, part, out, min_removed_cos, max_error);
    const size_t turning_count = turning.size() / 3 + removed.size();
    auto hold_more = [&] {
      const bool around_made = marched.hold(std::move(turning), kHeldRings, held);
      const bool around_removed = marched.hold(std::move(removed), kHeldRingsAroundRemoved, held);
      return around_made || around_removed;
    };
    if (turning_count == 0 || turn.action == TurnLimit::kCount || round == kHoldRounds ||
        !hold_more()) {
      relative_error = std::max(relative_error, error);
      turning_left += static_cast<int64_t>(turning_count);
      return out;
    }
  }
}

}  // namespace

SimplifiedBrick simplify_brick_mesh(const BrickMesh& brick, float max_error, BorderHold hold,
                                    const NormalTurnLimit& turn) {
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
  // The simplifier's error is relative to the mesh's extent.
  const float scale = meshopt_simplifyScale(positions, vertex_count, sizeof(glm::vec3));
  if (!(scale > 0.0f) || std::all_of(band.begin(), band.end(), [](bool b) { return b; }))
    return {brick, 0.0f};
  MarchedTriangles marched_triangles(in);
  // meshoptimizer does not check every collapse against folding the
  // surface onto itself: now and then (one brick of the played demo's
  // thousand) a collapse makes an edge of four triangles. Such a result is
  // refused and the brick simplified again, less, and at worst kept as
  // marched.
  float target = max_error;
  for (int attempt = 0; attempt < 3; ++attempt, target *= 0.5f) {
    // The simplifier's error is an estimate: the marched vertices measured
    // up to 1.8 times as far from the simplified surface, so it is asked
    // for half the bound.
    const float relative_target = kEstimateShare * target / scale;
    float relative_error = 0.0f;
    int64_t turning = 0;
    // The brick inside its band first, then what that held where the
    // shading turns: there only collapses that keep the turn across short
    // triangles stay (mostly along a crease, not across it).
    std::vector<bool> held_first = band;
    const std::vector<unsigned> smooth = simplify_part(
        in, marched_triangles, held_first, relative_target, target, turn, relative_error, turning);
    std::vector<bool> held_then(held_first.size());
    for (size_t t = 0; t < held_then.size(); ++t)
      held_then[t] = !held_first[t] || band[t];
    const std::vector<unsigned> creases = simplify_part(
        in, marched_triangles, held_then, relative_target, target, turn, relative_error, turning);
    // Marched: what both held.
    std::vector<unsigned> indices;
    for (size_t t = 0; t < in.triangles.size(); ++t)
      if (held_first[t] && held_then[t])
        indices.insert(indices.end(), {in.triangles[t].x, in.triangles[t].y, in.triangles[t].z});
    indices.insert(indices.end(), smooth.begin(), smooth.end());
    indices.insert(indices.end(), creases.begin(), creases.end());
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
        number_vertices_in_use_order(out);
      }
      return {std::move(out), relative_error * scale / kEstimateShare, turning};
    }
  }
  return {brick, 0.0f};
}

}  // namespace sculpt::core
