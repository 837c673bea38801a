#include "sculpt/hal/pose/pose_integrator.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace sculpt::hal {

PoseIntegrator::PoseIntegrator(PoseIntegratorConfig config, ToolPose start)
    : config_(config),
      pose_(start),
      position_(start.position),
      tracker_(config.tracker),
      tracker_filter_(config.tracker_filter) {}

void PoseIntegrator::reset(ToolPose start) {
  pose_ = start;
  position_ = glm::dvec3(start.position);
  streams_.clear();
  lose_tracking();
}

void PoseIntegrator::lose_tracking() {
  // The filter starts again too: smoothing from the pose before the loss
  // would drag the tool from there, the jump re-anchoring avoids.
  tracker_.unanchor();
  tracker_filter_.reset();
}

void PoseIntegrator::start_stream(uint32_t device_id) {
  end_stream(device_id);
  lose_tracking();
}

void PoseIntegrator::end_stream(uint32_t device_id) {
  std::erase_if(streams_, [&](const Stream& s) { return s.device_id == device_id; });
}

PoseIntegrator::Stream* PoseIntegrator::stream(uint32_t device_id) {
  for (Stream& s : streams_)
    if (s.device_id == device_id) return &s;
  return nullptr;
}

void PoseIntegrator::set_clutch(bool held) {
  if (held == clutched_) return;
  clutched_ = held;
  if (!held) lose_tracking();
}

void PoseIntegrator::calibrate_tracker(const TrackerCalibration& calibration) {
  tracker_.calibrate(calibration);
  tracker_filter_.reset();
}

void PoseIntegrator::clamp_position(glm::vec3 lo, glm::vec3 hi) {
  const glm::dvec3 clamped = glm::clamp(position_, glm::dvec3(lo), glm::dvec3(hi));
  if (clamped == position_) return;
  position_ = clamped;
  pose_.position = glm::vec3(clamped);
}

void PoseIntegrator::place(glm::vec3 position) {
  position_ = glm::dvec3(position);
  pose_.position = position;
}

const ToolPose& PoseIntegrator::update(const InputEvent& m) {
  if (m.kind != InputKind::kMotion) return pose_;
  const bool position =
      config_.mode == ControlMode::kPosition || (config_.mode == ControlMode::kAuto && m.absolute);
  Stream* known = stream(m.device_id);
  if (known != nullptr && m.t_ns <= known->last_t_ns) return pose_;
  // The device's first sample since its stream started: a rate-controlled
  // one only sets its time and integral (below); a pose is a pose.
  const bool first = known == nullptr;
  Stream& s = first ? streams_.emplace_back(Stream{m.device_id}) : *known;
  s.last_t_ns = m.t_ns;
  pose_.t_ns = std::max(pose_.t_ns, m.t_ns);
  const std::array<double, kAxisCount> last_integral = s.last_integral;
  s.last_integral = m.integral;
  // Clutched, the time moves on and a 3D mouse's integral is taken up, so
  // letting go moves the tool by nothing the hand did while holding.
  if (clutched_) return pose_;
  if (m.has_pose) {
    // Another sensor's poses must not enter the driving sensor's filter.
    if (tracker_.anchored() && m.pose.sensor != tracker_.sensor()) return pose_;
    const int64_t t_ns = pose_.t_ns;
    pose_ = tracker_.map(tracker_filter_.filter(m.pose, m.t_ns), pose_);
    position_ = glm::dvec3(pose_.position);
    pose_.t_ns = t_ns;
    return pose_;
  }
  if (position) {
    pose_.position = config_.workspace_center + glm::vec3(m.axes[kTx], m.axes[kTy], m.axes[kTz]) *
                                                    config_.workspace_half_extent;
    position_ = glm::dvec3(pose_.position);
    const glm::vec3 euler = glm::vec3(m.axes[kRx], m.axes[kRy], m.axes[kRz]) * config_.max_angle;
    pose_.orientation = glm::normalize(glm::quat(euler));
    return pose_;
  }
  if (first) return pose_;
  std::array<double, kAxisCount> d{};
  for (int i = 0; i < kAxisCount; ++i)
    d[i] = m.integral[i] - last_integral[i];
  position_ += glm::dvec3(d[kTx], d[kTy], d[kTz]) * double{config_.max_speed};
  pose_.position = glm::vec3(position_);
  // Angular velocity in world axes: twisting the cap about +Y turns the tool
  // about world +Y whatever the tool's current orientation, as users expect of
  // a 3D mouse. Over one step the rotation vector is the integrated twist.
  const glm::vec3 turn =
      glm::vec3(glm::dvec3(d[kRx], d[kRy], d[kRz]) * double{config_.max_angular_speed});
  const float angle = glm::length(turn);
  if (angle > 0.0f) {
    pose_.orientation = glm::normalize(glm::angleAxis(angle, turn / angle) * pose_.orientation);
  }
  return pose_;
}

}  // namespace sculpt::hal
