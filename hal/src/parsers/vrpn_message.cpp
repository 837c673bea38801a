// VRPN's wire format, written from its published source (github.com/vrpn/vrpn
// at commit 893c7496, files vrpn_Connection.C, vrpn_Connection.h,
// vrpn_Tracker.C, vrpn_Shared.h):
// - the cookie: write_vrpn_cookie() prints "%.16s  %c" of vrpn_MAGIC ("vrpn:
//   ver. 07.38") and the log mode digit, and vrpn_COOKIE_SIZE = 16 +
//   vrpn_ALIGN (8) = 24 bytes go on the wire; check_vrpn_cookie() compares
//   through the last '.', so any 07.xx minor version is accepted;
//   finish_new_connection_setup() reads the log mode at byte 18 and refuses
//   anything outside 0..3;
// - a message: getOneTCPMessage() reads five network-order int32 (length,
//   tv_sec, tv_usec, sender, type), skips to vrpn_ALIGN, and reads the
//   payload rounded up to vrpn_ALIGN; the length counts the aligned header;
// - descriptions: pack_sender_description()/pack_type_description() send
//   htonl(strlen + 1) and the name with its NUL, the sender field holding
//   the id described, the type -1 (sender) or -2 (type);
// - Pos_Quat: vrpn_Tracker::encode_to() buffers d_sensor twice (the second
//   only to align), pos[3], d_quat[4] in x, y, z, w order (VRPN's q_type),
//   each in network order via vrpn_buffer(); positions are in metres.
// Nothing of VRPN's code is used; this is the format only.

#include "sculpt/hal/parsers/vrpn_message.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace sculpt::hal {
namespace {

constexpr std::string_view kMagic = "vrpn: ver. 07.38";
constexpr std::string_view kMagicMajor = "vrpn: ver. 07.";
constexpr size_t kLogModeAt = 18;  // after the 16 magic bytes and two spaces
constexpr size_t kAlign = 8;
constexpr double kMmPerM = 1000.0;

uint32_t read_u32_be(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}
int32_t read_i32_be(const uint8_t* p) {
  return static_cast<int32_t>(read_u32_be(p));
}
double read_f64_be(const uint8_t* p) {
  uint64_t u = 0;
  for (int i = 0; i < 8; ++i)
    u = (u << 8) | p[i];
  return std::bit_cast<double>(u);
}
void write_u32_be(uint8_t* p, uint32_t v) {
  for (int i = 3; i >= 0; --i, v >>= 8)
    p[i] = static_cast<uint8_t>(v & 0xff);
}
void write_f64_be(uint8_t* p, double v) {
  uint64_t u = std::bit_cast<uint64_t>(v);
  for (int i = 7; i >= 0; --i, u >>= 8)
    p[i] = static_cast<uint8_t>(u & 0xff);
}
size_t align_up(size_t n) {
  return (n + kAlign - 1) / kAlign * kAlign;
}

}  // namespace

std::array<uint8_t, kVrpnCookieBytes> make_vrpn_cookie() {
  std::array<uint8_t, kVrpnCookieBytes> out{};
  std::memcpy(out.data(), kMagic.data(), kMagic.size());
  out[16] = ' ';
  out[17] = ' ';
  out[kLogModeAt] = '0';
  return out;
}

VrpnCookieError check_vrpn_cookie(std::span<const uint8_t> bytes) {
  if (bytes.size() < kVrpnCookieBytes) return VrpnCookieError::kShort;
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), kVrpnCookieBytes);
  if (text.substr(0, 11) != kMagicMajor.substr(0, 11)) return VrpnCookieError::kNotVrpn;
  if (text.substr(0, kMagicMajor.size()) != kMagicMajor) return VrpnCookieError::kMajorVersion;
  const char mode = text[kLogModeAt];
  if (mode < '0' || mode > '3') return VrpnCookieError::kBadLogMode;
  return VrpnCookieError::kNone;
}

VrpnFrameResult next_vrpn_message(std::span<const uint8_t> buffer, VrpnMessage& out) {
  if (buffer.size() < 4) return VrpnFrameResult::kNeedMore;
  // The length alone decides whether the stream is still framed: check it
  // before waiting for a header that may never come.
  const uint32_t length = read_u32_be(buffer.data());
  out.length = length;  // also on kBadLength, for the log line
  if (length < kVrpnHeaderBytes || length > kVrpnMaxMessageBytes)
    return VrpnFrameResult::kBadLength;
  const size_t payload_bytes = length - kVrpnHeaderBytes;
  const size_t consumed = kVrpnHeaderBytes + align_up(payload_bytes);
  if (buffer.size() < consumed) return VrpnFrameResult::kNeedMore;
  out.length = length;
  out.time_sec = read_i32_be(buffer.data() + 4);
  out.time_usec = read_i32_be(buffer.data() + 8);
  out.sender = read_i32_be(buffer.data() + 12);
  out.type = read_i32_be(buffer.data() + 16);
  out.payload = buffer.subspan(kVrpnHeaderBytes, payload_bytes);
  out.consumed = consumed;
  return VrpnFrameResult::kMessage;
}

