#include "sculpt/hal/pose/pose_integrator.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace sculpt::hal {

PoseIntegrator::PoseIntegrator(PoseIntegratorConfig config, ToolPose start)
    : config_(config), pose_(start) {}

void PoseIntegrator::reset(ToolPose start) {
  pose_ = start;
  have_time_ = false;
}

const ToolPose& PoseIntegrator::update(const InputEvent& m) {
  if (m.kind != InputKind::kMotion) return pose_;
  const bool position =
      config_.mode == ControlMode::kPosition || (config_.mode == ControlMode::kAuto && m.absolute);
  if (have_time_ && m.t_ns <= pose_.t_ns) return pose_;
  if (position) {
    pose_.position = config_.workspace_center + glm::vec3(m.axes[kTx], m.axes[kTy], m.axes[kTz]) *
                                                    config_.workspace_half_extent;
    const glm::vec3 euler = glm::vec3(m.axes[kRx], m.axes[kRy], m.axes[kRz]) * config_.max_angle;
    pose_.orientation = glm::normalize(glm::quat(euler));
    pose_.t_ns = m.t_ns;
    have_time_ = true;
    return pose_;
  }
  if (!have_time_) {
    // The first sample has no interval to integrate over.
    pose_.t_ns = m.t_ns;
    have_time_ = true;
    return pose_;
  }
  const int64_t step_ns = std::min(m.t_ns - pose_.t_ns, config_.max_step_ns);
  const float dt = static_cast<float>(step_ns) * 1e-9f;
  pose_.position += glm::vec3(m.axes[kTx], m.axes[kTy], m.axes[kTz]) * (config_.max_speed * dt);
  // Angular velocity in world axes: twisting the cap about +Y turns the tool
  // about world +Y whatever the tool's current orientation, as users expect of
  // a 3D mouse.
  const glm::vec3 omega =
      glm::vec3(m.axes[kRx], m.axes[kRy], m.axes[kRz]) * config_.max_angular_speed;
  const float angle = glm::length(omega) * dt;
  if (angle > 0.0f) {
    pose_.orientation =
        glm::normalize(glm::angleAxis(angle, glm::normalize(omega)) * pose_.orientation);
  }
  pose_.t_ns = m.t_ns;
  return pose_;
}

}  // namespace sculpt::hal
