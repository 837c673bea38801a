#include "sculpt/station/app/brush_preview.h"

#include <algorithm>
#include <cassert>

#include "sculpt/core/grid/grid_index.h"

namespace sculpt::station {

bool BrushPreview::due(size_t samples, size_t shown) {
  if (samples < 2) return false;
  if (shown == 0) return true;
  return samples >= shown + std::max<size_t>(2, shown / 8);
}

void BrushPreview::keep(const core::Volume& volume, const core::Box& region) {
  if (!before_ || before_->dims() != volume.dims() ||
      before_->brick_edge() != volume.brick_edge() || before_->levels() != volume.levels()) {
    before_ = std::make_unique<core::Volume>(volume.dims(), uint8_t{0}, volume.options());
    is_kept_.assign(static_cast<size_t>(volume.brick_count()), false);
  }
  const core::Box bricks = volume.bricks_overlapping(region);
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        const glm::ivec3 b(x, y, z);
        const size_t index = core::grid_index(b, before_->brick_grid());
        if (is_kept_[index]) continue;
        is_kept_[index] = true;
        kept_.push_back({b, volume.brick_version(b)});
        before_->replace_brick(b, volume.brick(b));
      }
}

int64_t BrushPreview::show(core::Volume& volume, const core::Box& region, size_t samples,
                           const std::function<int64_t()>& apply) {
  revert(volume);
  keep(volume, region);
  active_ = true;
  shown_samples_ = samples;
  return apply();
}

int64_t BrushPreview::extend(core::Volume& volume, const core::Box& region, size_t samples,
                             const std::function<int64_t(const core::Volume& before)>& apply) {
  assert(active_ && samples > shown_samples_);
  keep(volume, region);
  shown_samples_ = samples;
  return apply(*before_);
}

void BrushPreview::revert(core::Volume& volume) {
  if (!active_) return;
  std::vector<uint8_t> voxels;
  for (const Kept& k : kept_) {
    if (volume.brick_version(k.brick) != k.version) {  // changed: put back
      const size_t edge = static_cast<size_t>(volume.brick_edge());
      voxels.resize(edge * edge * edge);
      before_->brick(k.brick).extract_level(0, voxels);
      volume.store_brick(k.brick, voxels);
    }
    // A stroke's kept bricks are not held past it.
    before_->replace_brick(k.brick, core::Brick());
    is_kept_[core::grid_index(k.brick, before_->brick_grid())] = false;
  }
  kept_.clear();
  active_ = false;
  shown_samples_ = 0;
}

}  // namespace sculpt::station
