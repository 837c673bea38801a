#include "sculpt/core/mesh/marching_cubes.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <type_traits>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"

namespace sculpt::core {
namespace {

// Corner k of a cell sits at (k & 1, (k >> 1) & 1, k >> 2); bit k of a cell's
// case is set when corner k is inside. Edges 0-3 run along x, 4-7 along y,
// 8-11 along z.
constexpr std::array<std::array<uint8_t, 2>, 12> kEdgeCorners = {{{0, 1},
                                                                  {2, 3},
                                                                  {4, 5},
                                                                  {6, 7},
                                                                  {0, 2},
                                                                  {1, 3},
                                                                  {4, 6},
                                                                  {5, 7},
                                                                  {0, 4},
                                                                  {1, 5},
                                                                  {2, 6},
                                                                  {3, 7}}};

constexpr glm::ivec3 corner_offset(int k) {
  return {k & 1, (k >> 1) & 1, k >> 2};
}
// Lower corner of each edge.
constexpr std::array<glm::ivec3, 12> kEdgeOrigin = {
    corner_offset(0), corner_offset(2), corner_offset(4), corner_offset(6),
    corner_offset(0), corner_offset(1), corner_offset(4), corner_offset(5),
    corner_offset(0), corner_offset(1), corner_offset(2), corner_offset(3)};

// The triangle table is generated rather than typed in: for every case and
// every way of resolving its ambiguous faces, the surface's boundary on each
// face is a set of segments fixed by that face alone, so neighbouring cells
// agree on it; chaining the segments gives closed loops, fanned into
// triangles. Resolving each face by its own data (the asymptotic decider) is
// what makes the surface free of holes.
struct Tables {
  // Per face: corners in counter-clockwise order seen from outside the cell,
  // and the edge from corner i to corner i+1.
  std::array<std::array<uint8_t, 4>, 6> face_corners{};
  std::array<std::array<uint8_t, 4>, 6> face_edges{};
  // Per case: ambiguous faces (bit f) and where its entries start; entry
  // first_entry[c] + d holds the triangles for decision bits d (bit j: the
  // j-th ambiguous face connects its inside corners).
  std::array<uint8_t, 256> ambiguous{};
  std::array<uint32_t, 256> first_entry{};
  std::vector<uint32_t> entry_begin;  // into tri_edges, one past the last entry too
  std::vector<uint8_t> tri_edges;     // three cell edges per triangle; 12 + k: centre k
  // Centre vertices of an entry: centre_masks[centre_begin[entry] + k] holds
  // the edges whose vertices centre k averages.
  std::vector<uint32_t> centre_begin;
  // Per entry: the cell edges whose vertices it uses.
  std::vector<uint16_t> entry_edges;
  std::vector<uint16_t> centre_masks;
};

bool edges_share_face(const Tables& t, int e1, int e2) {
  for (const auto& fe : t.face_edges) {
    const bool has1 = std::find(fe.begin(), fe.end(), e1) != fe.end();
    const bool has2 = std::find(fe.begin(), fe.end(), e2) != fe.end();
    if (has1 && has2) return true;
  }
  return false;
}

int edge_between(int a, int b) {
  for (int e = 0; e < 12; ++e) {
    if ((kEdgeCorners[e][0] == a && kEdgeCorners[e][1] == b) ||
        (kEdgeCorners[e][0] == b && kEdgeCorners[e][1] == a))
      return e;
  }
  assert(false);
  return -1;
}

Tables build_tables() {
  Tables t;
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2, side = f % 2;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    // (u, v, +axis) is right-handed: counter-clockwise in (u, v) faces +axis.
    std::array<glm::ivec2, 4> uv = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
    if (side == 0) uv = {{{0, 0}, {0, 1}, {1, 1}, {1, 0}}};
    for (int i = 0; i < 4; ++i) {
      glm::ivec3 p(0);
      p[axis] = side;
      p[u] = uv[i].x;
      p[v] = uv[i].y;
      t.face_corners[f][i] = static_cast<uint8_t>(p.x + 2 * p.y + 4 * p.z);
    }
    for (int i = 0; i < 4; ++i) {
      t.face_edges[f][i] =
          static_cast<uint8_t>(edge_between(t.face_corners[f][i], t.face_corners[f][(i + 1) % 4]));
    }
  }
  t.entry_begin.push_back(0);
  t.centre_begin.push_back(0);
  for (int c = 0; c < 256; ++c) {
    auto inside = [c](int corner) { return ((c >> corner) & 1) != 0; };
    std::vector<int> amb_faces;
    for (int f = 0; f < 6; ++f) {
      const auto& fc = t.face_corners[f];
      if (inside(fc[0]) == inside(fc[2]) && inside(fc[1]) == inside(fc[3]) &&
          inside(fc[0]) != inside(fc[1])) {
        t.ambiguous[c] |= static_cast<uint8_t>(1 << f);
        amb_faces.push_back(f);
      }
    }
    t.first_entry[c] = static_cast<uint32_t>(t.entry_begin.size() - 1);
    for (int d = 0; d < (1 << amb_faces.size()); ++d) {
      // next[e]: the edge the surface's boundary reaches after edge e.
      std::array<int, 12> next;
      next.fill(-1);
      for (int f = 0; f < 6; ++f) {
        const auto& fc = t.face_corners[f];
        bool connect = false;
        for (size_t j = 0; j < amb_faces.size(); ++j)
          if (amb_faces[j] == f) connect = ((d >> j) & 1) != 0;
        for (int i = 0; i < 4; ++i) {
          // Walking the face counter-clockwise, a segment runs from an
          // outside-to-inside crossing to an inside-to-outside one, so the
          // loops wind counter-clockwise seen from outside the material.
          if (inside(fc[i]) || !inside(fc[(i + 1) % 4])) continue;
          const int step = connect ? 3 : 1;  // previous or next crossing
          for (int k = 1, j = (i + step) % 4; k < 4; ++k, j = (j + step) % 4) {
            if (inside(fc[j]) && !inside(fc[(j + 1) % 4])) {
              next[t.face_edges[f][i]] = t.face_edges[f][j];
              break;
            }
          }
        }
      }
      std::array<bool, 12> done{};
      for (int e0 = 0; e0 < 12; ++e0) {
        if (next[e0] < 0 || done[e0]) continue;
        std::vector<int> loop;
        for (int e = e0; !done[e]; e = next[e]) {
          done[e] = true;
          loop.push_back(e);
          assert(next[e] >= 0);
        }
        // Fan from an apex none of whose diagonals lies on a cell face: such
        // a diagonal could coincide with one in the cell across that face
        // (only on faces crossed four times), giving an edge in four
        // triangles. Loops with no such apex fan from a vertex at their centre.
        const size_t len = loop.size();
        int apex = -1;
        for (size_t a = 0; a < len && apex < 0; ++a) {
          bool ok = true;
          for (size_t k = 2; k + 1 < len && ok; ++k) {
            ok = !edges_share_face(t, loop[a], loop[(a + k) % len]);
          }
          if (ok) apex = static_cast<int>(a);
        }
        if (apex >= 0) {
          for (size_t k = 1; k + 1 < len; ++k) {
            t.tri_edges.push_back(static_cast<uint8_t>(loop[static_cast<size_t>(apex)]));
            t.tri_edges.push_back(static_cast<uint8_t>(loop[(apex + k) % len]));
            t.tri_edges.push_back(static_cast<uint8_t>(loop[(apex + k + 1) % len]));
          }
        } else {
          const auto centre =
              static_cast<uint8_t>(12 + t.centre_masks.size() - t.centre_begin.back());
          assert(centre < 16);
          uint16_t mask = 0;
          for (int e : loop)
            mask |= static_cast<uint16_t>(1u << e);
          t.centre_masks.push_back(mask);
          for (size_t k = 0; k < len; ++k) {
            t.tri_edges.push_back(centre);
            t.tri_edges.push_back(static_cast<uint8_t>(loop[k]));
            t.tri_edges.push_back(static_cast<uint8_t>(loop[(k + 1) % len]));
          }
        }
      }
      uint16_t edges = 0;
      for (size_t k = t.entry_begin.back(); k < t.tri_edges.size(); ++k) {
        if (t.tri_edges[k] < 12) edges |= static_cast<uint16_t>(1u << t.tri_edges[k]);
      }
      for (size_t k = t.centre_begin.back(); k < t.centre_masks.size(); ++k)
        edges |= t.centre_masks[k];
      t.entry_edges.push_back(edges);
      t.entry_begin.push_back(static_cast<uint32_t>(t.tri_edges.size()));
      t.centre_begin.push_back(static_cast<uint32_t>(t.centre_masks.size()));
    }
  }
  return t;
}

const Tables& tables() {
  static const Tables t = build_tables();
  return t;
}

// A cache slot of one cell edge: valid while `stamp` matches the plane's.
struct Slot {
  uint32_t stamp = 0;
  uint32_t vertex = 0;
};

// Bit i of a column (corner rows (y,z), (y+1,z), (y,z+1), (y+1,z+1)) moved
// to bit 2i, the corner it is at the cell's lower x.
constexpr std::array<uint8_t, 16> kSpread = {0,  1,  4,  5,  16, 17, 20, 21,
                                             64, 65, 68, 69, 80, 81, 84, 85};

struct Scratch {
  std::vector<uint8_t> columns;
  std::vector<uint8_t> inside;
  std::vector<uint8_t> row_any, row_all;
  std::vector<Slot> xy[2][2];  // [plane parity][axis x or y]
  std::vector<Slot> z;
  uint32_t stamp = 0;
};

}  // namespace

