// OpenTrack's "UDP over network" output, checked against its published
// source (github.com/opentrack/opentrack, commit 03d28dde, files
// proto-udp/ftnoir_protocol_ftn.cpp and api/plugin-api.hpp): udp::pose()
// writes the `const double headpose[6]` array as it is in memory,
// sizeof(double[6]) = 48 bytes, and the array is indexed by `enum Axis { TX,
// TY, TZ, Yaw, Pitch, Roll }`. OpenTrack's translation is in cm and its
// rotation in degrees. There is no header, no version and no checksum, so
// the length and finiteness are all a receiver can check.

#include "sculpt/hal/parsers/opentrack_datagram.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace sculpt::hal {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMmPerCm = 10.0;

double read_f64_le(const uint8_t* p) {
  uint64_t u = 0;
  for (int i = 7; i >= 0; --i)
    u = (u << 8) | p[i];
  return std::bit_cast<double>(u);
}

void write_f64_le(uint8_t* p, double v) {
  uint64_t u = std::bit_cast<uint64_t>(v);
  for (int i = 0; i < 8; ++i, u >>= 8)
    p[i] = static_cast<uint8_t>(u & 0xff);
}

}  // namespace

std::string_view describe(OpenTrackDatagramError error) {
  switch (error) {
    case OpenTrackDatagramError::kNone:
      return "ok";
    case OpenTrackDatagramError::kShort:
      return "short datagram (want 48 bytes: six float64)";
    case OpenTrackDatagramError::kLong:
      return "long datagram (want 48 bytes: six float64)";
    case OpenTrackDatagramError::kNotFinite:
      return "NaN or infinity in the datagram";
  }
  return "?";
}

std::array<double, 4> quat_from_yaw_pitch_roll_deg(double yaw_deg, double pitch_deg,
                                                   double roll_deg) {
  const double h = kPi / 360.0;  // degrees to half-angle radians
  const double cy = std::cos(yaw_deg * h), sy = std::sin(yaw_deg * h);
  const double cp = std::cos(pitch_deg * h), sp = std::sin(pitch_deg * h);
  const double cr = std::cos(roll_deg * h), sr = std::sin(roll_deg * h);
  // (cy, 0, sy, 0) * (cp, sp, 0, 0) * (cr, 0, 0, sr), multiplied out.
  return {cy * cp * cr + sy * sp * sr, cy * sp * cr + sy * cp * sr, sy * cp * cr - cy * sp * sr,
          cy * cp * sr - sy * sp * cr};
}

OpenTrackDatagramError decode_opentrack_datagram(std::span<const uint8_t> bytes, TrackerPose& out) {
  if (bytes.size() < kOpenTrackDatagramBytes) return OpenTrackDatagramError::kShort;
  if (bytes.size() > kOpenTrackDatagramBytes) return OpenTrackDatagramError::kLong;
  double v[6];
  for (int i = 0; i < 6; ++i) {
    v[i] = read_f64_le(bytes.data() + 8 * i);
    if (!std::isfinite(v[i])) return OpenTrackDatagramError::kNotFinite;
  }
  const std::array<double, 3> mm = {v[0] * kMmPerCm, v[1] * kMmPerCm, v[2] * kMmPerCm};
  // A finite cm value near the float64 limit overflows in mm.
  for (double c : mm)
    if (!std::isfinite(c)) return OpenTrackDatagramError::kNotFinite;
  out.sensor = 0;
  out.position_mm = mm;
  out.quat_wxyz = quat_from_yaw_pitch_roll_deg(v[3], v[4], v[5]);
  return OpenTrackDatagramError::kNone;
}

std::array<uint8_t, kOpenTrackDatagramBytes> encode_opentrack_datagram(double x_cm, double y_cm,
                                                                       double z_cm, double yaw_deg,
                                                                       double pitch_deg,
                                                                       double roll_deg) {
  std::array<uint8_t, kOpenTrackDatagramBytes> out{};
  const double v[6] = {x_cm, y_cm, z_cm, yaw_deg, pitch_deg, roll_deg};
  for (int i = 0; i < 6; ++i)
    write_f64_le(out.data() + 8 * i, v[i]);
  return out;
}

}  // namespace sculpt::hal
