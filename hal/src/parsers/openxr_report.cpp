// The OpenXR controller report (see the header for the layout).

#include "sculpt/hal/parsers/openxr_report.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace sculpt::hal {
namespace {

constexpr uint8_t kFormat = 'X';

void put64(uint8_t* at, double v) {
  const auto bits = std::bit_cast<uint64_t>(v);
  for (int i = 0; i < 8; ++i)
    at[i] = static_cast<uint8_t>(bits >> (8 * i));
}

double get64(const uint8_t* at) {
  uint64_t bits = 0;
  for (int i = 7; i >= 0; --i)
    bits = bits << 8 | at[i];
  return std::bit_cast<double>(bits);
}

}  // namespace

std::array<uint8_t, kOpenXrReportBytes> encode_openxr_report(const OpenXrControllerState& s) {
  std::array<uint8_t, kOpenXrReportBytes> b{};
  b[0] = kFormat;
  b[1] = s.tracked ? 1 : 0;
  b[2] = static_cast<uint8_t>(s.buttons);
  b[3] = static_cast<uint8_t>(s.buttons >> 8);
  const auto trigger = std::bit_cast<uint32_t>(s.trigger);
  for (int i = 0; i < 4; ++i)
    b[4 + i] = static_cast<uint8_t>(trigger >> (8 * i));
  for (int i = 0; i < 3; ++i)
    put64(&b[8 + 8 * i], s.position_mm[i]);
  for (int i = 0; i < 4; ++i)
    put64(&b[32 + 8 * i], s.quat_wxyz[i]);
  return b;
}

OpenXrReportError decode_openxr_report(std::span<const uint8_t> bytes, OpenXrControllerState& out) {
  if (bytes.size() != kOpenXrReportBytes) return OpenXrReportError::kSize;
  if (bytes[0] != kFormat || (bytes[1] & ~1u) != 0) return OpenXrReportError::kFormat;
  OpenXrControllerState s;
  s.tracked = bytes[1] & 1u;
  s.buttons = static_cast<uint16_t>(bytes[2] | bytes[3] << 8);
  uint32_t trigger = 0;
  for (int i = 3; i >= 0; --i)
    trigger = trigger << 8 | bytes[4 + i];
  s.trigger = std::bit_cast<float>(trigger);
  if (!std::isfinite(s.trigger)) return OpenXrReportError::kNotFinite;
  double norm2 = 0;
  for (int i = 0; i < 3; ++i) {
    s.position_mm[i] = get64(&bytes[8 + 8 * i]);
    if (!std::isfinite(s.position_mm[i])) return OpenXrReportError::kNotFinite;
  }
  for (int i = 0; i < 4; ++i) {
    s.quat_wxyz[i] = get64(&bytes[32 + 8 * i]);
    if (!std::isfinite(s.quat_wxyz[i])) return OpenXrReportError::kNotFinite;
    norm2 += s.quat_wxyz[i] * s.quat_wxyz[i];
  }
  if (s.tracked) {
    // A float quaternion from the runtime is unit only to float precision.
    if (!std::isfinite(norm2) || norm2 < 1e-6) return OpenXrReportError::kNotRotation;
    const double n = std::sqrt(norm2);
    for (double& c : s.quat_wxyz)
      c /= n;
  }
  out = s;
  return OpenXrReportError::kNone;
}

void OpenXrReportParser::parse(const RawEvent& event, std::vector<InputEvent>& out) {
  ++counters_.reports;
  if (event.kind != RawEventKind::kReport) {
    if (event.kind != RawEventKind::kRemoved) ++counters_.unknown_reports;
    return;
  }
  OpenXrControllerState s;
  const OpenXrReportError e =
      event.truncated ? OpenXrReportError::kSize : decode_openxr_report(event.bytes(), s);
  if (e != OpenXrReportError::kNone) {
    ++(e == OpenXrReportError::kSize && event.size < kOpenXrReportBytes
           ? counters_.short_reports
           : counters_.invalid_reports);
    return;
  }
  InputEvent base;
  base.t_ns = event.t_ns;
  if (s.tracked) {
    InputEvent m = base;
    m.kind = InputKind::kMotion;
    m.absolute = true;
    m.has_pose = true;
    m.pose.position_mm = s.position_mm;
    m.pose.quat_wxyz = s.quat_wxyz;
    out.push_back(m);
  } else if (tracked_) {
    InputEvent lost = base;
    lost.kind = InputKind::kTrackingLost;
    out.push_back(lost);
  }
  tracked_ = s.tracked;
  const uint16_t changed = static_cast<uint16_t>(s.buttons ^ buttons_);
  for (int b = 0; b < 16; ++b) {
    if (!((changed >> b) & 1u)) continue;
    InputEvent press = base;
    press.kind = InputKind::kButton;
    press.button = b;
    press.pressed = (s.buttons >> b) & 1u;
    out.push_back(press);
  }
  buttons_ = s.buttons;
}

}  // namespace sculpt::hal
