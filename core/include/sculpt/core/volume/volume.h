#pragma once
// The material: a bricked voxel volume held as 3D Haar wavelets (DESIGN.md §4).
//
// Voxels are uint8 densities (0 empty, 255 full, surface at 127.5), x fastest,
// voxel centres at integer coordinates. The volume is cut into cubic bricks of
// a power-of-two edge; a brick is uniform (O(1) memory) or holds the lossless
// Haar pyramid of its voxels. Any size works: the bricks on the far faces are
// padded by repeating the last voxel, so padding never biases a coarse level.
//
// Because Haar supports never overlap, a brick-wise transform with levels <=
// log2(brick edge) gives exactly the coefficients of a whole-volume transform
// (only their order in memory differs), so level k of the volume is the tiling
// of level k of its bricks.
//
// Thread safety: const member functions may run concurrently; editing needs
// exclusive access.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/volume/brick.h"

namespace sculpt::core {

struct VolumeOptions {
  /// Brick edge in voxels: a power of two in [2, 128].
  int brick_edge = 32;
  /// Wavelet levels per brick, at most log2(brick_edge).
  int levels = 5;
  /// Threads for whole-volume work (0 = all cores).
  int threads = 0;
};

/// Memory and sparsity figures of a volume.
struct VolumeStats {
  int64_t bricks = 0;
  int64_t uniform_bricks = 0;
  int64_t detail_coefficients = 0;
  int64_t zero_detail_coefficients = 0;
  size_t memory_bytes = 0;
};

class Volume {
 public:
  /// Largest edge accepted on any axis, and the largest voxel count: 2^32,
  /// the limit the NRRD reader and the session's volume command keep too (a
  /// volume of 2^40 voxels was accepted and wrote tens of GB no reader took).
  static constexpr int kMaxEdge = 1 << 16;
  static constexpr int64_t kMaxVoxels = int64_t{1} << 32;

  /// Checks `dims` and `options`; the error names what is out of range.
  static Status validate(glm::ivec3 dims, const VolumeOptions& options);
  /// A volume of `dims` voxels all equal to `fill`. Asserts validate() passed.
  Volume(glm::ivec3 dims, uint8_t fill, const VolumeOptions& options = {});
  /// Encodes a dense grid (in parallel).
  static Volume from_dense(const DenseGrid<uint8_t>& grid, const VolumeOptions& options = {});
  /// Fills a brick's voxels: `fill(box, out)` writes box.size() voxels, x fastest.
  using BrickFill = std::function<void(const Box& box, std::span<uint8_t> out)>;
  /// Builds a volume brick by brick (in parallel), never holding it densely.
  static Volume from_bricks(glm::ivec3 dims, const VolumeOptions& options, const BrickFill& fill);

  glm::ivec3 dims() const { return dims_; }
  int brick_edge() const { return options_.brick_edge; }
  int levels() const { return options_.levels; }
  const VolumeOptions& options() const { return options_; }
  /// Number of bricks along each axis.
  glm::ivec3 brick_grid() const { return grid_; }
  int64_t brick_count() const { return static_cast<int64_t>(bricks_.size()); }
  /// Size of level k: ceil(dims / 2^k).
  glm::ivec3 level_dims(int level) const;
  /// The voxels brick `b` covers, clipped to the volume (level 0).
  Box brick_box(glm::ivec3 b) const;
  /// Bricks overlapping the level-0 region (clipped to the brick grid).
  Box bricks_overlapping(const Box& region) const;
  const Brick& brick(glm::ivec3 b) const { return bricks_[brick_index(b)]; }

  /// Voxel at p, 0 outside the volume. O(levels).
  uint8_t voxel(glm::ivec3 p) const;
  /// Voxels of `region` at `level` (region in that level's coordinates);
  /// voxels outside the volume read 0.
  DenseGrid<uint8_t> read(const Box& region, int level = 0) const;
  /// The whole volume at `level` (in parallel).
  DenseGrid<uint8_t> to_dense(int level = 0) const;

  /// Writes `values` with its first voxel at `origin` (level 0), clipped to
  /// the volume; re-encodes only the bricks it touches.
  void write(glm::ivec3 origin, const DenseGrid<uint8_t>& values);

