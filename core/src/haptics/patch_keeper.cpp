#include "sculpt/core/haptics/patch_keeper.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>

namespace sculpt::core {
namespace {

// A value depends on the material within its seed reach + 2 voxels
// (distance_patch.h); the band plus that margin bounds the reach. In the
// patch's voxels.
Box watched_region(const DistancePatch& patch) {
  Box box = patch.box();
  const int margin = static_cast<int>(std::ceil(patch.options().band_vox)) + 4;
  box.lo -= margin;
  box.hi += margin;
  return box;
}

// A level's mirror only ever reads its own level 0: small bricks, one level.
constexpr VolumeOptions kMirrorOptions{16, 1, 1};

}  // namespace

SpherePatch sphere_patch(float radius_vox, int volume_levels) {
  SpherePatch p;
  const int max_level = std::min(kMaxSpherePatchLevel, volume_levels);
  const float r = std::max(radius_vox, 0.0f);
  while (p.level < max_level && r / p.scale() > kMaxSpherePatchRadiusVox)
    ++p.level;
  p.options.band_vox = band_for_sphere(r / p.scale());
  p.options.edge = patch_edge_for_reach(0.0f, p.options.band_vox);
  p.options.threads = 1;
  return p;
}

PatchKeeper::PatchKeeper(PatchExchange& exchange, const DistancePatchOptions& options, int level)
    : exchange_(&exchange), patch_(options), level_(std::max(level, 0)) {}

PatchKeeper::PatchKeeper(const DistancePatchOptions& options, int level)
    : exchange_(nullptr), patch_(options), level_(std::max(level, 0)) {}

void PatchKeeper::remember_versions(const Volume& volume) {
  const glm::ivec3 grid = volume.brick_grid();
  versions_.assign(static_cast<size_t>(volume.brick_count()), 0);
  for (int z = 0; z < grid.z; ++z)
    for (int y = 0; y < grid.y; ++y)
      for (int x = 0; x < grid.x; ++x)
        versions_[(static_cast<size_t>(z) * grid.y + y) * grid.x + x] =
            volume.brick_version({x, y, z});
  stores_seen_ = volume.stores();
}

std::vector<glm::ivec3> PatchKeeper::changed_bricks(const Volume& volume) {
  std::vector<glm::ivec3> changed;
  const glm::ivec3 grid = volume.brick_grid();
  // At level 0 only the bricks under the patch matter: a re-centre reads
  // the others afresh. A level's mirror must follow every brick.
  Box bricks{glm::ivec3(0), grid};
  if (level_ == 0) bricks = volume.bricks_overlapping(watched_region(patch_));
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        uint64_t& seen = versions_[(static_cast<size_t>(z) * grid.y + y) * grid.x + x];
        const uint64_t now = volume.brick_version({x, y, z});
        if (now != seen) changed.push_back({x, y, z});
        seen = now;
      }
  stores_seen_ = volume.stores();
  return changed;
}

std::vector<glm::ivec3> PatchKeeper::mirror_bricks() {
  return mirror_->take_dirty_bricks();
}

const Volume& PatchKeeper::source(const Volume& volume, std::span<const glm::ivec3> changed) {
  if (level_ == 0) return volume;
  const int round_up = (1 << level_) - 1;
  for (const glm::ivec3& b : changed) {
    const Box box = volume.brick_box(b);
    const Box at_level{box.lo >> level_, (box.hi + round_up) >> level_};
    mirror_->write(at_level.lo, volume.read(at_level, level_));
  }
  return *mirror_;
}

bool PatchKeeper::update(const Volume& volume, uint64_t generation, glm::vec3 centre_vox) {
  assert(level_ <= volume.levels());
  const auto started = std::chrono::steady_clock::now();
  const SpherePatch mapping{level_, {}};
  const glm::vec3 centre = mapping.to_patch(centre_vox);
  bool changed = false;
  if (!built_ || generation != generation_) {
    if (level_ > 0)
      mirror_ =
          std::make_unique<Volume>(Volume::from_dense(volume.to_dense(level_), kMirrorOptions));
    patch_.build(level_ > 0 ? *mirror_ : volume, centre);
    if (mirror_) (void)mirror_->take_dirty_bricks();
    remember_versions(volume);
    built_ = true;
    generation_ = generation;
    ++figures_.builds;
    changed = true;
  } else {
    if (volume.stores() != stores_seen_) {
      const std::vector<glm::ivec3> bricks = changed_bricks(volume);
      if (!bricks.empty()) {
        const Volume& from = source(volume, bricks);
        if (level_ == 0) {
          patch_.refresh_bricks(from, bricks);
        } else {
          patch_.refresh_bricks(from, mirror_bricks());
        }
        ++figures_.refreshes;
        changed = true;
      }
    }
    if (patch_.off_centre(centre)) {
      // At level 0, bricks changed outside the watched region are read
      // afresh by the re-centre: remember them as seen.
      patch_.recentre(level_ > 0 ? *mirror_ : volume, centre);
      if (level_ == 0) remember_versions(volume);
      ++figures_.recentres;
      changed = true;
    }
  }
  if (changed) {
    if (exchange_ != nullptr) {
      copy_snapshot(patch_.snapshot(), exchange_->back());
      exchange_->publish();
    }
    ++figures_.publishes;
    const std::chrono::duration<double, std::milli> took =
        std::chrono::steady_clock::now() - started;
    figures_.slowest_update_ms = std::max(figures_.slowest_update_ms, took.count());
  }
  return changed;
}

}  // namespace sculpt::core
