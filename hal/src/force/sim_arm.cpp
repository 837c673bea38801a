#include "sculpt/hal/force/sim_arm.h"

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace sculpt::hal {

SimArm::SimArm(HandScript hand, const SimArmOptions& options)
    : hand_(std::move(hand)), options_(options), position_mm_(options.start_mm) {
  const ForceLimits& l = sim_arm_limits();
  info_.backend = "sim";
  info_.path = "arm";
  info_.name = std::string(l.name);
  info_.manufacturer = "sculpt";
  info_.vendor_id = l.vendor_id;
  info_.product_id = l.product_id;
}

const ForceLimits& SimArm::limits() const {
  return sim_arm_limits();
}

ForceIo SimArm::read(ForceDeviceState& out) {
  if (removed_) return ForceIo::kRemoved;
  const double tick_s = static_cast<double>(options_.tick_ns) * 1e-9;
  const double t0_s = t_s();
  // In whole nanoseconds, so an unplug on a tick boundary is exact.
  const auto unplug_ns = static_cast<int64_t>(std::llround(hand_.unplug_s * 1e9));
  if (hand_.unplug_s >= 0.0 && (ticks_ + 1) * options_.tick_ns > unplug_ns) {
    removed_ = true;
    motor_force_n_ = glm::vec3(0.0f);
    return ForceIo::kRemoved;
  }
  // Metres inside the integration keep the units of N·s/m and kg honest;
  // the hand's spring is N/mm, i.e. 1000 N/m.
  const int n = options_.substeps > 0 ? options_.substeps : 1;
  const float h = static_cast<float>(tick_s / n);
  const float hand_k = hand_.stiffness_n_per_mm * 1000.0f;
  for (int i = 0; i < n; ++i) {
    const double t = t0_s + tick_s * (i + 1) / n;
    const glm::vec3 x_m = position_mm_ * 1e-3f;
    const glm::vec3 v_m = velocity_mm_per_s_ * 1e-3f;
    const glm::vec3 target_m = hand_.target_at(t) * 1e-3f;
    const glm::vec3 hand_n = hand_k * (target_m - x_m) - hand_.damping_ns_per_m * v_m;
    const glm::vec3 total_n = motor_force_n_ + hand_n - options_.damping_ns_per_m * v_m;
    const glm::vec3 v_next_m = v_m + total_n * (h / options_.mass_kg);
    velocity_mm_per_s_ = v_next_m * 1000.0f;
    position_mm_ += velocity_mm_per_s_ * h;
  }
  ++ticks_;
  // The force written during this tick reaches the motors for the next one.
  motor_force_n_ = written_n_;

  const float step = options_.encoder_step_mm;
  out.position_mm = step > 0.0f ? glm::round(position_mm_ / step) * step : position_mm_;
  out.buttons = hand_.buttons_at(t_s());
  out.homed = true;
  return ForceIo::kOk;
}

ForceIo SimArm::write(glm::vec3 force_n) {
  if (removed_) return ForceIo::kRemoved;
  const float limit = limits().max_force_n;
  const float magnitude = glm::length(force_n);
  if (!std::isfinite(magnitude)) {
    written_n_ = glm::vec3(0.0f);
    return ForceIo::kFault;
  }
  written_n_ = magnitude > limit ? force_n * (limit / magnitude) : force_n;
  return ForceIo::kOk;
}

void SimArm::zero() noexcept {
  written_n_ = glm::vec3(0.0f);
  motor_force_n_ = glm::vec3(0.0f);
}

}  // namespace sculpt::hal
