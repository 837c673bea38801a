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

#include "mesh/cube_tables.h"
#include "mesh/march_cells.h"

namespace sculpt::core {
namespace {

using detail::corner_offset;
using detail::kEdgeOrigin;
using detail::kFixedTriangles;

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
  const detail::CubeTables& tab = detail::cube_tables();
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

  // Twice the density's slope along one axis at sample i. The density
  // ramps over two voxels across the surface (density_from_distance) and is
  // clipped to 0 and 255 beyond, so a central difference whose far sample
  // lies past the ramp reads that axis's slope short, and the normal tilts
  // by how far the surface lies between grid points: rings of shading on a
  // sphere (1.2 degrees off on average, 5.3 at most; tested). The samples
  // beside a crossed edge lie on the ramp, and so does one of their
  // neighbours on each axis: where one neighbour reads 0 or 255 and the
  // other does not, the difference on the other's side is taken, doubled:
  // the central one plus or minus the second difference, without a branch
  // (which clipped is a coin toss to the branch predictor: the march took
  // 8% longer with one). Integer differences for bytes: exact, fewer
  // conversions.
  using Sample = std::conditional_t<std::is_same_v<T, uint8_t>, int, float>;
  auto slope = [&](int64_t i, int64_t stride) -> Sample {
    const Sample below = g[i - stride], here = g[i], above = g[i + stride];
    const int below_clipped = (below == 0) | (below == 255);
    const int above_clipped = (above == 0) | (above == 255);
    // +1: 2 (here - below); -1: 2 (above - here); 0: above - below.
    const auto side = static_cast<Sample>(above_clipped - below_clipped);
    return (above - below) + side * (2 * here - above - below);
  };
  auto gradient = [&](int64_t i) {
    return glm::vec3(static_cast<float>(slope(i, 1)), static_cast<float>(slope(i, sx)),
                     static_cast<float>(slope(i, sxy)));
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
      // The crossing moves the point by t along its edge's axis; the other
      // coordinates add 0 (the same float). Written component by component,
      // never through an index: an indexed write puts a vector in memory,
      // and reading it back whole stalled the loop on store forwarding.
      const glm::vec3 base(origin + p);
      const glm::vec3 pos(base.x + (axis == 0 ? t : 0.0f), base.y + (axis == 1 ? t : 0.0f),
                          base.z + (axis == 2 ? t : 0.0f));
      const glm::vec3 grad = gradient(i0) * (1.0f - t) + gradient(i1) * t;
      const float len = glm::length(grad);
      s.positions[index] = pos * scale;
      if (len > 0.0f) {
        s.normals[index] = grad * (-1.0f / len);  // one division instead of three
      } else {
        // A flat gradient: face down the edge.
        const float down = v1 > v0 ? -1.0f : 1.0f;
        s.normals[index] =
            glm::vec3(axis == 0 ? down : 0.0f, axis == 1 ? down : 0.0f, axis == 2 ? down : 0.0f);
      }
      // Only an edge on the block's boundary can be shared: the key is not
      // asked for inside (most vertices; the caller's key is a call away).
      const bool on_boundary = (axis != 0 && (p.x == 0 || p.x == n.x)) ||
                               (axis != 1 && (p.y == 0 || p.y == n.y)) ||
                               (axis != 2 && (p.z == 0 || p.z == n.z));
      if (!on_boundary) continue;
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
      {
        // The two byte loops below vectorise only over locals whose address
        // never escapes: n, sx and sxy are captured by the lambdas above, so
        // a byte store (which may alias anything) made the compiler reload
        // them every byte and keep the loops scalar, a third of the march.
        const int nx = n.x;
        const int64_t dy = sx, dz = sxy;
        {
          // Column bits of the four rows around this row of cells: a cell's
          // case interleaves the columns at its x and x + 1.
          const uint8_t* __restrict flags = in;
          uint8_t* __restrict columns = s.columns.data();
          for (int x = 0; x <= nx; ++x) {
            columns[x] = static_cast<uint8_t>(flags[x] | (flags[x + dy] << 1) |
                                              (flags[x + dz] << 2) | (flags[x + dy + dz] << 3));
          }
        }
        // Cells the surface crosses: their columns differ, or a column is
        // neither all out (0) nor all in (15). Packed into bits below, then
        // the set bits in turn: branching cell by cell mispredicted at every
        // way in and out of the surface.
        const uint8_t* __restrict column = s.columns.data();
        uint8_t* __restrict cells_crossed = s.crossed.data();
        for (int x = 0; x < nx; ++x)
          cells_crossed[x] = static_cast<uint8_t>((column[x] != column[x + 1]) |
                                                  ((column[x] != 0) & (column[x] != 15)));
      }
      const uint8_t* col = s.columns.data();
      uint8_t* crossed = s.crossed.data();
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

namespace detail {

void march_float_cells(const float* samples, glm::ivec3 cells, glm::ivec3 origin, int level,
                       float iso, const std::function<uint64_t(glm::ivec3, int)>& seam_key,
                       BrickMesh& out) {
  march_cells(samples, cells, origin, level, iso, seam_key, out);
}

void march_byte_cells(const uint8_t* samples, glm::ivec3 cells, glm::ivec3 origin, int level,
                      float iso, const std::function<uint64_t(glm::ivec3, int)>& seam_key,
                      BrickMesh& out) {
  march_cells(samples, cells, origin, level, iso, seam_key, out);
}

}  // namespace detail
}  // namespace sculpt::core
