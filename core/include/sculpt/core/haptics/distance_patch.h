#pragma once
// The sculpting side's half of the haptic contact (DESIGN.md §5a): a dense
// local signed-distance patch around the tool, built from the material near
// it, refreshed after each dab over the changed region only, and moved with
// the tool by computing only the part that is new.
//
// The distance is measured to the 127.5 iso-surface of the trilinear density.
// Along a grid edge the trilinear density is linear, so every edge whose ends
// lie on both sides of 127.5 gives an exact surface point (a seed), with the
// surface normal there from the density gradient. Each voxel takes the nearest
// seed within reach = ceil(band + 0.87) voxels (0.87: how far a smooth
// surface's point lies at most from a crossing on its cell's edges), and its
// value is the distance to that seed's tangent plane (exact for planes; about
// e^2 / 2R off on a surface of radius R when the seed is e voxels beside the
// true foot point). Seeds come from the edges along the axis nearest the
// normal, one per column of the surface. A voxel with no seed in reach is at
// least reach - sqrt(3) - 1 from the surface and stores that bound,
// clamp_vox. See distance_patch.cpp.
//
// Every value depends only on the material within reach + 2 voxels of it,
// and ties between seeds break the same way whatever region is computed, so
// a refreshed or moved patch holds exactly the values a patch built from
// scratch would.
//
// Thread safety: one owner (the sculpting thread); the tick reads a copy
// through PatchExchange.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/cell_marks.h"
#include "sculpt/core/haptics/patch_snapshot.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct DistancePatchOptions {
  /// Values per axis (a cube of edge^3 voxels); at least 8.
  int edge = 48;
  /// Half width in voxels of the band where values are accurate to 0.1 voxel.
  float band_vox = 4.0f;
  /// Threads computing the values (split in z); the values never depend on
  /// it. 1 keeps the work on the sculpting thread alone.
  int threads = 1;
};

/// The patch edge that covers a tool reaching `reach_vox` from its pivot with
/// room to move before a re-centre: at least 48, a multiple of 8.
int patch_edge_for_reach(float reach_vox, float band_vox = 4.0f);

/// The band a sphere proxy of `radius_vox` needs: the constraint phi = r
/// inside it, and the bound stored far from the material (clamp_vox) above r,
/// so a free proxy moves in long steps: max(4, ceil(r) + 3).
float band_for_sphere(float radius_vox);

class DistancePatch {
 public:
  explicit DistancePatch(const DistancePatchOptions& options = {});

  /// Builds the patch centred on `centre_vox` from scratch.
  void build(const Volume& volume, glm::vec3 centre_vox);
  /// Re-reads the material inside `changed` (material voxels, e.g. a dab's
  /// box) and recomputes the values it can affect: those a changed seed
  /// reaches and those that changed side. Does nothing before build().
  void refresh(const Volume& volume, const Box& changed);
  /// refresh() over the bricks a dab stored (Volume::take_dirty_bricks), in
  /// one pass.
  void refresh_bricks(const Volume& volume, std::span<const glm::ivec3> bricks);
  /// Centres the patch on `centre_vox`, keeping the values that stay inside
  /// and computing the rest. Builds when the move is larger than the patch.
  void recentre(const Volume& volume, glm::vec3 centre_vox);
  /// Whether `p` (material voxels) is more than edge / 8 off the centre.
  bool off_centre(glm::vec3 p) const;

  const PatchSnapshot& snapshot() const { return snapshot_; }
  /// The material voxels the values cover.
  Box box() const;
  glm::vec3 centre() const;
  const DistancePatchOptions& options() const { return options_; }
  /// Voxels whose value the last build, refresh or re-centre computed.
  int64_t last_computed_voxels() const { return last_computed_; }

 private:
  struct Seed {
    glm::vec3 point;   // on the iso-surface, material voxels
    glm::vec3 normal;  // outward unit normal
    glm::ivec3 edge;   // the edge's lower end
    int axis;          // and its direction
  };
  // refresh() over several boxes of material at once.
  void refresh_boxes(const Volume& volume, std::span<const Box> changed);
  // The edges looked at: every edge whose seed can reach a value.
  Box seed_box() const;
  // Copies the material's density over `region` in; returns the bounding box
  // of the voxels that differ from what was held (empty: none). Runs of
  // voxels that changed side go to `flipped` when given.
  Box read_density(const Volume& volume, const Box& region, std::vector<Box>* flipped = nullptr);
  // Recomputes the values of `region` from the seeds held; with `stale`,
  // only those of its marked cells, from the seeds that reach one.
  void compute(const Box& region, const CellMarks* stale = nullptr);
  // Appends the seeds on the edges with both ends in `scan`, in order.
  void find_seeds(const Box& scan, std::vector<Seed>& out);
  // Writes the values of `clip` (a z slab of `region`; with `stale`, only
  // its marked cells) from the nearest seeds offered; returns how many.
  int64_t write_values(const Box& region, const Box& clip, size_t stride, const CellMarks* stale);

  DistancePatchOptions options_;
  int reach_;   // how far a seed is offered: ceil(band + sqrt(3)) voxels
  int margin_;  // density kept beyond the values on each side: reach_ + 2
  PatchSnapshot snapshot_;
  // The material's density over box() grown by margin_ on each side.
  Box density_box_;
  std::vector<uint8_t> density_;
  // Every seed of seed_box(), in order (z, y, axis, x of the edge).
  std::vector<Seed> seeds_;
  int64_t last_computed_ = 0;
  // Scratch reused between computations (grown, never shrunk).
  std::vector<Seed> found_, merged_, offered_;
  std::vector<Box> flipped_, brick_boxes_;
  CellMarks stale_;
  std::vector<glm::vec3> seed_points_;
  std::vector<uint32_t> best_key_;  // nearest_seed.h
  std::vector<uint8_t> row_sides_;
};

}  // namespace sculpt::core
