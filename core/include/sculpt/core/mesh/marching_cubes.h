#pragma once
// Marching cubes over the bricked wavelet volume (DESIGN.md §4 "Meshing";
// paper "Discrete tools for virtual sculpture" §2.3).
//
// The surface is the iso-level `iso` of the uint8 density (inside: density >
// iso). Cells span the level's voxel centres and one layer of cells beyond
// every face of the volume, where the outside reads 0, so the mesh of any
// volume is closed. Each cell edge the surface crosses gets exactly one
// vertex, shared by the cells around it; ambiguous faces are resolved by the
// asymptotic decider (Nielson & Hamann 1991), which both cells sharing a face
// evaluate identically, so the surface has no holes.
//
// Level k: level-k voxel i (the mean of level-0 voxels [i 2^k, (i+1) 2^k))
// is placed at i 2^k in level-0 voxel units, so the grid planes of every
// level meet at the brick faces (what joins bricks of different levels, see
// mixed_level_mesh.h). The price: a level-k surface sits (2^k - 1) / 2 voxels
// toward -x, -y, -z from the level-0 one.
//
// This file marches blocks of cells (march_block); the whole-volume surface,
// cached per brick, is MeshCache (mesh_cache.h), and joining brick meshes is
// brick_mesh.h.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/mesh/brick_mesh.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct MarchingCubesOptions {
  /// Iso-level in density units, 0 <= iso < 255; inside is density > iso.
  float iso = 127.5f;
  /// Threads for whole-volume extraction (0 = all cores).
  int threads = 0;
};

/// A block of cells to march, with its voxels.
struct MarchBlock {
  /// Voxels (cells + 3)^3 per axis, x fastest: the cells' corners plus one
  /// voxel below and two above on each axis for central-difference normals.
  const uint8_t* voxels = nullptr;
  /// Cells per axis; cell (0,0,0) has its lower corner at `origin`.
  glm::ivec3 cells{0};
  /// Level coordinates of the first cell's lower corner (may be -1).
  glm::ivec3 origin{0};
  /// Size of the level, for the edge keys.
  glm::ivec3 level_dims{0};
  int level = 0;
  float iso = 127.5f;
};

/// Marches the cells of `block` into `out` (cleared first). No heap
/// allocation beyond the growth of `out` and of per-thread scratch.
void march_block(const MarchBlock& block, BrickMesh& out);

}  // namespace sculpt::core
