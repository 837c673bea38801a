#include "sculpt/station/view/lod_selector.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::station {
namespace {

// Hysteresis: a few frames in a row must agree before the bias moves, so one
// slow frame (a large dab's re-mesh) does not make the picture pop.
constexpr int kFramesToAct = 8;
constexpr float kBiasStep = 0.25f;

}  // namespace

void LodSelector::set_policy(const LodPolicy& policy) {
  policy_ = policy;
  bias_ = std::clamp(bias_, 0.0f, static_cast<float>(std::max(policy_.max_level, 0)));
}

std::vector<int> LodSelector::select(glm::ivec3 grid, int edge, glm::vec3 eye,
                                     float focal_px) const {
  const bool budgeted = policy_.frame_budget_ms > 0;
  std::vector<int> levels(static_cast<size_t>(grid.x) * grid.y * grid.z, 0);
  const int max_level = std::max(policy_.max_level, 0);
  if (policy_.fixed_level >= 0) {
    std::fill(levels.begin(), levels.end(), std::min(policy_.fixed_level, max_level));
    return levels;
  }
  // Level k's voxels span 2^k focal / d pixels at distance d: the coarsest
  // level within the error is floor(log2(error d / focal)).
  const float per_voxel = std::max(policy_.max_pixel_error, 1e-3f) / std::max(focal_px, 1e-3f);
  const glm::vec3 e(static_cast<float>(edge));
  size_t i = 0;
  for (int z = 0; z < grid.z; ++z) {
    for (int y = 0; y < grid.y; ++y) {
      for (int x = 0; x < grid.x; ++x, ++i) {
        // The brick's nearest point: its finest detail on screen.
        const glm::vec3 lo = glm::vec3(x, y, z) * e;
        const float d = glm::length(glm::clamp(eye, lo, lo + e) - eye);
        const float level = std::log2(std::max(d * per_voxel, 1.0f)) + (budgeted ? bias_ : 0.0f);
        levels[i] = std::clamp(static_cast<int>(std::floor(level)), 0, max_level);
      }
    }
  }
  return levels;
}

bool LodSelector::frame_done(double frame_ms) {
  if (policy_.fixed_level >= 0 || policy_.frame_budget_ms <= 0) return false;
  const float old = bias_;
  if (frame_ms > policy_.frame_budget_ms) {
    fast_frames_ = 0;
    if (++slow_frames_ >= kFramesToAct) {
      bias_ = std::min(bias_ + kBiasStep, static_cast<float>(std::max(policy_.max_level, 0)));
      slow_frames_ = 0;
    }
  } else if (frame_ms < 0.6 * policy_.frame_budget_ms) {
    slow_frames_ = 0;
    if (++fast_frames_ >= kFramesToAct) {
      bias_ = std::max(bias_ - kBiasStep, 0.0f);
      fast_frames_ = 0;
    }
  } else {
    slow_frames_ = fast_frames_ = 0;
  }
  return bias_ != old;
}

}  // namespace sculpt::station
