#pragma once
// The sculpting thread's half of the haptic contact (DESIGN.md §5a): it keeps
// the distance patch around the proxy and current with the material, and
// publishes it to the haptic loop (PatchExchange) only when it changed.
// Called every poll (1 kHz): when nothing was sculpted and the proxy stays
// near the patch's centre, it costs a comparison of two counters.
//
// Changes are found by brick versions, not by Volume::take_dirty_bricks(), so
// the patch shares the volume with the mesher and the project's autosave
// without taking their changes from them.
//
// Thread safety: one thread (the station's sculpting thread).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/haptics/patch_exchange.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct PatchKeeperFigures {
  int64_t builds = 0;     ///< from scratch (first time, a new volume)
  int64_t refreshes = 0;  ///< after material changed under the patch
  int64_t recentres = 0;  ///< after the proxy moved away from the centre
  int64_t publishes = 0;  ///< snapshots handed to the haptic loop
  /// The slowest update (build, refresh or re-centre, and the copy), ms: the
  /// time the sculpting thread gave to it once.
  double slowest_update_ms = 0.0;
};

/// The patch a sphere proxy of `radius_vox` (full-resolution voxels) needs.
/// The band must reach past the radius, and a patch's cost grows with the
/// cube of its band (built at full resolution: a 4-voxel radius 2 ms, 12
/// voxels 145 ms, 24 voxels a second), so a big sphere's patch is read from
/// the coarsest level, at most kMaxSpherePatchLevel, that keeps its radius within
/// kMaxSpherePatchRadiusVox of that level's voxels. The proxy reads the field
/// at its centre only (phi - r), so the patch covers the band around the
/// centre's path, not the sphere's reach too.
struct SpherePatch {
  int level = 0;
  DistancePatchOptions options;
  /// Full-resolution voxels per patch voxel, 2^level.
  float scale() const { return static_cast<float>(1 << level); }
  /// A full-resolution point in the patch's voxels, and back. Level k's
  /// voxel i averages full-resolution voxels 2^k i .. 2^k (i + 1) - 1, so it
  /// sits at 2^k i + (2^k - 1) / 2: without that half-cell shift a coarse
  /// surface lies 1.5 voxels off at level 2.
  glm::vec3 to_patch(glm::vec3 p) const { return (p - 0.5f * (scale() - 1.0f)) / scale(); }
  glm::vec3 from_patch(glm::vec3 p) const { return p * scale() + 0.5f * (scale() - 1.0f); }
};
inline constexpr float kMaxSpherePatchRadiusVox = 5.0f;
/// The coarsest level a sphere's patch is read from.
inline constexpr int kMaxSpherePatchLevel = 4;
/// For a volume of `volume_levels` levels (the level chosen never exceeds them).
SpherePatch sphere_patch(float radius_vox, int volume_levels);

class PatchKeeper {
 public:
  /// Publishes into `exchange`, which must have been made with options.edge.
  /// `level` > 0: the patch is of the pyramid's level `level` (its voxels
  /// 2^level full-resolution ones a side), read from a mirror of that level
  /// that follows the volume's changed bricks; centres are still given in
  /// full-resolution voxels. At most the volume's levels.
  PatchKeeper(PatchExchange& exchange, const DistancePatchOptions& options, int level = 0);
  /// Without an exchange: the owner reads patch() itself, on its own thread.
  explicit PatchKeeper(const DistancePatchOptions& options, int level = 0);

  /// Keeps the patch around `centre_vox` (the proxy) and current with
  /// `volume`, whose `generation` moves on when it is replaced; publishes
  /// when anything changed. Returns whether it published.
  bool update(const Volume& volume, uint64_t generation, glm::vec3 centre_vox);

  const DistancePatch& patch() const { return patch_; }
  const PatchKeeperFigures& figures() const { return figures_; }
  /// The pyramid level the patch is of.
  int level() const { return level_; }

 private:
  // Bricks whose version moved since the last look, among those whose
  // material the patch's values can depend on.
  std::vector<glm::ivec3> changed_bricks(const Volume& volume);
  void remember_versions(const Volume& volume);

  // The volume the patch reads: `volume` itself at level 0, else the mirror
  // of its level, brought up to date with `changed` first.
  const Volume& source(const Volume& volume, std::span<const glm::ivec3> changed);
  // The mirror's bricks that source() changed.
  std::vector<glm::ivec3> mirror_bricks();

  PatchExchange* exchange_;  // null: nothing published
  DistancePatch patch_;
  int level_ = 0;
  std::unique_ptr<Volume> mirror_;  // level_ > 0: the volume at level_
  bool built_ = false;
  uint64_t generation_ = 0;
  uint64_t stores_seen_ = 0;
  std::vector<uint64_t> versions_;  // per brick of the volume, at the last look
  PatchKeeperFigures figures_;
};

}  // namespace sculpt::core
