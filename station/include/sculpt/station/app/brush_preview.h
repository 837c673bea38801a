#pragma once
// Live feedback for the ball brushes (clay, flatten, inflate, pinch, grab).
// A core brush is a function of its whole path (clay fits its plane at the
// start, grab drags what lay under the start), so while the press goes on
// the station shows the brush applied to the path so far and, when more of
// the path has come, puts the material back and applies it again to the
// longer path. When the press ends the material is put back once more and
// the brush applied for real, as one undo step: what is left is exactly
// what applying the whole path at once leaves, so recordings replay bit for
// bit whether or not previews were shown.
//
// A preview writes no undo step (it runs on a scratch sculptor) and keeps
// the bricks it may change as they were (compressed, as the volume holds
// them), so putting them back is exact. Only bricks a preview changed are
// stored again: the rest keep their versions and meshes. A brush whose
// result at a voxel does not depend on the path's far parts (smoothing)
// need not start again: extend() brushes again only what the path's new
// samples reach, reading the kept material.
//
// Thread safety: the sculpting thread's, like the volume.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {

class BrushPreview {
 public:
  /// Whether a preview of a path of `samples` samples is due, the last one
  /// having shown `shown` (0: none yet): after the first two samples, then
  /// whenever the path has grown by an eighth since (at least two samples),
  /// so a long stroke's previews cost a bounded multiple of its length.
  static bool due(size_t samples, size_t shown);

  /// Puts back the bricks the last preview changed, then keeps the bricks
  /// overlapping `region` (voxels) as they are now and runs `apply`, which
  /// may change only those: the brush on the path's first `samples`
  /// samples. Returns what `apply` returns.
  int64_t show(core::Volume& volume, const core::Box& region, size_t samples,
               const std::function<int64_t()>& apply);
  /// Runs `apply` without putting anything back first: the brush on the
  /// path's first `samples` samples (more than shown_samples(), asserted,
  /// a preview being active) written only where it differs from the last
  /// preview's, within `region`. Keeps the bricks overlapping `region` not
  /// kept yet (none of the earlier previews changed them); `apply` reads
  /// the material as it was before the stroke from the volume it is given
  /// (the volume's dims, holding it for every kept brick; other bricks are
  /// the volume's own). Returns what `apply` returns.
  int64_t extend(core::Volume& volume, const core::Box& region, size_t samples,
                 const std::function<int64_t(const core::Volume& before)>& apply);
  /// Puts back the bricks the last preview changed (nothing if none).
  void revert(core::Volume& volume);
  /// A preview is shown and not reverted.
  bool active() const { return active_; }
  /// Samples of the path the shown preview covers (0 when none).
  size_t shown_samples() const { return shown_samples_; }

 private:
  struct Kept {
    glm::ivec3 brick;
    uint64_t version;  // the brick's version when kept
  };
  // Keeps the bricks overlapping `region` that are not kept yet.
  void keep(const core::Volume& volume, const core::Box& region);
  std::vector<Kept> kept_;
  std::vector<bool> is_kept_;  // by brick (core::grid_index): whether in kept_
  // The material before the stroke: the kept bricks as they were, the
  // other bricks uniform (unread).
  std::unique_ptr<core::Volume> before_;
  bool active_ = false;
  size_t shown_samples_ = 0;
};

}  // namespace sculpt::station
