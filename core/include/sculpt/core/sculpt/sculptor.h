#pragma once
// Sculpting a Volume with a discrete tool ("Discrete tools for virtual
// sculpture" §3.3): each dab places the tool, finds the collision of its
// rotated bounding box with the volume, and combines the tool's filling
// percentage (its rotated density / 255, times the dab's strength) with the
// material voxel by voxel.
//
// A dab visits only the bricks its box overlaps, skips those the tool cannot
// reach or cannot change (a uniform empty brick under subtraction, a uniform
// full one under addition), rotates tool voxels only where the material can
// change (through the RotatedToolCache), and re-encodes and marks dirty only
// the bricks whose voxels changed. It keeps the decoded voxels of recently
// edited bricks, checked against Volume::brick_version, so a stroke's
// overlapping dabs decode each brick once.
//
// Strokes group dabs for undo; a dab outside a stroke is a stroke of its own.
// With a mirror plane set, every dab is also applied mirrored (tool mirrored,
// orientation reflected), within the same stroke. Where the two overlap the
// operation applies twice.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/sculpt/combine_row.h"
#include "sculpt/core/sculpt/undo_history.h"
#include "sculpt/core/tool/rotated_tool_cache.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/tool/tool_rotation.h"
#include "sculpt/core/volume/stored_voxels.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// How a tool voxel's filling f (0..255, already scaled by strength)
/// combines with a material voxel m.
enum class SculptMode {
  kAdd,         // min(255, m + f)                 (§3.3 "adding material")
  kSubtract,    // max(0, m - f)                   (§3.3 "subtracting material")
  kUnion,       // max(m, f)
  kDifference,  // min(m, 255 - f)
  kSmooth,      // m + f/255 * (mean of m's 3x3x3 neighbourhood - m)
};

/// "add", "subtract", "union", "difference", "smooth"; nullopt otherwise.
std::optional<SculptMode> parse_sculpt_mode(const std::string& name);
const char* sculpt_mode_name(SculptMode mode);

struct Dab {
  /// Where the tool's pivot goes, material voxel units (sub-voxel allowed).
  glm::vec3 position_vox{0.0f};
  /// Tool-to-material rotation (unit quaternion).
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  SculptMode mode = SculptMode::kAdd;
  /// Scales the filling percentage, in [0, 1].
  float strength = 1.0f;
};

/// Mirror symmetry across the plane normal to `axis` (0 x, 1 y, 2 z) through
/// `centre_vox` on that axis.
struct MirrorPlane {
  int axis = 0;
  float centre_vox = 0.0f;
};

/// What one dab did, and where its time went (nanoseconds, steady clock,
/// measured per brick: decode, apply = rotate on contact + combine, encode).
struct DabStats {
  int bricks_overlapped = 0;
  int bricks_decoded = 0;
  int bricks_reused = 0;  // decoded voxels still valid from an earlier dab
  int bricks_changed = 0;
  int64_t voxels_changed = 0;
  int64_t decode_ns = 0;
  int64_t apply_ns = 0;
  int64_t encode_ns = 0;
  DabStats& operator+=(const DabStats& o);
};

struct SculptorOptions {
  Sampling sampling = Sampling::kTrilinear;
  /// Decoded bricks kept between dabs (edge^3 bytes each): consecutive dabs
  /// overlap, and a brick whose version has not changed since this sculptor
  /// stored it needs no decoding.
  size_t decoded_bricks = 64;
  size_t cache_max_bytes = RotatedToolCache::kDefaultMaxBytes;
  /// Dab positions snap to 1/subvoxel_steps voxel (see RotatedToolCache).
  int subvoxel_steps = RotatedToolCache::kDefaultSubvoxelSteps;
  size_t undo_max_bytes = UndoHistory::kDefaultMaxBytes;
  /// Keep a copy of the voxels of each brick a stroke stores, for
  /// take_stored_voxels() (stored_voxels.h): a mesher then need not decode
  /// them again. Off where nothing takes them (a replay).
  bool hand_over_voxels = false;
};

