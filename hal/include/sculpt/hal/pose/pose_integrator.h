#pragma once
// Turns normalised motion into a tool pose (DESIGN.md §5).
// Rate control (3D mice): deflection is velocity. Each sample's deflection is
// held from the previous sample's time to its own and integrated, so the pose
// depends on the sample times, not on how often the main loop looks.
// Position control (trackers, absolute axes): the sample is the pose, mapped
// into a workspace box and an angle range.

#include <cstdint>

#include "sculpt/hal/input/input_event.h"
#include "sculpt/hal/pose/tool_pose.h"

namespace sculpt::hal {

enum class ControlMode : uint8_t {
  kAuto,  ///< rate for relative samples, position for absolute ones
  kRate,
  kPosition,
};

struct PoseIntegratorConfig {
  ControlMode mode = ControlMode::kAuto;
  float max_speed = 200.0f;  ///< rate control: world units per second at full deflection
  float max_angular_speed = 3.14159265f;  ///< rate control: rad/s at full twist
  /// Rate control: the longest interval integrated, ns. A gap longer than
  /// this (a stalled device, a reconnect) moves the tool by this much at most.
  int64_t max_step_ns = 50'000'000;
  glm::vec3 workspace_center{0.0f};      ///< position control: pose at axes = 0
  float workspace_half_extent = 100.0f;  ///< position control: world units at axis = ±1
  float max_angle = 3.14159265f;         ///< position control: rad at rotation axis = ±1
};

class PoseIntegrator {
 public:
  explicit PoseIntegrator(PoseIntegratorConfig config = {}, ToolPose start = {});
  /// Advances to a kMotion sample and returns the new pose. Samples not later
  /// than the last one change nothing.
  const ToolPose& update(const InputEvent& motion);
  const ToolPose& pose() const { return pose_; }
  /// Restarts from `start`; the next sample only sets the time.
  void reset(ToolPose start);

 private:
  PoseIntegratorConfig config_;
  ToolPose pose_;
  bool have_time_ = false;
};

}  // namespace sculpt::hal
