#pragma once
// The surface of a volume at one level of detail, kept per brick and brought
// up to date incrementally (paper "Discrete tools for virtual sculpture" §2.3).
//
// update() compares each brick's Volume::brick_version() with the version it
// last meshed (so several caches, one per level or per consumer, can follow
// the same volume; it never calls take_dirty_bricks()). A changed brick is
// decoded once; it and each neighbour whose mesh reads voxels of it that
// really changed are re-meshed, nothing else. The cache keeps the decoded
// voxels of non-uniform bricks at its level, so a re-mesh needs no decoding
// of neighbours; a brick whose neighbourhood is uniform on one side of the
// iso-level costs no meshing at all.
//
// Brick b owns the cells whose lower corner lies in b (plus, for the first
// brick on an axis, the layer of cells just outside the volume), so every
// cell is meshed by exactly one brick.
//
// One cache holds one level; a view mixing levels per brick is cached by
// MixedLevelMeshCache (mixed_level_mesh.h).
//
// Thread safety: update() needs exclusive access to the cache and read access
// to the volume; const members may run concurrently.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/util/progress.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// What one update() did.
struct MeshUpdate {
  int64_t bricks_changed = 0;  ///< bricks whose version differed
  int64_t bricks_decoded = 0;  ///< of those, non-uniform ones decoded
  int64_t bricks_meshed = 0;   ///< bricks marched (uniform neighbourhoods excluded)
  /// Bricks given back a mesh kept from an earlier level of detail instead
  /// of marched (MixedLevelMeshCache only: zooming back re-meshes nothing).
  int64_t bricks_reused = 0;
  /// Of bricks_decoded, those whose voxels were given instead (the voxels a
  /// sculptor stored: MixedLevelMeshCache::update's `stored`).
  int64_t bricks_given = 0;
  /// Of bricks_given, those whose voxels were compared with the kept ones
  /// only where the sculptor said they changed (StoredVoxels::changed).
  int64_t bricks_compared_where_changed = 0;
};

class MeshCache {
 public:
  /// A cache of the surface at `level` (0 = full resolution, at most the
  /// volume's levels) and `options.iso`.
  explicit MeshCache(int level = 0, const MarchingCubesOptions& options = {});

  /// Brings the meshes up to date with `volume`. A different volume (or one
  /// of another shape) than the previous call's is meshed from scratch.
  /// `progress` (optional, progress.h) counts bricks; a cancelled update
  /// leaves meshes to discard, and the next update starts from scratch.
  MeshUpdate update(const Volume& volume, Progress* progress = nullptr);

  int level() const { return level_; }
  float iso() const { return options_.iso; }
  glm::ivec3 brick_grid() const { return grid_; }
  /// The mesh of brick b's cells (empty before the first update()).
  const BrickMesh& brick_mesh(glm::ivec3 b) const { return bricks_[index(b)].mesh; }
  int64_t triangle_count() const;
  /// All bricks welded into one mesh, in brick order.
  Mesh welded_mesh() const;

 private:
  struct CachedBrick {
    uint64_t version = 0;
    uint8_t uniform = 0;          // value when `voxels` is empty
    std::vector<uint8_t> voxels;  // (edge >> level)^3 when not uniform
    // Bit (dz+1)*9 + (dy+1)*3 + (dx+1): whether the voxels brick b + d reads
    // from this brick hold any voxel inside / outside the iso-level.
    uint32_t any_inside = 0;
    uint32_t any_outside = 0;
    BrickMesh mesh;
  };
  size_t index(glm::ivec3 b) const { return grid_index(b, grid_); }
  void reset(const Volume& volume);
  void classify(std::span<const uint8_t> voxels, CachedBrick& cb) const;
  // Decodes brick b; returns the bit (dz+1)*9 + (dy+1)*3 + (dx+1) for each
  // brick b + d whose mesh reads voxels of b that changed.
  uint32_t refresh(const Volume& volume, glm::ivec3 b, bool first);
  // The cells brick b owns, the voxels its march reads (cells plus one below
  // and two above), their part inside the level, and the bricks holding it.
  struct MarchRegion {
    glm::ivec3 cells_lo{0}, cells_hi{0};
    Box voxels, inside, bricks;
  };
  MarchRegion march_region(glm::ivec3 b) const;
  // Whether the voxels brick b's march reads hold both sides of the
  // iso-level (from the neighbours' summaries, without reading voxels).
  bool has_surface(glm::ivec3 b) const;
  // Re-marches brick b from the cached voxels.
  void remesh(glm::ivec3 b, std::vector<uint8_t>& scratch);

  int level_;
  MarchingCubesOptions options_;
  const Volume* volume_ = nullptr;
  glm::ivec3 dims_{0};
  glm::ivec3 level_dims_{0};
  glm::ivec3 grid_{0};
  int m_ = 0;  // brick edge at this level
  std::vector<CachedBrick> bricks_;
};

/// The whole surface of `volume` at `level`, welded across bricks.
Mesh marching_cubes(const Volume& volume, int level = 0, const MarchingCubesOptions& options = {});

}  // namespace sculpt::core
