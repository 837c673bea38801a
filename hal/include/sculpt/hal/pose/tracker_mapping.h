#pragma once
// Tracker space to the sculpture, relative to an anchor: the first pose
// (and the first after tracking was lost, or after the tool was put
// elsewhere) maps to where the tool is, so the tool never jumps; later poses
// move it by the tracker's motion since then.
//
//   position_vox = anchor_tool + scale_vox_per_mm * R * (p_mm - anchor_p_mm)
//   orientation  = (R * q * anchor_q^-1 * R^-1) * anchor_tool_orientation
//
// R (`tracker_to_sculpture`) turns the tracker's axes into the sculpture's
// (DESIGN.md §3 frame); the identity when the tracker already uses it.

#include <cstdint>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/hal/pose/tool_pose.h"
#include "sculpt/hal/types/tracker_pose.h"

namespace sculpt::hal {

struct TrackerCalibration {
  /// Sculpture units (voxels) per millimetre of tracker motion: at 1, a
  /// 256-voxel block spans 25.6 cm of hand travel.
  double scale_vox_per_mm = 1.0;
  glm::dquat tracker_to_sculpture{1.0, 0.0, 0.0, 0.0};  ///< unit quaternion
};

class TrackerMapping {
 public:
  explicit TrackerMapping(TrackerCalibration calibration = {}) : calibration_(calibration) {}
  /// The tool pose for `pose`; anchors on it first when not anchored (then
  /// the result is `tool`, unchanged). Poses of another sensor than the
  /// anchored one return `tool` unchanged: one sensor drives the tool.
  ToolPose map(const TrackerPose& pose, const ToolPose& tool);
  /// The next pose anchors again (tracking lost, tool placed, clutch).
  void unanchor() { anchored_ = false; }
  /// A new calibration; the next pose anchors again under it.
  void calibrate(const TrackerCalibration& calibration) {
    calibration_ = calibration;
    anchored_ = false;
  }
  const TrackerCalibration& calibration() const { return calibration_; }
  bool anchored() const { return anchored_; }
  /// The sensor that drives the tool (meaningful when anchored).
  int32_t sensor() const { return sensor_; }

 private:
  TrackerCalibration calibration_;
  bool anchored_ = false;
  int32_t sensor_ = 0;
  glm::dvec3 anchor_mm_{0.0};
  glm::dquat anchor_q_{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 anchor_tool_vox_{0.0};
  glm::dquat anchor_tool_q_{1.0, 0.0, 0.0, 0.0};
};

}  // namespace sculpt::hal
