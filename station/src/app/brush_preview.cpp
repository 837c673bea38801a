#include "sculpt/station/app/brush_preview.h"

#include <algorithm>
#include <cassert>

namespace sculpt::station {

bool BrushPreview::due(size_t samples, size_t shown) {
  if (samples < 2) return false;
  if (shown == 0) return true;
  return samples >= shown + std::max<size_t>(2, shown / 8);
}

int64_t BrushPreview::show(core::Volume& volume, const core::Box& region, size_t samples,
                           const std::function<int64_t()>& apply) {
  revert(volume);
  const core::Box bricks = volume.bricks_overlapping(region);
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        const glm::ivec3 b(x, y, z);
        kept_.push_back({b, volume.brick(b), volume.brick_version(b)});
      }
  active_ = true;
  shown_samples_ = samples;
  return apply();
}

void BrushPreview::revert(core::Volume& volume) {
  if (!active_) return;
  std::vector<uint8_t> voxels;
  for (Kept& k : kept_) {
    if (volume.brick_version(k.brick) == k.version) continue;  // unchanged
    const size_t edge = static_cast<size_t>(volume.brick_edge());
    voxels.resize(edge * edge * edge);
    k.before.extract_level(0, voxels);
    volume.store_brick(k.brick, voxels);
  }
  kept_.clear();
  active_ = false;
  shown_samples_ = 0;
}

}  // namespace sculpt::station