// Marches n cells per axis whose samples g ((n + 3)^3, one below and two
// above the cells' corners) are uint8 densities or float values; cell (0,0,0)
// has its lower corner at level point `origin`. seam_key(p, axis) gives the
// welding key of the edge from local point p, or kNotSeam.
template <class T, class SeamKey>
void march_cells(const T* g, glm::ivec3 n, glm::ivec3 origin, int level, float iso,
                 const SeamKey& seam_key, BrickMesh& out) {
  out.clear();
  const Tables& tab = tables();
  if (n.x <= 0 || n.y <= 0 || n.z <= 0) return;
  const glm::ivec3 dims = n + 3;
  const int64_t sx = dims.x, sxy = int64_t{dims.x} * dims.y;

  thread_local Scratch s;
  const size_t total = static_cast<size_t>(sxy) * dims.z;
  if (s.inside.size() < total) s.inside.resize(total);
  if (s.columns.size() < static_cast<size_t>(dims.x)) s.columns.resize(static_cast<size_t>(dims.x));
  const size_t rows = static_cast<size_t>(n.y + 1) * (n.z + 1);
  if (s.row_any.size() < rows) {
    s.row_any.resize(rows);
    s.row_all.resize(rows);
  }
  const size_t plane = static_cast<size_t>(n.x + 1) * (n.y + 1);
  for (auto& p : s.xy)
    for (auto& a : p)
      if (a.size() < plane) a.assign(plane, Slot{});
  if (s.z.size() < plane) s.z.assign(plane, Slot{});
  if (s.stamp > 0xFFFF0000u) {  // wrap: forget every slot
    for (auto& p : s.xy)
      for (auto& a : p)
        std::fill(a.begin(), a.end(), Slot{});
    std::fill(s.z.begin(), s.z.end(), Slot{});
    s.stamp = 0;
  }
  const uint32_t base = s.stamp + 1;
  s.stamp += static_cast<uint32_t>(n.z + 2);

  // Grid point (x, y, z) of the cells (0..n) is voxel (x+1, y+1, z+1).
  auto at = [&](int x, int y, int z) { return ((z + 1) * sxy + (y + 1) * sx) + (x + 1); };
  // Inside flags of the corner points, and per row whether any / all are
  // inside, so rows of cells far from the surface are skipped whole.
  // Densities are integers: v > iso is v >= floor(iso) + 1, a byte compare.
  const int threshold = static_cast<int>(std::floor(iso)) + 1;
  int any_total = 0, all_total = 0;
  for (int z = 0; z <= n.z; ++z)
    for (int y = 0; y <= n.y; ++y) {
      const int64_t i0 = at(0, y, z);
      uint8_t* in = s.inside.data() + i0;
      const T* row = g + i0;
      // Plain loops over locals whose address never escapes (a byte store
      // may alias anything else), so they vectorise.
      const int points = n.x + 1;
      if constexpr (std::is_same_v<T, uint8_t>) {
        const auto t = static_cast<uint8_t>(std::clamp(threshold, 0, 255));  // byte compares
        for (int x = 0; x < points; ++x)
          in[x] = row[x] >= t;
      } else {
        const float t = iso;
        for (int x = 0; x < points; ++x)
          in[x] = row[x] > t;
      }
      uint8_t any = 0, all = 1;
      for (int x = 0; x < points; ++x) {
        any |= in[x];
        all &= in[x];
      }
      const size_t r = static_cast<size_t>(z) * (n.y + 1) + y;
      s.row_any[r] = any;
      s.row_all[r] = all;
      any_total += any;
      all_total += all;
    }
  if (any_total == 0 || all_total == static_cast<int>(rows)) return;

  const float scale = static_cast<float>(1 << level);
  const int64_t step[3] = {1, sx, sxy};

  auto gradient = [&](int64_t i) {
    return glm::vec3(float(g[i + 1]) - float(g[i - 1]), float(g[i + sx]) - float(g[i - sx]),
                     float(g[i + sxy]) - float(g[i - sxy]));
  };
  auto make_vertex = [&](glm::ivec3 p, int axis) -> uint32_t {
    const int64_t i0 = at(p.x, p.y, p.z);
    const int64_t i1 = i0 + step[axis];
    const float v0 = g[i0], v1 = g[i1];
    const float t = (iso - v0) / (v1 - v0);
    glm::vec3 pos = glm::vec3(origin + p);
    pos[axis] += t;
    glm::vec3 grad = gradient(i0) * (1.0f - t) + gradient(i1) * t;
    const float len = glm::length(grad);
    glm::vec3 normal(0.0f);
    if (len > 0.0f) {
      normal = -grad / len;
    } else {
      normal[axis] = v1 > v0 ? -1.0f : 1.0f;  // flat gradient: face down the edge
    }
    const auto index = static_cast<uint32_t>(out.mesh.positions.size());
    out.mesh.positions.push_back(pos * scale);
    out.mesh.normals.push_back(normal);
    out.seam_keys.push_back(seam_key(p, axis));
    return index;
  };

  // A vertex inside the cell, at the mean of a loop's vertices; no other
  // cell uses it.
  auto make_centre = [&](uint16_t mask, const uint32_t* vertices) -> uint32_t {
    glm::vec3 pos(0.0f), normal(0.0f);
    int count = 0;
    for (int e = 0; e < 12; ++e) {
      if (!((mask >> e) & 1)) continue;
      pos += out.mesh.positions[vertices[e]];
      normal += out.mesh.normals[vertices[e]];
      ++count;
    }
    const float len = glm::length(normal);
    const auto index = static_cast<uint32_t>(out.mesh.positions.size());
    out.mesh.positions.push_back(pos / static_cast<float>(count));
    out.mesh.normals.push_back(len > 0.0f ? normal / len
                                          : out.mesh.normals[vertices[std::countr_zero(mask)]]);
    out.seam_keys.push_back(BrickMesh::kNotSeam);
    return index;
  };
  int64_t corner_delta[8];
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o = corner_offset(k);
    corner_delta[k] = o.x + o.y * sx + o.z * sxy;
  }
  uint32_t edge_vertex[16];
  for (int z = 0; z < n.z; ++z) {
    Slot* xy_lo[2] = {s.xy[z & 1][0].data(), s.xy[z & 1][1].data()};
    Slot* xy_hi[2] = {s.xy[(z + 1) & 1][0].data(), s.xy[(z + 1) & 1][1].data()};
    Slot* zs = s.z.data();
    const uint32_t stamp_lo = base + static_cast<uint32_t>(z);
    const uint32_t stamp_hi = stamp_lo + 1;
    for (int y = 0; y < n.y; ++y) {
      const size_t r = static_cast<size_t>(z) * (n.y + 1) + y;
      const size_t rows4[4] = {r, r + 1, r + static_cast<size_t>(n.y + 1),
                               r + static_cast<size_t>(n.y + 2)};
      bool all_out = true, all_in = true;
      for (size_t q : rows4) {
        all_out = all_out && !s.row_any[q];
        all_in = all_in && s.row_all[q];
      }
      if (all_out || all_in) continue;
      const int64_t row0 = at(0, y, z);
      const uint8_t* in = s.inside.data() + row0;
      // Column bits of the four rows around this row of cells: a cell's case
      // interleaves the columns at its x and x + 1.
      uint8_t* col = s.columns.data();
      for (int x = 0; x <= n.x; ++x) {
        col[x] = static_cast<uint8_t>(in[x] | (in[x + sx] << 1) | (in[x + sxy] << 2) |
                                      (in[x + sx + sxy] << 3));
      }
      for (int x = 0; x < n.x; ++x) {
        if (x + 9 <= n.x + 1) {
          // Eight cells at once: nine equal columns all out or all in.
          uint64_t a, b;
          std::memcpy(&a, col + x, 8);
          std::memcpy(&b, col + x + 1, 8);
          if (a == b && (a == 0 || a == 0x0F0F0F0F0F0F0F0Full)) {
            x += 7;
            continue;
          }
        }
        if (col[x] == col[x + 1] && (col[x] == 0 || col[x] == 15)) continue;
        const unsigned c = kSpread[col[x]] | (kSpread[col[x + 1]] << 1);
        unsigned decision = 0;
        if (const uint8_t amb = tab.ambiguous[c]; amb != 0) {
          int j = 0;
          for (int f = 0; f < 6; ++f) {
            if (!((amb >> f) & 1)) continue;
            const auto& fc = tab.face_corners[f];
            float val[4];
            for (int i = 0; i < 4; ++i)
              val[i] = float(g[row0 + x + corner_delta[fc[i]]]) - iso;
            // Inside diagonal (p, q), outside (r, s): the bilinear saddle is
            // inside when p q > r s. Products commute, so the cell on the
            // other side of the face decides the same.
            const bool d0_in = val[0] > 0.0f;
            const float pq = d0_in ? val[0] * val[2] : val[1] * val[3];
            const float rs = d0_in ? val[1] * val[3] : val[0] * val[2];
            if (pq > rs) decision |= 1u << j;
            ++j;
          }
        }
        const uint32_t entry = tab.first_entry[c] + decision;
        const uint32_t e_begin = tab.entry_begin[entry], e_end = tab.entry_begin[entry + 1];
        for (uint32_t needed = tab.entry_edges[entry]; needed != 0; needed &= needed - 1) {
          const int e = std::countr_zero(needed);
          const glm::ivec3 p = glm::ivec3(x, y, z) + kEdgeOrigin[e];
          const int axis = e >> 2;
          const size_t slot = static_cast<size_t>(p.y) * (n.x + 1) + p.x;
          Slot* sl;
          uint32_t stamp;
          if (axis == 2) {
            sl = &zs[slot];
            stamp = stamp_lo;
          } else if (p.z == z) {
            sl = &xy_lo[axis][slot];
            stamp = stamp_lo;
          } else {
            sl = &xy_hi[axis][slot];
            stamp = stamp_hi;
          }
          if (sl->stamp != stamp) {
            sl->stamp = stamp;
            sl->vertex = make_vertex(p, axis);
          }
          edge_vertex[e] = sl->vertex;
        }
        for (uint32_t k = tab.centre_begin[entry]; k < tab.centre_begin[entry + 1]; ++k) {
          edge_vertex[12 + k - tab.centre_begin[entry]] =
              make_centre(tab.centre_masks[k], edge_vertex);
        }
        for (uint32_t k = e_begin; k < e_end; k += 3) {
          out.mesh.triangles.emplace_back(edge_vertex[tab.tri_edges[k]],
                                          edge_vertex[tab.tri_edges[k + 1]],
                                          edge_vertex[tab.tri_edges[k + 2]]);
        }
      }
    }
  }
}

