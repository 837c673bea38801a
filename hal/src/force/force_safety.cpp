#include "sculpt/hal/force/force_safety.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::hal {

ForceSafety::ForceSafety(const ForceLimits& limits, const ForceSafetyOptions& options)
    : limits_(limits), options_(options) {}

void ForceSafety::enable() {
  if (enabled_) return;
  enabled_ = true;
  ramp_pending_ = true;
}

void ForceSafety::drop() {
  if (enabled_) ++counters_.drops;
  enabled_ = false;
}

glm::vec3 ForceSafety::filter(glm::vec3 wanted_n, int64_t t_ns) {
  const bool late = have_last_ && t_ns - last_t_ns_ > options_.watchdog_ns;
  have_last_ = true;
  last_t_ns_ = t_ns;
  ramp_ = 0.0f;
  if (!enabled_) return glm::vec3(0.0f);
  // An interruption restarts the ramp from zero: whatever the hand did while
  // the loop was away, the force it meets again grows in gently.
  if (ramp_pending_ || late) {
    ramp_pending_ = false;
    ramp_start_ns_ = t_ns;
    if (late) {
      ++counters_.watchdog_trips;
      return glm::vec3(0.0f);
    }
  }
  if (!std::isfinite(wanted_n.x) || !std::isfinite(wanted_n.y) || !std::isfinite(wanted_n.z)) {
    ++counters_.non_finite;
    ramp_start_ns_ = t_ns;
    return glm::vec3(0.0f);
  }
  const float magnitude = glm::length(wanted_n);
  if (magnitude > limits_.max_force_n) {
    ++counters_.clamped;
    wanted_n *= limits_.max_force_n / magnitude;
  }
  const double elapsed_s = static_cast<double>(t_ns - ramp_start_ns_) * 1e-9;
  ramp_ = options_.ramp_s > 0.0
              ? static_cast<float>(std::clamp(elapsed_s / options_.ramp_s, 0.0, 1.0))
              : 1.0f;
  return wanted_n * ramp_;
}

}  // namespace sculpt::hal
