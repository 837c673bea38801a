#pragma once
// Internal to the mesh module: the marching cubes case tables, generated at
// start-up (cube_tables.cpp) rather than typed in, and the cell geometry they
// are written against.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace sculpt::core::detail {

// Corner k of a cell sits at (k & 1, (k >> 1) & 1, k >> 2); bit k of a cell's
// case is set when corner k is inside. Edges 0-3 run along x, 4-7 along y,
// 8-11 along z.
inline constexpr std::array<std::array<uint8_t, 2>, 12> kEdgeCorners = {{{0, 1},
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
inline constexpr std::array<glm::ivec3, 12> kEdgeOrigin = {
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
inline constexpr uint32_t kFixedTriangles = 4;

struct CubeTables {
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

/// The tables, built once on first use (thread-safe).
const CubeTables& cube_tables();

}  // namespace sculpt::core::detail
