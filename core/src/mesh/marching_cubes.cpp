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

#include "march_cells.h"
#include "sculpt/core/mesh/mesh_cache.h"

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
// Most cells of a smooth surface make one to four triangles: the march
// writes that many before it looks at the count (see build_tables).
constexpr uint32_t kFixedTriangles = 4;

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
  // Most triangles and centre vertices of any entry, to size a row's output.
  uint32_t max_triangles = 0;
  uint32_t max_centres = 0;
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
      t.max_triangles = std::max(
          t.max_triangles, static_cast<uint32_t>((t.tri_edges.size() - t.entry_begin.back()) / 3));
      t.max_centres = std::max(
          t.max_centres, static_cast<uint32_t>(t.centre_masks.size() - t.centre_begin.back()));
      t.entry_begin.push_back(static_cast<uint32_t>(t.tri_edges.size()));
      t.centre_begin.push_back(static_cast<uint32_t>(t.centre_masks.size()));
    }
  }
  // The march writes kFixedTriangles triangles of every entry before it
  // counts them; the last entry's may read past its end.
  t.tri_edges.resize(t.tri_edges.size() + 3 * kFixedTriangles, 0);
  return t;
}

const Tables& tables() {
  static const Tables t = build_tables();
  return t;
}

// The slot table holding edge e's vertex: x edges of the cell's lower and
// upper z plane (0, 1), y edges likewise (2, 3), z edges (4).
constexpr std::array<uint8_t, 12> kEdgeSlotTable = {0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4, 4};

// Which of a cell's edges the cell makes the vertex of, by whether it lies
// on the block's low x, y and z face (bits 0, 1, 2). Cells are marched z,
// then y, then x ascending, and a crossed edge is needed by every cell
// around it; the first of those to be marched makes its vertex and the
// others read it from the slot tables. Inside the block that is the cell
// below and behind the edge, so a cell makes the three edges at its upper
// corner (3, 7, 11); on a low face there is no cell before it.
constexpr std::array<uint16_t, 8> kOwnedEdges = [] {
  std::array<uint16_t, 8> owned{};
  for (int face = 0; face < 8; ++face)
    for (int e = 0; e < 12; ++e) {
      const int axis = e >> 2;
      bool first = true;
      for (int b = 0; b < 3; ++b)
        if (b != axis) first = first && (kEdgeOrigin[e][b] == 1 || ((face >> b) & 1) != 0);
      if (first) owned[face] |= static_cast<uint16_t>(1u << e);
    }
  return owned;
}();

// Bit i of a column (corner rows (y,z), (y+1,z), (y,z+1), (y+1,z+1)) moved
// to bit 2i, the corner it is at the cell's lower x.
constexpr std::array<uint8_t, 16> kSpread = {0,  1,  4,  5,  16, 17, 20, 21,
                                             64, 65, 68, 69, 80, 81, 84, 85};

// A vector whose resize() leaves new elements uninitialised: the march sizes
// its output buffers ahead of each row of cells and writes them by index.
template <class T>
struct UninitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitAllocator<U>;
  };
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) {}
  template <class U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using UninitVector = std::vector<T, UninitAllocator<T>>;

// Grows `v` to at least `n` elements (doubling, so rows amortise).
template <class T>
void ensure_size(UninitVector<T>& v, size_t n) {
  if (v.size() < n) v.resize(std::max(n, 2 * v.size()));
}

// A vertex the march asked for: the crossing on the edge from grid point p
// along `axis`, or (axis kCentre) the centre of a loop, kept in `centres`.
struct PendingVertex {
  uint8_t x, y, z, axis;
};
constexpr uint8_t kCentre = 3;
struct PendingCentre {
  uint32_t vertex;
  uint16_t edges;            // the loop's cell edges
  uint32_t edge_vertex[12];  // their vertices
};

inline int round_up8(int n) {
  return (n + 7) & ~7;
}

// Eight 0/1 flags as the low eight bits, flag i at bit i: the multiply
// gathers each byte's low bit into the top byte.
inline uint64_t pack_flags8(const uint8_t* flags) {
  uint64_t w;
  std::memcpy(&w, flags, 8);
  return (w * 0x0102040810204080ull) >> 56;
}

