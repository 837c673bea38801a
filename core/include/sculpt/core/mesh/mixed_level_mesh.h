#pragma once
// One surface from bricks meshed at different levels of detail, without
// cracks (DESIGN.md §4 "Mixed levels must not show cracks"), cached per brick.
//
// The method (a documented alternative to Transvoxel's transition cells):
//  1. Every brick marches its own box [b e, (b+1) e] on its level's grid;
//     level-k point i sits at i 2^k, so all levels' grid planes meet on the
//     brick faces.
//  2. Samples on a brick face, edge or corner are taken from the coarsest
//     level among the bricks sharing it, interpolated (bilinearly on a face,
//     linearly along an edge) to the finer grids. Inside one square of the
//     coarser grid the finer brick's face samples are then the bilinear
//     interpolant of the square's corners, so both sides cross every coarse
//     grid line at the same point (welded by the key of the coarse edge) and
//     pair those crossings the same way (the asymptotic decider is exactly
//     the bilinear interpolant's topology).
//  3. Inside each such coarse square the finer brick's surface meets the face
//     along a polyline from one crossing to the other where the coarser
//     brick's meets it along one segment. The finer brick closes each of
//     these thin planar gaps itself: it fans the polyline, closed by the
//     chord between its ends, from the polyline's centroid ("stitching").
//     A gap never spans two squares, two faces or two bricks, so each is a
//     disc and the stitch keeps the topology; and a brick's stitch reads only
//     its own mesh, so it is cached with it.
// The result is closed and manifold (every edge in exactly two triangles,
// consistently oriented, the Euler characteristic of the shape) for closed
// shapes that stay clear of the volume's low faces by one coarse voxel (the
// whole-level meshes of marching_cubes.h have no such limit).

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/stored_voxels.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct MixedLevelStats {
  int64_t stitch_loops = 0;      ///< gaps closed in brick faces
  int64_t stitch_triangles = 0;  ///< triangles added for them
  MixedLevelStats& operator+=(const MixedLevelStats& o) {
    stitch_loops += o.stitch_loops;
    stitch_triangles += o.stitch_triangles;
    return *this;
  }
};

/// The per-brick meshes of a volume whose bricks each have their own level of
/// detail (a renderer's LOD by camera distance), kept up to date
/// incrementally. Brick b's mesh (brick_mesh) is its surface at its level plus
/// the stitch toward coarser face neighbours, so drawing every brick's mesh
/// shows a closed surface; welded_mesh() joins them into one indexed mesh.
///
/// update() re-meshes a brick only when voxels its mesh reads changed (a
/// brick whose Volume::brick_version moved is decoded again at the levels
/// kept for it and compared, giving the box that changed) or when its own or
/// a neighbour's level changed (26 neighbours; 124 at one-voxel bricks);
/// everything else is kept. Decoded level voxels are kept per brick and
/// level, checked against brick versions.
///
/// A brick whose level changes while the voxels its mesh reads do not keeps
/// the mesh it had (per level and neighbours' levels, as the discrete-tools
/// paper caches per level), so changing the level of detail back, as when
/// zooming out and in again, re-meshes nothing it meshed before. Kept meshes
/// are bounded in bytes (kept_mesh_budget); the least recently kept go first,
/// and any change to the voxels a brick reads drops that brick's.
///
/// Thread safety: update() needs exclusive access to the cache and read
/// access to the volume; const members may run concurrently.
class MixedLevelMeshCache {
 public:
  /// Default bound on the meshes kept from other levels: the 512^3 bust's
  /// full-detail surface (0.83 M triangles, 0.42 M vertices with normals) is
  /// about 20 MB, so several levels of a larger sculpture fit.
  static constexpr size_t kDefaultKeptMeshBudget = size_t{256} << 20;

  explicit MixedLevelMeshCache(const MarchingCubesOptions& options = {});

  /// Bytes the meshes kept from other levels may take (0: keep none).
  void set_kept_mesh_budget(size_t bytes) { kept_budget_bytes_ = bytes; }
  size_t kept_mesh_bytes() const { return kept_bytes_; }

  /// Asked before each brick update() meshes, from the threads meshing
  /// (none by default): once it says true, update() meshes no more bricks and
  /// returns, and the cache is fit only to be discarded (a refinement of a
  /// volume that a newer one replaced: the station's refiner spent up to
  /// 60 ms finishing such a pass beside the new volume's first dabs).
  void set_cancel(std::function<bool()> cancelled) { cancelled_ = std::move(cancelled); }