std::string_view describe(VrpnPayloadError error) {
  switch (error) {
    case VrpnPayloadError::kNone:
      return "ok";
    case VrpnPayloadError::kShort:
      return "payload shorter than its layout";
    case VrpnPayloadError::kLong:
      return "payload longer than its layout";
    case VrpnPayloadError::kBadName:
      return "description with a bad name";
    case VrpnPayloadError::kBadSensor:
      return "negative sensor number";
    case VrpnPayloadError::kNotFinite:
      return "NaN or infinity in the pose";
    case VrpnPayloadError::kNotRotation:
      return "quaternion of zero length";
  }
  return "?";
}

VrpnPayloadError decode_vrpn_description(std::span<const uint8_t> payload, std::string_view& name) {
  if (payload.size() < 4) return VrpnPayloadError::kShort;
  const uint32_t length = read_u32_be(payload.data());
  if (length < 1 || length > kVrpnMaxNameBytes) return VrpnPayloadError::kBadName;
  if (payload.size() < 4 + size_t{length}) return VrpnPayloadError::kShort;
  if (payload.size() > 4 + size_t{length}) return VrpnPayloadError::kLong;
  const std::string_view text(reinterpret_cast<const char*>(payload.data() + 4), length);
  if (text.back() != '\0' || text.find('\0') != length - 1) return VrpnPayloadError::kBadName;
  name = text.substr(0, length - 1);
  return VrpnPayloadError::kNone;
}

VrpnPayloadError decode_vrpn_pos_quat(std::span<const uint8_t> payload, TrackerPose& out) {
  if (payload.size() < kVrpnPosQuatBytes) return VrpnPayloadError::kShort;
  if (payload.size() > kVrpnPosQuatBytes) return VrpnPayloadError::kLong;
  const int32_t sensor = read_i32_be(payload.data());
  if (sensor < 0) return VrpnPayloadError::kBadSensor;
  std::array<double, 3> mm;
  for (int i = 0; i < 3; ++i) {
    mm[i] = read_f64_be(payload.data() + 8 + 8 * i) * kMmPerM;
    if (!std::isfinite(mm[i])) return VrpnPayloadError::kNotFinite;
  }
  double xyzw[4];
  double norm2 = 0;
  for (int i = 0; i < 4; ++i) {
    xyzw[i] = read_f64_be(payload.data() + 32 + 8 * i);
    if (!std::isfinite(xyzw[i])) return VrpnPayloadError::kNotFinite;
  }
  // Scale before squaring so a huge but finite quaternion does not overflow.
  double largest = 0;
  for (double c : xyzw)
    largest = std::max(largest, std::fabs(c));
  if (largest < 1e-9) return VrpnPayloadError::kNotRotation;
  for (double& c : xyzw) {
    c /= largest;
    norm2 += c * c;
  }
  const double inv = 1.0 / std::sqrt(norm2);
  out.sensor = sensor;
  out.position_mm = mm;
  out.quat_wxyz = {xyzw[3] * inv, xyzw[0] * inv, xyzw[1] * inv, xyzw[2] * inv};
  return VrpnPayloadError::kNone;
}

std::array<uint8_t, kVrpnPosQuatBytes> encode_vrpn_pos_quat(int32_t sensor,
                                                            std::array<double, 3> position_m,
                                                            std::array<double, 4> quat_xyzw) {
  std::array<uint8_t, kVrpnPosQuatBytes> out{};
  write_u32_be(out.data(), static_cast<uint32_t>(sensor));
  write_u32_be(out.data() + 4, static_cast<uint32_t>(sensor));  // VRPN's alignment filler
  for (int i = 0; i < 3; ++i)
    write_f64_be(out.data() + 8 + 8 * i, position_m[i]);
  for (int i = 0; i < 4; ++i)
    write_f64_be(out.data() + 32 + 8 * i, quat_xyzw[i]);
  return out;
}

std::vector<uint8_t> encode_vrpn_description(std::string_view name) {
  std::vector<uint8_t> out(4 + name.size() + 1, 0);
  write_u32_be(out.data(), static_cast<uint32_t>(name.size() + 1));
  std::memcpy(out.data() + 4, name.data(), name.size());
  return out;
}

std::vector<uint8_t> encode_vrpn_message(int32_t sender, int32_t type,
                                         std::span<const uint8_t> payload, int32_t time_sec,
                                         int32_t time_usec) {
  std::vector<uint8_t> out(kVrpnHeaderBytes + align_up(payload.size()), 0);
  write_u32_be(out.data(), static_cast<uint32_t>(kVrpnHeaderBytes + payload.size()));
  write_u32_be(out.data() + 4, static_cast<uint32_t>(time_sec));
  write_u32_be(out.data() + 8, static_cast<uint32_t>(time_usec));
  write_u32_be(out.data() + 12, static_cast<uint32_t>(sender));
  write_u32_be(out.data() + 16, static_cast<uint32_t>(type));
  if (!payload.empty()) std::memcpy(out.data() + kVrpnHeaderBytes, payload.data(), payload.size());
  return out;
}

}  // namespace sculpt::hal
