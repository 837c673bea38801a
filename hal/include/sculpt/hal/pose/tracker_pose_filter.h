#pragma once
// The one-euro filter (one_euro_filter.h) on a tracker's pose: position per
// axis in mm, orientation as a quaternion (slerp toward each new sample by
// the filter's factor, speed the angle turned per second), never on Euler
// angles, which jump at their wrap-around and lock at gimbal poles.

#include <cstdint>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/hal/types/tracker_pose.h"

namespace sculpt::hal {

struct TrackerFilterParams {
  bool enabled = true;
  double min_cutoff_hz = 1.0;    ///< cutoff at rest, Hz: lower = steadier
  double beta_per_mm_s = 0.007;  ///< position: cutoff increase per mm/s of speed
  double beta_per_rad_s = 0.3;   ///< orientation: cutoff increase per rad/s of turn
  double d_cutoff_hz = 1.0;      ///< cutoff of the speed estimates, Hz
};

class TrackerPoseFilter {
 public:
  explicit TrackerPoseFilter(TrackerFilterParams params = {}) : params_(params) {}
  /// Filters `pose` observed at t_ns. The first sample (and the first after
  /// reset()) passes unchanged; a sample not later than the previous one
  /// returns the previous output.
  TrackerPose filter(const TrackerPose& pose, int64_t t_ns);
  void reset() { initialised_ = false; }

 private:
  TrackerPose restart(const TrackerPose& pose, int64_t t_ns);  // passes `pose` unchanged

  TrackerFilterParams params_;
  bool initialised_ = false;
  int64_t t_prev_ns_ = 0;
  TrackerPose prev_;
  glm::dvec3 position_mm_{0.0};
  glm::dquat orientation_{1.0, 0.0, 0.0, 0.0};
  double speed_mm_s_ = 0.0;
  double turn_rad_s_ = 0.0;
};

}  // namespace sculpt::hal
