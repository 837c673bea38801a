#pragma once
// The bytes of one OpenTrack "UDP over network" datagram to a TrackerPose.
// Pure: no socket, no state, no allocation, so it can be fuzzed and a
// recorded datagram decodes to the same pose again.
//
// Wire format: exactly 48 bytes, six IEEE-754 float64 in the sender's host
// order (little-endian on every platform OpenTrack ships for; this decoder
// reads little-endian whatever the host): x, y, z in cm, then yaw, pitch,
// roll in degrees.
//
// Orientation convention (ours; OpenTrack's own signs depend on the user's
// mapping settings): frame +X right, +Y up, +Z toward the user (DESIGN.md
// §3); q = Ry(yaw) * Rx(pitch) * Rz(roll), each a right-handed rotation
// about that axis, applied intrinsically yaw first.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "sculpt/hal/types/tracker_pose.h"

namespace sculpt::hal {

inline constexpr size_t kOpenTrackDatagramBytes = 48;

enum class OpenTrackDatagramError : uint8_t {
  kNone,
  kShort,      ///< fewer than 48 bytes
  kLong,       ///< more than 48 bytes (not OpenTrack's format)
  kNotFinite,  ///< a NaN or an infinity among the six numbers
};

/// "short datagram (want 48 bytes)" etc.; "ok" for kNone.
std::string_view describe(OpenTrackDatagramError error);

/// Decodes `bytes` into `out` (sensor 0). On an error `out` is untouched.
OpenTrackDatagramError decode_opentrack_datagram(std::span<const uint8_t> bytes, TrackerPose& out);

/// The datagram OpenTrack would send for these values (tests, benchmarks, seeds).
std::array<uint8_t, kOpenTrackDatagramBytes> encode_opentrack_datagram(double x_cm, double y_cm,
                                                                       double z_cm, double yaw_deg,
                                                                       double pitch_deg,
                                                                       double roll_deg);

/// The quaternion (w, x, y, z) of the convention above.
std::array<double, 4> quat_from_yaw_pitch_roll_deg(double yaw_deg, double pitch_deg,
                                                   double roll_deg);

}  // namespace sculpt::hal
