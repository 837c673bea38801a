#include "sculpt/hal/pose/tracker_mapping.h"

#include <cmath>

namespace sculpt::hal {
namespace {

glm::dvec3 position_of(const TrackerPose& p) {
  return {p.position_mm[0], p.position_mm[1], p.position_mm[2]};
}
glm::dquat orientation_of(const TrackerPose& p) {
  return glm::normalize(glm::dquat(p.quat_wxyz[0], p.quat_wxyz[1], p.quat_wxyz[2], p.quat_wxyz[3]));
}

}  // namespace

ToolPose TrackerMapping::map(const TrackerPose& pose, const ToolPose& tool) {
  if (!anchored_) {
    anchored_ = true;
    sensor_ = pose.sensor;
    anchor_mm_ = position_of(pose);
    anchor_q_ = orientation_of(pose);
    anchor_tool_vox_ = glm::dvec3(tool.position);
    anchor_tool_q_ = glm::dquat(tool.orientation);
    return tool;
  }
  if (pose.sensor != sensor_) return tool;
  const glm::dquat& r = calibration_.tracker_to_sculpture;
  // In double: the tracker's millimetres far from its origin and a small
  // scale would lose the motion's last digits in float.
  const glm::dvec3 position_vox =
      anchor_tool_vox_ + calibration_.scale_vox_per_mm * (r * (position_of(pose) - anchor_mm_));
  // The decoders pass any finite number, and 1e300 mm less -1e300 mm is no
  // longer one (rotated, it becomes NaN): such a pose moves nothing.
  const glm::vec3 position_f(position_vox);
  if (!std::isfinite(position_f.x) || !std::isfinite(position_f.y) || !std::isfinite(position_f.z))
    return tool;
  ToolPose out = tool;
  out.position = position_f;
  // The tracker's turn since the anchor, in world axes, expressed in the
  // sculpture's axes and applied to the tool's orientation at the anchor.
  const glm::dquat turn = r * (orientation_of(pose) * glm::inverse(anchor_q_)) * glm::inverse(r);
  out.orientation = glm::quat(glm::normalize(turn * anchor_tool_q_));
  return out;
}

}  // namespace sculpt::hal