// Whether any and whether all of `count` 0/1 flags are 1, eight at a time:
// a byte loop's vector reduction per row of corners cost more than the row.
inline void flags_any_all(const uint8_t* flags, int count, uint8_t& any, uint8_t& all) {
  constexpr uint64_t kOnes = 0x0101010101010101ull;
  uint64_t or_words = 0, and_words = kOnes;
  int x = 0;
  for (; x + 8 <= count; x += 8) {
    uint64_t w;
    std::memcpy(&w, flags + x, 8);
    or_words |= w;
    and_words &= w;
  }
  uint8_t or_tail = 0, and_tail = 1;
  for (; x < count; ++x) {
    or_tail |= flags[x];
    and_tail &= flags[x];
  }
  any = static_cast<uint8_t>((or_words != 0) | or_tail);
  all = static_cast<uint8_t>((and_words == kOnes) & and_tail);
}

struct Scratch {
  // The brick's mesh as it is marched; copied into the caller's BrickMesh.
  // Cells only number their vertices; one pass after the march computes
  // them, a tight loop free of the march's unpredictable branches.
  UninitVector<PendingVertex> pending;
  std::vector<PendingCentre> centres;
  UninitVector<glm::vec3> positions, normals;
  UninitVector<glm::uvec3> triangles;
  std::vector<uint8_t> columns, crossed;
  std::vector<uint8_t> inside;
  std::vector<uint8_t> row_any, row_all;
  // Vertex of each cell edge's crossing, written by the cell that makes it.
  std::vector<uint32_t> xy[2][2];  // [plane parity][axis x or y]
  std::vector<uint32_t> z;
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

