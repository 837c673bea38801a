#pragma once
// One absolute pose from a tracker (OpenTrack, VRPN), decoded from the bytes
// a session records, so a replay decodes the same pose again.
//
// Frame: the tracker's own, unscaled; calibration into the sculpture happens
// after the parser. Position in millimetres, orientation a unit quaternion.

#include <array>
#include <cmath>
#include <cstdint>

namespace sculpt::hal {

struct TrackerPose {
  int32_t sensor = 0;                   ///< which sensor of the tracker (OpenTrack: always 0)
  std::array<double, 3> position_mm{};  ///< x, y, z in mm
  std::array<double, 4> quat_wxyz{1, 0, 0, 0};  ///< unit quaternion w, x, y, z
};

/// What every decoder promises of a pose it accepts: all numbers finite and
/// the quaternion of unit length (its squared norm within `tolerance` of 1).
inline bool is_finite_unit_pose(const TrackerPose& pose, double tolerance = 1e-9) {
  for (double c : pose.position_mm)
    if (!std::isfinite(c)) return false;
  double norm2 = 0;
  for (double c : pose.quat_wxyz) {
    if (!std::isfinite(c)) return false;
    norm2 += c * c;
  }
  return std::fabs(norm2 - 1.0) <= tolerance;
}

}  // namespace sculpt::hal