  /// Decodes brick `b` at `level` into `out` ((edge >> level)^3, x fastest).
  /// A brick among the last kRecentBricks stored is copied, not decoded.
  void decode_brick(glm::ivec3 b, std::span<uint8_t> out, int level = 0) const;
  /// How many of the bricks stored last keep their voxels decoded: what a
  /// dab of a 32^3 tool stores, for the reads that follow it (the haptic
  /// patch, the mesher).
  static constexpr int kRecentBricks = 16;
  /// Stores the full-resolution voxels of brick `b` (edge^3, x fastest):
  /// re-encodes it, re-pads its out-of-volume part, and marks it dirty.
  void store_brick(glm::ivec3 b, std::span<uint8_t> voxels);
  /// store_brick() for voxels that differ from the stored ones only inside
  /// `changed` (level-0 volume coordinates): re-encodes only the wavelet
  /// coefficients over that part of the brick. Same stored result.
  void store_brick(glm::ivec3 b, std::span<uint8_t> voxels, const Box& changed);
  /// One brick for store_bricks(): its voxels and the part that changed.
  struct BrickStore {
    glm::ivec3 brick;
    std::span<uint8_t> voxels;  // edge^3, x fastest; re-padded as stored
    Box changed;                // level-0 volume coordinates
  };
  /// store_brick(brick, voxels, changed) for each, in order, with the
  /// re-encodes spread over `threads` threads (0 = default_threads()): a big
  /// dab stores a hundred bricks, and their encodes were most of its time on
  /// the sculpting thread. The same volume, versions and dirty list as the
  /// stores one by one; the bricks must differ.
  void store_bricks(std::span<const BrickStore> stores, int threads = 0);
  /// Puts a copy of another volume's brick `b` (same brick edge and levels)
  /// in place of this one's and moves its version on: how a mirror of the
  /// volume on another thread (the station's mesher) follows the sculpting
  /// without sharing it. Not marked dirty.
  void replace_brick(glm::ivec3 b, Brick brick);
  /// Calls `edit(brick_origin, voxels)` on each brick overlapping `region`
  /// with its decoded voxels (edge^3, x fastest; brick_origin is the voxel
  /// index of voxels[0]), then stores it back. The path every sculpting
  /// operation takes: only the touched bricks are decoded and re-encoded.
  void edit(const Box& region,
            const std::function<void(glm::ivec3 brick_origin, std::span<uint8_t> voxels)>& edit);

  /// Incremented each time brick `b` is stored; mesh caches compare it.
  uint64_t brick_version(glm::ivec3 b) const { return versions_[brick_index(b)]; }
  /// Incremented each time any brick is stored: a reader polling for
  /// changes (the mesher's, a thousand times a second) compares this before
  /// looking at every brick's version.
  uint64_t stores() const { return stores_; }
  /// Bricks stored since the previous call, in brick order; clears the set.
  std::vector<glm::ivec3> take_dirty_bricks();

  VolumeStats stats() const;
  /// A 64-bit hash (FNV-1a over 8-byte words) of the level-0 voxels in
  /// x-fastest order: equal for equal contents whatever the brick edge.
  uint64_t content_hash() const;

 private:
  size_t brick_index(glm::ivec3 b) const { return grid_index(b, grid_); }
  glm::ivec3 brick_coord(int64_t index) const { return grid_position(index, grid_); }
  // Repeats the last in-volume voxel into the part of a border brick that lies
  // outside the volume.
  void pad_outside(glm::ivec3 b, std::span<uint8_t> voxels) const;

  // Keeps the voxels of brick index `i` just stored (after padding) among
  // the recent ones, replacing the oldest.
  void remember_stored(size_t i, std::span<const uint8_t> voxels);
  // Drops brick index `i` from the recent ones (its voxels there are old).
  void forget_stored(size_t i);
  // The re-encode of store_brick(b, voxels, changed), without the book-keeping
  // below: touches brick `b` only, so different bricks may run at once.
  void encode_stored(glm::ivec3 b, std::span<uint8_t> voxels, const Box& changed);
  // The book-keeping of a store: the brick's version, the store count and the
  // dirty list.
  void count_stored(size_t i);

  glm::ivec3 dims_;
  VolumeOptions options_;
  glm::ivec3 grid_;
  std::vector<Brick> bricks_;
  std::vector<uint64_t> versions_;
  uint64_t stores_ = 0;
  std::vector<uint8_t> dirty_flags_;
  std::vector<int64_t> dirty_list_;
  // The recently stored bricks: index (-1: free slot) and decoded voxels,
  // slot k at k * edge^3; written only by store_brick (exclusive access).
  std::array<int64_t, kRecentBricks> recent_brick_ = [] {
    std::array<int64_t, kRecentBricks> none;
    none.fill(-1);
    return none;
  }();
  std::vector<uint8_t> recent_voxels_;
  int recent_next_ = 0;
};

}  // namespace sculpt::core
