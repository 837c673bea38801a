#pragma once
// Level of detail per brick ("Discrete tools for virtual sculpture" §2.3):
// a brick far from the camera is drawn from a coarser level of the wavelet
// pyramid, the coarsest whose voxels still span at most `max_pixel_error`
// pixels on screen, so the picture at automatic level is the full-detail
// picture to within a pixel (a level chosen by distance alone showed facets
// and blobby eyes on a head that filled a third of the window). Optionally
// (a frame budget above 0) a bias adapted to the measured frame time trades
// detail for speed when frames run over budget and takes it back when they
// run well under. GL-free, so the policy is tested without a window.

#include <vector>

#include <glm/vec3.hpp>

namespace sculpt::station {

struct LodPolicy {
  /// The most pixels one voxel of a brick's level may span on screen (at
  /// the brick's nearest point; with no bias).
  float max_pixel_error = 1.0f;
  /// Coarsest level drawn (never above the volume's levels).
  int max_level = 2;
  /// Frame-time budget, milliseconds, for the adaptive bias; 0: no bias
  /// (the default: on a software renderer frames run long whatever the
  /// level, and the bias only coarsened the picture).
  double frame_budget_ms = 0.0;
  /// A fixed level for every brick instead (-1: automatic).
  int fixed_level = -1;
};

class LodSelector {
 public:
  explicit LodSelector(LodPolicy policy = {}) : policy_(policy) {}
  const LodPolicy& policy() const { return policy_; }
  void set_policy(const LodPolicy& policy);

  /// Levels for a grid of bricks of `brick_edge` voxels, brick index
  /// (b.z * grid.y + b.y) * grid.x + b.x, seen from `eye` by a camera of
  /// `focal_px` (pixels a voxel spans at a distance of one voxel:
  /// OrbitCamera::focal_length_px).
  std::vector<int> select(glm::ivec3 brick_grid, int brick_edge, glm::vec3 eye,
                          float focal_px) const;

  /// Feeds the time the last frame took; returns whether the bias changed.
  bool frame_done(double frame_ms);
  /// Added to every brick's level, in [0, max_level] (0 when fixed).
  float bias() const { return bias_; }

 private:
  LodPolicy policy_;
  float bias_ = 0.0f;
  int slow_frames_ = 0;
  int fast_frames_ = 0;
};

}  // namespace sculpt::station
