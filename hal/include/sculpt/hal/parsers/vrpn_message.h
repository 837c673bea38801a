#pragma once
// The VRPN wire protocol as far as a tracker client needs it, as pure
// functions on bytes (no socket, no state), so each can be fuzzed and a
// recorded Pos_Quat payload decodes to the same pose again.
//
// Stream: a 24-byte cookie each way, then messages. A message is a header of
// five big-endian int32 (total length, time sec, time usec, sender, type),
// padded to 24 bytes, then the payload padded to a multiple of 8 bytes; the
// length counts the 24 header bytes and the unpadded payload.
// System messages have negative types: -1 describes a sender, -2 a type
// (the message's sender field is the id being described; the payload is a
// big-endian int32 name length counting the NUL, then the name and its NUL).
// "vrpn_Tracker Pos_Quat": int32 sensor, 4 bytes of padding, position x, y,
// z (float64, metres), quaternion x, y, z, w (float64): 64 bytes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "sculpt/hal/types/tracker_pose.h"

namespace sculpt::hal {

inline constexpr size_t kVrpnCookieBytes = 24;
inline constexpr size_t kVrpnHeaderBytes = 24;
inline constexpr size_t kVrpnPosQuatBytes = 64;
/// VRPN's own TCP buffer (vrpn_CONNECTION_TCP_BUFLEN): no real message is longer.
inline constexpr uint32_t kVrpnMaxMessageBytes = 64000;
/// VRPN's name buffers (vrpn_CNAME) hold 100 bytes with the NUL.
inline constexpr size_t kVrpnMaxNameBytes = 100;
inline constexpr int32_t kVrpnSenderDescription = -1;
inline constexpr int32_t kVrpnTypeDescription = -2;
inline constexpr std::string_view kVrpnPosQuatType = "vrpn_Tracker Pos_Quat";

/// The cookie this client sends: "vrpn: ver. 07.38", two spaces, log mode
/// '0' (no remote logging), NUL padding to 24 bytes.
std::array<uint8_t, kVrpnCookieBytes> make_vrpn_cookie();

enum class VrpnCookieError : uint8_t {
  kNone,
  kShort,         ///< fewer than 24 bytes
  kNotVrpn,       ///< does not start "vrpn: ver. "
  kMajorVersion,  ///< another major version than 07 (VRPN itself refuses those)
  kBadLogMode,    ///< the log mode byte is not '0'..'3'
};
VrpnCookieError check_vrpn_cookie(std::span<const uint8_t> bytes);

struct VrpnMessage {
  uint32_t length = 0;  ///< header + unpadded payload, as on the wire
  int32_t time_sec = 0;
  int32_t time_usec = 0;
  int32_t sender = 0;
  int32_t type = 0;
  std::span<const uint8_t> payload;  ///< unpadded, inside the framed buffer
  size_t consumed = 0;               ///< bytes of the buffer this message takes, padding included
};

enum class VrpnFrameResult : uint8_t {
  kMessage,   ///< `out` holds the first message of the buffer
  kNeedMore,  ///< the buffer holds a partial message (or nothing)
  /// out.length is below 24 or above kVrpnMaxMessageBytes: the stream is lost
  kBadLength,
};
/// Frames the first message at the start of `buffer` (a TCP stream after the cookie).
VrpnFrameResult next_vrpn_message(std::span<const uint8_t> buffer, VrpnMessage& out);

enum class VrpnPayloadError : uint8_t {
  kNone,
  kShort,        ///< payload shorter than its layout
  kLong,         ///< payload longer than its layout
  kBadName,      ///< description: length not 1..100, no NUL at the end, or a NUL inside
  kBadSensor,    ///< Pos_Quat: negative sensor number
  kNotFinite,    ///< Pos_Quat: NaN or infinity (or overflow in mm)
  kNotRotation,  ///< Pos_Quat: quaternion of (near) zero length
};
std::string_view describe(VrpnPayloadError error);

/// A sender or type description's name (a view into `payload`, NUL excluded).
VrpnPayloadError decode_vrpn_description(std::span<const uint8_t> payload, std::string_view& name);

/// A Pos_Quat payload to a pose: position in mm, the quaternion reordered to
/// w, x, y, z and normalised. On an error `out` is untouched.
VrpnPayloadError decode_vrpn_pos_quat(std::span<const uint8_t> payload, TrackerPose& out);

/// Encoders, for the tests' scripted server, the fuzz seeds and benchmarks.
std::array<uint8_t, kVrpnPosQuatBytes> encode_vrpn_pos_quat(int32_t sensor,
                                                            std::array<double, 3> position_m,
                                                            std::array<double, 4> quat_xyzw);
std::vector<uint8_t> encode_vrpn_description(std::string_view name);
/// One framed message: header, payload, padding.
std::vector<uint8_t> encode_vrpn_message(int32_t sender, int32_t type,
                                         std::span<const uint8_t> payload, int32_t time_sec = 0,
                                         int32_t time_usec = 0);

}  // namespace sculpt::hal
