#pragma once
// The distance shell of Jones & Satherley §3.5: the voxels on both sides of
// the surface, with their sub-voxel distances, as the start of the chamfer,
// vector and exact transforms (`--init shell`).
//
//   B   = inside voxels with an outside 26-neighbour (equation 3's zeros)
//   S_v = B and the 26-neighbours of every voxel of B
//   S_n = S_v and the 26-neighbours of every voxel of S_v (the voxels the
//         central-difference normals of S_v read)
// Inside means phi < 0 (density above 127.5 for level_function(density)).
// Distances are to the tiling-tetrahedra triangulation of phi's zero level,
// in voxel units, negative inside.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/distance/surface_index.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

/// B: 1 at inside voxels (mask != 0) with an outside 26-neighbour in the grid.
DenseGrid<uint8_t> boundary_voxels(const DenseGrid<uint8_t>& inside, int threads = 0);

struct DistanceShell {
  enum : uint8_t { kNone = 0, kOuter = 1, kInner = 2 };
  /// Per voxel: kInner in S_v, kOuter in S_n but not S_v, kNone elsewhere.
  DenseGrid<uint8_t> membership;
  /// Per voxel: its slot in the arrays below, -1 outside S_n.
  DenseGrid<int32_t> slot;
  /// S_n voxels (linear indices, ascending).
  std::vector<int32_t> voxels;
  /// Per S_n voxel: the nearest surface point, voxel units.
  std::vector<glm::vec3> closest;
  /// Per S_n voxel: signed distance to the surface, voxel units.
  std::vector<float> distance;
  /// Per S_n voxel: the index (SurfaceIndex::triangles()) of the triangle
  /// holding `closest`.
  std::vector<int32_t> triangle;
};

/// The shell of phi's zero level; `surface` must be SurfaceIndex(phi).
DistanceShell distance_shell(const DenseGrid<float>& phi, const SurfaceIndex& surface,
                             int threads = 0);

}  // namespace sculpt::core
