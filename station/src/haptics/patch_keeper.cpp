#include "sculpt/station/haptics/patch_keeper.h"

#include <cmath>

namespace sculpt::station {
namespace {

// A value depends on the material within its seed reach + 2 voxels
// (distance_patch.h); the band plus that margin bounds the reach.
core::Box watched_region(const core::DistancePatch& patch) {
  core::Box box = patch.box();
  const int margin = static_cast<int>(std::ceil(patch.options().band_vox)) + 4;
  box.lo -= margin;
  box.hi += margin;
  return box;
}

}  // namespace

PatchKeeper::PatchKeeper(core::PatchExchange& exchange, const core::DistancePatchOptions& options)
    : exchange_(exchange), patch_(options) {}

void PatchKeeper::remember_versions(const core::Volume& volume) {
  const glm::ivec3 grid = volume.brick_grid();
  versions_.assign(static_cast<size_t>(volume.brick_count()), 0);
  for (int z = 0; z < grid.z; ++z)
    for (int y = 0; y < grid.y; ++y)
      for (int x = 0; x < grid.x; ++x)
        versions_[(static_cast<size_t>(z) * grid.y + y) * grid.x + x] =
            volume.brick_version({x, y, z});
  stores_seen_ = volume.stores();
}

std::vector<glm::ivec3> PatchKeeper::changed_bricks(const core::Volume& volume) {
  std::vector<glm::ivec3> changed;
  const glm::ivec3 grid = volume.brick_grid();
  const core::Box bricks = volume.bricks_overlapping(watched_region(patch_));
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        uint64_t& seen = versions_[(static_cast<size_t>(z) * grid.y + y) * grid.x + x];
        const uint64_t now = volume.brick_version({x, y, z});
        if (now != seen) changed.push_back({x, y, z});
        seen = now;
      }
  // Bricks outside the watched region keep their old versions: when the
  // patch moves over them, recentre() reads them whole anyway.
  stores_seen_ = volume.stores();
  return changed;
}

bool PatchKeeper::update(const core::Volume& volume, uint64_t generation, glm::vec3 centre_vox) {
  bool changed = false;
  if (!built_ || generation != generation_) {
    patch_.build(volume, centre_vox);
    remember_versions(volume);
    built_ = true;
    generation_ = generation;
    ++figures_.builds;
    changed = true;
  } else {
    if (volume.stores() != stores_seen_) {
      const std::vector<glm::ivec3> bricks = changed_bricks(volume);
      if (!bricks.empty()) {
        patch_.refresh_bricks(volume, bricks);
        ++figures_.refreshes;
        changed = true;
      }
    }
    if (patch_.off_centre(centre_vox)) {
      // Bricks that changed outside the watched region are read afresh by
      // the re-centre; remember them as seen.
      patch_.recentre(volume, centre_vox);
      remember_versions(volume);
      ++figures_.recentres;
      changed = true;
    }
  }
  if (changed) {
    core::copy_snapshot(patch_.snapshot(), exchange_.back());
    exchange_.publish();
    ++figures_.publishes;
  }
  return changed;
}

}  // namespace sculpt::station