void march_block(const MarchBlock& block, BrickMesh& out) {
  const glm::ivec3 n = block.cells;
  const glm::ivec3 ld = block.level_dims;
  const uint64_t kx = static_cast<uint64_t>(ld.x) + 2, ky = static_cast<uint64_t>(ld.y) + 2;
  // An edge on the block's boundary is shared with another brick's cells;
  // its key names it in the whole level.
  auto key = [&](glm::ivec3 p, int axis) -> uint64_t {
    bool seam = false;
    for (int b = 0; b < 3; ++b)
      if (b != axis && (p[b] == 0 || p[b] == n[b])) seam = true;
    if (!seam) return BrickMesh::kNotSeam;
    const glm::ivec3 q = block.origin + p + 1;
    return ((static_cast<uint64_t>(q.z) * ky + static_cast<uint64_t>(q.y)) * kx +
            static_cast<uint64_t>(q.x)) *
               3 +
           static_cast<uint64_t>(axis);
  };
  // March into warm per-thread buffers, then copy once: growing fresh
  // vectors vertex by vertex costs a dozen reallocations and page faults.
  thread_local BrickMesh scratch;
  march_cells(block.voxels, n, block.origin, block.level, block.iso, key, scratch);
  out.mesh.positions.assign(scratch.mesh.positions.begin(), scratch.mesh.positions.end());
  out.mesh.normals.assign(scratch.mesh.normals.begin(), scratch.mesh.normals.end());
  out.mesh.triangles.assign(scratch.mesh.triangles.begin(), scratch.mesh.triangles.end());
  out.seam_keys.assign(scratch.seam_keys.begin(), scratch.seam_keys.end());
}

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
    for (size_t v = 0; v < m.positions.size(); ++v) {
      const auto next = static_cast<uint32_t>(out.positions.size());
      if (b->seam_keys[v] != BrickMesh::kNotSeam) {
        auto [it, inserted] = seam.try_emplace(b->seam_keys[v], next);
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

Mesh marching_cubes(const Volume& volume, int level, const MarchingCubesOptions& options) {
  MeshCache cache(level, options);
  cache.update(volume);
  return cache.welded_mesh();
}

namespace {

// Samples of every level, decoded brick by brick on first use.
class LevelSamples {
 public:
  LevelSamples(const Volume& volume, std::span<const int> levels) : v_(volume), levels_(levels) {}

  int brick_level(glm::ivec3 b) const {
    const glm::ivec3 g = v_.brick_grid();
    return levels_[(static_cast<size_t>(b.z) * g.y + b.y) * g.x + b.x];
  }

  // Level-k voxel P (level coordinates); 0 outside the volume.
  float raw(int k, glm::ivec3 p) {
    const glm::ivec3 d = v_.level_dims(k);
    if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, d)))
      return 0.0f;
    const int m = v_.brick_edge() >> k;
    const glm::ivec3 b = p / m;
    const glm::ivec3 g = v_.brick_grid();
    const uint64_t key = ((static_cast<uint64_t>(b.z) * g.y + b.y) * g.x + b.x) * 8 + k;
    auto it = cache_.find(key);
    if (it == cache_.end()) {
      std::vector<uint8_t> voxels(static_cast<size_t>(m) * m * m);
      v_.decode_brick(b, voxels, k);
      it = cache_.emplace(key, std::move(voxels)).first;
    }
    const glm::ivec3 l = p - b * m;
    return it->second[(static_cast<size_t>(l.z) * m + l.y) * m + l.x];
  }

  // The sample every brick sharing level-k point P agrees on: from the
  // coarsest level among them, interpolated where P is not on its grid.
  float shared(int k, glm::ivec3 p) {
    const glm::ivec3 d = v_.level_dims(k);
    if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, d)))
      return 0.0f;
    const int s = 1 << k;
    const glm::ivec3 x = p * s;  // level-0 position
    const int lambda = coarsest_level_at(x * 2);
    if (lambda <= k) return raw(k, p);
    const int big = 1 << lambda;
    glm::ivec3 i0;
    glm::vec3 w;
    for (int a = 0; a < 3; ++a) {
      i0[a] = x[a] / big;
      w[a] = static_cast<float>(x[a] - i0[a] * big) / static_cast<float>(big);
    }
    float value = 0.0f;
    for (int c = 0; c < 8; ++c) {
      const glm::ivec3 o = corner_offset(c);
      float weight = 1.0f;
      for (int a = 0; a < 3; ++a)
        weight *= o[a] ? w[a] : 1.0f - w[a];
      if (weight == 0.0f) continue;
      value += weight * shared(lambda, i0 + o);
    }
    return value;
  }

  // Coarsest level among the bricks whose closed box holds the level-0
  // point x2 / 2 (doubled so edge midpoints are integers).
  int coarsest_level_at(glm::ivec3 x2) const {
    const int e2 = 2 * v_.brick_edge();
    const glm::ivec3 g = v_.brick_grid();
    glm::ivec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
      const int b = x2[a] / e2;
      lo[a] = (x2[a] % e2 == 0) ? b - 1 : b;
      hi[a] = b;
      lo[a] = std::clamp(lo[a], 0, g[a] - 1);
      hi[a] = std::clamp(hi[a], 0, g[a] - 1);
    }
    int lambda = 0;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
          lambda = std::max(lambda, brick_level({x, y, z}));
    return lambda;
  }

  const Volume& volume() const { return v_; }

 private:
  const Volume& v_;
  std::span<const int> levels_;
  std::unordered_map<uint64_t, std::vector<uint8_t>> cache_;
};