  /// Brings the meshes up to date with `volume` and `brick_levels` (one per
  /// brick, index (b.z * grid.y + b.y) * grid.x + b.x, each in
  /// [0, volume.levels()]). A different volume (or one of another shape)
  /// than the previous call's is meshed from scratch. bricks_changed counts
  /// bricks whose inputs (versions, levels) changed, bricks_decoded the
  /// (brick, level) decodes, bricks_meshed the non-empty meshes rebuilt.
  /// `stored`: level-0 voxels of some bricks (stored_voxels.h), taken (moved
  /// out) instead of decoding a brick whose version they are of.
  MeshUpdate update(const Volume& volume, std::span<const int> brick_levels,
                    StoredVoxelsByBrick* stored = nullptr);

  float iso() const { return options_.iso; }
  glm::ivec3 brick_grid() const { return grid_; }
  /// Level of brick b as of the last update().
  int brick_level(glm::ivec3 b) const { return bricks_[index(b)].level; }
  /// Brick b's mesh (level-0 voxel units), stitch included; empty before
  /// the first update().
  const BrickMesh& brick_mesh(glm::ivec3 b) const {
    const std::shared_ptr<const BrickMesh>& mesh = bricks_[index(b)].mesh;
    return mesh ? *mesh : no_mesh();
  }
  /// The same mesh, shared: update() makes a brick's next mesh anew and
  /// never changes one it made, so a holder (a renderer, the simplifier)
  /// keeps this one as it is without a copy. An empty brick's is empty.
  std::shared_ptr<const BrickMesh> shared_brick_mesh(glm::ivec3 b) const;
  /// Incremented each time update() rebuilds brick b's mesh (0 before the
  /// first): a renderer re-uploads exactly the bricks whose count moved.
  uint64_t brick_mesh_version(glm::ivec3 b) const { return bricks_[index(b)].mesh_version; }
  /// Reads of parallel meshing that update() did not decode beforehand
  /// (correct, but slower; 0 unless the neighbourhood rule is broken).
  int64_t unforeseen_decodes() const { return unforeseen_decodes_.n.load(); }
  /// Stitching figures of the current meshes, summed over bricks.
  MixedLevelStats stats() const;
  int64_t triangle_count() const;
  /// All bricks welded into one mesh, in brick order.
  Mesh welded_mesh() const;

 private:
  // A brick's mesh at one level among given neighbours' levels.
  struct LevelMesh {
    int level = -1;
    // Levels of the bricks around, in neighbourhood order; empty before the
    // first meshing.
    std::vector<int8_t> levels;
    // Null when it has no surface. Shared with those it was handed to
    // (shared_brick_mesh): replaced by a new mesh, never changed.
    std::shared_ptr<const BrickMesh> mesh;
    MixedLevelStats stats;
    uint64_t kept_order = 0;  // when it was kept (least recent dropped first)
  };
  struct CachedBrick : LevelMesh {
    uint64_t mesh_version = 0;
    // Its meshes at other levels, valid while the voxels it reads stay.
    std::vector<LevelMesh> kept;
  };
  struct Decoded {
    uint64_t version = 0;
    std::vector<uint8_t> voxels;  // (edge >> level)^3
  };
  size_t index(glm::ivec3 b) const { return grid_index(b, grid_); }
  static const BrickMesh& no_mesh();
  bool in_grid(glm::ivec3 b) const;
  int level_of(glm::ivec3 b) const { return levels_[index(b)]; }
  // The neighbourhood radius a brick at `level` reads (halo two voxels up).
  int reach(int level) const { return (edge_ >> level) >= 2 ? 1 : 2; }
  // Agreed samples already computed during one brick's meshing, by level
  // and point (mixed_level_mesh.cpp).
  class SharedMemo;
  // Level-k voxel p (level coordinates), 0 outside the volume.
  float raw(int k, glm::ivec3 p, SharedMemo& memo);
  // Brick b's level-k voxels: kept in decoded_, or for a uniform brick the
  // one buffer of its value (uniform_), or while frozen, when neither was
  // made beforehand, this thread's scratch (*scratch set).
  const Decoded& decoded(glm::ivec3 b, int k, bool* scratch = nullptr);
  // Brick b's level-k entry in decoded_ (made if missing) and whether its
  // voxels must be decoded: when they are not current it is sized and
  // marked current, and the caller decodes into it before anything reads.
  std::pair<Decoded*, bool> entry_for(glm::ivec3 b, int k);
  // decoded(b, k)'s voxels, kept valid across further calls: an unforeseen
  // decode while frozen goes to `spare`, not to the thread's one scratch.
  const uint8_t* decoded_voxels(glm::ivec3 b, int k, std::vector<uint8_t>& spare);
  // The sample all bricks sharing level-k point p agree on.
  float shared(int k, glm::ivec3 p, SharedMemo& memo);
  float shared_value(int k, glm::ivec3 p, SharedMemo& memo);
  // An agreed sample as every brick reads it: one exactly at the iso-level
  // moved just below it (shared()).
  float tie_moved(float v) const { return v == options_.iso ? options_.iso - 1.0f / 1024.0f : v; }
  // Finest and coarsest level among the bricks whose closed box holds
  // level-0 point x2 / 2 (doubled so edge midpoints are integers).
  glm::ivec2 levels_at(glm::ivec3 x2) const;
  int coarsest_level_at(glm::ivec3 x2) const;
  // Whether every brick within `r` of b (outside the volume: 0) is uniform
  // with one value: then b's mesh is empty whatever its level.
  bool uniform_around(glm::ivec3 b, int r) const;
  // The levels of the bricks within two of b (the widest reach), bit k set
  // for level k.
  unsigned levels_used_around(glm::ivec3 b) const;
  // A brick's uniform value, or kNotUniform.
  static constexpr int16_t kNotUniform = -1;
  static int16_t uniform_value_of(const Brick& brick);
  // Meshes brick b at cb.level into cb.
  void mesh_brick(glm::ivec3 b, CachedBrick& cb);
  void stitch(glm::ivec3 b, int k, BrickMesh& out, MixedLevelStats& st) const;
  // Moves cb's current mesh into its kept ones / gives it back the kept mesh
  // for its (new) level and levels around, if there is one / drops them all.
  void keep_mesh(CachedBrick& cb);
  bool take_kept_mesh(CachedBrick& cb);
  void drop_kept_meshes(CachedBrick& cb);
  // Drops the least recently kept meshes until the budget holds.
  void trim_kept_meshes();

