#include "sculpt/hal/haptics/haptic_loop.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace sculpt::hal {

HapticLoop::HapticLoop(ForceDevice& device, ForceLaw& law, const HapticLoopOptions& options)
    : device_(device),
      law_(law),
      options_(options),
      safety_(device.limits(), options.safety),
      records_(std::max<size_t>(options.record_capacity, 1)) {}

HapticRequest HapticLoop::take_request() {
  const HapticRequest request = request_.exchange(HapticRequest::kNone, std::memory_order_acquire);
  switch (request) {
    case HapticRequest::kEnable:
      safety_.enable();
      if (state() == HapticLoopState::kFaulted) state_.store(HapticLoopState::kRunning);
      break;
    case HapticRequest::kDrop:
      safety_.drop();
      break;
    case HapticRequest::kNone:
      break;
  }
  return request;
}

void HapticLoop::publish() {
  if (!records_.try_push(last_)) live_.records_dropped.fetch_add(1, std::memory_order_relaxed);
}

bool HapticLoop::tick(int64_t t_ns) {
  if (state() == HapticLoopState::kRemoved) return false;
  const HapticRequest request = take_request();
  const uint32_t index = ticks_++;

  if (have_last_tick_) {
    const int64_t period_ns = t_ns - last_tick_ns_;
    const double period_us = static_cast<double>(period_ns) * 1e-3;
    periods_.add(period_us);
    if (period_ns > options_.late_period_ns)
      live_.late_ticks.fetch_add(1, std::memory_order_relaxed);
    if (period_us > live_.worst_period_us.load(std::memory_order_relaxed))
      live_.worst_period_us.store(static_cast<float>(period_us), std::memory_order_relaxed);
  }
  have_last_tick_ = true;
  last_tick_ns_ = t_ns;

  HapticInput input;
  input.t_ns = t_ns;
  const ForceIo read = device_.read(input.device);
  if (read == ForceIo::kRemoved) {
    // Nothing can be written to a device that is gone; zero() is for a
    // transport that still half works (the cable back in before we noticed).
    device_.zero();
    safety_.drop();
    state_.store(HapticLoopState::kRemoved, std::memory_order_release);
    last_ = {.t_ns = t_ns,
             .position_mm = last_.position_mm,
             .index = index,
             .read = read,
             .request = request};
    publish();
    return false;
  }
  if (input.device.buttons & options_.drop_buttons) safety_.drop();

  glm::vec3 wanted(0.0f);
  uint64_t law_inputs = 0;
  if (read == ForceIo::kOk && input.device.homed && state() == HapticLoopState::kRunning) {
    try {
      wanted = law_.force_n(input);
      law_inputs = law_.inputs();
    } catch (...) {
      // A law that throws is a bug; the hand must not feel it. Force stays
      // off until someone enables it again.
      state_.store(HapticLoopState::kFaulted);
      safety_.drop();
      wanted = glm::vec3(0.0f);
    }
  }
  glm::vec3 force = safety_.filter(wanted, t_ns);
  if (read == ForceIo::kFault) {
    live_.device_faults.fetch_add(1, std::memory_order_relaxed);
    safety_.interrupt();
    force = glm::vec3(0.0f);
  }
  if (!input.device.homed) force = glm::vec3(0.0f);
  if (device_.write(force) != ForceIo::kOk) {
    live_.device_faults.fetch_add(1, std::memory_order_relaxed);
    device_.zero();
    safety_.interrupt();
    force = glm::vec3(0.0f);
  }

  last_ = {.t_ns = t_ns,
           .position_mm = input.device.position_mm,
           .buttons = input.device.buttons,
           .force_n = force,
           .index = index,
           .read = read,
           .homed = input.device.homed,
           .request = request,
           .law_inputs = law_inputs};
  publish();
  live_.ticks.fetch_add(1, std::memory_order_relaxed);
  const float magnitude = glm::length(force);
  if (magnitude > live_.max_force_n.load(std::memory_order_relaxed))
    live_.max_force_n.store(magnitude, std::memory_order_relaxed);
  live_.ramp.store(safety_.ramp(), std::memory_order_relaxed);
  return true;
}

}  // namespace sculpt::hal
