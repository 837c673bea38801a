#pragma once
// The surface at several levels of detail at once, for a view that picks a
// level per brick (LodSelector). Level 0 is the StationLoop's own cache;
// coarser levels have caches here, brought up to date only while some brick
// is drawn at them. Each cache is incremental (MeshCache), so a dab costs a
// re-mesh of its bricks at each level in use.
//
// Neighbouring bricks drawn at different levels meet with small seams where
// the coarse and fine surfaces part by under a coarse voxel (the crack-free
// mixed-level mesh of core/mesh/mixed_level_mesh.h is built for export and
// is not yet cached per brick). The LOD policy keeps level changes far from
// the camera, where such seams are below a pixel.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {

class SurfaceLod {
 public:
  explicit SurfaceLod(int max_level);
  int max_level() const { return static_cast<int>(caches_.size()); }

  /// Brings the levels used in `levels` (one per brick) up to date.
  void update(const core::Volume& volume, std::span<const int> levels);
  /// Brick b's mesh at `level` (>= 1; level 0 is the StationLoop's cache).
  const core::BrickMesh& brick_mesh(glm::ivec3 b, int level) const;

  /// A number that changes whenever brick b's mesh may have changed: the sum
  /// of the versions of the bricks its cells read (b and its 26 neighbours).
  static uint64_t neighbourhood_stamp(const core::Volume& volume, glm::ivec3 b);

 private:
  std::vector<std::unique_ptr<core::MeshCache>> caches_;  // levels 1..max
};

}  // namespace sculpt::station