  MarchingCubesOptions options_;
  std::function<bool()> cancelled_;
  const Volume* volume_ = nullptr;
  glm::ivec3 dims_{0};
  glm::ivec3 grid_{0};
  int edge_ = 0;
  std::vector<int> levels_;
  std::array<glm::ivec3, 8> level_dims_{};  // volume_->level_dims(k), looked up per sample
  std::vector<CachedBrick> bricks_;
  std::vector<uint64_t> seen_versions_;            // brick versions as of the last update
  std::vector<int16_t> seen_uniform_;              // their uniform values then (or kNotUniform)
  std::unordered_map<uint64_t, Decoded> decoded_;  // key: brick index * 8 + level
  // A uniform brick's voxels, one buffer per value and level (key: value *
  // 8 + level) shared by every uniform brick: the air and the solid around a
  // sculpture are most of the bricks a change's meshes read (the demo's
  // first ball: 290 of 382), and kept one 32 KiB buffer each they cost more
  // to fill than the ball's own bricks did to decode. Made outside the
  // parallel meshing only.
  std::unordered_map<int, Decoded> uniform_;
  // Keys added to decoded_ since update() last forgot unused ones: with the
  // levels as they were, only these can have become unused.
  std::vector<uint64_t> decoded_added_;
  int64_t decodes_ = 0;
  // While stale bricks are meshed in parallel: decoded_ is read only.
  bool frozen_ = false;
  // A count that copies with the cache (std::atomic alone does not).
  struct Counter {
    std::atomic<int64_t> n{0};
    Counter() = default;
    Counter(const Counter& o) : n(o.n.load()) {}
    Counter& operator=(const Counter& o) {
      n = o.n.load();
      return *this;
    }
    void add() { n.fetch_add(1, std::memory_order_relaxed); }
  };
  Counter unforeseen_decodes_;
  size_t kept_budget_bytes_ = kDefaultKeptMeshBudget;
  size_t kept_bytes_ = 0;
  uint64_t kept_count_ = 0;  // meshes kept so far: the next one's kept_order
};

/// The surface of `volume` with brick b at level brick_levels[i], i the brick
/// index ((b.z * grid.y + b.y) * grid.x + b.x), each in [0, volume.levels()]:
/// MixedLevelMeshCache::update() then welded_mesh().
Mesh mixed_level_mesh(const Volume& volume, std::span<const int> brick_levels,
                      const MarchingCubesOptions& options = {}, MixedLevelStats* stats = nullptr);

}  // namespace sculpt::core
