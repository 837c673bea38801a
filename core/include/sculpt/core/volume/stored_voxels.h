#pragma once
// The level-0 voxels of bricks as a sculptor stored them, for a mesher that
// would otherwise decode the same bricks again.
//
// A big dab's bricks were decoded twice: by the sculptor, which combines
// the tool into their voxels and encodes them, and by the mesher, which
// decodes each stored brick to see what moved and to march it (a fifth of
// the update after a 66-voxel ball: 60-107 bricks, 2 ms on two cores). A
// sculptor asked to (SculptorOptions::hand_over_voxels) keeps a copy of
// what it stored, and MixedLevelMeshCache::update() takes it instead of
// decoding: the same bytes, as the wavelets are lossless.

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "sculpt/core/grid/box.h"

namespace sculpt::core {

/// A brick's voxels (edge^3, x fastest) at one version of it.
struct StoredVoxels {
  uint64_t version = 0;  ///< Volume::brick_version() they are the voxels of
  std::vector<uint8_t> voxels;
  /// The version whose voxels these differ from only inside `changed`
  /// (level-0 volume coordinates), if known: a mesher holding that
  /// version's voxels compares only there to find what moved.
  std::optional<uint64_t> changed_from;
  Box changed;
};

/// `later`, stored after `earlier` (the version `later` changed from):
/// what changed since `earlier` changed from, or unknown.
inline void follow(const StoredVoxels& earlier, StoredVoxels& later) {
  if (!earlier.changed_from || later.changed_from != earlier.version) {
    later.changed_from.reset();
    return;
  }
  later.changed_from = earlier.changed_from;
  later.changed = hull(earlier.changed, later.changed);
}

/// By brick index (grid_index()).
using StoredVoxelsByBrick = std::unordered_map<int64_t, StoredVoxels>;

}  // namespace sculpt::core