class Sculptor {
 public:
  /// Sculpts `volume`, which must outlive the sculptor.
  explicit Sculptor(Volume& volume, const SculptorOptions& options = {});

  /// Sets the tool (copied; prepared once, its rotation caches reset).
  void set_tool(Tool tool);
  void set_sampling(Sampling sampling);
  void set_mirror(std::optional<MirrorPlane> mirror) { mirror_ = mirror; }

  void begin_stroke() { history_.begin_stroke(); }
  void end_stroke() { history_.end_stroke(); }
  /// Applies one dab (and its mirror image). Asserts a tool is set.
  DabStats dab(const Dab& dab);
  /// An edit of `region` made outside the sculptor (a station brush such as
  /// the hypertexture): `edit` runs as a stroke of its own, so undo and redo
  /// cover it like any other (a stroke in progress is closed first).
  void external_edit(const Box& region, const std::function<void()>& edit);
  bool undo() { return history_.undo(volume_); }
  bool redo() { return history_.redo(volume_); }

  /// Drops the kept decoded bricks. Needed only if the volume object was
  /// replaced wholesale (assigned a new Volume): brick versions restart then,
  /// and could match stale kept voxels. Edits through Volume's members are
  /// always seen.
  void forget_decoded_bricks() { decoded_.clear(); }

  const UndoHistory& history() const { return history_; }
  /// The voxels of the bricks strokes stored since the last call, when
  /// SculptorOptions::hand_over_voxels (else none). Never taken, they are
  /// dropped past kMaxHandedBricks.
  StoredVoxelsByBrick take_stored_voxels() { return std::exchange(stored_voxels_, {}); }
  static constexpr size_t kMaxHandedBricks = 1024;  // 32 MiB of 32^3 bricks
  /// The cache of the tool (mirrored = false) or of its mirror image.
  const RotatedToolCache& cache(bool mirrored = false) const;
  /// The rotation caches' counts over this sculptor's life: every tool's
  /// caches, mirror images included (bytes and entries: those held now).
  RotatedToolCacheStats rotation_cache_stats() const;
  const Volume& volume() const { return volume_; }

 private:
  // Swept strokes (stroke.h) share the tool, its caches, the mirror and the
  // undo history, and store bricks as dabs do.
  friend class SweptStroke;

  DabStats apply(RotatedToolCache& cache, const Dab& dab);
  // Keeps brick b's stored voxels for take_stored_voxels(): `voxels` at
  // `version`, which differ from version `changed_from` only inside `changed`.
  void hand_over(glm::ivec3 b, StoredVoxels voxels);
  void rebuild_caches();
  // The cache of the tool mirrored across `axis`, made on first use.
  RotatedToolCache& mirror_cache(int axis);

  Volume& volume_;
  SculptorOptions options_;
  std::optional<Tool> tool_;
  std::unique_ptr<RotatedToolCache> cache_;
  std::unique_ptr<RotatedToolCache> mirror_caches_[3];
  // The counts of the caches set_tool() and set_sampling() dropped.
  RotatedToolCacheStats retired_cache_stats_;
  std::optional<MirrorPlane> mirror_;
  UndoHistory history_;
  struct DecodedBrick {
    uint64_t version = 0;
    uint64_t last_use = 0;
    // The brick's voxels, then kCombineRowSlack bytes that combine_row()
    // may read and rewrite past a row.
    std::vector<uint8_t> voxels;
    std::span<uint8_t> brick() {
      return std::span<uint8_t>(voxels).first(voxels.size() - kCombineRowSlack);
    }
  };
  // The brick's current voxels, decoded unless still valid from earlier.
  DecodedBrick& decoded_brick(glm::ivec3 b, DabStats& stats);
  std::unordered_map<int64_t, DecodedBrick> decoded_;
  uint64_t use_clock_ = 0;
  StoredVoxelsByBrick stored_voxels_;  // for take_stored_voxels()
};

}  // namespace sculpt::core
