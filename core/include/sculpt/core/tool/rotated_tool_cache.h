#pragma once
// Cache of rotated tool voxels ("Discrete tools for virtual sculpture" §3.1,
// second and third improvements): voxels are rotated only where the tool
// touches material that can change, and kept per placement, so a tool that
// moves without turning, or turns back, is not rotated again; only voxels
// newly entering the contact region are.
//
// A placement is keyed by its orientation binned finely enough that the
// rotated tool cannot be told apart from the exact one (bin_orientation()),
// and the sub-voxel part of the pivot position quantised to
// 1/subvoxel_steps voxel (default 1/16: at most 1/32 voxel off, far inside
// the material's 2-voxel density ramp, while a tool moving without turning
// finds its offsets again). The placement actually applied is the binned one,
// so a hit returns exactly what a miss computes. Integer moves of the
// position reuse the entry (the rotated voxels are relative to the anchor).
//
// A new entry costs only the rows a dab reaches: rows are zeroed when first
// filled, not the whole rotated box when the entry is made.
//
// Memory is bounded: entries are evicted least recently used once their
// bytes exceed the cap. The cache is not thread-safe (one per sculpting
// thread: acquire() on one thread); an entry's rows may be asked for by
// several threads at once.

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/tool/tool_rotation.h"

namespace sculpt::core {

struct RotatedToolCacheStats {
  int64_t placements = 0;        // acquire() calls
  int64_t placement_hits = 0;    // of which found an entry
  int64_t voxels_requested = 0;  // rotated voxels asked for by row()
  int64_t voxels_reused = 0;     // of which were already rotated
  int64_t voxels_rotated = 0;    // voxels rotated (gaps filled included)
  int64_t evictions = 0;
  size_t bytes = 0;  // held by the cached entries
  size_t entries = 0;
  /// Share of placements that found their entry, in [0, 1].
  double placement_hit_rate() const {
    return placements ? static_cast<double>(placement_hits) / static_cast<double>(placements) : 0.0;
  }
  /// Counts summed (bytes and entries too: both are what is held now).
  RotatedToolCacheStats& operator+=(const RotatedToolCacheStats& o);
  /// The counts of a cache being dropped: as these, holding nothing.
  RotatedToolCacheStats retired() const {
    RotatedToolCacheStats r = *this;
    r.bytes = 0;
    r.entries = 0;
    return r;
  }
  /// Share of requested voxels served without rotating, in [0, 1].
  double voxel_hit_rate() const {
    return voxels_requested
               ? static_cast<double>(voxels_reused) / static_cast<double>(voxels_requested)
               : 0.0;
  }
};

/// The rotated voxels of one placement, filled lazily row stretch by row stretch.
class RotatedToolEntry {
 public:
  static constexpr size_t kRowSlack = 32;

  RotatedToolEntry(const PreparedTool& tool, const glm::mat3& rotation, glm::vec3 offset,
                   Sampling sampling, RotatedToolCacheStats* stats);
  /// Voxels that can be non-zero, relative to the placement's anchor.
  const Box& box() const { return frame_.box(); }
  /// The rotation applied (the quantised orientation).
  const glm::mat3& rotation() const { return rotation_; }
  /// The pivot's offset from the anchor, in [0, 1) per axis.
  glm::vec3 offset() const { return offset_; }
  /// Rotated voxels [x0, x1) of row (y, z) (anchor-relative, inside box()),
  /// rotating those not yet computed. Valid until the next call; readable
  /// for kRowSlack bytes past x1.
  const uint8_t* row(int y, int z, int x0, int x1) { return row(y, z, x0, x1, *stats_); }
  /// row(), counting in `stats` instead of the cache's: threads filling
  /// different rows of one entry at once each count in their own (the
  /// cache takes the sums, RotatedToolCache::add_row_counts()).
  const uint8_t* row(int y, int z, int x0, int x1, RotatedToolCacheStats& stats) {
    // The hit (every voxel of an unchanged orientation's dab) inline.
    const Box& b = frame_.box();
    assert(x0 >= b.lo.x && x1 <= b.hi.x && x0 <= x1 && y >= b.lo.y && y < b.hi.y && z >= b.lo.z &&
           z < b.hi.z);
    const size_t r = static_cast<size_t>(z - b.lo.z) * b.size().y + (y - b.lo.y);
    const int a = x0 - b.lo.x, e = x1 - b.lo.x;
    const uint32_t done = done_[r].load(std::memory_order_acquire);
    if (done_lo(done) <= a && e <= done_hi(done) && a < e) {
      stats.voxels_requested += e - a;
      stats.voxels_reused += e - a;
      return &values_[r * stride_ + static_cast<size_t>(a)];
    }
    return rotate_row(y, z, x0, x1, stats);
  }
  /// The stretch [x0, x1) of row (y, z) (anchor-relative, inside box())
  /// within the tool's reach and support: outside it the row's voxels are 0.
  /// Empty (x0 == x1) when the row misses them.
  std::pair<int, int> reach(int y, int z) const {
    const Box& b = frame_.box();
    const size_t r = static_cast<size_t>(z - b.lo.z) * b.size().y + (y - b.lo.y);
    return {b.lo.x + plans_[r].x0, b.lo.x + plans_[r].x1};
  }
  size_t memory_bytes() const;

