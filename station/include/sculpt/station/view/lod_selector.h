#pragma once
// Level of detail per brick ("Discrete tools for virtual sculpture" §2.3):
// a brick far from the camera is drawn from a coarser level of the wavelet
// pyramid. The level grows by one each time the distance doubles past
// `full_detail_distance`; a bias, adapted to the measured frame time, trades
// detail for speed when frames run over budget and takes it back when they
// run well under. GL-free, so the policy is tested without a window.

#include <vector>

#include <glm/vec3.hpp>

namespace sculpt::station {

struct LodPolicy {
  /// Bricks nearer than this (voxels, from the eye to the brick's centre)
  /// are drawn at full detail when the bias is 0.
  float full_detail_distance = 400.0f;
  /// Coarsest level drawn (never above the volume's levels).
  int max_level = 2;
  /// Frame-time budget, milliseconds: under 16.7 (60 frames per second) with
  /// room for the frames that run long (a big dab, a re-mesh).
  double frame_budget_ms = 12.0;
  /// A fixed level for every brick instead (-1: automatic).
  int fixed_level = -1;
};

class LodSelector {
 public:
  explicit LodSelector(LodPolicy policy = {}) : policy_(policy) {}
  const LodPolicy& policy() const { return policy_; }
  void set_policy(const LodPolicy& policy);

  /// Levels for a grid of bricks of `brick_edge` voxels, brick index
  /// (b.z * grid.y + b.y) * grid.x + b.x, seen from `eye`.
  std::vector<int> select(glm::ivec3 brick_grid, int brick_edge, glm::vec3 eye) const;

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