uint64_t pack_edge(int level, glm::ivec3 lower, int axis) {
  // 19 bits per coordinate (level-0 coordinates up to 2^16, plus margin).
  return (static_cast<uint64_t>(level) << 59) | (static_cast<uint64_t>(axis) << 57) |
         (static_cast<uint64_t>(lower.z + 1) << 38) | (static_cast<uint64_t>(lower.y + 1) << 19) |
         static_cast<uint64_t>(lower.x + 1);
}

}  // namespace

Mesh mixed_level_mesh(const Volume& volume, std::span<const int> brick_levels,
                      const MarchingCubesOptions& options, MixedLevelStats* stats) {
  assert(static_cast<int64_t>(brick_levels.size()) == volume.brick_count());
  LevelSamples samples(volume, brick_levels);
  const glm::ivec3 grid = volume.brick_grid();
  const int e = volume.brick_edge();
  std::vector<BrickMesh> meshes(brick_levels.size());
  std::vector<float> block;
  for (int bz = 0; bz < grid.z; ++bz)
    for (int by = 0; by < grid.y; ++by)
      for (int bx = 0; bx < grid.x; ++bx) {
        const glm::ivec3 b(bx, by, bz);
        const int k = samples.brick_level(b);
        assert(k >= 0 && k <= volume.levels());
        const int m = e >> k, s = 1 << k;
        const glm::ivec3 origin = b * m;
        const int side = m + 3;
        block.assign(static_cast<size_t>(side) * side * side, 0.0f);
        bool any_in = false, any_out = false;
        size_t i = 0;
        for (int z = -1; z <= m + 1; ++z)
          for (int y = -1; y <= m + 1; ++y)
            for (int x = -1; x <= m + 1; ++x, ++i) {
              const glm::ivec3 p(x, y, z);
              const bool on_grid = glm::all(glm::greaterThanEqual(p, glm::ivec3(0))) &&
                                   glm::all(glm::lessThanEqual(p, glm::ivec3(m)));
              const bool boundary =
                  on_grid && (x == 0 || y == 0 || z == 0 || x == m || y == m || z == m);
              const float v = boundary ? samples.shared(k, origin + p) : samples.raw(k, origin + p);
              block[i] = v;
              if (on_grid) {
                any_in = any_in || v > options.iso;
                any_out = any_out || !(v > options.iso);
              }
            }
        if (!any_in || !any_out) continue;
        const size_t index = (static_cast<size_t>(bz) * grid.y + by) * grid.x + bx;
        auto key = [&](glm::ivec3 p, int axis) -> uint64_t {
          bool seam = false;
          for (int a = 0; a < 3; ++a)
            if (a != axis && (p[a] == 0 || p[a] == m)) seam = true;
          if (!seam) return BrickMesh::kNotSeam;
          const glm::ivec3 x = (origin + p) * s;
          glm::ivec3 mid2 = x * 2;
          mid2[axis] += s;
          const int lambda = samples.coarsest_level_at(mid2);
          const int big = 1 << lambda;
          bool on_line = true;
          for (int a = 0; a < 3; ++a)
            if (a != axis && x[a] % big != 0) on_line = false;
          if (lambda > k && on_line) {
            glm::ivec3 lower = x / big;
            return pack_edge(lambda, lower, axis);
          }
          return pack_edge(k, x / s, axis);
        };
        march_cells(block.data(), glm::ivec3(m), origin, k, options.iso, key, meshes[index]);
      }
  std::vector<const BrickMesh*> parts;
  for (const BrickMesh& bm : meshes)
    if (!bm.empty()) parts.push_back(&bm);
  Mesh mesh = weld_brick_meshes(parts);

  // Stitch: chain the edges used by one triangle into loops and fan each
  // loop, reversed, so every edge ends in exactly two triangles.
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = t[c], b = t[(c + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  // Which brick each triangle came from: a gap is bounded alternately by the
  // finer and the coarser brick's edges.
  std::vector<uint32_t> source;
  source.reserve(mesh.triangles.size());
  for (size_t i = 0; i < parts.size(); ++i)
    source.insert(source.end(), parts[i]->mesh.triangles.size(), static_cast<uint32_t>(i));
  struct Next {
    uint32_t to, brick;
  };
  std::multimap<uint32_t, Next> next;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const glm::uvec3 t = mesh.triangles[i];
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = t[c], b = t[(c + 1) % 3];
      if (uses[{std::min(a, b), std::max(a, b)}] == 1) next.emplace(a, Next{b, source[i]});
    }
  }
  MixedLevelStats st;
  auto on_face = [&](uint32_t v) {
    const glm::vec3 p = mesh.positions[v];
    for (int a = 0; a < 3; ++a) {
      const float r = std::fmod(p[a], static_cast<float>(e));
      if (r == 0.0f) return true;
    }
    return false;
  };
  // A walk along the boundary edges can pass a shared vertex (on a coarse
  // grid line) more than once; every return to a vertex already on the walk
  // closes one simple loop, which is cut off and filled.
  // Each loop is fanned from a new vertex at its centroid: a fan from one
  // of its own vertices could repeat a diagonal of another loop through the
  // same vertices (loops bend round brick edges where levels alternate).
  auto fill = [&](std::span<const uint32_t> loop) {
    if (loop.size() < 3) return;
    ++st.stitch_loops;
    glm::vec3 centre(0.0f), normal(0.0f);
    for (uint32_t v : loop) {
      st.stitch_off_face += !on_face(v);
      centre += mesh.positions[v];
      normal += mesh.normals[v];
    }
    const auto c = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(centre / static_cast<float>(loop.size()));
    const float len = glm::length(normal);
    mesh.normals.push_back(len > 0.0f ? normal / len : mesh.normals[loop[0]]);
    for (size_t k = 0; k < loop.size(); ++k) {
      mesh.triangles.emplace_back(c, loop[(k + 1) % loop.size()], loop[k]);
      ++st.stitch_triangles;
    }
  };
  std::vector<uint32_t> path;
  std::unordered_map<uint32_t, size_t> on_path;
  while (!next.empty()) {
    path.clear();
    on_path.clear();
    uint32_t at = next.begin()->first;
    uint32_t prev = at, from_brick = ~0u;
    while (true) {
      if (auto seen = on_path.find(at); seen != on_path.end()) {
        const size_t from = seen->second;
        fill(std::span<const uint32_t>(path).subspan(from));
        for (size_t k = from; k < path.size(); ++k)
          on_path.erase(path[k]);
        path.resize(from);
      }
      auto found = next.find(at);
      if (found == next.end()) break;  // an open chain: left open, the checks report it
      if (prev != at && next.count(at) > 1) {
        // Prefer the other brick's edges; among several, hug the gap.
        int others = 0;
        for (auto [it, end] = next.equal_range(at); it != end; ++it)
          others += it->second.brick != from_brick;
        // Several gaps meet here: hug the gap we came along. It lies right of
        // the incoming edge (seen from outside), so its next edge is the
        // first one counter-clockwise from the way back.
        const glm::vec3 p = mesh.positions[at];
        const glm::vec3 n = mesh.normals[at];
        auto flat = [&](glm::vec3 d) { return d - n * glm::dot(d, n); };
        const glm::vec3 r = flat(mesh.positions[prev] - p);
        const glm::vec3 q = glm::cross(n, r);
        float best = 10.0f;
        for (auto [it, end] = next.equal_range(at); it != end; ++it) {
          if (others > 0 && it->second.brick == from_brick) continue;
          const glm::vec3 d = flat(mesh.positions[it->second.to] - p);
          float angle = std::atan2(glm::dot(d, q), glm::dot(d, r));
          if (angle <= 0.0f) angle += 2.0f * std::numbers::pi_v<float>;
          if (angle < best) {
            best = angle;
            found = it;
          }
        }
      }
      prev = at;
      from_brick = found->second.brick;
      on_path.emplace(at, path.size());
      path.push_back(at);
      at = found->second.to;
      next.erase(found);
    }
  }
  if (stats) *stats = st;
  return mesh;
}

}  // namespace sculpt::core