 private:
  // row() when some of the voxels are not rotated yet.
  const uint8_t* rotate_row(int y, int z, int x0, int x1, RotatedToolCacheStats& stats);

  const PreparedTool* tool_;
  glm::mat3 rotation_;
  glm::vec3 offset_;
  RotationFrame frame_;
  RotatedToolCacheStats* stats_;
  // The box's voxels, x fastest, each row followed by kRowSlack zero bytes
  // of its own: a row's consumer may read a vector's width past its end
  // (combine_row()), and threads filling neighbouring rows at once
  // (Sculptor's big dabs) must not have it read the next row's.
  size_t stride_;
  size_t values_size_;
  // Not zeroed as a whole: a row's bytes (and its slack) are zeroed when the
  // row is first filled (rotate_row()).
  std::unique_ptr<uint8_t[]> values_;
  // Per row (y, z) of the box, the computed stretch [lo, hi) of x offsets,
  // packed lo | hi << 16. Threads may fill rows of one entry at once (a
  // stroke's bricks side by side in x share rows, and so do two placements
  // of one entry at different anchors): a row's stretch is published
  // (release) after its values are written, so a reader whose stretch is
  // covered reads finished values without a lock; a stretch only grows, and
  // growing it writes only bytes outside it.
  std::unique_ptr<std::atomic<uint32_t>[]> done_;
  // Per row, held while its stretch grows (rotate_row()).
  std::unique_ptr<std::atomic<bool>[]> filling_;
  static int done_lo(uint32_t done) { return static_cast<int>(done & 0xFFFFu); }
  static int done_hi(uint32_t done) { return static_cast<int>(done >> 16); }
  // Per row, its stretch within reach and support and its core (box-relative
  // x offsets), found once per placement: a dab then needs no square root
  // and no clipping per row, and the stroke skips what reads zero. Sampling
  // a row piecemeal found them anew each time: a turning ring's stroke spent
  // more on that than on sampling (docs/performance.md).
  std::vector<RotationFrame::RowPlan> plans_;
};

/// A point at this distance from where it should be changes a trilinear
/// sample by at most one density step (1/255) wherever the tool is sampled,
/// measured over 30 random orientations each of cubes, cylinders, a ring and
/// a cone (at 0.012 the ring and an 18x11 cylinder already show steps of 2;
/// docs/performance.md). RotatedToolCache's test
/// BinnedOrientationDiffersFromTheExactOneByAtMostOneDensityStep holds it.
inline constexpr float kOrientationToleranceVox = 0.008f;

/// The step of each quaternion component of an orientation's bin for a tool
/// whose farthest sampled point is `reach_vox` from its pivot: turning to
/// the bin's centre moves no point of the tool more than
/// kOrientationToleranceVox (a quaternion moved by d turns by at most 2 d
/// radians, and rounding four components moves it by at most step).
inline double orientation_bin_step(float reach_vox) {
  return static_cast<double>(kOrientationToleranceVox) / (2.0 * std::max(1.0f, reach_vox));
}

/// `orientation` (unit) moved to the centre of its bin (canonical sign:
/// q and -q are one rotation), and the bin's integer coordinates in `key`.
glm::quat bin_orientation(const glm::quat& orientation, double step, int32_t key[4]);

class RotatedToolCache {
 public:
  static constexpr size_t kDefaultMaxBytes = size_t{64} << 20;
  static constexpr int kDefaultSubvoxelSteps = 16;

  /// `subvoxel_steps` in [1, 4096]: positions snap to 1/subvoxel_steps voxel.
  RotatedToolCache(std::shared_ptr<const PreparedTool> tool, Sampling sampling,
                   size_t max_bytes = kDefaultMaxBytes, int subvoxel_steps = kDefaultSubvoxelSteps);

  struct Placement {
    std::shared_ptr<RotatedToolEntry> entry;
    /// Target voxel of the entry's local (0, 0, 0).
    glm::ivec3 anchor{0};
  };
  /// The entry for the tool turned by `orientation` (unit quaternion, tool to
  /// target) with its pivot at `position` (target voxel units).
  Placement acquire(const glm::quat& orientation, glm::vec3 position);

  const PreparedTool& tool() const { return *tool_; }
  Sampling sampling() const { return sampling_; }
  const RotatedToolCacheStats& stats() const { return stats_; }
  /// Adds row counts made in a thread's own stats (RotatedToolEntry::row()).
  void add_row_counts(const RotatedToolCacheStats& counts) {
    stats_.voxels_requested += counts.voxels_requested;
    stats_.voxels_reused += counts.voxels_reused;
    stats_.voxels_rotated += counts.voxels_rotated;
  }
  void clear();

 private:
  struct Key {
    int32_t q[4];
    int16_t f[3];
    friend bool operator==(const Key&, const Key&) = default;
  };
  struct KeyHash {
    size_t operator()(const Key& k) const;
  };
  struct Slot {
    std::shared_ptr<RotatedToolEntry> entry;
    std::list<Key>::iterator lru;
  };
  void evict_to(size_t budget);

  std::shared_ptr<const PreparedTool> tool_;
  Sampling sampling_;
  size_t max_bytes_;
  int subvoxel_steps_;
  double bin_step_;     // orientation_bin_step() of the tool's reach
  std::list<Key> lru_;  // most recent first
  std::unordered_map<Key, Slot, KeyHash> slots_;
  RotatedToolCacheStats stats_;
};

}  // namespace sculpt::core