  assert(n.x < 255 && n.y < 255 && n.z < 255);  // grid points fit PendingVertex
  thread_local Scratch s;
  s.centres.clear();
  const size_t total = static_cast<size_t>(sxy) * dims.z;
  if (s.inside.size() < total) s.inside.resize(total);
  if (s.columns.size() < static_cast<size_t>(dims.x)) s.columns.resize(static_cast<size_t>(dims.x));
  if (s.crossed.size() < static_cast<size_t>(round_up8(n.x))) s.crossed.resize(round_up8(n.x));
  const size_t rows = static_cast<size_t>(n.y + 1) * (n.z + 1);
  if (s.row_any.size() < rows) {
    s.row_any.resize(rows);
    s.row_all.resize(rows);
  }
  const size_t plane = static_cast<size_t>(n.x + 1) * (n.y + 1);
  for (auto& p : s.xy)
    for (auto& a : p)
      if (a.size() < plane) a.resize(plane);
  if (s.z.size() < plane) s.z.resize(plane);

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
      flags_any_all(in, points, any, all);
      const size_t r = static_cast<size_t>(z) * (n.y + 1) + y;
      s.row_any[r] = any;
      s.row_all[r] = all;
      any_total += any;
      all_total += all;
    }
  if (any_total == 0 || all_total == static_cast<int>(rows)) return;

  const float scale = static_cast<float>(1 << level);
  const int64_t step[3] = {1, sx, sxy};
  size_t vertex_count = 0, triangle_count = 0;
  // A cell adds at most its 12 edges' vertices and its centres.
  const size_t row_vertices = static_cast<size_t>(n.x) * (12 + tab.max_centres);
  const size_t row_triangles = static_cast<size_t>(n.x) * tab.max_triangles + kFixedTriangles;

  auto gradient = [&](int64_t i) {
    if constexpr (std::is_same_v<T, uint8_t>) {
      // Integer differences are exact: the same values, fewer conversions.
      return glm::vec3(static_cast<float>(int{g[i + 1]} - int{g[i - 1]}),
                       static_cast<float>(int{g[i + sx]} - int{g[i - sx]}),
                       static_cast<float>(int{g[i + sxy]} - int{g[i - sxy]}));
    } else {
      return glm::vec3(g[i + 1] - g[i - 1], g[i + sx] - g[i - sx], g[i + sxy] - g[i - sxy]);
    }
  };
  // Cells number their vertices as they need them; compute_vertices()
  // fills them in after the march.
  auto pending = [](glm::ivec3 p, int axis) {
    return PendingVertex{static_cast<uint8_t>(p.x), static_cast<uint8_t>(p.y),
                         static_cast<uint8_t>(p.z), static_cast<uint8_t>(axis)};
  };
  auto make_vertex = [&](glm::ivec3 p, int axis) -> uint32_t {
    const auto index = static_cast<uint32_t>(vertex_count++);
    s.pending[index] = pending(p, axis);
    return index;
  };
  // A vertex inside the cell, at the mean of a loop's vertices; no other
  // cell uses it.
  auto make_centre = [&](uint16_t mask, const uint32_t* vertices) -> uint32_t {
    const auto index = static_cast<uint32_t>(vertex_count++);
    s.pending[index] = {0, 0, 0, kCentre};
    PendingCentre& c = s.centres.emplace_back();
    c.vertex = index;
    c.edges = mask;
    std::copy(vertices, vertices + 12, c.edge_vertex);
    return index;
  };
  auto compute_vertices = [&] {
    for (size_t index = 0; index < vertex_count; ++index) {
      const PendingVertex pv = s.pending[index];
      if (pv.axis == kCentre) continue;
      const int axis = pv.axis;
      const glm::ivec3 p(pv.x, pv.y, pv.z);
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
        normal = grad * (-1.0f / len);  // one division instead of three
      } else {
        normal[axis] = v1 > v0 ? -1.0f : 1.0f;  // flat gradient: face down the edge
      }
      s.positions[index] = pos * scale;
      s.normals[index] = normal;
      if (const uint64_t key = seam_key(p, axis); key != BrickMesh::kNotSeam)
        out.seams.push_back({static_cast<uint32_t>(index), key});
    }
    for (const PendingCentre& c : s.centres) {
      glm::vec3 pos(0.0f), normal(0.0f);
      for (uint32_t e = c.edges; e != 0; e &= e - 1) {
        pos += s.positions[c.edge_vertex[std::countr_zero(e)]];
        normal += s.normals[c.edge_vertex[std::countr_zero(e)]];
      }
      const float len = glm::length(normal);
      s.positions[c.vertex] = pos / static_cast<float>(std::popcount(c.edges));
      s.normals[c.vertex] =
          len > 0.0f ? normal / len : s.normals[c.edge_vertex[std::countr_zero(c.edges)]];
    }
  };
  int64_t corner_delta[8];
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o = corner_offset(k);
    corner_delta[k] = o.x + o.y * sx + o.z * sxy;
  }
  // Where the slot of a cell's edge e lies relative to the cell's own slot.
  size_t edge_slot_delta[12];
  for (int e = 0; e < 12; ++e)
    edge_slot_delta[e] =
        static_cast<size_t>(kEdgeOrigin[e].y) * (n.x + 1) + static_cast<size_t>(kEdgeOrigin[e].x);
  uint32_t edge_vertex[16];
  for (int z = 0; z < n.z; ++z) {
    // The slot tables of this layer of cells, as kEdgeSlotTable numbers them.
    uint32_t* const slot_tables[5] = {s.xy[z & 1][0].data(), s.xy[(z + 1) & 1][0].data(),
                                      s.xy[z & 1][1].data(), s.xy[(z + 1) & 1][1].data(),
                                      s.z.data()};
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
      ensure_size(s.pending, vertex_count + row_vertices);
      ensure_size(s.triangles, triangle_count + row_triangles);
      const int64_t row0 = at(0, y, z);
      const int face_bits = (y == 0 ? 2 : 0) | (z == 0 ? 4 : 0);
      const size_t row_slot = static_cast<size_t>(y) * (n.x + 1);
      const uint8_t* in = s.inside.data() + row0;
      // Column bits of the four rows around this row of cells: a cell's case
      // interleaves the columns at its x and x + 1.
      uint8_t* col = s.columns.data();
      for (int x = 0; x <= n.x; ++x) {
        col[x] = static_cast<uint8_t>(in[x] | (in[x + sx] << 1) | (in[x + sxy] << 2) |
                                      (in[x + sx + sxy] << 3));
      }
      // Cells the surface crosses: their columns differ, or a column is
      // neither all out (0) nor all in (15). A byte loop that vectorises,
      // packed into bits, then the set bits in turn: branching cell by cell
      // mispredicted at every way in and out of the surface.
      uint8_t* crossed = s.crossed.data();
      for (int x = 0; x < n.x; ++x)
        crossed[x] = static_cast<uint8_t>((col[x] != col[x + 1]) | (col[x] != 0 && col[x] != 15));
      std::fill(crossed + n.x, crossed + round_up8(n.x), uint8_t{0});
      for (int word = 0; word < n.x; word += 64) {
        uint64_t cells = 0;
        for (int b = 0; b < 64 && word + b < n.x; b += 8)
          cells |= pack_flags8(crossed + word + b) << b;
        for (; cells != 0; cells &= cells - 1) {
          const int x = word + std::countr_zero(cells);
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
          const size_t cell_slot = row_slot + static_cast<size_t>(x);
          const uint16_t needed = tab.entry_edges[entry];
          // Every slot is read, needed or not: twelve loads cost less than
          // the mispredicted branches of picking the needed ones. Slots of
          // edges that are not crossed hold stale numbers no triangle uses.
          for (int e = 0; e < 12; ++e)
            edge_vertex[e] = slot_tables[kEdgeSlotTable[e]][cell_slot + edge_slot_delta[e]];
          const int face = face_bits | (x == 0 ? 1 : 0);
          if (face == 0) {
            // Inside the block a cell makes the vertices of edges 3, 7 and 11
            // when they are crossed; without a branch, a number is only kept
            // (the count moves on) when the edge is crossed.
            for (const int e : {3, 7, 11}) {
              const auto v = static_cast<uint32_t>(vertex_count);
              s.pending[v] = pending(glm::ivec3(x, y, z) + kEdgeOrigin[e], e >> 2);
              slot_tables[kEdgeSlotTable[e]][cell_slot + edge_slot_delta[e]] = v;
              edge_vertex[e] = v;
              vertex_count += (needed >> e) & 1u;
            }
          } else {
            for (uint32_t make = needed & kOwnedEdges[face]; make != 0; make &= make - 1) {
              const int e = std::countr_zero(make);
              const uint32_t v = make_vertex(glm::ivec3(x, y, z) + kEdgeOrigin[e], e >> 2);
              slot_tables[kEdgeSlotTable[e]][cell_slot + edge_slot_delta[e]] = v;
              edge_vertex[e] = v;
            }
          }
          for (uint32_t k = tab.centre_begin[entry]; k < tab.centre_begin[entry + 1]; ++k) {
            edge_vertex[12 + k - tab.centre_begin[entry]] =
                make_centre(tab.centre_masks[k], edge_vertex);
          }
          // kFixedTriangles are written whatever the count (the buffer has
          // room); those past the entry's end are overwritten later or cut.
          auto triangle = [&](uint32_t k) {
            return glm::uvec3(edge_vertex[tab.tri_edges[k]], edge_vertex[tab.tri_edges[k + 1]],
                              edge_vertex[tab.tri_edges[k + 2]]);
          };
          for (uint32_t k = 0; k < kFixedTriangles; ++k)
            s.triangles[triangle_count + k] = triangle(e_begin + 3 * k);
          for (uint32_t k = e_begin + 3 * kFixedTriangles; k < e_end; k += 3)
            s.triangles[triangle_count + (k - e_begin) / 3] = triangle(k);
          triangle_count += (e_end - e_begin) / 3;
        }
      }
    }
  }
  ensure_size(s.positions, vertex_count);
  ensure_size(s.normals, vertex_count);
  compute_vertices();
  // One exact-size copy into the caller's mesh (whose capacity a cache
  // reuses from the brick's previous mesh).
  out.mesh.positions.assign(s.positions.begin(), s.positions.begin() + vertex_count);
  out.mesh.normals.assign(s.normals.begin(), s.normals.begin() + vertex_count);
  out.mesh.triangles.assign(s.triangles.begin(), s.triangles.begin() + triangle_count);
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
  march_cells(block.voxels, n, block.origin, block.level, block.iso, key, out);
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

Mesh marching_cubes(const Volume& volume, int level, const MarchingCubesOptions& options) {
  MeshCache cache(level, options);
  cache.update(volume);
  return cache.welded_mesh();
}

namespace detail {

void march_float_cells(const float* samples, glm::ivec3 cells, glm::ivec3 origin, int level,
                       float iso, const std::function<uint64_t(glm::ivec3, int)>& seam_key,
                       BrickMesh& out) {
  march_cells(samples, cells, origin, level, iso, seam_key, out);
}

}  // namespace detail
}  // namespace sculpt::core
