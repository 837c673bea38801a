#pragma once
// Turns normalised motion into a tool pose (DESIGN.md §5).
// Rate control (3D mice): deflection is velocity. The motion moves the tool
// by the difference of InputEvent::integral (deflection integrated over the
// sample times by DeflectionIntegral, which MotionPipeline runs), so the pose
// depends on the sample times, not on how often the main loop looks or how
// many samples it skipped. Each device's pipeline integrates its own
// deflection, so the differences, and the order of sample times, are kept
// per device: two 3D mice at once each move the tool by their own motion.
// Position control (trackers, absolute axes): the sample is the pose, mapped
// into a workspace box and an angle range; a tracker's pose (has_pose) is
// mapped by TrackerMapping, anchored where the tool is so nothing jumps.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/hal/pose/tool_pose.h"
#include "sculpt/hal/pose/tracker_mapping.h"
#include "sculpt/hal/pose/tracker_pose_filter.h"
#include "sculpt/hal/types/input_event.h"

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
  glm::vec3 workspace_center{0.0f};       ///< position control: pose at axes = 0
  float workspace_half_extent = 100.0f;   ///< position control: world units at axis = ±1
  float max_angle = 3.14159265f;          ///< position control: rad at rotation axis = ±1
  TrackerCalibration tracker{};           ///< trackers' poses (InputEvent::has_pose)
  /// Smooths trackers' poses before the calibration (restarts on each anchor).
  TrackerFilterParams tracker_filter{};
};

class PoseIntegrator {
 public:
  explicit PoseIntegrator(PoseIntegratorConfig config = {}, ToolPose start = {});
  /// Advances to a kMotion sample and returns the new pose. A device's
  /// samples not later than its last one change nothing; a rate-controlled
  /// device's first one (since its stream started) only sets its time.
  const ToolPose& update(const InputEvent& motion);
  const ToolPose& pose() const { return pose_; }
  /// Restarts from `start`; every device's next sample only sets its time.
  /// Keeps the position inside [lo, hi] (world units) without forgetting
  /// the time of the last sample: the station bounds the tool to a margin
  /// around the volume, so a device held at full deflection cannot drive it
  /// (and the stroke behind it) out to infinity.
  void clamp_position(glm::vec3 lo, glm::vec3 hi);
  /// Puts the tool at `position` without forgetting the time of the last
  /// sample (the station's touch mode holds it on the material); the next
  /// rate-control sample moves it on from there.
  void place(glm::vec3 position);
  /// Also re-anchors a tracker: its next pose maps to `start`.
  void reset(ToolPose start);
  /// A tracker lost its target: its next pose anchors where the tool is.
  void lose_tracking();
  /// Device `device_id`'s stream starts (plugged in, or back after an
  /// unplug): its deflection integral starts again from zero, so its first
  /// sample only sets the time (the difference from the last stream's
  /// integral would throw the tool), and a tracker anchors where the tool is.
  void start_stream(uint32_t device_id);
  /// Device `device_id` is gone: its stream is forgotten (a device plugged
  /// in again gets a new id, so streams would pile up).
  void end_stream(uint32_t device_id);
  /// Devices with a stream under way.
  size_t stream_count() const { return streams_.size(); }
  /// The clutch (the station's key or a device button): while held, motion
  /// samples keep their time but move nothing, so the hand can move back
  /// without the tool; when let go a tracker anchors again where the tool
  /// is, and a 3D mouse goes on from there. Absolute axes (a position-
  /// controlled joystick) have no anchor: they move the tool again at once.
  void set_clutch(bool held);
  bool clutched() const { return clutched_; }
  /// A new tracker calibration; the next pose anchors where the tool is.
  void calibrate_tracker(const TrackerCalibration& calibration);
  const TrackerCalibration& tracker_calibration() const { return tracker_.calibration(); }

 private:
  PoseIntegratorConfig config_;
  ToolPose pose_;
  glm::dvec3 position_{0.0};  // accumulated in double: a long session must not drift
  // Where each device that sent a sample since its stream started is: its
  // last sample's time and deflection integral. A handful of devices at most.
  struct Stream {
    uint32_t device_id = 0;
    int64_t last_t_ns = 0;
    std::array<double, kAxisCount> last_integral{};
  };
  std::vector<Stream> streams_;
  Stream* stream(uint32_t device_id);
  bool clutched_ = false;
  TrackerMapping tracker_;
  TrackerPoseFilter tracker_filter_;
};

}  // namespace sculpt::hal
