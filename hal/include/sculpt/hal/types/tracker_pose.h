#pragma once
// One absolute pose from a tracker (OpenTrack, VRPN), decoded from the bytes
// a session records, so a replay decodes the same pose again.
//
// Frame: the tracker's own, unscaled; calibration into the sculpture happens
// after the parser. Position in millimetres, orientation a unit quaternion.

#include <array>
#include <cstdint>

namespace sculpt::hal {

struct TrackerPose {
  int32_t sensor = 0;                   ///< which sensor of the tracker (OpenTrack: always 0)
  std::array<double, 3> position_mm{};  ///< x, y, z in mm
  std::array<double, 4> quat_wxyz{1, 0, 0, 0};  ///< unit quaternion w, x, y, z
};

}  // namespace sculpt::hal
